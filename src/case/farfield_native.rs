//! A flow domain around a native body: `[mesh] farfield = { shape = "box", size = 20 }` (or
//! `--farfield box:20`) on a case that gives only the body. The far field is written into the
//! case as native entries — straight edges and bilinear patches, as a user would write them —
//! before the model is built, so the loader checks, projects and orients it like any other:
//!
//! - `box`: the body's bounding box grown by `size` body lengths on every side (as for CAD);
//!   the body's regions become one cavity of the new region `flow`;
//! - `half-box`: the same box cut by the body's symmetry plane, a body face whose surface lies
//!   in a coordinate plane with the whole body on one side, its outline spanning much of the
//!   body along the plane (not a flat tip; the nearest the origin; y first on ties, then z,
//!   then x). That face goes: the box's face on the plane, `symmetry`, gets its
//!   loops as holes, so the body and the far field make one shell.
//!
//! The far field's faces are named `farfield` once built. Spheres are CAD-only (OCCT's
//! sphere): a native sphere would be bicubic patches, not a sphere.

use super::farfield::{spans_the_body, FarBoundary, FarfieldShape, FarfieldSpec, FlowDomain};
use super::schema::{CaseFile, EdgeEntry, FaceEntry, RegionEntry, SurfaceEntry, VertexEntry, P3};
use glam::DVec3;
use std::ops::Range;
use toml::Spanned;

/// The far field's faces are named this in the model.
pub const FARFIELD: &str = "farfield";
/// The face on the symmetry plane.
pub const SYMMETRY: &str = "symmetry";
/// The region between the far field and the body.
const FLOW: &str = "flow";
/// Prefix of the generated entries' names (renamed `farfield` once built).
const PREFIX: &str = "farfield_";

/// What `wrap` added: the far-field faces' names (to rename) and the domain's diagonal.
pub struct Wrapped {
    pub far_faces: Vec<String>,
    /// The body's faces, by name.
    pub body_faces: Vec<String>,
    pub domain_extent: f64,
    /// The box (after the symmetry cut) and the symmetry plane (axis, coordinate).
    pub far_box: (P3, P3),
    pub symmetry: Option<(usize, f64)>,
}

/// The body's symmetry plane: axis, coordinate, body above it, and the face lying in it.
struct Plane {
    axis: usize,
    at: f64,
    above: bool,
    face: usize,
}

