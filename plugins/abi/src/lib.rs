//! The C interface of tetrafoil's geometry plugins (`include/tetrafoil_geometry.h`, version 1)
//! as Rust types, shared by the core, which loads plugins, and by plugins written in Rust (the
//! OpenCASCADE bridge's). Field order and types follow the header exactly; the core's tests
//! build C plugins against the header and load them through these.

use std::ffi::{c_char, c_void};

pub const ABI_VERSION: u32 = 1;
pub const ENTRY_POINT: &[u8] = b"tetrafoil_geometry_plugin\0";

pub type Status = i32;
pub const OK: Status = 0;
pub const NOT_FOUND: Status = 1;

pub const ENTITY_VERTEX: i32 = 1;
pub const ENTITY_EDGE: i32 = 2;
pub const ENTITY_FACE: i32 = 3;
pub const ENTITY_USE: i32 = 4;
pub const ENTITY_SHELL: i32 = 5;
pub const ENTITY_SOLID: i32 = 6;
pub const ENTITY_LINE: i32 = 7;

pub const MESSAGE_LEN: usize = 512;

pub const ERR_IO: Status = 2;
pub const ERR_FORMAT: Status = 3;
pub const ERR_ENTITY: Status = 4;
pub const ERR_EVAL: Status = 5;
pub const ERR_UNSUPPORTED: Status = 6;
pub const ERR_INTERNAL: Status = 7;

pub const ENTITY_NONE: i32 = 0;

pub const EDGE_DEGENERATE: u32 = 1;
pub const FACE_REVERSED: u32 = 1;
pub const USE_REVERSED: u32 = 1;
pub const USE_SEAM: u32 = 2;
pub const USE_PCURVE: u32 = 4;
pub const PLUGIN_SERIAL: u32 = 1;

#[repr(C)]
pub struct Error {
    pub entity_kind: i32,
    pub entity: i32,
    pub message: [c_char; MESSAGE_LEN],
}

impl Error {
    pub fn new() -> Self {
        Error {
            entity_kind: 0,
            entity: -1,
            message: [0; MESSAGE_LEN],
        }
    }

    /// Fill the block: the entity and the message (cut to fit, NUL-terminated).
    pub fn set(&mut self, entity_kind: i32, entity: i32, message: &str) {
        self.entity_kind = entity_kind;
        self.entity = entity;
        let mut n = message.len().min(MESSAGE_LEN - 1);
        while !message.is_char_boundary(n) {
            n -= 1;
        }
        for (dst, &b) in self.message.iter_mut().zip(&message.as_bytes()[..n]) {
            *dst = b as c_char;
        }
        self.message[n] = 0;
    }
}

impl Default for Error {
    fn default() -> Self {
        Self::new()
    }
}

/// The plugin's open model (opaque).
#[repr(C)]
pub struct Model {
    _private: [u8; 0],
}

#[repr(C)]
#[derive(Clone, Copy)]
pub struct TfVertex {
    pub point: [f64; 3],
    pub tolerance: f64,
}

#[repr(C)]
#[derive(Clone, Copy)]
pub struct TfEdge {
    pub v0: i32,
    pub v1: i32,
    pub flags: u32,
    pub reserved: u32,
    pub t_range: [f64; 2],
    pub tolerance: f64,
}

#[repr(C)]
#[derive(Clone, Copy)]
pub struct TfEdgeUse {
    pub edge: i32,
    pub flags: u32,
}

#[repr(C)]
#[derive(Clone, Copy)]
pub struct TfLoop {
    pub first_use: i32,
    pub n_uses: i32,
}

#[repr(C)]
#[derive(Clone, Copy)]
pub struct TfFace {
    pub name: *const c_char,
    pub flags: u32,
    pub first_loop: i32,
    pub n_loops: i32,
    pub reserved: u32,
    pub u_range: [f64; 2],
    pub v_range: [f64; 2],
    pub u_period: f64,
    pub v_period: f64,
    pub tolerance: f64,
}

#[repr(C)]
#[derive(Clone, Copy)]
pub struct TfFaceRef {
    pub face: i32,
    pub reversed: u32,
}

#[repr(C)]
#[derive(Clone, Copy)]
pub struct TfShell {
    pub first_face: i32,
    pub n_faces: i32,
}

#[repr(C)]
#[derive(Clone, Copy)]
pub struct TfSolid {
    pub name: *const c_char,
    pub first_shell: i32,
    pub n_shells: i32,
}

