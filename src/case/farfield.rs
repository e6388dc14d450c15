//! A flow domain from a body: most aircraft CAD is the body, not the fluid. `[mesh] farfield =
//! { shape = "half-sphere", size = 50 }` in a case file, or `--farfield half-sphere:50`,
//! builds the far-field solid around the body and cuts the body out of it (OCCT's Boolean
//! cut):
//!
//! - `box`: the body's bounding box grown by `size` body lengths on every side;
//! - `sphere`: radius `size` body lengths plus the body's half diagonal, about its centre;
//! - `half-box`, `half-sphere`: the same, cut by the body's symmetry plane, which is found:
//!   a plane face of the body lying in a coordinate plane (its vertices and points along its
//!   edges) with the whole body (its bounding box) on one side, no other face touching that
//!   plane, and spanning much of the body along the plane (not a flat tip or end cap) (the one nearest the origin when there are several; y
//!   first on ties, then z, then x).
//!
//! The body length is the longest side of the body's bounding box. The domain's faces are
//! named `farfield`, `symmetry` (on the plane) and as the body's faces were (`body` for those without a name); the body keeps
//! the spacing it would have alone (1/20 of its diagonal by default, or the size given),
//! graded out to a far field spaced 1/20 of the domain's diagonal (`sizing/body.rs`).

use super::kernel_file::{FarfieldRequest, KernelFile};
use crate::model::foreign::ForeignSource;
use glam::DVec3;
use std::str::FromStr;

/// The far-field solid's shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FarfieldShape {
    Box,
    Sphere,
    HalfBox,
    HalfSphere,
}

/// Shape names as the case file and the command line write them.
const SHAPES: [(&str, FarfieldShape); 4] = [
    ("box", FarfieldShape::Box),
    ("sphere", FarfieldShape::Sphere),
    ("half-box", FarfieldShape::HalfBox),
    ("half-sphere", FarfieldShape::HalfSphere),
];

/// Below this many body lengths the far field would sit on the body's own flow.
pub const MIN_BODY_LENGTHS: f64 = 1.0;

impl FarfieldShape {
    pub fn parse(name: &str) -> Result<Self, String> {
        SHAPES
            .iter()
            .find(|(n, _)| *n == name)
            .map(|&(_, s)| s)
            .ok_or_else(|| {
                let known: Vec<&str> = SHAPES.iter().map(|(n, _)| *n).collect();
                format!(
                    "unknown far-field shape '{name}' (known: {})",
                    known.join(", ")
                )
            })
    }

    pub fn name(self) -> &'static str {
        SHAPES
            .iter()
            .find(|(_, s)| *s == self)
            .map_or("", |(n, _)| n)
    }

    /// Cut by the body's symmetry plane.
    pub fn is_half(self) -> bool {
        matches!(self, Self::HalfBox | Self::HalfSphere)
    }
}

/// A far field: its shape and its distance from the body in body lengths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FarfieldSpec {
    pub shape: FarfieldShape,
    pub size: f64,
}

impl FarfieldSpec {
    /// A spec after checking its size.
    pub fn new(shape: FarfieldShape, size: f64) -> Result<Self, String> {
        if !(size.is_finite() && size >= MIN_BODY_LENGTHS) {
            return Err(format!(
                "the far field must lie at least {MIN_BODY_LENGTHS} body length from the body \
                 (size in body lengths), got {size}"
            ));
        }
        Ok(Self { shape, size })
    }
}

impl FromStr for FarfieldSpec {
    type Err = String;

    /// `shape:size`, e.g. `box:20` or `half-sphere:50`.
    fn from_str(s: &str) -> Result<Self, String> {
        let (shape, size) = s
            .split_once(':')
            .ok_or_else(|| format!("'{s}': expected shape:size, e.g. box:20 or half-sphere:50"))?;
        let size: f64 = size
            .trim()
            .parse()
            .map_err(|_| format!("'{s}': the size '{size}' is not a number of body lengths"))?;
        Self::new(FarfieldShape::parse(shape.trim())?, size)
    }
}

/// What the domain was built from: the body's faces (ids in the new model) and extent, which
/// the sizing uses to keep the body fine under a coarse far field.
#[derive(Clone, Debug, PartialEq)]
pub struct FlowDomain {
    pub body_faces: Vec<usize>,
    /// The diagonal of the far-field solid's bounding box.
    pub domain_extent: f64,
    /// The far field's outer surface (the whole box or sphere before the symmetry cut).
    pub outer: FarBoundary,
    /// A half model's symmetry plane: coordinate axis and value.
    pub symmetry: Option<(usize, f64)>,
}

