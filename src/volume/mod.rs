//! Volume meshing (seed paper, "Volume mesh generation"): the Delaunay tetrahedralisation of
//! the surface mesh's nodes, boundary recovery, region classification, interior points by the
//! centroid method, then quality improvement, all through one kernel ([`delaunay`]).
//!
//! Entry point: [`mesh_volume`].

mod boundary;
mod classify;
pub mod delaunay;
mod extract;
pub mod improve;
pub mod interior;
pub mod intersect;
mod peel;
pub mod recover;
pub mod slivers;

pub use boundary::{gather, OUTSIDE};
pub use improve::ImproveReport;
pub use interior::InteriorReport;
pub use recover::RecoveryReport;
pub use slivers::SliverReport;

use crate::mesh::validity::{self, ValidityReport};
use crate::mesh::{LayerTag, VolumeMesh};
use crate::model::Model;
use crate::progress::Reporter;
use crate::sizing::SizingField;
use crate::surface::SurfaceMesh;
use delaunay::{Delaunay, DelaunayError};
use glam::DVec3;
use std::time::Instant;

/// Why a volume mesh could not be made. Every variant names the model entity involved.
#[derive(Debug, thiserror::Error)]
pub enum VolumeError {
    #[error("the surface mesh has no triangles")]
    Empty,
    #[error("volume meshing {0}")]
    Cancelled(#[from] crate::progress::Cancelled),
    #[error("Delaunay tetrahedralisation of the surface nodes failed: {0}")]
    Delaunay(#[from] DelaunayError),
    #[error(
        "the surface mesh intersects itself: {face} crosses {other} near {} (faces of one \
         shell crossing, or solids that touch or overlap without shared faces — an assembly \
         must have its contacts imprinted, e.g. by a boolean fragment/general fuse)",
        crate::geometry::Xyz(*.at)
    )]
    Intersecting {
        face: String,
        other: String,
        at: DVec3,
    },
    #[error("boundary recovery failed on {face} near {}: {detail}", crate::geometry::Xyz(*.at))]
    Recovery {
        face: String,
        /// The model face, when a face's triangle (not an embedded segment) failed.
        face_index: Option<usize>,
        at: DVec3,
        detail: String,
    },
    #[error(
        "the surface mesh does not enclose a consistent volume at {face} near {}: one side \
         is {says}, the rest of that piece of volume is {majority} (self-intersecting surface, \
         or a face oriented against its shell)",
        crate::geometry::Xyz(*.at)
    )]
    Sides {
        face: String,
        at: DVec3,
        says: String,
        majority: String,
    },
    #[error("{region} received no tetrahedra: its shells enclose no volume the mesh can fill")]
    EmptyRegion { region: String },
}

/// Options for [`mesh_volume`].
#[derive(Clone, Copy, Debug)]
pub struct VolumeOptions<'a> {
    /// Insert interior points (off: the boundary-conforming tetrahedralisation of the surface
    /// nodes alone).
    pub interior_points: bool,
    /// Flip and smooth towards larger dihedral angles.
    pub improve: bool,
    /// Told each step's start and end (`"delaunay"` … `"extraction"`, as in
    /// [`VolumeReport::seconds`]) and the `"interior"` points inserted of those expected; asked
    /// after each step and each round of insertion whether to stop.
    pub progress: Reporter<'a>,
}

impl Default for VolumeOptions<'_> {
    fn default() -> Self {
        VolumeOptions {
            interior_points: true,
            improve: true,
            progress: Reporter::default(),
        }
    }
}

/// What [`mesh_volume`] did, stage by stage.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct VolumeReport {
    pub boundary_points: usize,
    pub boundary_triangles: usize,
    pub duplicate_surface_nodes: usize,
    pub recovery: RecoveryReport,
    pub interior: InteriorReport,
    pub improve: ImproveReport,
    pub slivers: SliverReport,
    /// Segments of embedded edges after recovery, and how many of them are no longer mesh
    /// edges at the end (later insertions and flips do not protect them yet).
    pub embedded_segments: usize,
    pub embedded_segments_lost: usize,
    /// Tets lying flat on a planar boundary face, given to the outside with the face's other
    /// diagonal taken (`peel.rs`).
    pub flat_boundary_tets_peeled: usize,
    /// Times the surfaces were meshed again, finer where they crossed themselves, before this
    /// volume mesh could be made (filled in by the pipeline).
    pub surface_remeshes: Vec<intersect::CrossingRemesh>,
    /// Seconds per sub-stage: delaunay, recovery, classification, interior, improvement,
    /// extraction.
    pub seconds: Vec<(String, f64)>,
    pub validity: ValidityReport,
}

/// Improvement and sliver removal are repeated at most this many times while slivers remain.
const SLIVER_RETRIES: usize = 2;

