//! CGNS (`.cgns`, HDF5) through the CGNS library: one base, one unstructured zone holding every
//! node, and element sections numbered consecutively from 1:
//!
//! - the cells, one section per region and kind (`TETRA_4`, `PYRA_5`, `PENTA_6`), named
//!   `<region>_tets` and so on (CGNS 3.4 allows no `FamilyName` under `Elements_t`, so the
//!   section's name is what tells the region);
//! - the boundary, one section per marker group and face kind (`TRI_3`, `QUAD_4`), a group's
//!   sections adjacent so one `BC_t` covers them: `PointRange` over their element numbers at
//!   `FaceCenter` (CGNS 3's form), type `FamilySpecified`, naming the group's family, whose
//!   `FamilyBC` is the kind `bc_guess` gives it (`BCFarfield`, `BCSymmetryPlane`, `BCWall`);
//!   a group with cells on both sides (a wake) has its sections but no `BC_t`.
//!
//! Node orders are the mesh's, which are CGNS's (a tet's first face turns towards its fourth
//! node; a pyramid's base towards its apex; a prism's bottom towards its top). CGNS names hold
//! at most 32 characters and no `/`: longer names are cut, and names made unique per level.
//!
//! The library is not thread-safe: one file is written at a time (the service may ask for
//! several at once).

use super::atomic::replace_atomic;
use super::bc_guess::{guess_all, BoundaryKind};
use super::cgns_lib::{bc, c_name, element, CgSize, Cgns};
use super::cgns_lib::{FACE_CENTER, FAMILY_SPECIFIED, FILE_HDF5, MODE_MODIFY, MODE_WRITE};
use super::cgns_lib::{NORMALIZED_BY_UNKNOWN_DIMENSIONAL, POINT_RANGE, REAL_DOUBLE, UNSTRUCTURED};
use super::names::{groups, Groups};
use crate::mesh::{CellKind, VolumeMesh};
use std::collections::HashSet;
use std::ffi::{c_int, c_void};
use std::path::Path;
use std::sync::{Mutex, OnceLock};

/// The loaded library, behind the lock that serialises every use of it.
static LIBRARY: OnceLock<Mutex<Cgns>> = OnceLock::new();

/// Write `m` to `path` as CGNS (atomically).
pub(crate) fn write(path: &Path, m: &VolumeMesh) -> std::io::Result<()> {
    let library = match LIBRARY.get() {
        Some(l) => l,
        None => {
            let loaded = Cgns::load()?;
            LIBRARY.get_or_init(|| Mutex::new(loaded))
        }
    };
    let lib = library.lock().unwrap_or_else(|e| e.into_inner());
    replace_atomic(path, |tmp| {
        let file = OpenFile::create(&lib, tmp)?;
        write_tree(&file, m)?;
        file.close()
    })
}

/// An open CGNS file, closed on drop when [`OpenFile::close`] was not reached.
struct OpenFile<'a> {
    lib: &'a Cgns,
    fn_: c_int,
    open: bool,
}

impl<'a> OpenFile<'a> {
    fn create(lib: &'a Cgns, path: &Path) -> std::io::Result<Self> {
        let name = c_name(&path.to_string_lossy());
        let mut fn_ = 0;
        // SAFETY: plain calls into the library with a NUL-terminated name and an out-pointer.
        unsafe {
            lib.check("cg_set_file_type", (lib.set_file_type)(FILE_HDF5))?;
            // Created, then reopened for modifying: a file open for writing only cannot be
            // read, and the zone size is read back (`check_size_width`).
            lib.check("cg_open", (lib.open)(name.as_ptr(), MODE_WRITE, &mut fn_))?;
            lib.check("cg_close", (lib.close)(fn_))?;
            lib.check("cg_open", (lib.open)(name.as_ptr(), MODE_MODIFY, &mut fn_))?;
        }
        Ok(Self {
            lib,
            fn_,
            open: true,
        })
    }