impl FlowDomain {
    /// The far field's spacing ([`size_domain`]): 1/20 of the domain's diagonal.
    pub fn far_spacing(&self) -> f64 {
        self.domain_extent / FAR_CELLS
    }
}

/// The far field's outer surface, for what must stop short of it (automatic wakes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FarBoundary {
    Box { lo: DVec3, hi: DVec3 },
    Sphere { centre: DVec3, radius: f64 },
}

impl FarBoundary {
    /// How far from `p` (inside) along the unit direction `d` the far field is.
    pub fn exit_distance(&self, p: DVec3, d: DVec3) -> f64 {
        match *self {
            FarBoundary::Box { lo, hi } => (0..3)
                .filter(|&a| d[a] != 0.0)
                .map(|a| {
                    let wall = if d[a] > 0.0 { hi[a] } else { lo[a] };
                    (wall - p[a]) / d[a]
                })
                .fold(f64::INFINITY, f64::min),
            FarBoundary::Sphere { centre, radius } => {
                // |p - c + t d| = r: t = -b + sqrt(b² - (|p - c|² - r²)), b = d·(p - c).
                let q = p - centre;
                let b = d.dot(q);
                let disc = b * b - (q.length_squared() - radius * radius);
                -b + disc.max(0.0).sqrt()
            }
        }
    }
}

/// Cells across the domain's diagonal at the far field.
const FAR_CELLS: f64 = 20.0;

/// Size a flow domain: the far field spaced 1/20 of the domain's diagonal (never finer than
/// the body), the body at `body_size`, graded between.
pub(crate) fn size_domain(
    sizing: &mut crate::sizing::SizingField,
    model: &crate::model::Model,
    domain: &FlowDomain,
    body_size: f64,
) {
    let far = (domain.domain_extent / FAR_CELLS).max(body_size);
    let samples = crate::sizing::body::body_samples(model, &domain.body_faces, body_size);
    sizing.keep_body_fine(far, samples);
}

/// The least product of the symmetry section's spans over the body's, along the plane's two
/// axes: the M6 wing's root spans 0.68 of it, the wing tip of a whole wing and fuselage 0.1.
const MIN_SECTION_SPAN: f64 = 0.25;

/// Whether a section lying in a plane across `axis` (its points `section`) spans much of the
/// body (bounding box `lo`..`hi`) along the plane's two axes ([`MIN_SECTION_SPAN`]).
pub(super) fn spans_the_body(
    section: &[[f64; 3]],
    (lo, hi): ([f64; 3], [f64; 3]),
    axis: usize,
    tol: f64,
) -> bool {
    let spans = |a: usize| {
        let (min, max) = (section.iter()).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
            (l.min(p[a]), h.max(p[a]))
        });
        (max - min) / (hi[a] - lo[a]).max(tol)
    };
    spans((axis + 1) % 3) * spans((axis + 2) % 3) >= MIN_SECTION_SPAN
}

