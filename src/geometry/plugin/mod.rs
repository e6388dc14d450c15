//! Foreign geometry from plugins: shared libraries implementing the C ABI of
//! `include/tetrafoil_geometry.h` (the contract: `docs/plugins.md`). A plugin opens a file,
//! gives its topology as plain arrays, and answers the geometry traits' questions; its
//! entities are [`Curve`](crate::geometry::Curve)s and [`Surface`](crate::geometry::Surface)s
//! like native ones, so a model mixes them with native Ferguson geometry.
//!
//! - [`library`]: loading a library and checking its table; every call goes through it.
//! - [`open`]: a file opened by a plugin, as a [`ForeignSource`](crate::model::foreign) to
//!   import.
//! - `handle`: an open file's handle and the query calls its entities make.
//! - [`entities`]: the plugin's curves, pcurves and surfaces behind the traits.
//!
//! Plugins are found ([`registry`]) from `--plugin PATH` (registered with [`add_path`] before
//! first use), then `TETRAFOIL_PLUGIN_PATH` (files or folders, `:`-separated), then the folder
//! of the running executable; in a folder, files named `libtetrafoil_*` / `tetrafoil_*` with the
//! platform's library suffix. The first plugin claiming an extension reads those files, except
//! that one found beside the executable leaves the built-in OpenCASCADE bridge its own.

mod entities;
mod handle;
pub mod library;
pub mod open;

pub use entities::{PluginCurve, PluginPcurve, PluginSurface};
pub use library::{LoadError, Plugin};
pub use open::PluginSource;

use tetrafoil_plugin_abi as abi;

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

/// The plugin ABI version this build speaks.
pub const ABI_VERSION: u32 = abi::ABI_VERSION;

/// Extensions the built-in OpenCASCADE bridge reads (none without the `occt` feature).
pub const BUILT_IN_EXTENSIONS: &[&str] = if cfg!(feature = "occt") {
    &["step", "stp", "iges", "igs", "brep", "brp"]
} else {
    &[]
};

/// The environment variable listing plugin files and folders.
pub const PATH_VARIABLE: &str = "TETRAFOIL_PLUGIN_PATH";

/// Plugins named on the command line, loaded first.
static EXPLICIT: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());
static REGISTRY: OnceLock<Registry> = OnceLock::new();

/// Name a plugin file to load before any found on the search path (`--plugin PATH`); must
/// come before the first use of [`registry`]. A plugin named this way that does not load is
/// an error at once.
pub fn add_path(path: &Path) -> Result<(), LoadError> {
    Plugin::load(path)?;
    EXPLICIT
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .push(path.to_path_buf());
    Ok(())
}

/// Where a plugin came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Origin {
    CommandLine,
    PathVariable,
    BesideExecutable,
}

impl Origin {
    pub fn describe(self) -> &'static str {
        match self {
            Origin::CommandLine => "--plugin",
            Origin::PathVariable => PATH_VARIABLE,
            Origin::BesideExecutable => "beside the executable",
        }
    }
}

/// The plugins found, in search order, and the files that looked like plugins but did not
/// load (with why).
#[derive(Default)]
pub struct Registry {
    pub plugins: Vec<(Arc<Plugin>, Origin)>,
    pub failed: Vec<(PathBuf, Origin, String)>,
}

impl Registry {
    /// Load every plugin on the search path.
    fn discover() -> Registry {
        let mut candidates: Vec<(PathBuf, Origin)> = Vec::new();
        let explicit = EXPLICIT.lock().unwrap_or_else(|e| e.into_inner()).clone();
        candidates.extend(explicit.into_iter().map(|p| (p, Origin::CommandLine)));
        if let Some(list) = std::env::var_os(PATH_VARIABLE) {
            for entry in std::env::split_paths(&list) {
                if entry.is_dir() {
                    candidates.extend(plugin_files(&entry).map(|p| (p, Origin::PathVariable)));
                } else if !entry.as_os_str().is_empty() {
                    candidates.push((entry, Origin::PathVariable));
                }
            }
        }
        if let Some(dir) = std::env::current_exe()
            .ok()
            .and_then(|e| e.parent().map(Path::to_path_buf))
        {
            candidates.extend(plugin_files(&dir).map(|p| (p, Origin::BesideExecutable)));
        }
        let mut registry = Registry::default();
        let mut seen: Vec<PathBuf> = Vec::new();
        for (path, origin) in candidates {
            let key = path.canonicalize().unwrap_or_else(|_| path.clone());
            if seen.contains(&key) {
                continue;
            }
            seen.push(key);
            match Plugin::load(&path) {
                Ok(p) => registry.plugins.push((p, origin)),
                Err(e) => {
                    log::warn!("{e}");
                    registry.failed.push((path, origin, e.to_string()));
                }
            }
        }
        registry
    }

    /// The first plugin claiming the extension of `path`. A plugin found beside the
    /// executable does not take the files the built-in OpenCASCADE bridge reads; one named by
    /// `--plugin` or `TETRAFOIL_PLUGIN_PATH` does.
    pub fn for_path(&self, path: &Path) -> Option<&Arc<Plugin>> {
        let ext = path.extension()?.to_str()?;
        let built_in = BUILT_IN_EXTENSIONS
            .iter()
            .any(|b| b.eq_ignore_ascii_case(ext));
        (self.plugins.iter())
            .filter(|(_, origin)| !(built_in && *origin == Origin::BesideExecutable))
            .map(|(p, _)| p)
            .find(|p| p.claims(ext))
    }
}

/// The plugins on the search path, loaded once per process.
pub fn registry() -> &'static Registry {
    REGISTRY.get_or_init(Registry::discover)
}

/// Files in `dir` named like plugins, sorted.
fn plugin_files(dir: &Path) -> impl Iterator<Item = PathBuf> {
    let suffix = std::env::consts::DLL_SUFFIX;
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
            (name.starts_with("libtetrafoil_") || name.starts_with("tetrafoil_"))
                && name.ends_with(suffix)
                && p.is_file()
        })
        .collect();
    files.sort();
    files.into_iter()
}
