//! Topology: regions → shells of oriented faces → faces bounded by loops of oriented edge uses
//! → edges between vertices. Geometry (surfaces, curves, points) hangs off the topology through
//! the traits of [`crate::geometry`], so native and foreign entities mix freely.
//!
//! Orientation is automatic ([`orient`]): users list faces and edges in any direction, and the
//! model works out which loop is outer and which way each face's normal must point.

#[cfg(feature = "occt")]
pub mod cad;
pub mod coincident;
pub mod foreign;
mod integrals;
pub mod orient;
mod pcurve;
pub mod summary;
pub mod validate;

pub use integrals::FaceIntegrals;
pub use pcurve::{project_pcurve, unwrap_near};

use crate::geometry::{newton, Curve, Curve2d, Surface};
use glam::{DVec2, DVec3};
use std::sync::Arc;

/// A point refined from its pcurve's (u,v) is taken when it lies within this fraction of the
/// surface's size from the edge: CAD edges stay off their faces by their tolerance (1e-6 to
/// 1e-4 of the model in the corpus); farther means the pcurve's guess is not near the edge.
const PCURVE_TRUST: f64 = 1e-3;

pub type VertexId = usize;
pub type EdgeId = usize;
pub type FaceId = usize;
pub type RegionId = usize;

/// A topological vertex and its point.
#[derive(Clone, Debug)]
pub struct Vertex {
    pub name: Option<String>,
    pub point: DVec3,
}

/// An edge: a piece `range` of a curve between two vertices. A degenerate edge (the pole of
/// a sphere) has no curve and its two vertices coincide.
#[derive(Clone)]
pub struct Edge {
    pub name: Option<String>,
    pub curve: Option<Arc<dyn Curve>>,
    pub range: (f64, f64),
    pub start: VertexId,
    pub end: VertexId,
}

impl Edge {
    pub fn is_degenerate(&self) -> bool {
        self.curve.is_none()
    }
    pub fn is_closed(&self) -> bool {
        self.start == self.end
    }
}

/// One use of an edge in a face loop. `reversed` means the loop runs from the edge's end to its
/// start. The pcurve maps the edge's own parameter to the face's (u,v).
#[derive(Clone)]
pub struct EdgeUse {
    pub edge: EdgeId,
    pub reversed: bool,
    pub pcurve: Option<Arc<dyn Curve2d>>,
}

/// A closed chain of edge uses on a face. A loop with no edges and a vertex is a vertex loop
/// (a sphere bounded only by a point).
#[derive(Clone, Default)]
pub struct Loop {
    pub uses: Vec<EdgeUse>,
    pub vertex: Option<VertexId>,
}

/// A face: a trimmed piece of a surface. After orientation, `loops[0]` is the outer loop and
/// runs counter-clockwise in (u,v); holes run clockwise.
#[derive(Clone)]
pub struct Face {
    pub name: Option<String>,
    pub surface: Arc<dyn Surface>,
    pub loops: Vec<Loop>,
}

/// A face in a shell. `reversed` is false when the surface normal `Su × Sv` points out of the
/// region (into the cavity for a cavity shell).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FaceUse {
    pub face: FaceId,
    pub reversed: bool,
}

/// A connected closed set of faces bounding a region.
#[derive(Clone, Debug, Default)]
pub struct Shell {
    pub faces: Vec<FaceUse>,
    /// Volume enclosed, positive, filled in by orientation.
    pub volume: f64,
}

/// A closed volume: after orientation `shells[0]` is the outer shell, the rest are cavities.
/// Embedded faces and edges lie inside it and the mesh must conform to them from both sides.
#[derive(Clone, Debug, Default)]
pub struct Region {
    pub name: Option<String>,
    pub shells: Vec<Shell>,
    pub embedded_faces: Vec<FaceId>,
    pub embedded_edges: Vec<EdgeId>,
}

/// The whole model.
#[derive(Clone, Default)]
pub struct Model {
    pub vertices: Vec<Vertex>,
    pub edges: Vec<Edge>,
    pub faces: Vec<Face>,
    pub regions: Vec<Region>,
    /// Queries a plugin kernel could not answer (empty for native and OpenCASCADE geometry).
    pub faults: crate::geometry::FaultLog,
}