    fn close(mut self) -> std::io::Result<()> {
        self.open = false;
        // SAFETY: `fn_` is an open file of this library.
        let status = unsafe { (self.lib.close)(self.fn_) };
        self.lib.check("cg_close", status)
    }
}

impl Drop for OpenFile<'_> {
    fn drop(&mut self) {
        if self.open {
            // SAFETY: as in `close`; the file is being abandoned after an error.
            unsafe { (self.lib.close)(self.fn_) };
        }
    }
}

/// A size or element number as the library's `cgsize_t`.
fn size(n: usize) -> std::io::Result<CgSize> {
    CgSize::try_from(n).map_err(|_| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!("this CGNS library holds 32-bit sizes; {n} is too many"),
        )
    })
}

/// Names unique within one level of the tree, cut to CGNS's 32 characters.
#[derive(Default)]
struct Names(HashSet<String>);

impl Names {
    fn unique(&mut self, wanted: &str) -> String {
        let base: String = wanted.replace('/', "_");
        for k in 0.. {
            let suffix = if k == 0 {
                String::new()
            } else {
                format!("_{k}")
            };
            let mut name = String::new();
            for c in base.chars() {
                if name.len() + c.len_utf8() + suffix.len() > 32 {
                    break;
                }
                name.push(c);
            }
            name.push_str(&suffix);
            if self.0.insert(name.clone()) {
                return name;
            }
        }
        unreachable!("some suffix is free")
    }
}

fn write_tree(file: &OpenFile, m: &VolumeMesh) -> std::io::Result<()> {
    let (lib, f) = (file.lib, file.fn_);
    let mut base = 0;
    let mut zone = 0;
    let n_cells = m.tets.len() + m.pyramids.len() + m.prisms.len();
    let zone_size = [size(m.points.len())?, size(n_cells)?, 0];
    // SAFETY (every block below): the library's calls with NUL-terminated names, arrays of the
    // lengths the calls read (sizes checked to fit `cgsize_t`), and out-pointers to locals.
    unsafe {
        let name = c_name("Base");
        lib.check(
            "cg_base_write",
            (lib.base_write)(f, name.as_ptr(), 3, 3, &mut base),
        )?;
        // The coordinates are in the model's unit, unknown here.
        lib.check("cg_goto", (lib.goto)(f, base, c"end".as_ptr()))?;
        let status = (lib.dataclass_write)(NORMALIZED_BY_UNKNOWN_DIMENSIONAL);
        lib.check("cg_dataclass_write", status)?;
        let name = c_name("Zone");
        let status = (lib.zone_write)(
            f,
            base,
            name.as_ptr(),
            zone_size.as_ptr(),
            UNSTRUCTURED,
            &mut zone,
        );
        lib.check("cg_zone_write", status)?;
    }
    check_size_width(file, base, zone, &zone_size)?;
    for (axis, label) in ["CoordinateX", "CoordinateY", "CoordinateZ"]
        .iter()
        .enumerate()
    {
        let values: Vec<f64> = m.points.iter().map(|p| p[axis]).collect();
        let name = c_name(label);
        let mut index = 0;
        // SAFETY: see above; `values` holds one double per zone vertex.
        let status = unsafe {
            (lib.coord_write)(
                f,
                base,
                zone,
                REAL_DOUBLE,
                name.as_ptr(),
                values.as_ptr() as *const c_void,
                &mut index,
            )
        };
        lib.check("cg_coord_write", status)?;
    }
    // Family names: marker groups first (their names are what solvers' setups refer to).
    let g = groups(&m.markers);
    let mut families = Names::default();
    let group_families: Vec<String> = g.names.iter().map(|n| families.unique(n)).collect();
    let mut sections = Names::default();
    let next = write_cells(file, base, zone, m, &mut sections)?;
    write_boundary(
        file,
        base,
        zone,
        m,
        &g,
        &group_families,
        next,
        &mut sections,
    )
}

