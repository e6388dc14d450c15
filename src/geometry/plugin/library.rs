//! One plugin library: loaded once, its table checked (ABI version, size, required entries,
//! strings), kept for the life of the process (its function pointers are used by entities
//! that may live as long), and every call into it made through [`Plugin::call`], which zeroes
//! the error block, serialises calls for a `TF_PLUGIN_SERIAL` plugin, and turns a failure
//! into a [`CallError`].

use libloading::Library;
use std::ffi::{c_char, CStr};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use tetrafoil_plugin_abi::{self as abi, Status};

/// Why a library is not a usable plugin.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    #[error("plugin {path}: cannot be loaded: {message}")]
    Open { path: String, message: String },
    #[error(
        "plugin {path}: not a tetrafoil geometry plugin (it exports no `tetrafoil_geometry_plugin`)"
    )]
    NoEntry { path: String },
    #[error("plugin {path}: `tetrafoil_geometry_plugin` returned no table")]
    NullTable { path: String },
    #[error(
        "plugin '{name}' ({path}) speaks plugin ABI version {found}; this tetrafoil speaks \
         version {expected} (include/tetrafoil_geometry.h): rebuild the plugin against it"
    )]
    Version {
        name: String,
        path: String,
        found: u32,
        expected: u32,
    },
    #[error("plugin '{name}' ({path}): {message}")]
    Table {
        name: String,
        path: String,
        message: String,
    },
}

/// A failed call into a plugin: the status and what the plugin said.
#[derive(Clone, Debug, PartialEq)]
pub struct CallError {
    pub status: Status,
    pub entity_kind: i32,
    pub entity: i32,
    pub message: String,
}

impl CallError {
    /// The status code's meaning, for messages.
    pub fn kind(&self) -> &'static str {
        match self.status {
            1 => "not found",
            2 => "I/O error",
            3 => "format error",
            4 => "entity error",
            5 => "evaluation error",
            6 => "unsupported",
            7 => "internal error",
            _ => "unknown status",
        }
    }
}

/// A loaded plugin.
pub struct Plugin {
    pub path: PathBuf,
    pub name: String,
    pub version: String,
    /// Extensions claimed, lower case without the dot.
    pub extensions: Vec<String>,
    pub(super) table: abi::Table,
    /// Held for a `TF_PLUGIN_SERIAL` plugin: one call at a time.
    serial: Option<Mutex<()>>,
    _library: Library,
}

// SAFETY: the table is read-only after loading: its strings (copied out at load) and function
// pointers live as long as the process, and calls into the plugin follow the thread rules of
// the contract (`call` serialises a `TF_PLUGIN_SERIAL` plugin).
unsafe impl Send for Plugin {}
unsafe impl Sync for Plugin {}

impl std::fmt::Debug for Plugin {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "plugin '{}' ({})", self.name, self.path.display())
    }
}

/// A C string from the plugin, checked.
///
/// # Safety
/// `p` is NULL or points to a NUL-terminated string that outlives the call.
unsafe fn text(p: *const c_char) -> Option<Result<String, ()>> {
    if p.is_null() {
        return None;
    }
    Some(
        CStr::from_ptr(p)
            .to_str()
            .map(str::to_string)
            .map_err(|_| ()),
    )
}