/// Which entity a message is about: "face 3 'wing_upper'".
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum EntityRef {
    Vertex(VertexId, Option<String>),
    Edge(EdgeId, Option<String>),
    Face(FaceId, Option<String>),
    Region(RegionId, Option<String>),
}

impl std::fmt::Display for EntityRef {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (kind, id, name) = match self {
            EntityRef::Vertex(i, n) => ("vertex", i, n),
            EntityRef::Edge(i, n) => ("edge", i, n),
            EntityRef::Face(i, n) => ("face", i, n),
            EntityRef::Region(i, n) => ("region", i, n),
        };
        match name {
            Some(n) => write!(f, "{kind} {id} '{n}'"),
            None => write!(f, "{kind} {id}"),
        }
    }
}

impl Model {
    pub fn vertex_ref(&self, id: VertexId) -> EntityRef {
        EntityRef::Vertex(id, self.vertices[id].name.clone())
    }
    pub fn edge_ref(&self, id: EdgeId) -> EntityRef {
        EntityRef::Edge(id, self.edges[id].name.clone())
    }
    pub fn face_ref(&self, id: FaceId) -> EntityRef {
        EntityRef::Face(id, self.faces[id].name.clone())
    }
    pub fn region_ref(&self, id: RegionId) -> EntityRef {
        EntityRef::Region(id, self.regions[id].name.clone())
    }

    /// Boundary marker of a face: its name, or `face_<id>`.
    pub fn face_marker(&self, id: FaceId) -> String {
        self.faces[id]
            .name
            .clone()
            .unwrap_or_else(|| format!("face_{id}"))
    }

    /// The point of an edge at parameter `t` (its vertex for a degenerate edge).
    pub fn edge_point(&self, id: EdgeId, t: f64) -> DVec3 {
        let e = &self.edges[id];
        match &e.curve {
            Some(c) => c.point(t),
            None => self.vertices[e.start].point,
        }
    }

    /// Start and end vertex of an edge use, in the loop's direction.
    pub fn use_vertices(&self, u: &EdgeUse) -> (VertexId, VertexId) {
        let e = &self.edges[u.edge];
        if u.reversed {
            (e.end, e.start)
        } else {
            (e.start, e.end)
        }
    }

    /// (u,v) on `face` of the point at edge parameter `t` of an edge use: from the pcurve, then
    /// refined by projecting the 3-D point with the pcurve's value as hint (a sampled pcurve is
    /// only close; an exact one is left as it is when the projection agrees).
    pub fn use_uv(&self, face: FaceId, u: &EdgeUse, t: f64) -> Option<DVec2> {
        let surface = &self.faces[face].surface;
        let p = self.edge_point(u.edge, t);
        match &u.pcurve {
            Some(pc) => {
                let guess = pc.point(t);
                let refined = match newton::project_local(surface.as_ref(), p, guess) {
                    // The pcurve says which part of the surface the edge runs on: refine its
                    // (u,v) there. A global projection (OCCT's, then a grid search whenever the
                    // edge lies off the surface by more than rounding, as CAD edges do by their
                    // tolerance) cost half the loading and boundary time of a Rhino file.
                    Some(uv)
                        if surface.point(uv).distance(p)
                            <= PCURVE_TRUST
                                * newton::surface_scale(surface.as_ref(), &surface.bounds()) =>
                    {
                        uv
                    }
                    // A pcurve that misses by that much is not to be trusted near its guess.
                    _ => surface.closest_uv(p, Some(guess))?,
                };
                // On a seam or pole, the projection may jump to the other side: keep the
                // pcurve's side when both map to the same 3-D point (to rounding: at a pole
                // every u is the same point, and a seam's two sides differ in the last bits).
                let noise = 1e-9 * p.abs().max_element().max(1.0);
                if surface.point(guess).distance(p) <= surface.point(refined).distance(p) + noise {
                    Some(guess)
                } else {
                    Some(refined)
                }
            }
            None => surface.closest_uv(p, None),
        }
    }

    /// All faces of region `r`'s shells.
    pub fn region_faces(&self, r: RegionId) -> impl Iterator<Item = FaceUse> + '_ {
        self.regions[r]
            .shells
            .iter()
            .flat_map(|s| s.faces.iter().copied())
    }
}
