//! A surface mesh that crosses itself — a thin trailing edge, a tight bend or two close faces
//! meshed coarser than the gap between them — is meshed again with the spacing halved around
//! every crossing, rather than failing the run: the volume stage's recovery or classification
//! failure is the symptom, [`all_crossings`] finds every crossing pair, and the case's sizing
//! field takes graded samples there ([`SizingField::refine_at_crossings`]).

use crate::case::Case;
use crate::sizing::{GradedSample, SizingField};
use crate::surface::SurfaceMesh;
use crate::volume::intersect::{all_crossings, CrossingRemesh};
use crate::volume::VolumeError;
use glam::DVec3;
use std::collections::BTreeSet;

/// How many times the surfaces are meshed again after crossing themselves, each time with the
/// spacing around the crossings halved again, before the volume stage's error stands.
pub const CROSSING_REMESHES: usize = 3;

/// Faces named in a re-mesh's note, at most.
const NAMED_FACES: usize = 6;

/// After the volume stage failed with `error` on `surface`: when the failure is one a crossing
/// surface causes, the surface does cross itself and fewer than [`CROSSING_REMESHES`] re-meshes
/// were `done`, add the finer spacing around every crossing to the case's sizing and say what
/// was done (the caller meshes curves and surfaces again). `None`: the error stands.
pub fn refine_crossings(
    case: &mut Case,
    surface: &SurfaceMesh,
    error: &VolumeError,
    done: usize,
) -> Option<CrossingRemesh> {
    let symptom = matches!(
        error,
        VolumeError::Intersecting { .. } | VolumeError::Recovery { .. } | VolumeError::Sides { .. }
    );
    if !symptom || done >= CROSSING_REMESHES {
        return None;
    }
    let points: Vec<[f64; 3]> = surface.points.iter().map(|p| p.to_array()).collect();
    let triangles: Vec<[u32; 3]> = surface
        .triangles
        .iter()
        .map(|t| t.map(|v| v as u32))
        .collect();
    let pairs = all_crossings(&points, &triangles);
    let samples = crossing_samples(surface, &case.sizing, &pairs);
    let first = samples.first()?;
    let faces: BTreeSet<usize> = pairs
        .iter()
        .flat_map(|&(a, b)| [surface.face_of[a], surface.face_of[b]])
        .collect();
    let remesh = CrossingRemesh {
        crossings: pairs.len(),
        faces: faces
            .iter()
            .take(NAMED_FACES)
            .map(|&f| case.model.face_ref(f).to_string())
            .chain(
                (faces.len() > NAMED_FACES).then(|| format!("{} more", faces.len() - NAMED_FACES)),
            )
            .collect(),
        at: first.point.to_array(),
        spacing: samples
            .iter()
            .map(|s| s.delta)
            .fold(f64::INFINITY, f64::min),
    };
    case.sizing.refine_at_crossings(&samples);
    Some(remesh)
}

/// One sample per crossing pair: at the centre of the two triangles, over the radius that
/// covers them, asking for half the spacing there (and no more than half their longest edge:
/// a triangle stretched beyond δ by a size floor or a narrow strip crosses at its own length).
fn crossing_samples(
    surface: &SurfaceMesh,
    sizing: &SizingField,
    pairs: &[(usize, usize)],
) -> Vec<GradedSample> {
    pairs
        .iter()
        .map(|&(a, b)| {
            let corners: Vec<DVec3> = [a, b]
                .iter()
                .flat_map(|&t| surface.triangles[t].map(|v| surface.points[v]))
                .collect();
            let centre = corners.iter().sum::<DVec3>() / corners.len() as f64;
            let longest = [a, b]
                .iter()
                .flat_map(|&t| {
                    let [p, q, r] = surface.triangles[t].map(|v| surface.points[v]);
                    [p.distance(q), q.distance(r), r.distance(p)]
                })
                .fold(0.0, f64::max);
            let reach = corners
                .iter()
                .map(|c| c.distance(centre))
                .fold(0.0, f64::max);
            GradedSample {
                point: centre,
                delta: 0.5 * sizing.spacing(centre).min(longest),
                r1: reach,
            }
        })
        .collect()
}
