//! OpenCASCADE as a tetrafoil geometry plugin: the crate's cdylib (`libtetrafoil_occt.so`)
//! exports `tetrafoil_geometry_plugin`, whose table (`include/tetrafoil_geometry.h`, version 1)
//! reads STEP, IGES and BREP and answers every query through the crate's thread-safe handles
//! (queries may run on many threads at once). Built into the rlib too, where nothing calls it.

mod model;
mod queries;

use tetrafoil_plugin_abi as abi;

/// The table and its strings: immutable statics, shared by every thread.
struct Static(abi::Table);
// SAFETY: the table is never written; its pointers are to static strings and functions.
unsafe impl Sync for Static {}

struct Extensions([*const std::ffi::c_char; 7]);
// SAFETY: pointers to static strings, never written.
unsafe impl Sync for Extensions {}

static EXTENSIONS: Extensions = Extensions([
    c"step".as_ptr(),
    c"stp".as_ptr(),
    c"iges".as_ptr(),
    c"igs".as_ptr(),
    c"brep".as_ptr(),
    c"brp".as_ptr(),
    std::ptr::null(),
]);

static TABLE: Static = Static(abi::Table {
    abi_version: abi::ABI_VERSION,
    struct_size: std::mem::size_of::<abi::Table>() as u32,
    name: c"occt".as_ptr(),
    version: c"7.8 bridge 0.1.0".as_ptr(),
    extensions: &EXTENSIONS.0 as *const _ as *const *const std::ffi::c_char,
    flags: 0,
    reserved: 0,
    open_file: Some(queries::open_file),
    close: Some(queries::close),
    topology: Some(queries::topology),
    curve_derivs: Some(queries::curve_derivs),
    pcurve_derivs: Some(queries::pcurve_derivs),
    surface_derivs: Some(queries::surface_derivs),
    open_buffer: None,
    curve_points: None,
    surface_points: None,
    curve_closest: Some(queries::curve_closest),
    surface_closest: Some(queries::surface_closest),
    surface_circle: Some(queries::surface_circle),
    sew: Some(queries::sew),
    fuse: Some(queries::fuse),
    bounding_box: Some(queries::bounding_box),
    heal: Some(queries::heal),
    farfield: Some(queries::farfield),
    solids_only: Some(queries::solids_only),
});

/// The plugin's one exported symbol.
#[no_mangle]
pub extern "C" fn tetrafoil_geometry_plugin() -> *const abi::Table {
    &TABLE.0
}