impl Plugin {
    /// Load the library at `path` and check its table.
    pub fn load(path: &Path) -> Result<Arc<Plugin>, LoadError> {
        let shown = path.display().to_string();
        // SAFETY: loading runs the library's initialisers; a plugin is code the user chose to
        // run, as any shared library is.
        let library = unsafe { Library::new(path) }.map_err(|e| LoadError::Open {
            path: shown.clone(),
            message: e.to_string(),
        })?;
        // SAFETY: the symbol's type is the header's `tf_entry_point`.
        let entry: abi::Entry = unsafe {
            *library
                .get::<abi::Entry>(abi::ENTRY_POINT)
                .map_err(|_| LoadError::NoEntry {
                    path: shown.clone(),
                })?
        };
        // SAFETY: the entry point takes nothing and returns a table or NULL.
        let raw = unsafe { entry() };
        if raw.is_null() {
            return Err(LoadError::NullTable { path: shown });
        }
        // SAFETY: every table begins with its version and size (two u32s), whatever version.
        let (version, size) = unsafe {
            let head = raw as *const u32;
            (*head, *head.add(1) as usize)
        };
        // The name comes after the two u32s in every version; read it only to name the plugin.
        let name_of = || {
            // SAFETY: as above, version-1 layout up to `name`.
            unsafe { text((*raw).name) }
                .and_then(Result::ok)
                .unwrap_or_else(|| "?".into())
        };
        if version != abi::ABI_VERSION {
            return Err(LoadError::Version {
                name: name_of(),
                path: shown,
                found: version,
                expected: abi::ABI_VERSION,
            });
        }
        let bad = |message: String| LoadError::Table {
            name: name_of(),
            path: shown.clone(),
            message,
        };
        if size < abi::REQUIRED_SIZE {
            return Err(bad(format!(
                "its table is {size} bytes, shorter than version 1's required part ({} bytes)",
                abi::REQUIRED_SIZE
            )));
        }
        // Copy what the plugin's table holds; entries past its size stay absent (NULL).
        let mut table: abi::Table = unsafe { std::mem::zeroed() };
        let n = size.min(std::mem::size_of::<abi::Table>());
        // SAFETY: the plugin says its table is `size` bytes long; `Table` is plain data in
        // which all-zero is valid (NULL pointers, `None` functions).
        unsafe {
            std::ptr::copy_nonoverlapping(raw as *const u8, &mut table as *mut _ as *mut u8, n)
        };
        // SAFETY: strings of the table live as long as the process (the contract).
        let name = match unsafe { text(table.name) } {
            Some(Ok(n)) if !n.is_empty() => n,
            _ => return Err(bad("its name is missing or not UTF-8".into())),
        };
        let version_text = match unsafe { text(table.version) } {
            Some(Ok(v)) => v,
            _ => return Err(bad("its version is missing or not UTF-8".into())),
        };
        let missing: Vec<&str> = [
            ("open_file", table.open_file.is_none()),
            ("close", table.close.is_none()),
            ("topology", table.topology.is_none()),
            ("curve_derivs", table.curve_derivs.is_none()),
            ("pcurve_derivs", table.pcurve_derivs.is_none()),
            ("surface_derivs", table.surface_derivs.is_none()),
        ]
        .into_iter()
        .filter_map(|(n, absent)| absent.then_some(n))
        .collect();
        if !missing.is_empty() {
            return Err(bad(format!(
                "required entries missing from its table: {}",
                missing.join(", ")
            )));
        }
        let extensions = unsafe { extensions(table.extensions) }.map_err(bad)?;
        Ok(Arc::new(Plugin {
            path: path.to_path_buf(),
            name,
            version: version_text,
            extensions,
            serial: (table.flags & abi::PLUGIN_SERIAL != 0).then(|| Mutex::new(())),
            table,
            _library: library,
        }))
    }

    /// Whether this plugin reads files with extension `ext` (any case, no dot).
    pub fn claims(&self, ext: &str) -> bool {
        self.extensions.iter().any(|e| e.eq_ignore_ascii_case(ext))
    }

    /// Run `f` with a fresh error block; a status other than `OK` (and `NOT_FOUND` when
    /// `not_found_ok`) becomes the error, with the plugin's message.
    pub(super) fn call(
        &self,
        f: impl FnOnce(*mut abi::Error) -> Status,
    ) -> Result<Status, CallError> {
        let mut err = abi::Error::new();
        let status = {
            let _one_at_a_time = self
                .serial
                .as_ref()
                .map(|m| m.lock().unwrap_or_else(|e| e.into_inner()));
            f(&mut err)
        };
        if status == abi::OK || status == abi::NOT_FOUND {
            return Ok(status);
        }
        // The message is NUL-terminated within its buffer, or cut at the buffer's end.
        let bytes: Vec<u8> = err
            .message
            .iter()
            .take_while(|&&c| c != 0)
            .map(|&c| c as u8)
            .collect();
        let message = String::from_utf8_lossy(&bytes).trim().to_string();
        Err(CallError {
            status,
            entity_kind: err.entity_kind,
            entity: err.entity,
            message: if message.is_empty() {
                "(no message)".into()
            } else {
                message
            },
        })
    }

    /// "plugin 'name' (path)", as messages name it.
    pub fn label(&self) -> String {
        format!("plugin '{}' ({})", self.name, self.path.display())
    }
}

/// The NULL-terminated extension list.
///
/// # Safety
/// `list` is NULL or a NULL-terminated array of C strings living as long as the process.
unsafe fn extensions(list: *const *const c_char) -> Result<Vec<String>, String> {
    let mut out = Vec::new();
    if list.is_null() {
        return Ok(out);
    }
    for k in 0.. {
        let p = *list.add(k);
        if p.is_null() {
            break;
        }
        match text(p) {
            Some(Ok(e)) => out.push(e.trim_start_matches('.').to_ascii_lowercase()),
            _ => return Err(format!("extension {k} is not UTF-8")),
        }
        if k > 256 {
            return Err("its extension list is not NULL-terminated".into());
        }
    }
    Ok(out)
}
