//! A CAD file made ready for meshing, the same way whatever kernel read it (the built-in
//! OpenCASCADE bridge or a plugin): its extent from the bounding box; a file without a solid
//! sewn at growing tolerances ([`SEW_STEPS`] of the diagonal, and the file's own largest edge
//! tolerance between them), then once more after the kernel's healing; construction faces
//! beside solids left out; two or more solids fused so their contacts are shared. Each step
//! the kernel cannot do is said, and the file goes on as it is.

use crate::model::foreign::ForeignSource;
use glam::DVec3;

/// Sewing tolerances tried in turn on a file without a solid, as fractions of its bounding-box
/// diagonal: tight first (faces exported with shared edges), then wider gaps (a surface set
/// trimmed loosely, or written in other units than it was modelled in). 1e-3 of the diagonal
/// is the widest: beyond it sewing merges edges of real features.
pub const SEW_STEPS: [f64; 3] = [1e-6, 1e-4, 1e-3];

/// What loading asks of a kernel's open file beyond its topology and geometry. Each
/// operation returns `None` when the kernel does not have it.
pub(crate) trait KernelFile: ForeignSource + Sized {
    /// "plugin 'x' (path)" or "OpenCASCADE": who read the file, for notes.
    fn kernel(&self) -> String;
    /// The model's box (low, high corners).
    fn bounding_box(&self) -> Option<Result<[DVec3; 2], String>>;
    fn sew(&self, tolerance: f64) -> Option<Result<Self, String>>;
    fn heal(&self, tolerance: f64) -> Option<Result<Self, String>>;
    fn fuse(&self, tolerance: f64) -> Option<Result<Self, String>>;
    /// The solids alone (faces and shells outside them dropped).
    fn solids_only(&self) -> Option<Result<Self, String>>;
    /// The flow domain around the solids (`case/farfield.rs` says what to build).
    fn farfield(&self, request: &FarfieldRequest) -> Option<Result<Self, String>>;
}

/// The far-field solid a kernel is asked to build around a body: a box about `centre` with
/// half extents `half`, or a sphere of radius `half[0]`; for a half model the plane
/// coordinate[axis] = at and the side kept (positive or not); gaps up to `fuzzy` are contact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FarfieldRequest {
    pub sphere: bool,
    pub centre: [f64; 3],
    pub half: [f64; 3],
    pub symmetry: Option<(usize, f64, bool)>,
    pub fuzzy: f64,
}

/// The file ready for import, and its bounding-box diagonal.
pub(crate) fn prepare<K: KernelFile>(file: K) -> Result<(K, f64), String> {
    let extent = match file.bounding_box() {
        Some(b) => b.map(|[lo, hi]| lo.distance(hi))?,
        None => fallback_extent(&file),
    };
    if !(extent.is_finite() && extent > 0.0) {
        return Err(format!(
            "{}: the model is empty (no bounding box)",
            file.file()
        ));
    }
    let file = if file.topology().solids.is_empty() {
        sew_into_solid(file, extent)?
    } else {
        skip_construction_faces(file)?
    };
    // An assembly's solids touch without sharing faces (a bolt head on a bracket): imprint
    // the contacts so the regions meet on one conforming interface.
    let file = if file.topology().solids.len() >= 2 {
        // Fuzzy at the model tolerance: a bolt head tangent to a plate's edge otherwise
        // leaves two vertices microns apart (l_bracket_assembly.step), a pinch no mesh closes.
        match file.fuse(1e-6 * extent) {
            Some(fused) => {
                let fused = fused?;
                let (a, b) = (file.topology(), fused.topology());
                if (a.solids.len(), a.faces.len()) != (b.solids.len(), b.faces.len())
                    || a.edges.len() != b.edges.len()
                {
                    log::warn!(
                        "{} has {} solids: imprinted their contacts (general fuse): {} solids, {} faces (were {})",
                        file.file(),
                        a.solids.len(),
                        b.solids.len(),
                        b.faces.len(),
                        a.faces.len()
                    );
                }
                fused
            }
            None => {
                log::warn!(
                    "{} has {} solids, and {} has no booleans: solids that touch must already \
                     share their contact faces",
                    file.file(),
                    file.topology().solids.len(),
                    file.kernel()
                );
                file
            }
        }
    } else {
        file
    };
    Ok((file, extent))
}

