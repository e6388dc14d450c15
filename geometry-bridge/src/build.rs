//! Construction: CAD models the project builds itself through OpenCASCADE and writes as STEP
//! (its shipped samples), so they exercise the CAD path with geometry whose answer is known.
use std::path::Path;

use crate::error::CadError;
use crate::ffi::bridge as ffi;
use crate::model::{occt, translator_lock};

/// What [`wing_in_box`] built: OCCT's volumes of the lofted wing and of the fluid solid, and
/// the fluid's faces by name.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WingInBox {
    pub wing_volume: f64,
    pub fluid_volume: f64,
    pub faces: usize,
    pub wing_faces: usize,
    pub symmetry_faces: usize,
}

/// Lofts a solid wing through closed `sections` (each a point list whose last point repeats
/// the first: a sharp trailing edge; each becomes one B-spline edge interpolating the points,
/// `BRepOffsetAPI_ThruSections` with planar end caps), cuts it from the box `box_lo..box_hi`
/// (`BRepAlgoAPI_Cut`) and writes the fluid solid to `path` as STEP through XDE: the solid is
/// named "fluid", its faces "wing", "symmetry" (the box face y = `box_lo[1]`) or "farfield".
pub fn wing_in_box(
    sections: &[Vec<[f64; 3]>],
    box_lo: [f64; 3],
    box_hi: [f64; 3],
    path: impl AsRef<Path>,
) -> Result<WingInBox, CadError> {
    let file = path.as_ref().display().to_string();
    let points: Vec<f64> = sections.iter().flatten().flatten().copied().collect();
    let counts: Vec<i32> = sections.iter().map(|s| s.len() as i32).collect();
    let bounds = [box_lo, box_hi].concat();
    let mut stats = ffi::BuildStats::default();
    {
        // The STEP writer's parameters are process-global, like the readers'.
        let _guard = translator_lock();
        ffi::quiet_messages();
        ffi::wing_in_box(&points, &counts, &bounds, &file, &mut stats)
            .map_err(|e| occt(&file, "wing-in-box construction", e))?;
    }
    Ok(WingInBox {
        wing_volume: stats.wing_volume,
        fluid_volume: stats.fluid_volume,
        faces: stats.faces as usize,
        wing_faces: stats.wing_faces as usize,
        symmetry_faces: stats.symmetry_faces as usize,
    })
}

/// Writes planar `polygons` (closed implicitly) to `path` as STEP loose faces, each with its
/// own edges: a surface set with no topology, which a reader must sew (test geometry for the
/// loader's sewing, e.g. a box whose faces are a small gap apart).
pub fn loose_polygons(polygons: &[Vec<[f64; 3]>], path: impl AsRef<Path>) -> Result<(), CadError> {
    let file = path.as_ref().display().to_string();
    let points: Vec<f64> = polygons.iter().flatten().flatten().copied().collect();
    let counts: Vec<i32> = polygons.iter().map(|p| p.len() as i32).collect();
    let _guard = translator_lock();
    ffi::quiet_messages();
    ffi::loose_polygons(&points, &counts, &file)
        .map_err(|e| occt(&file, "loose-face construction", e))
}

/// One part of a [`lofted_body`]: closed sections lofted into a solid, optionally from a nose
/// point and to a tail point (a pointed end; otherwise a planar cap).
#[derive(Debug, Clone, PartialEq)]
pub struct LoftedPart {
    /// Its faces' name in the file (the boundary marker).
    pub name: String,
    /// The sections in loft order. Rings (`ring`) do not repeat their first point and become
    /// periodic B-splines; aerofoils end where they start (a sharp trailing edge).
    pub sections: Vec<Vec<[f64; 3]>>,
    pub ring: bool,
    pub nose: Option<[f64; 3]>,
    pub tail: Option<[f64; 3]>,
}

/// What [`lofted_body`] built: OCCT's volumes of the parts (summed, overlaps counted twice)
/// and of the body, its faces, and those on the symmetry plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoftedBody {
    pub parts_volume: f64,
    pub volume: f64,
    pub faces: usize,
    pub symmetry_faces: usize,
}

/// Lofts each part (`BRepOffsetAPI_ThruSections`), fuses them into one solid
/// (`BRepAlgoAPI_Fuse`), cuts it to y ≥ 0 when `half` (`BRepAlgoAPI_Cut`) and writes it to
/// `path` as STEP through XDE: the solid named "body", each face after the part it came from
/// (through the booleans' history), the faces of the cut "symmetry".
pub fn lofted_body(
    parts: &[LoftedPart],
    half: bool,
    path: impl AsRef<Path>,
) -> Result<LoftedBody, CadError> {
    let file = path.as_ref().display().to_string();
    let sections = parts.iter().flat_map(|p| &p.sections);
    let points: Vec<f64> = sections.clone().flatten().flatten().copied().collect();
    let counts: Vec<i32> = sections.map(|s| s.len() as i32).collect();
    let per_part: Vec<i32> = parts.iter().map(|p| p.sections.len() as i32).collect();
    let flags: Vec<i32> = (parts.iter())
        .map(|p| p.ring as i32 | (p.nose.is_some() as i32) << 1 | (p.tail.is_some() as i32) << 2)
        .collect();
    let tips: Vec<f64> = (parts.iter())
        .flat_map(|p| [p.nose.unwrap_or_default(), p.tail.unwrap_or_default()].concat())
        .collect();
    let names: Vec<&str> = parts.iter().map(|p| p.name.as_str()).collect();
    let mut stats = ffi::BodyStats::default();
    {
        let _guard = translator_lock();
        ffi::quiet_messages();
        ffi::lofted_body(
            &points,
            &counts,
            &per_part,
            &flags,
            &tips,
            &names.join("\n"),
            half,
            &file,
            &mut stats,
        )
        .map_err(|e| occt(&file, "lofted-body construction", e))?;
    }
    Ok(LoftedBody {
        parts_volume: stats.parts_volume,
        volume: stats.volume,
        faces: stats.faces as usize,
        symmetry_faces: stats.symmetry_faces as usize,
    })
}