/// A stage run on the kernel after the isotropic interior points and improvement (directional
/// refinement): it sees the tets, their regions (per tet slot), the region on a tet's side
/// of a recovered face, and the first point that is not a boundary node; it returns each
/// kernel point's place in the layers it made (indexed by kernel point, empty for none).
pub type KernelStage<'a> = &'a mut dyn FnMut(
    &mut Delaunay,
    &mut Vec<u32>,
    &dyn Fn(&Delaunay, u32, u8) -> Option<u32>,
    u32,
) -> Vec<Option<LayerTag>>;

/// Tetrahedralise the regions of `model` bounded by `surface`.
pub fn mesh_volume(
    model: &Model,
    surface: &SurfaceMesh,
    sizing: &SizingField,
    options: VolumeOptions,
) -> Result<(VolumeMesh, VolumeReport), VolumeError> {
    mesh_volume_with(model, surface, sizing, options, None, None)
}

/// [`mesh_volume`] with a stage of the caller's run after improvement, before extraction, and
/// a zone the isotropic interior points keep out of.
pub fn mesh_volume_with(
    model: &Model,
    surface: &SurfaceMesh,
    sizing: &SizingField,
    options: VolumeOptions,
    after_improvement: Option<KernelStage>,
    interior_keep_out: Option<&interior::KeepOut<'_>>,
) -> Result<(VolumeMesh, VolumeReport), VolumeError> {
    let mut report = VolumeReport::default();
    let mut clock = Instant::now();
    // Each step's end: timed, told, and the place to stop a cancelled run.
    let mut lap = |report: &mut VolumeReport, name: &str| {
        let now = Instant::now();
        let seconds = (now - clock).as_secs_f64();
        report.seconds.push((name.to_string(), seconds));
        options.progress.finished(name, seconds);
        clock = now;
        options.progress.check()
    };
    options.progress.started("delaunay");
    let input = boundary::gather(surface);
    if input.triangles.is_empty() {
        return Err(VolumeError::Empty);
    }
    let sides = boundary::face_sides(model);
    report.boundary_points = input.points.len();
    report.boundary_triangles = input.triangles.len();
    let coords: Vec<[f64; 3]> = input.points.iter().map(|p| p.to_array()).collect();
    let mut dt = Delaunay::from_vec(coords)?;

    // Nodes at the same place (both sides of a pole, say) become one; triangles that
    // collapse are dropped.
    let mut same = (0..input.points.len() as u32).collect::<Vec<_>>();
    for d in dt.duplicates() {
        same[d.index as usize] = d.of;
    }
    report.duplicate_surface_nodes = dt.duplicates().len();
    let mut triangles = Vec::with_capacity(input.triangles.len());
    let mut parent = Vec::with_capacity(input.triangles.len());
    let mut face_of_input = Vec::with_capacity(input.triangles.len());
    for (t, &f) in input.triangles.iter().zip(&input.face_of) {
        let t = t.map(|v| same[v as usize]);
        if t[0] != t[1] && t[1] != t[2] && t[2] != t[0] {
            parent.push(triangles.len() as u32);
            triangles.push(t);
            face_of_input.push(f);
        }
    }
    // Embedded edges' segments, on the same merged nodes.
    let mut segments = Vec::with_capacity(input.segments.len());
    let mut segment_edge = Vec::with_capacity(input.segments.len());
    for (s, &e) in input.segments.iter().zip(&input.segment_edge) {
        let s = s.map(|v| same[v as usize]);
        if s[0] != s[1] {
            segments.push(s);
            segment_edge.push(e);
        }
    }
    lap(&mut report, "delaunay")?;
    options.progress.started("recovery");

    // The surface as given: recovery splits `triangles` at Steiner points, and a failure is
    // tested for self-intersection on the surface the user's model made, not on those splits
    // (a half-recovered split can cross its neighbour where the surface does not).
    let surface_triangles = triangles.clone();
    let mut segment_parent = Vec::new();
    let recovered = recover::recover_boundary_and_segments(
        &mut dt,
        &mut triangles,
        &mut parent,
        &mut segments,
        &mut segment_parent,
    );
    report.recovery = match recovered {
        Ok(r) => r,
        Err(e) if e.segment.is_some() => {
            let s = e.segment.unwrap_or(0) as usize;
            return Err(VolumeError::Recovery {
                face: model.edge_ref(segment_edge[s]).to_string(),
                face_index: None,
                at: DVec3::from_array(e.points[0]),
                detail: e.why.to_string(),
            });
        }
        Err(e) => {
            // Say why, when the reason is a self-intersecting surface.
            let coords: Vec<[f64; 3]> = (0..dt.num_points() as u32).map(|v| dt.point(v)).collect();
            let face = |k: usize| model.face_ref(face_of_input[k]).to_string();
            let near = e.parent as usize;
            if let Some((a, b)) = intersect::crossing_near(&coords, &surface_triangles, near) {
                return Err(VolumeError::Intersecting {
                    face: face(a),
                    other: face(b),
                    at: DVec3::from_array(coords[surface_triangles[a][0] as usize]),
                });
            }
            return Err(VolumeError::Recovery {
                face: model.face_ref(face_of_input[e.parent as usize]).to_string(),
                face_index: Some(face_of_input[e.parent as usize]),
                at: DVec3::from_array(e.points[0]),
                detail: e.why.to_string(),
            });
        }
    };
    lap(&mut report, "recovery")?;
    options.progress.started("classification");

    let face_of = |k: u32| face_of_input[parent[k as usize] as usize];
    let triangle_of = classify::triangle_index(&triangles);
    let side_regions = |k: u32| sides[face_of(k)];
    let reclassify = |dt: &Delaunay| classify::classify(dt, &triangles, &triangle_of, side_regions);
    let conflict = |dt: &Delaunay, c: classify::SideConflict| {
        let k = c.triangle as usize;
        let name = |r: u32| match r {
            OUTSIDE => "outside every region".to_string(),
            r => model.region_ref(r as usize).to_string(),
        };
        VolumeError::Sides {
            face: model.face_ref(face_of(c.triangle)).to_string(),
            at: DVec3::from_array(dt.point(triangles[k][0])),
            says: name(c.says),
            majority: name(c.majority),
        }
    };
    let mut region_of = reclassify(&dt).map_err(|c| conflict(&dt, c))?;
    lap(&mut report, "classification")?;
    options.progress.started("interior");

    let first_movable = dt.num_points() as u32;
    let side = |dt: &Delaunay, t: u32, f: u8| {
        classify::side_of(dt, t, f, &triangles, &triangle_of, &side_regions).map(|v| v.1)
    };
    if options.interior_points {
        report.interior = interior::insert_interior_points(
            &mut dt,
            sizing,
            &mut region_of,
            &side,
            interior_keep_out,
            options.progress,
        );
    }
    lap(&mut report, "interior")?;
    options.progress.started("improvement");

    // Sliver removal leaves alone the tets the refinement's layers replace: its points there
    // would only be cleared again. (Flips and smoothing still run there: the cube cavity's
    // layers came out with a 174° tet when the zone was left unpolished.)
    let leave = |dt: &Delaunay, t: u32| {
        interior_keep_out.is_some_and(|zone| {
            let v = dt.tet(t).map(|i| DVec3::from_array(dt.point(i)));
            let centre = (v[0] + v[1] + v[2] + v[3]) * 0.25;
            zone(centre, sizing.spacing(centre))
        })
    };
    if options.improve {
        report.improve = improve::improve(&mut dt, &mut region_of, first_movable);
        report.slivers = slivers::remove_slivers(&mut dt, &mut region_of, first_movable, &leave);
        // A new point's smoothing can leave slivers among movable points (a cascade in a
        // region at the size floor): flips and smoothing handle those, then points again.
        for _ in 0..SLIVER_RETRIES {
            if report.slivers.left == 0 || options.progress.cancelled() {
                break;
            }
            // The refined zone had its polish in the first pass.
            improve::improve_except(&mut dt, &mut region_of, first_movable, &leave);
            let again = slivers::remove_slivers(&mut dt, &mut region_of, first_movable, &leave);
            report.slivers.points += again.points;
            report.slivers.left = again.left;
        }
    }
    lap(&mut report, "improvement")?;
    let next = if after_improvement.is_some() {
        "refinement"
    } else {
        "extraction"
    };
    options.progress.started(next);

    let mut layers = Vec::new();
    if let Some(stage) = after_improvement {
        layers = stage(&mut dt, &mut region_of, &side, first_movable);
        lap(&mut report, "refinement")?;
        options.progress.started("extraction");
    }

    report.embedded_segments = segments.len();
    report.embedded_segments_lost = segments.iter().filter(|s| !dt.has_edge(s[0], s[1])).count();

    report.flat_boundary_tets_peeled =
        peel::peel_flat_boundary_tets(&mut dt, &mut region_of, &mut triangles, face_of);
    let mesh = extract::volume_mesh(model, &dt, &region_of, &triangles, face_of, &layers);
    for (r, _) in model.regions.iter().enumerate() {
        if !mesh.tet_region.contains(&(r as u32)) {
            return Err(VolumeError::EmptyRegion {
                region: model.region_ref(r).to_string(),
            });
        }
    }
    report.validity = validity::check(&mesh);
    lap(&mut report, "extraction")?;
    Ok((mesh, report))
}
