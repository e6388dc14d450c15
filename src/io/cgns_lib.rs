//! The CGNS mid-level library, loaded at run time (`libloading`): the few calls the CGNS
//! writer makes, with the enum values of `cgnslib.h` (CGNS 3.4). Loaded rather than linked so
//! the binary builds and runs without the library; only writing `.cgns` needs it, and then a
//! missing library is a clear error naming what to install.
//!
//! `cgsize_t` is taken as 32-bit, as Debian's `libcgns` (3.4, legacy build) has it. The writer
//! reads the zone size back after writing it, so a library built with 64-bit sizes is caught
//! and refused, never written to with the wrong width.

use libloading::Library;
use std::ffi::{c_char, c_int, CStr, CString};

/// `cgsize_t` of the library (see the module doc).
pub(crate) type CgSize = i32;

pub(crate) const MODE_WRITE: c_int = 1;
pub(crate) const MODE_MODIFY: c_int = 2;
pub(crate) const FILE_HDF5: c_int = 2;
pub(crate) const UNSTRUCTURED: c_int = 3;
pub(crate) const REAL_DOUBLE: c_int = 4;
pub(crate) const POINT_RANGE: c_int = 4;
pub(crate) const FACE_CENTER: c_int = 4;
pub(crate) const FAMILY_SPECIFIED: c_int = 25;
/// `DataClass_t`: lengths in the model's own unit, which the mesh does not know.
pub(crate) const NORMALIZED_BY_UNKNOWN_DIMENSIONAL: c_int = 4;

/// CGNS element types the writer uses.
pub(crate) mod element {
    use std::ffi::c_int;
    pub const TRI_3: c_int = 5;
    pub const QUAD_4: c_int = 7;
    pub const TETRA_4: c_int = 10;
    pub const PYRA_5: c_int = 12;
    pub const PENTA_6: c_int = 14;
}

/// CGNS boundary-condition types the writer uses.
pub(crate) mod bc {
    use std::ffi::c_int;
    pub const FARFIELD: c_int = 7;
    pub const SYMMETRY_PLANE: c_int = 16;
    pub const WALL: c_int = 20;
}

/// Sonames tried in order when `TETRAFOIL_CGNS_LIB` does not name the library.
const NAMES: [&str; 6] = [
    "libcgns.so",
    "libcgns.so.4.4",
    "libcgns.so.4.3",
    "libcgns.so.4.2",
    "libcgns.so.4.1",
    "libcgns.so.3.4",
];

type Sz = *const CgSize;

/// The loaded library's entry points.
pub(crate) struct Cgns {
    pub open: unsafe extern "C" fn(*const c_char, c_int, *mut c_int) -> c_int,
    pub close: unsafe extern "C" fn(c_int) -> c_int,
    pub set_file_type: unsafe extern "C" fn(c_int) -> c_int,
    pub base_write: unsafe extern "C" fn(c_int, *const c_char, c_int, c_int, *mut c_int) -> c_int,
    pub zone_write:
        unsafe extern "C" fn(c_int, c_int, *const c_char, Sz, c_int, *mut c_int) -> c_int,
    pub zone_read: unsafe extern "C" fn(c_int, c_int, c_int, *mut c_char, *mut CgSize) -> c_int,
    pub coord_write: unsafe extern "C" fn(
        c_int,
        c_int,
        c_int,
        c_int,
        *const c_char,
        *const std::ffi::c_void,
        *mut c_int,
    ) -> c_int,
    #[allow(clippy::type_complexity)]
    pub section_write: unsafe extern "C" fn(
        c_int,
        c_int,
        c_int,
        *const c_char,
        c_int,
        CgSize,
        CgSize,
        c_int,
        Sz,
        *mut c_int,
    ) -> c_int,
    pub family_write: unsafe extern "C" fn(c_int, c_int, *const c_char, *mut c_int) -> c_int,
    pub fambc_write:
        unsafe extern "C" fn(c_int, c_int, c_int, *const c_char, c_int, *mut c_int) -> c_int,
    #[allow(clippy::type_complexity)]
    pub boco_write: unsafe extern "C" fn(
        c_int,
        c_int,
        c_int,
        *const c_char,
        c_int,
        c_int,
        CgSize,
        Sz,
        *mut c_int,
    ) -> c_int,
    pub boco_gridlocation_write: unsafe extern "C" fn(c_int, c_int, c_int, c_int, c_int) -> c_int,
    pub goto: unsafe extern "C" fn(c_int, c_int, ...) -> c_int,
    pub famname_write: unsafe extern "C" fn(*const c_char) -> c_int,
    pub dataclass_write: unsafe extern "C" fn(c_int) -> c_int,
    pub get_error: unsafe extern "C" fn() -> *const c_char,
    _library: Library,
}