/// Write the far field of `spec` around the native body of `file` into `file` (generated
/// entries carry `span`, the `[mesh] farfield` key's, for messages).
pub fn wrap(
    file: &mut CaseFile,
    spec: FarfieldSpec,
    span: Range<usize>,
) -> Result<Wrapped, String> {
    if matches!(
        spec.shape,
        FarfieldShape::Sphere | FarfieldShape::HalfSphere
    ) {
        return Err(format!(
            "a far field around a native body is a box or half-box; {} is built through CAD \
             (write the body as STEP and use `[mesh] cad`)",
            spec.shape.name()
        ));
    }
    let (lo, hi) = bounds(file).ok_or("the case gives no body (no vertices or surfaces)")?;
    let length = (0..3).map(|a| hi[a] - lo[a]).fold(0.0, f64::max);
    if length <= 0.0 {
        return Err("the body has no extent".into());
    }
    let far = spec.size * length;
    // The CAD far field's box: the body's, grown by `far` on every side.
    let mut box_lo: P3 = std::array::from_fn(|a| lo[a] - far);
    let mut box_hi: P3 = std::array::from_fn(|a| hi[a] + far);
    let plane = if spec.shape.is_half() {
        let p = symmetry_plane(file, length, (lo, hi)).ok_or(
            "half-box: no face of the body lies in a coordinate plane with the whole body on one \
             side and spanning much of the body (a half model's symmetry face; a flat wing tip \
             or end cap is not one); use box",
        )?;
        if p.above {
            box_lo[p.axis] = p.at;
        } else {
            box_hi[p.axis] = p.at;
        }
        Some(p)
    } else {
        None
    };
    let names = |v: &[String]| v.iter().map(|n| spanned(n, &span)).collect::<Vec<_>>();
    for name in entry_names(file) {
        if name.starts_with(PREFIX) || name == SYMMETRY || name == FLOW {
            return Err(format!(
                "the body has an entry named '{name}': the far field's entries are named \
                 {PREFIX}*, {SYMMETRY} and {FLOW}"
            ));
        }
    }
    // The body: the faces of its regions (all faces when it names none); its regions go.
    let cap = plane
        .as_ref()
        .map(|p| file.faces[p.face].name.get_ref().clone());
    let mut body: Vec<String> = if file.regions.is_empty() {
        file.faces
            .iter()
            .map(|f| f.name.get_ref().clone())
            .collect()
    } else {
        let mut v: Vec<String> = Vec::new();
        for r in &file.regions {
            for f in &r.faces {
                if !v.contains(f.get_ref()) {
                    v.push(f.get_ref().clone());
                }
            }
        }
        v
    };
    body.retain(|f| Some(f) != cap.as_ref());
    let embedded_faces: Vec<String> = (file.regions.iter())
        .flat_map(|r| r.embedded_faces.iter().map(|f| f.get_ref().clone()))
        .collect();
    let embedded_edges: Vec<String> = (file.regions.iter())
        .flat_map(|r| r.embedded_edges.iter().map(|e| e.get_ref().clone()))
        .collect();
    let holes: Vec<Vec<String>> = match (&plane, &cap) {
        (Some(p), Some(_)) => (file.faces[p.face].loops.iter())
            .map(|l| l.iter().map(|e| e.get_ref().clone()).collect())
            .collect(),
        _ => Vec::new(),
    };
    if let Some(p) = &plane {
        file.faces.remove(p.face);
    }
    let far_faces = add_box(file, box_lo, box_hi, plane.as_ref(), &holes, &span);
    let mut faces: Vec<String> = far_faces.clone();
    if plane.is_some() {
        faces.push(SYMMETRY.to_string());
    }
    faces.extend(body.iter().cloned());
    file.regions = vec![RegionEntry {
        name: spanned(FLOW, &span),
        faces: names(&faces),
        embedded_faces: names(&embedded_faces),
        embedded_edges: names(&embedded_edges),
    }];
    let domain_extent = (0..3)
        .map(|a| (box_hi[a] - box_lo[a]).powi(2))
        .sum::<f64>()
        .sqrt();
    log::info!(
        "native flow domain {} at {} body lengths (body length {length:.4}): {} body faces",
        spec.shape.name(),
        spec.size,
        body.len()
    );
    Ok(Wrapped {
        far_faces,
        body_faces: body,
        domain_extent,
        far_box: (box_lo, box_hi),
        symmetry: plane.as_ref().map(|p| (p.axis, p.at)),
    })
}

fn spanned(name: &str, span: &Range<usize>) -> Spanned<String> {
    Spanned::new(span.clone(), name.to_string())
}

fn entry_names(file: &CaseFile) -> Vec<String> {
    let mut v: Vec<String> = Vec::new();
    v.extend(file.vertices.iter().map(|x| x.name.get_ref().clone()));
    v.extend(file.curves.iter().map(|x| x.name.get_ref().clone()));
    v.extend(
        file.surfaces
            .iter()
            .map(|x| x.get_ref().name.get_ref().clone()),
    );
    v.extend(file.edges.iter().map(|x| x.name.get_ref().clone()));
    v.extend(file.faces.iter().map(|x| x.name.get_ref().clone()));
    v
}

/// The bounding box of the body's vertices and control points.
fn bounds(file: &CaseFile) -> Option<(P3, P3)> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    let mut add = |p: &P3| {
        for a in 0..3 {
            lo[a] = lo[a].min(p[a]);
            hi[a] = hi[a].max(p[a]);
        }
    };
    file.vertices.iter().for_each(|v| add(&v.point));
    file.curves
        .iter()
        .flat_map(|c| &c.points)
        .for_each(&mut add);
    for s in &file.surfaces {
        control_points(s.get_ref()).iter().for_each(&mut add);
    }
    (lo[0] <= hi[0]).then_some((lo, hi))
}

