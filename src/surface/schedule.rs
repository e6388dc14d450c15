//! Which meshing work runs when. First every face's boundary and split plan, across the
//! threads; then the jobs — whole faces and the parts of split faces alike — largest expected
//! first, each to whichever thread is free; then each split face's parts merged. Ordering
//! faces by boundary nodes instead put a cylinder of 1028 triangles and 80 boundary nodes
//! behind a plane of 440 and 84, and the run ended on it with the other thread idle
//! (hemisphere_cylinder_domain.stp); a split face's parts waited behind its own thread's other
//! work. Every job's result depends on its face alone, so the mesh is the same on any number
//! of threads.

use super::advance::{self, FaceTriangulation};
use super::boundary::{self, Boundary};
use super::split::{self, Plan};
use super::{fallback, improve, improve_all, SurfaceError, SurfaceOptions};
use crate::curve::CurveMesh;
use crate::geometry::Surface;
use crate::model::{FaceId, Model};
use crate::sizing::SizingField;
use rayon::prelude::*;

/// A face ready to mesh: whole, or cut into parts (its boundary kept for a fallback).
enum Prepared {
    Whole(Boundary),
    Split(Boundary, Plan),
}

/// One piece of work: a whole face, or one part of a split face.
#[derive(Clone, Copy)]
struct Job {
    face: FaceId,
    part: Option<usize>,
    expected: f64,
}

/// A job's triangulation and whether the Delaunay fallback made it.
type JobResult = Result<(FaceTriangulation, bool), SurfaceError>;

/// How a face was meshed.
#[derive(Clone, Copy, Debug)]
pub struct Meshed {
    /// Parts meshed concurrently (1: whole).
    pub parts: usize,
    /// By the constrained-Delaunay fallback (the front could not close, or `delaunay_only`).
    pub by_delaunay: bool,
}

impl Meshed {
    fn whole(by_delaunay: bool) -> Self {
        Meshed {
            parts: 1,
            by_delaunay,
        }
    }
}

/// Every face's triangulation and how it was meshed, in face order.
pub fn mesh_faces(
    model: &Model,
    curves: &CurveMesh,
    sizing: &SizingField,
    options: SurfaceOptions,
) -> Vec<Result<(FaceTriangulation, Meshed), SurfaceError>> {
    let prepared: Vec<Result<(Prepared, f64), SurfaceError>> = (0..model.faces.len())
        .into_par_iter()
        .map(|f| prepare(model, curves, sizing, f, options))
        .collect();
    let mut jobs = Vec::new();
    for (face, p) in prepared.iter().enumerate() {
        match p {
            Ok((Prepared::Whole(_), expected)) => jobs.push(Job {
                face,
                part: None,
                expected: *expected,
            }),
            Ok((Prepared::Split(_, plan), _)) => {
                jobs.extend(plan.parts.iter().enumerate().map(|(k, part)| Job {
                    face,
                    part: Some(k),
                    expected: part.expected,
                }))
            }
            Err(_) => {}
        }
    }
    jobs.sort_by(|a, b| {
        b.expected
            .total_cmp(&a.expected)
            .then((a.face, a.part).cmp(&(b.face, b.part)))
    });
    let (done, total) = (std::sync::atomic::AtomicU64::new(0), jobs.len() as u64);
    options.progress.progress("surfaces", 0, total);
    let mut meshed = in_order(&jobs, |job| {
        // A cancelled run skips the jobs left; `mesh_surfaces` then returns `Cancelled`.
        if options.progress.cancelled() {
            return None;
        }
        let result = mesh_job(model, sizing, &prepared, job, options.delaunay_only);
        let k = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        options.progress.progress("surfaces", k, total);
        result
    });
    if options.progress.cancelled() {
        return Vec::new();
    }
    meshed.sort_by_key(|(k, _)| (jobs[*k].face, jobs[*k].part));
    // Each face's results, parts in order.
    let mut by_face: Vec<Vec<Option<JobResult>>> =
        (0..model.faces.len()).map(|_| Vec::new()).collect();
    for (k, result) in meshed {
        by_face[jobs[k].face].push(result);
    }
    prepared
        .into_par_iter()
        .zip(by_face)
        .enumerate()
        .map(|(face, (p, results))| {
            let surface = model.faces[face].surface.as_ref();
            match p? {
                (Prepared::Whole(b), _) => match results.into_iter().next().flatten() {
                    Some(result) => result.map(|(t, d)| (t, Meshed::whole(d))),
                    None => mesh_whole(model, surface, sizing, face, &b, options.delaunay_only)
                        .map(|(t, d)| (t, Meshed::whole(d))),
                },
                (Prepared::Split(b, plan), _) => {
                    let parts: Option<Vec<FaceTriangulation>> = results
                        .into_iter()
                        .map(|r| r.and_then(|r| r.ok()).map(|(t, _)| t))
                        .collect();
                    match parts {
                        Some(parts) => {
                            let meshed = Meshed {
                                parts: parts.len(),
                                by_delaunay: false,
                            };
                            Ok((merge_parts(surface, plan, parts), meshed))
                        }
                        None => mesh_whole(model, surface, sizing, face, &b, false)
                            .map(|(t, d)| (t, Meshed::whole(d))),
                    }
                }
            }
        })
        .collect()
}