/// A library built with 64-bit `cgsize_t` would have read the zone size with the wrong width:
/// read it back into a buffer large enough for either width and compare.
fn check_size_width(
    file: &OpenFile,
    base: c_int,
    zone: c_int,
    written: &[CgSize; 3],
) -> std::io::Result<()> {
    let mut back = [0 as CgSize; 18];
    let mut name = [0 as std::ffi::c_char; 64];
    // SAFETY: `back` is room for 9 sizes of 64 bits; `name` for a 32-character name.
    let status =
        unsafe { (file.lib.zone_read)(file.fn_, base, zone, name.as_mut_ptr(), back.as_mut_ptr()) };
    file.lib.check("cg_zone_read", status)?;
    if back[..3] != written[..] {
        return Err(std::io::Error::other(
            "the CGNS library found uses 64-bit sizes (cgsize_t); tetrafoil writes through a \
             32-bit build such as Debian's libcgns (set TETRAFOIL_CGNS_LIB to one)",
        ));
    }
    Ok(())
}

/// The cell sections, region by region; returns the next element number.
fn write_cells(
    file: &OpenFile,
    base: c_int,
    zone: c_int,
    m: &VolumeMesh,
    sections: &mut Names,
) -> std::io::Result<usize> {
    let mut next = 1usize;
    for (r, region) in m.regions.iter().enumerate() {
        let region = super::clean_name(&region.name);
        for (kind, label, ctype) in [
            (CellKind::Tet, "tets", element::TETRA_4),
            (CellKind::Pyramid, "pyramids", element::PYRA_5),
            (CellKind::Prism, "prisms", element::PENTA_6),
        ] {
            let mut nodes = Vec::new();
            let mut count = 0;
            for (_, c, _) in m
                .cells()
                .filter(|&(k, _, cr)| k == kind && cr as usize == r)
            {
                for &v in c {
                    nodes.push(size(v as usize + 1)?);
                }
                count += 1;
            }
            if count == 0 {
                continue;
            }
            let name = sections.unique(&format!("{region}_{label}"));
            write_section(file, base, zone, &name, ctype, next, count, &nodes)?;
            next += count;
        }
    }
    Ok(next)
}

/// The boundary sections and one `BC_t` per marker group (named as its family), elements
/// numbered from `next`.
#[allow(clippy::too_many_arguments)]
fn write_boundary(
    file: &OpenFile,
    base: c_int,
    zone: c_int,
    m: &VolumeMesh,
    g: &Groups,
    group_families: &[String],
    mut next: usize,
    sections: &mut Names,
) -> std::io::Result<()> {
    let kinds = guess_all(m, g);
    for (k, group) in group_families.iter().enumerate() {
        let in_group = |marker: u32| g.of[marker as usize] == k;
        let tris: Vec<CgSize> = (m.boundary.iter().zip(&m.boundary_marker))
            .filter(|&(_, &marker)| in_group(marker))
            .flat_map(|(f, _)| f.iter().map(|&v| v as usize + 1))
            .map(size)
            .collect::<std::io::Result<_>>()?;
        let quads: Vec<CgSize> = (m.boundary_quads.iter().zip(&m.quad_marker))
            .filter(|&(_, &marker)| in_group(marker))
            .flat_map(|(f, _)| f.iter().map(|&v| v as usize + 1))
            .map(size)
            .collect::<std::io::Result<_>>()?;
        if tris.is_empty() && quads.is_empty() {
            continue;
        }
        let first = next;
        let both = !tris.is_empty() && !quads.is_empty();
        for (nodes, per, ctype, label) in [
            (&tris, 3, element::TRI_3, "tris"),
            (&quads, 4, element::QUAD_4, "quads"),
        ] {
            if nodes.is_empty() {
                continue;
            }
            let wanted = if both {
                format!("{group}_{label}")
            } else {
                group.clone()
            };
            let name = sections.unique(&wanted);
            let count = nodes.len() / per;
            write_section(file, base, zone, &name, ctype, next, count, nodes)?;
            next += count;
        }
        let kind = match kinds[k] {
            BoundaryKind::FarField => bc::FARFIELD,
            BoundaryKind::Symmetry(_) => bc::SYMMETRY_PLANE,
            BoundaryKind::Wall => bc::WALL,
            // Its faces are in the file; a boundary condition there would make it a wall.
            BoundaryKind::Interior => continue,
        };
        write_family(file, base, group, kind)?;
        let range = [size(first)?, size(next - 1)?];
        let name = c_name(group);
        let (lib, f) = (file.lib, file.fn_);
        let mut b = 0;
        // SAFETY: see write_tree; `range` holds the two element numbers PointRange reads.
        unsafe {
            let status = (lib.boco_write)(
                f,
                base,
                zone,
                name.as_ptr(),
                FAMILY_SPECIFIED,
                POINT_RANGE,
                2,
                range.as_ptr(),
                &mut b,
            );
            lib.check("cg_boco_write", status)?;
            let status = (lib.boco_gridlocation_write)(f, base, zone, b, FACE_CENTER);
            lib.check("cg_boco_gridlocation_write", status)?;
        }
        set_family(file, base, zone, b, group)?;
    }
    Ok(())
}