fn control_points(s: &SurfaceEntry) -> Vec<P3> {
    let mut v: Vec<P3> = s.grid.iter().flatten().flatten().copied().collect();
    v.extend(s.corners.iter().flatten().flatten().copied());
    v
}

/// The body's symmetry plane: a face whose surface's control points all lie in one coordinate
/// plane (a planar patch: its tangents too), with the body's box on one side, and whose
/// outline spans much of the body along the plane ([`spans_the_body`], as for CAD: a flat
/// wing tip or end cap nearer the origin is not a half model's plane).
fn symmetry_plane(file: &CaseFile, length: f64, (lo, hi): (P3, P3)) -> Option<Plane> {
    let tol = 1e-9 * length;
    let mut found: Vec<Plane> = Vec::new();
    for (k, face) in file.faces.iter().enumerate() {
        let Some(s) = file
            .surfaces
            .iter()
            .map(|s| s.get_ref())
            .find(|s| s.name.get_ref() == face.surface.get_ref())
        else {
            continue;
        };
        let pts = control_points(s);
        let Some(first) = pts.first() else {
            continue;
        };
        let flat_tangents = |axis: usize| {
            [&s.u_tangents, &s.v_tangents, &s.twists]
                .iter()
                .all(|t| t.iter().flatten().flatten().all(|d| d[axis].abs() <= tol))
        };
        for axis in 0..3 {
            let at = first[axis];
            if !pts.iter().all(|p| (p[axis] - at).abs() <= tol) || !flat_tangents(axis) {
                continue;
            }
            let above = lo[axis] >= at - tol;
            let below = hi[axis] <= at + tol;
            let outline = outline_points(file, face);
            if (above || below) && spans_the_body(&outline, (lo, hi), axis, tol) {
                found.push(Plane {
                    axis,
                    at,
                    above,
                    face: k,
                });
            }
        }
    }
    // Nearest the origin first; then y, z, x (an aircraft's symmetry plane is y = 0).
    let rank = |axis: usize| [2, 0, 1][axis];
    found.sort_by(|a, b| {
        let key = |p: &Plane| {
            (
                (p.at.abs() / length * 1e6).round() as i64,
                rank(p.axis),
                p.face,
            )
        };
        key(a).cmp(&key(b))
    });
    found.into_iter().next()
}

/// The vertices and curve points of `face`'s loops.
fn outline_points(file: &CaseFile, face: &FaceEntry) -> Vec<P3> {
    let vertex = |name: &str| {
        (file.vertices.iter())
            .find(|v| v.name.get_ref() == name)
            .map(|v| v.point)
    };
    let mut out = Vec::new();
    for name in face.loops.iter().flatten() {
        let Some(e) = file
            .edges
            .iter()
            .find(|e| e.name.get_ref() == name.get_ref())
        else {
            continue;
        };
        out.extend(vertex(e.start.get_ref()));
        out.extend(vertex(e.end.get_ref()));
        if let Some(c) = &e.curve {
            if let Some(c) = file.curves.iter().find(|x| x.name.get_ref() == c.get_ref()) {
                out.extend(c.points.iter().copied());
            }
        }
    }
    out
}