/// One job's triangulation: `None` when a part failed (its face is then meshed whole).
fn mesh_job(
    model: &Model,
    sizing: &SizingField,
    prepared: &[Result<(Prepared, f64), SurfaceError>],
    job: &Job,
    delaunay_only: bool,
) -> Option<JobResult> {
    let surface = model.faces[job.face].surface.as_ref();
    match (&prepared[job.face], job.part) {
        (Ok((Prepared::Whole(b), _)), None) => Some(mesh_whole(
            model,
            surface,
            sizing,
            job.face,
            b,
            delaunay_only,
        )),
        (Ok((Prepared::Split(_, plan), _)), Some(k)) => {
            let part = &plan.parts[k];
            let fixed = part.pool_ids.len();
            let tri = advance::advance(surface, sizing, part.boundary.clone())
                .ok()
                .map(|mut t| {
                    improve_all(&mut t, surface, fixed, &[]);
                    t
                });
            // A part that fails sends its face back to be meshed whole.
            tri.map(|t| Ok((t, false)))
        }
        _ => None,
    }
}

/// A face's boundary, its split plan (unless `whole_faces`) and its expected triangles.
fn prepare(
    model: &Model,
    curves: &CurveMesh,
    sizing: &SizingField,
    face: FaceId,
    options: SurfaceOptions,
) -> Result<(Prepared, f64), SurfaceError> {
    let surface = model.faces[face].surface.as_ref();
    let boundary = boundary::face_boundary(model, curves, sizing, face)?;
    let plan = (!options.whole_faces && !options.delaunay_only)
        .then(|| split::plan(surface, sizing, &boundary))
        .flatten();
    Ok(match plan {
        Some(plan) => {
            let expected = plan.parts.iter().map(|p| p.expected).sum();
            (Prepared::Split(boundary, plan), expected)
        }
        None => {
            let expected = split::expected_triangles(surface, sizing, &boundary);
            (Prepared::Whole(boundary), expected)
        }
    })
}

/// Triangulate and improve a face whole: by the advancing front, or where it cannot close
/// (or `delaunay_only`) by the constrained-Delaunay fallback; the flag says which did.
fn mesh_whole(
    model: &Model,
    surface: &dyn Surface,
    sizing: &SizingField,
    face: FaceId,
    boundary: &Boundary,
    delaunay_only: bool,
) -> Result<(FaceTriangulation, bool), SurfaceError> {
    let fixed = boundary.vertices.len();
    let front = if delaunay_only {
        None
    } else {
        Some(advance::advance(surface, sizing, boundary.clone()))
    };
    let (mut tri, by_delaunay) = match front {
        Some(Ok(tri)) => (tri, false),
        Some(Err(stuck)) => match fallback::triangulate(surface, sizing, boundary) {
            Ok(tri) => {
                log::info!(
                    "{}: the advancing front could not close near xyz = {}; meshed by \
                     constrained Delaunay in (u,v)",
                    model.face_ref(face),
                    crate::geometry::Xyz(stuck.xyz)
                );
                (tri, true)
            }
            Err(refusal) => {
                log::debug!(
                    "{}: Delaunay fallback refused: {refusal:?}",
                    model.face_ref(face)
                );
                return Err(SurfaceError::Stuck {
                    face: model.face_ref(face).to_string(),
                    u: stuck.uv.x,
                    v: stuck.uv.y,
                    xyz: stuck.xyz,
                });
            }
        },
        None => match fallback::triangulate(surface, sizing, boundary) {
            Ok(tri) => (tri, true),
            Err(refusal) => {
                let uv = refusal.uv();
                return Err(SurfaceError::Stuck {
                    face: model.face_ref(face).to_string(),
                    u: uv.x,
                    v: uv.y,
                    xyz: surface.point(uv),
                });
            }
        },
    };
    improve_all(&mut tri, surface, fixed, &boundary.slits);
    Ok((tri, by_delaunay))
}

/// Merge a split face's meshed parts on their shared cut nodes and improve once more around
/// the cuts.
fn merge_parts(
    surface: &dyn Surface,
    plan: Plan,
    meshed: Vec<FaceTriangulation>,
) -> FaceTriangulation {
    let pool = plan.vertices.len();
    let mut tri = FaceTriangulation {
        vertices: plan.vertices,
        triangles: Vec::new(),
    };
    for (part, m) in plan.parts.iter().zip(meshed) {
        let mut ids = part.pool_ids.clone();
        for v in &m.vertices[ids.len()..] {
            ids.push(tri.vertices.len());
            tri.vertices.push(*v);
        }
        tri.triangles
            .extend(m.triangles.iter().map(|t| t.map(|k| ids[k])));
    }
    let near_cut: Vec<bool> = (0..tri.vertices.len())
        .map(|v| (plan.first_cut..pool).contains(&v))
        .collect();
    improve::swap_diagonals_near(&mut tri, &near_cut);
    improve::smooth_vertices(&mut tri, surface, |v| near_cut[v]);
    improve::swap_diagonals_near(&mut tri, &near_cut);
    tri
}

/// `work` on every item, the items handed out in their order to whichever thread is free
/// (one worker per thread pulling from a shared cursor), so the largest jobs start first
/// and small ones fill in at the end; returns each item's index with its result. An indexed
/// parallel iterator splits the list in halves instead: with two threads one took the two
/// largest faces in turn while the other ran out of work (cylinder_catia_trimmed.igs: 1.5x
/// on two threads instead of 2).
fn in_order<I: Sync, T: Send>(items: &[I], work: impl Fn(&I) -> T + Sync) -> Vec<(usize, T)> {
    let cursor = std::sync::atomic::AtomicUsize::new(0);
    let done = std::sync::Mutex::new(Vec::with_capacity(items.len()));
    rayon::scope(|scope| {
        for _ in 0..rayon::current_num_threads() {
            scope.spawn(|_| loop {
                let k = cursor.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let Some(item) = items.get(k) else { break };
                let result = work(item);
                done.lock()
                    .unwrap_or_else(|e| e.into_inner())
                    .push((k, result));
            });
        }
    });
    done.into_inner().unwrap_or_else(|e| e.into_inner())
}