/// The body's symmetry plane (axis, coordinate, body on the positive side), if it has one.
/// The face's edges are sampled, not only its vertices (a face whose vertices are all on one
/// line — a fuselage's profile from nose to tail — lies in none of the planes through it),
/// and the body's side is judged by its bounding box `lo`..`hi` (a wing tip's vertices may
/// all be above a plane its surfaces cross) or by its vertices and edge samples where that box
/// reaches across the plane (a box from control points). A face is flat when its surface, sampled inside
/// the (u,v) box of its boundary, lies in the plane too.
fn symmetry_plane(
    body: &impl ForeignSource,
    length: f64,
    (lo, hi): ([f64; 3], [f64; 3]),
) -> Option<(usize, f64, bool)> {
    let t = body.topology();
    let tol = 1e-7 * length;
    // A bounding box from the surfaces' control points may stand a little off the geometry.
    let box_tol = 1e-4 * length;
    let edge_samples = |f: usize| -> Vec<[f64; 3]> {
        (t.faces[f].loops.iter().flatten())
            .filter_map(|u| {
                let e = &t.edges[u.edge];
                let curve = (!e.degenerate).then(|| body.curve(u.edge).ok()).flatten()?;
                let [t0, t1] = e.t_range;
                Some([0.25, 0.5, 0.75].map(|s| curve.point(t0 + s * (t1 - t0)).to_array()))
            })
            .flatten()
            .collect()
    };
    // Points of the face's surface on a 3 × 3 grid inside the (u,v) box of its boundary.
    let interior_samples = |f: usize| -> Option<Vec<[f64; 3]>> {
        let surface = body.surface(f).ok()?;
        let (mut lo_uv, mut hi_uv) = (glam::DVec2::INFINITY, glam::DVec2::NEG_INFINITY);
        for (l, lp) in t.faces[f].loops.iter().enumerate() {
            for (k, u) in lp.iter().enumerate() {
                let pc = body.pcurve(f, l, k).ok()??;
                let [t0, t1] = t.edges[u.edge].t_range;
                for s in [0.0, 0.25, 0.5, 0.75, 1.0] {
                    let uv = pc.point(t0 + s * (t1 - t0));
                    (lo_uv, hi_uv) = (lo_uv.min(uv), hi_uv.max(uv));
                }
            }
        }
        let at = |a: f64, b: f64| {
            let uv = lo_uv + (hi_uv - lo_uv) * glam::DVec2::new(a, b);
            surface.point(uv).to_array()
        };
        let s = [0.25, 0.5, 0.75];
        Some(
            s.iter()
                .flat_map(|&a| s.iter().map(move |&b| at(a, b)))
                .collect(),
        )
    };
    let face_vertices = |f: usize| -> Vec<usize> {
        (t.faces[f].loops.iter().flatten())
            .flat_map(|u| [t.edges[u.edge].v0, t.edges[u.edge].v1])
            .collect()
    };
    let flat_in = |f: usize, axis: usize, at: f64| -> bool {
        let vertices = face_vertices(f);
        !vertices.is_empty()
            && (vertices.iter()).all(|&v| (t.vertices[v].point[axis] - at).abs() <= tol)
            && (edge_samples(f).iter()).all(|p| (p[axis] - at).abs() <= 1e3 * tol)
            && interior_samples(f)
                .is_some_and(|ps| ps.iter().all(|p| (p[axis] - at).abs() <= 1e3 * tol))
    };
    // The body's extent from its vertices and edges: the kernel's box may hold a trimmed
    // surface's control points (a fuselage ring cut at its symmetry plane reaches across it).
    let mut boundary_extent = [(f64::INFINITY, f64::NEG_INFINITY); 3];
    let boundary_points =
        (t.vertices.iter().map(|v| v.point)).chain((0..t.faces.len()).flat_map(edge_samples));
    for p in boundary_points {
        for (a, e) in boundary_extent.iter_mut().enumerate() {
            *e = (e.0.min(p[a]), e.1.max(p[a]));
        }
    }
    let mut found: Vec<(usize, f64, bool)> = Vec::new();
    for f in 0..t.faces.len() {
        let Some(&first) = face_vertices(f).first() else {
            continue;
        };
        for axis in 0..3 {
            let at = t.vertices[first].point[axis];
            if !flat_in(f, axis, at) {
                continue;
            }
            let (side_lo, side_hi) = boundary_extent[axis];
            let above = lo[axis].max(side_lo) >= at - box_tol;
            let below = hi[axis].min(side_hi) <= at + box_tol;
            if !(above || below) {
                continue;
            }
            let in_plane = |v: usize| (t.vertices[v].point[axis] - at).abs() <= tol;
            // The flat faces must be the body's only contact with the plane: a vertex on it
            // that no flat face there holds is another face touching it (a part resting on
            // a face, not a half model), and the cut would leave edges of three faces.
            let plane_faces: Vec<usize> = (0..t.faces.len())
                .filter(|&g| face_vertices(g).iter().all(|&v| in_plane(v)))
                .filter(|&g| g == f || flat_in(g, axis, at))
                .collect();
            let on_plane_faces: std::collections::HashSet<usize> =
                plane_faces.iter().flat_map(|&g| face_vertices(g)).collect();
            let only_contact = (0..t.vertices.len())
                .filter(|&v| in_plane(v))
                .all(|v| on_plane_faces.contains(&v));
            // A half model is cut through its middle: its section spans much of the body
            // across the plane. A flat end (a wing tip, a cylinder's cap) at one side of a
            // whole model spans a fraction of it.
            let section: Vec<[f64; 3]> = (plane_faces.iter())
                .flat_map(|&g| {
                    let corners = face_vertices(g).into_iter().map(|v| t.vertices[v].point);
                    corners.chain(edge_samples(g))
                })
                .collect();
            if only_contact && spans_the_body(&section, (lo, hi), axis, tol) {
                found.push((axis, at, above));
            }
        }
    }
    // Nearest the origin first; then y, z, x (an aircraft's symmetry plane is y = 0).
    let rank = |axis: usize| [2, 0, 1][axis];
    found.sort_by(|a, b| {
        let key = |p: &(usize, f64, bool)| ((p.1.abs() / length * 1e6).round() as i64, rank(p.0));
        key(a).cmp(&key(b))
    });
    found.dedup();
    found.first().copied()
}