/// The box `lo`..`hi`: 8 vertices, 12 straight edges, 6 bilinear faces; on a symmetry plane
/// the face there is `symmetry`, with `holes` (the body's cap's loops) as its inner loops.
/// Returns the names of the far-field faces.
fn add_box(
    file: &mut CaseFile,
    lo: P3,
    hi: P3,
    plane: Option<&Plane>,
    holes: &[Vec<String>],
    span: &Range<usize>,
) -> Vec<String> {
    let s = |n: &str| spanned(n, span);
    let corner = |i: usize, j: usize, k: usize| -> P3 {
        [[lo[0], hi[0]][i], [lo[1], hi[1]][j], [lo[2], hi[2]][k]]
    };
    let vname = |i: usize, j: usize, k: usize| format!("{PREFIX}v{i}{j}{k}");
    for i in 0..2 {
        for j in 0..2 {
            for k in 0..2 {
                file.vertices.push(VertexEntry {
                    name: s(&vname(i, j, k)),
                    point: corner(i, j, k),
                });
            }
        }
    }
    // Edge along `axis` through the corner whose other two indices are `a`, `b` (in axis order).
    let ijk = |axis: usize, t: usize, a: usize, b: usize| -> (usize, usize, usize) {
        match axis {
            0 => (t, a, b),
            1 => (a, t, b),
            _ => (a, b, t),
        }
    };
    let ename =
        |axis: usize, a: usize, b: usize| format!("{PREFIX}{}{a}{b}", ["x", "y", "z"][axis]);
    for axis in 0..3 {
        for a in 0..2 {
            for b in 0..2 {
                let (i0, j0, k0) = ijk(axis, 0, a, b);
                let (i1, j1, k1) = ijk(axis, 1, a, b);
                file.edges.push(EdgeEntry {
                    name: s(&ename(axis, a, b)),
                    start: s(&vname(i0, j0, k0)),
                    end: s(&vname(i1, j1, k1)),
                    curve: None,
                    degenerate: false,
                });
            }
        }
    }
    let mut far = Vec::new();
    for axis in 0..3 {
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        for side in 0..2 {
            let label = format!("{}{}", ["x", "y", "z"][axis], ["min", "max"][side]);
            let on_plane = plane.is_some_and(|p| p.axis == axis && (side == 0) == p.above);
            let name = if on_plane {
                SYMMETRY.to_string()
            } else {
                format!("{PREFIX}{label}")
            };
            let surface = format!("{PREFIX}{label}_plane");
            // Corner (a along u, b along v) of this side.
            let at = |a: usize, b: usize| -> P3 {
                let mut idx = [0usize; 3];
                idx[axis] = side;
                idx[u] = a;
                idx[v] = b;
                corner(idx[0], idx[1], idx[2])
            };
            file.surfaces.push(Spanned::new(
                span.clone(),
                SurfaceEntry {
                    name: s(&surface),
                    grid: None,
                    corners: Some([[at(0, 0), at(0, 1)], [at(1, 0), at(1, 1)]]),
                    u_tangents: None,
                    v_tangents: None,
                    twists: None,
                },
            ));
            // The four edges round this side: along u at b = 0, 1 and along v at a = 0, 1.
            let edge_along = |along: usize, other: usize, o: usize| {
                // The edge along `along` whose index on `axis` is `side` and on `other` is `o`.
                let mut idx = [0usize; 3];
                idx[axis] = side;
                idx[other] = o;
                let rest: Vec<usize> = (0..3).filter(|&c| c != along).collect();
                ename(along, idx[rest[0]], idx[rest[1]])
            };
            let outer = vec![
                s(&edge_along(u, v, 0)),
                s(&edge_along(v, u, 1)),
                s(&edge_along(u, v, 1)),
                s(&edge_along(v, u, 0)),
            ];
            let mut loops = vec![outer];
            if on_plane {
                loops.extend(holes.iter().map(|l| l.iter().map(|e| s(e)).collect()));
            } else {
                far.push(name.clone());
            }
            file.faces.push(FaceEntry {
                name: s(&name),
                surface: s(&surface),
                loops,
            });
        }
    }
    far
}

/// Name the far field's faces `farfield` in the built model and say which are the body's.
pub fn name_domain(model: &mut crate::model::Model, wrapped: &Wrapped) -> FlowDomain {
    let mut body_faces = Vec::new();
    for (k, face) in model.faces.iter_mut().enumerate() {
        let Some(name) = face.name.as_deref() else {
            continue;
        };
        if wrapped.far_faces.iter().any(|f| f == name) {
            face.name = Some(FARFIELD.to_string());
        } else if wrapped.body_faces.iter().any(|f| f == name) {
            body_faces.push(k);
        }
    }
    let (lo, hi) = wrapped.far_box;
    FlowDomain {
        body_faces,
        domain_extent: wrapped.domain_extent,
        outer: FarBoundary::Box {
            lo: DVec3::from_array(lo),
            hi: DVec3::from_array(hi),
        },
        symmetry: wrapped.symmetry,
    }
}