/// One element section of `count` elements numbered from `start`.
#[allow(clippy::too_many_arguments)]
fn write_section(
    file: &OpenFile,
    base: c_int,
    zone: c_int,
    name: &str,
    ctype: c_int,
    start: usize,
    count: usize,
    nodes: &[CgSize],
) -> std::io::Result<()> {
    let name = c_name(name);
    let mut s = 0;
    // SAFETY: see write_tree; `nodes` holds `count` elements of `ctype`'s node count.
    let status = unsafe {
        (file.lib.section_write)(
            file.fn_,
            base,
            zone,
            name.as_ptr(),
            ctype,
            size(start)?,
            size(start + count - 1)?,
            0,
            nodes.as_ptr(),
            &mut s,
        )
    };
    file.lib.check("cg_section_write", status)
}

/// A `Family_t` under the base with a `FamilyBC` of type `bc`.
fn write_family(file: &OpenFile, base: c_int, name: &str, bc: c_int) -> std::io::Result<()> {
    let (lib, f) = (file.lib, file.fn_);
    let family = c_name(name);
    let mut index = 0;
    // SAFETY: see write_tree.
    unsafe {
        let status = (lib.family_write)(f, base, family.as_ptr(), &mut index);
        lib.check("cg_family_write", status)?;
        let label = c_name("FamBC");
        let mut b = 0;
        let status = (lib.fambc_write)(f, base, index, label.as_ptr(), bc, &mut b);
        lib.check("cg_fambc_write", status)?;
    }
    Ok(())
}

/// `FamilyName` under boundary condition `bc` of the zone.
fn set_family(
    file: &OpenFile,
    base: c_int,
    zone: c_int,
    bc: c_int,
    family: &str,
) -> std::io::Result<()> {
    let (lib, f) = (file.lib, file.fn_);
    let family = c_name(family);
    let (z, zbc, b, end) = (c"Zone_t", c"ZoneBC_t", c"BC_t", c"end");
    // SAFETY: cg_goto reads (label, index) pairs up to "end", all given here.
    let status = unsafe {
        (lib.goto)(
            f,
            base,
            z.as_ptr(),
            zone,
            zbc.as_ptr(),
            1 as c_int,
            b.as_ptr(),
            bc,
            end.as_ptr(),
        )
    };
    lib.check("cg_goto", status)?;
    // SAFETY: a NUL-terminated name for the node cg_goto reached.
    let status = unsafe { (lib.famname_write)(family.as_ptr()) };
    lib.check("cg_famname_write", status)
}