/// The domain between `spec`'s far field and the body `body`, with what the sizing needs;
/// built by the kernel that read the body.
pub(crate) fn build_domain<K: KernelFile>(
    body: K,
    spec: FarfieldSpec,
    extent: f64,
) -> Result<(K, FlowDomain), String> {
    let [lo, hi] = match body.bounding_box() {
        Some(b) => b?.map(|p| p.to_array()),
        None => {
            return Err(format!(
                "{}: {} gives no bounding box, which a far field needs",
                body.file(),
                body.kernel()
            ))
        }
    };
    let length = (0..3)
        .map(|a| hi[a] - lo[a])
        .fold(0.0, f64::max)
        .max(1e-12 * extent);
    let centre: [f64; 3] = std::array::from_fn(|a| 0.5 * (lo[a] + hi[a]));
    let symmetry = if spec.shape.is_half() {
        let plane = symmetry_plane(&body, length, (lo, hi)).ok_or_else(|| {
            format!(
                "{}: --farfield {}: no flat face of the body lies in a coordinate plane with \
                 the whole body on one side, nothing else of it touching that plane, and \
                 spanning much of the body (a half model's symmetry face; a flat wing tip or \
                 end cap is not one); use box or sphere",
                body.file(),
                spec.shape.name()
            )
        })?;
        Some(plane)
    } else {
        None
    };
    let far = spec.size * length;
    let half_diagonal = 0.5 * (0..3).map(|a| (hi[a] - lo[a]).powi(2)).sum::<f64>().sqrt();
    let sphere = matches!(
        spec.shape,
        FarfieldShape::Sphere | FarfieldShape::HalfSphere
    );
    let request = FarfieldRequest {
        sphere,
        centre,
        half: if sphere {
            [far + half_diagonal; 3]
        } else {
            std::array::from_fn(|a| 0.5 * (hi[a] - lo[a]) + far)
        },
        symmetry,
        fuzzy: 1e-6 * extent,
    };
    let domain_extent = 2.0 * request.half.iter().map(|h| h * h).sum::<f64>().sqrt();
    let domain = match body.farfield(&request) {
        Some(d) => d?,
        None => {
            return Err(format!(
                "{}: a {} far field needs booleans, which {} does not have: give the flow \
                 domain in the file",
                body.file(),
                spec.shape.name(),
                body.kernel()
            ))
        }
    };
    let t = domain.topology();
    let solids = t.solids.len();
    if solids != 1 {
        return Err(format!(
            "{}: cutting the body out of the far field ({}) made {solids} solids, not one",
            body.file(),
            spec.shape.name()
        ));
    }
    let body_faces: Vec<usize> = (t.faces.iter().enumerate())
        .filter(|(_, f)| !matches!(f.name.as_deref(), Some("farfield" | "symmetry")))
        .map(|(k, _)| k)
        .collect();
    if body_faces.is_empty() {
        return Err(format!(
            "{}: the far field ({}) holds no face of the body: is the body inside it?",
            body.file(),
            spec.shape.name()
        ));
    }
    log::info!(
        "{}: flow domain {} at {} body lengths (body length {length:.4}{}): {} body faces",
        body.file(),
        spec.shape.name(),
        spec.size,
        symmetry.map_or(String::new(), |(axis, at, _)| format!(
            ", symmetry plane {} = {at:.6}",
            ["x", "y", "z"][axis]
        )),
        body_faces.len()
    );
    Ok((
        domain,
        FlowDomain {
            body_faces,
            domain_extent,
            outer: if sphere {
                FarBoundary::Sphere {
                    centre: DVec3::from_array(centre),
                    radius: request.half[0],
                }
            } else {
                let (c, h) = (DVec3::from_array(centre), DVec3::from_array(request.half));
                FarBoundary::Box {
                    lo: c - h,
                    hi: c + h,
                }
            },
            symmetry: symmetry.map(|(axis, at, _)| (axis, at)),
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn specs_parse_and_bad_ones_say_why() {
        let s: FarfieldSpec = "half-sphere:50".parse().unwrap();
        assert_eq!(s.shape, FarfieldShape::HalfSphere);
        assert_eq!(s.size, 50.0);
        assert!(s.shape.is_half());
        let e = "cylinder:20".parse::<FarfieldSpec>().unwrap_err();
        assert!(e.contains("unknown far-field shape 'cylinder'") && e.contains("half-box"));
        let e = "box:0.5".parse::<FarfieldSpec>().unwrap_err();
        assert!(e.contains("at least 1 body length"), "{e}");
        let e = "box".parse::<FarfieldSpec>().unwrap_err();
        assert!(e.contains("expected shape:size"), "{e}");
        let e = "box:far".parse::<FarfieldSpec>().unwrap_err();
        assert!(e.contains("'far' is not a number"), "{e}");
    }
}
