//! Where a job's files live: `DATA/jobs/<id>/input/` (what was uploaded, under names the
//! server chose) and `DATA/jobs/<id>/out/` (results, each written to a temporary name and
//! renamed, so a result file is whole or absent). Ids are made here and checked before any
//! path is built from one, so no request can name a path.

use std::path::{Path, PathBuf};

/// The data folder's layout.
#[derive(Clone, Debug)]
pub struct Layout {
    pub data: PathBuf,
}

impl Layout {
    pub fn database(&self) -> PathBuf {
        self.data.join("jobs.sqlite")
    }

    pub fn jobs(&self) -> PathBuf {
        self.data.join("jobs")
    }

    /// A job's folder; `id` must have passed [`valid_id`].
    pub fn job(&self, id: &str) -> PathBuf {
        self.jobs().join(id)
    }

    pub fn input(&self, id: &str) -> PathBuf {
        self.job(id).join("input")
    }

    pub fn out(&self, id: &str) -> PathBuf {
        self.job(id).join("out")
    }

    /// The result file of one format.
    pub fn result(&self, id: &str, format: &str, extension: &str) -> PathBuf {
        self.out(id).join(format!("mesh-{format}.{extension}"))
    }

    /// The boundary triangles as JSON, for the web page's viewer.
    pub fn surface(&self, id: &str) -> PathBuf {
        self.out(id).join("surface.json")
    }

    pub fn report(&self, id: &str) -> PathBuf {
        self.out(id).join("report.json")
    }
}

/// A new job id: 16 hex digits from the clock, the process and a counter, mixed.
pub fn new_id() -> String {
    use std::hash::{BuildHasher, Hasher};
    use std::sync::atomic::{AtomicU64, Ordering};
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos() as u64)
        .unwrap_or(0);
    // RandomState is seeded per process: ids are not guessable from the clock alone.
    let mut h = std::collections::hash_map::RandomState::new().build_hasher();
    h.write_u64(nanos);
    h.write_u32(std::process::id());
    h.write_u64(COUNTER.fetch_add(1, Ordering::Relaxed));
    format!("{:016x}", h.finish())
}

/// Whether `id` has the shape of one of ours (so it can be joined to a path).
pub fn valid_id(id: &str) -> bool {
    id.len() == 16
        && id
            .bytes()
            .all(|b| b.is_ascii_hexdigit() && !b.is_ascii_uppercase())
}

/// Write `bytes` to `path` durably: temporary file, fsync, rename.
pub fn write_file(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    crate::io::write_atomic(path, |w| w.write_all(bytes))
}

/// Empty a job's result folder (the partial files of an interrupted run).
pub fn clear_out(layout: &Layout, id: &str) -> std::io::Result<()> {
    let out = layout.out(id);
    if out.exists() {
        std::fs::remove_dir_all(&out)?;
    }
    std::fs::create_dir_all(&out)
}

/// Remove a job's folder.
pub fn remove_job(layout: &Layout, id: &str) -> std::io::Result<()> {
    let dir = layout.job(id);
    if dir.exists() {
        std::fs::remove_dir_all(dir)?;
    }
    Ok(())
}

/// Remove folders under `jobs/` that belong to no job (an upload the server died writing,
/// before its job row was committed).
pub fn sweep_orphans(layout: &Layout, known: &[String]) -> std::io::Result<usize> {
    let mut removed = 0;
    let Ok(entries) = std::fs::read_dir(layout.jobs()) else {
        return Ok(0);
    };
    for entry in entries {
        let entry = entry?;
        let name = entry.file_name().to_string_lossy().into_owned();
        if !known.contains(&name) && entry.path().is_dir() {
            std::fs::remove_dir_all(entry.path())?;
            removed += 1;
        }
    }
    Ok(removed)
}