pub const FARFIELD_BOX: i32 = 0;
pub const FARFIELD_SPHERE: i32 = 1;

/// `tf_farfield`: the far-field solid and the symmetry plane of a flow domain.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct Farfield {
    pub shape: i32,
    pub symmetry_axis: i32,
    pub symmetry_side: i32,
    pub reserved: u32,
    pub centre: [f64; 3],
    pub half: [f64; 3],
    pub symmetry_at: f64,
    pub fuzzy: f64,
}

#[repr(C)]
pub struct Topology {
    pub n_vertices: i32,
    pub n_edges: i32,
    pub n_faces: i32,
    pub n_loops: i32,
    pub n_uses: i32,
    pub n_shells: i32,
    pub n_face_refs: i32,
    pub n_solids: i32,
    pub n_solid_shells: i32,
    pub vertices: *const TfVertex,
    pub edges: *const TfEdge,
    pub faces: *const TfFace,
    pub loops: *const TfLoop,
    pub uses: *const TfEdgeUse,
    pub shells: *const TfShell,
    pub face_refs: *const TfFaceRef,
    pub solids: *const TfSolid,
    pub solid_shells: *const i32,
}

pub type Eval =
    unsafe extern "C" fn(*const Model, i32, usize, *const f64, *mut f64, *mut Error) -> Status;

/// The plugin's table. Entries past the plugin's `struct_size` read as absent.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct Table {
    pub abi_version: u32,
    pub struct_size: u32,
    pub name: *const c_char,
    pub version: *const c_char,
    pub extensions: *const *const c_char,
    pub flags: u32,
    pub reserved: u32,
    pub open_file:
        Option<unsafe extern "C" fn(*const c_char, *mut *mut Model, *mut Error) -> Status>,
    pub close: Option<unsafe extern "C" fn(*mut Model)>,
    pub topology: Option<unsafe extern "C" fn(*const Model, *mut Topology, *mut Error) -> Status>,
    pub curve_derivs: Option<Eval>,
    pub pcurve_derivs: Option<Eval>,
    pub surface_derivs: Option<Eval>,
    pub open_buffer: Option<
        unsafe extern "C" fn(
            *const c_void,
            usize,
            *const c_char,
            *mut *mut Model,
            *mut Error,
        ) -> Status,
    >,
    pub curve_points: Option<Eval>,
    pub surface_points: Option<Eval>,
    pub curve_closest: Option<
        unsafe extern "C" fn(
            *const Model,
            i32,
            *const f64,
            *const f64,
            *mut f64,
            *mut Error,
        ) -> Status,
    >,
    pub surface_closest: Option<
        unsafe extern "C" fn(
            *const Model,
            i32,
            *const f64,
            *const f64,
            *mut f64,
            *mut Error,
        ) -> Status,
    >,
    #[allow(clippy::type_complexity)]
    pub surface_circle: Option<
        unsafe extern "C" fn(
            *const Model,
            i32,
            *const f64,
            *const f64,
            *const f64,
            f64,
            usize,
            *mut f64,
            *mut usize,
            *mut Error,
        ) -> Status,
    >,
    pub sew: Option<unsafe extern "C" fn(*const Model, f64, *mut *mut Model, *mut Error) -> Status>,
    pub fuse:
        Option<unsafe extern "C" fn(*const Model, f64, *mut *mut Model, *mut Error) -> Status>,
    pub bounding_box: Option<unsafe extern "C" fn(*const Model, *mut f64, *mut Error) -> Status>,
    pub heal:
        Option<unsafe extern "C" fn(*const Model, f64, *mut *mut Model, *mut Error) -> Status>,
    pub farfield: Option<
        unsafe extern "C" fn(*const Model, *const Farfield, *mut *mut Model, *mut Error) -> Status,
    >,
    pub solids_only:
        Option<unsafe extern "C" fn(*const Model, *mut *mut Model, *mut Error) -> Status>,
}

/// `tf_entry_point`: the one symbol a plugin exports.
pub type Entry = unsafe extern "C" fn() -> *const Table;

/// Bytes of the table up to and including `surface_derivs`: what a version-1 plugin must give.
pub const REQUIRED_SIZE: usize =
    std::mem::offset_of!(Table, surface_derivs) + std::mem::size_of::<Option<Eval>>();
