use std::io::Write;
use std::path::{Path, PathBuf};

/// Write `path` atomically: fill `path.tmp-<pid>` through `fill`, flush, sync, rename.
pub fn write_atomic(
    path: &Path,
    fill: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    replace_atomic(path, |tmp| {
        let file = std::fs::File::create(tmp)?;
        let mut w = std::io::BufWriter::new(file);
        fill(&mut w)?;
        w.flush()?;
        w.get_ref().sync_all()
    })
}

/// Make `path` atomically through a writer that wants a file name (a library that opens the
/// file itself): `make` creates `path.tmp-<pid>`, which is renamed onto `path` when it
/// succeeds and removed when it fails.
pub(crate) fn replace_atomic(
    path: &Path,
    make: impl FnOnce(&Path) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(format!(".tmp-{}", std::process::id()));
    let tmp = PathBuf::from(tmp);
    let result = make(&tmp).and_then(|()| std::fs::rename(&tmp, path));
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}