/// An error from the library: the call, and the library's own message.
pub(crate) fn failure(what: &str, message: String) -> std::io::Error {
    std::io::Error::other(format!("CGNS library: {what} failed: {message}"))
}

impl Cgns {
    /// Load the library, or say what to install.
    pub fn load() -> std::io::Result<Self> {
        // A path given in TETRAFOIL_CGNS_LIB is the only one tried.
        let candidates: Vec<std::ffi::OsString> = match std::env::var_os("TETRAFOIL_CGNS_LIB") {
            Some(path) => vec![path],
            None => NAMES.iter().map(|n| n.into()).collect(),
        };
        let mut tried = Vec::new();
        for name in candidates {
            // SAFETY: loading the CGNS library runs its (and HDF5's) initialisers, which have
            // no preconditions on us.
            match unsafe { Library::new(&name) } {
                Ok(library) => return Self::bind(library, &name.to_string_lossy()),
                Err(e) => tried.push(format!("{}: {e}", name.to_string_lossy())),
            }
        }
        Err(std::io::Error::new(
            std::io::ErrorKind::NotFound,
            format!(
                "CGNS output needs the CGNS library (Debian/Ubuntu: apt-get install libcgns-dev; \
                 or set TETRAFOIL_CGNS_LIB to its path); not found ({})",
                tried.join("; ")
            ),
        ))
    }

    fn bind(library: Library, name: &str) -> std::io::Result<Self> {
        macro_rules! sym {
            ($s:literal) => {
                // SAFETY: the type given at each use is the prototype in cgnslib.h (3.4) with
                // cgsize_t as CgSize; a wrong width is caught by the writer's read-back.
                *unsafe { library.get(concat!($s, "\0").as_bytes()) }.map_err(|e| {
                    std::io::Error::other(format!("CGNS library {name} lacks {}: {e}", $s))
                })?
            };
        }
        Ok(Self {
            open: sym!("cg_open"),
            close: sym!("cg_close"),
            set_file_type: sym!("cg_set_file_type"),
            base_write: sym!("cg_base_write"),
            zone_write: sym!("cg_zone_write"),
            zone_read: sym!("cg_zone_read"),
            coord_write: sym!("cg_coord_write"),
            section_write: sym!("cg_section_write"),
            family_write: sym!("cg_family_write"),
            fambc_write: sym!("cg_fambc_write"),
            boco_write: sym!("cg_boco_write"),
            boco_gridlocation_write: sym!("cg_boco_gridlocation_write"),
            goto: sym!("cg_goto"),
            famname_write: sym!("cg_famname_write"),
            dataclass_write: sym!("cg_dataclass_write"),
            get_error: sym!("cg_get_error"),
            _library: library,
        })
    }

    /// `Ok` when a call returned `CG_OK`, else the library's message.
    pub fn check(&self, what: &str, status: c_int) -> std::io::Result<()> {
        if status == 0 {
            return Ok(());
        }
        // SAFETY: cg_get_error returns a pointer to a NUL-terminated static buffer.
        let message = unsafe { CStr::from_ptr((self.get_error)()) };
        Err(failure(what, message.to_string_lossy().into_owned()))
    }
}

/// A C string for a name the writer made (never holds a NUL: names are cleaned).
pub(crate) fn c_name(name: &str) -> CString {
    CString::new(name.replace('\0', "_")).unwrap_or_default()
}