/// The diagonal of the vertices and of a 5 × 5 grid on each face's parameter rectangle, for a
/// kernel that gives no bounding box (a sphere has one vertex).
fn fallback_extent(file: &impl KernelFile) -> f64 {
    let t = file.topology();
    let mut points: Vec<DVec3> = t
        .vertices
        .iter()
        .map(|v| DVec3::from_array(v.point))
        .collect();
    for f in 0..t.faces.len() {
        let Ok(s) = file.surface(f) else { continue };
        let b = s.bounds();
        for i in 0..5 {
            for j in 0..5 {
                let (a, c) = (i as f64 / 4.0, j as f64 / 4.0);
                points.push(s.point(glam::DVec2::new(
                    b.u.0 + a * (b.u.1 - b.u.0),
                    b.v.0 + c * (b.v.1 - b.v.0),
                )));
            }
        }
    }
    let lo = points.iter().fold(DVec3::INFINITY, |a, p| a.min(*p));
    let hi = points.iter().fold(DVec3::NEG_INFINITY, |a, p| a.max(*p));
    if points.is_empty() {
        0.0
    } else {
        lo.distance(hi)
    }
}

/// Sew a file's faces into a solid: at each tolerance of [`sewing_tolerances`] in turn, then,
/// if every one leaves the shells open, once more at the widest after the kernel's healing
/// (gaps inside a face's own wires, tiny edges). The error says what was tried and where it is
/// open.
fn sew_into_solid<K: KernelFile>(file: K, extent: f64) -> Result<K, String> {
    let tolerances = sewing_tolerances(&file, extent);
    let mut tried = Vec::new();
    let mut last: Option<K> = None;
    let widest = tolerances.last().copied().unwrap_or(extent * SEW_STEPS[0]);
    let faces = file.topology().faces.len();
    // Each tolerance as the file is, then the widest once more after healing.
    let attempts = (tolerances.iter().map(|&t| (t, false))).chain(std::iter::once((widest, true)));
    for (tol, heal) in attempts {
        let healed;
        let source = if heal {
            match file.heal(tol) {
                Some(h) => {
                    healed = h?;
                    &healed
                }
                None => break,
            }
        } else {
            &file
        };
        let Some(sewn) = source.sew(tol) else {
            return Err(format!(
                "{}: contains no solid ({faces} faces), and {} does not sew",
                file.file(),
                file.kernel()
            ));
        };
        let sewn = sewn?;
        tried.push(format!(
            "{tol:.3e}{}",
            if heal { " after healing" } else { "" }
        ));
        if !sewn.topology().solids.is_empty() {
            log::warn!(
                "{} has no solid: {} its {faces} faces at tolerance {tol:.3e} into {} solid(s) ({} free edges left)",
                file.file(),
                if heal { "healed and sewed" } else { "sewed" },
                sewn.topology().solids.len(),
                sewn.topology().free_edges().len()
            );
            return Ok(sewn);
        }
        if !heal {
            last = Some(sewn);
        }
    }
    let diagnosed = last.as_ref().map_or(file.topology(), |l| l.topology());
    Err(format!(
        "{}: contains no solid, and sewing at tolerance {} closes none: {}",
        file.file(),
        tried.join(" then "),
        diagnosed.open_boundary_diagnosis(12)
    ))
}

/// The tolerances [`sew_into_solid`] tries, ascending: [`SEW_STEPS`] of the diagonal, and the
/// file's own largest edge tolerance (a little over it) where it lies between the first and the
/// last step — the gap the exporting system said its edges may have.
fn sewing_tolerances(file: &impl KernelFile, extent: f64) -> Vec<f64> {
    let mut tolerances: Vec<f64> = SEW_STEPS.iter().map(|r| r * extent).collect();
    let own = file.topology().max_edge_tolerance() * 1.5;
    let (lo, hi) = (tolerances[0], tolerances[tolerances.len() - 1]);
    if own > lo && own < hi && tolerances.iter().all(|t| (own / t - 1.0).abs() > 0.1) {
        tolerances.push(own);
        tolerances.sort_by(f64::total_cmp);
    }
    tolerances
}

/// A file with solids may also carry surfaces and open shells beside them (construction
/// geometry, `SHELL_BASED_SURFACE_MODEL` items): they bound no volume, and meshed with the
/// solid they made its surface cross itself or enclose no consistent volume. They are left
/// out, with a note naming them.
fn skip_construction_faces<K: KernelFile>(file: K) -> Result<K, String> {
    let outside = file.topology().faces_outside_solids();
    if outside.is_empty() {
        return Ok(file);
    }
    let t = file.topology();
    let named: Vec<String> = outside.iter().take(8).map(|&f| t.face_label(f)).collect();
    let more = outside.len().saturating_sub(named.len());
    let more = if more > 0 {
        format!(" and {more} more")
    } else {
        String::new()
    };
    let Some(kept) = file.solids_only() else {
        log::warn!(
            "{}: {} face(s) belong to no solid ({}{more}), and {} cannot drop them",
            file.file(),
            outside.len(),
            named.join(", "),
            file.kernel()
        );
        return Ok(file);
    };
    log::warn!(
        "{}: {} face(s) belong to no solid and are not meshed (construction geometry beside the \
         {} solid(s)): {}{more}; face ids below are those of the solids alone",
        file.file(),
        outside.len(),
        t.solids.len(),
        named.join(", ")
    );
    kept
}
