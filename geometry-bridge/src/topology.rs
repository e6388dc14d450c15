//! Plain-data topology of a CAD model. Ids are 0-based positions in the TopExp::MapShapes
//! order of the model's shape, stable for the lifetime of a `CadModel`.
use crate::ffi::bridge as ffi;

/// A topological vertex.
#[derive(Debug, Clone, PartialEq)]
pub struct Vertex {
    pub point: [f64; 3],
    pub tolerance: f64,
}

/// A topological edge. `v0`/`v1` are the vertices at `t_range[0]`/`t_range[1]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Edge {
    pub v0: usize,
    pub v1: usize,
    /// Collapsed to a point (e.g. at a sphere's pole); has pcurves but no 3-D curve.
    pub degenerate: bool,
    pub has_curve: bool,
    pub t_range: [f64; 2],
    /// Starts and ends at the same vertex.
    pub closed: bool,
    pub tolerance: f64,
}

/// One traversal of an edge by a face loop.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EdgeUse {
    pub edge: usize,
    /// Traversed from `t_range[1]` to `t_range[0]` (relative to the face's forward side).
    pub reversed: bool,
    /// The edge is a seam of this face: it occurs twice in the loop, once per pcurve.
    pub seam: bool,
}

/// A face: a trimmed region of one surface.
#[derive(Debug, Clone, PartialEq)]
pub struct Face {
    pub name: Option<String>,
    /// plane, cylinder, cone, sphere, torus, bspline, bezier, revolution, extrusion, offset, other.
    pub surface_kind: String,
    /// The face's normal is opposite to the surface's du × dv.
    pub orientation_reversed: bool,
    /// Loops of edge uses, outer loop first (BRepTools::OuterWire), each in wire order.
    pub loops: Vec<Vec<EdgeUse>>,
    pub u_range: [f64; 2],
    pub v_range: [f64; 2],
    pub u_period: Option<f64>,
    pub v_period: Option<f64>,
    pub tolerance: f64,
}

/// A connected set of faces. `faces` holds (face id, reversed within this shell).
#[derive(Debug, Clone, PartialEq)]
pub struct Shell {
    pub faces: Vec<(usize, bool)>,
    /// Every non-degenerate edge of the shell is used exactly twice by its faces.
    pub closed: bool,
    /// The source declared the shell open (OCCT's `Closed` flag unset, e.g. a STEP
    /// OPEN_SHELL), whatever its edges say.
    pub declared_open: bool,
}

/// A solid: its shells (outer and cavities, in file order) and name.
#[derive(Debug, Clone, PartialEq)]
pub struct Solid {
    pub shells: Vec<usize>,
    pub name: Option<String>,
}

/// Entity counts, for reports.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counts {
    pub vertices: usize,
    pub edges: usize,
    pub faces: usize,
    pub shells: usize,
    pub solids: usize,
}

/// The whole model's topology.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CadTopology {
    pub vertices: Vec<Vertex>,
    pub edges: Vec<Edge>,
    pub faces: Vec<Face>,
    pub shells: Vec<Shell>,
    pub solids: Vec<Solid>,
    /// Faces that belong to no shell.
    pub free_faces: Vec<usize>,
    /// Non-degenerate edges used by exactly one face use (a boundary of an open surface set).
    pub free_edges: Vec<usize>,
}

impl CadTopology {
    pub fn counts(&self) -> Counts {
        Counts {
            vertices: self.vertices.len(),
            edges: self.edges.len(),
            faces: self.faces.len(),
            shells: self.shells.len(),
            solids: self.solids.len(),
        }
    }

    /// Number of uses of each edge by the given faces (a seam counts twice).
    pub fn edge_use_counts(&self, faces: impl IntoIterator<Item = usize>) -> Vec<usize> {
        let mut n = vec![0usize; self.edges.len()];
        for f in faces {
            for u in self.faces[f].loops.iter().flatten() {
                n[u.edge] += 1;
            }
        }
        n
    }

    /// Edges of a shell's faces used once (open boundary) or more than twice (non-manifold).
    pub fn shell_bad_edges(&self, shell: usize) -> Vec<usize> {
        let n = self.edge_use_counts(self.shells[shell].faces.iter().map(|f| f.0));
        (0..n.len())
            .filter(|&e| n[e] != 0 && n[e] != 2 && !self.edges[e].degenerate)
            .collect()
    }

    pub(crate) fn from_ffi(t: ffi::Topology) -> Result<Self, String> {
        let idx = |i: i32, what: &str| -> Result<usize, String> {
            usize::try_from(i).map_err(|_| format!("{what} missing"))
        };
        let vertices = t
            .vertices
            .iter()
            .map(|v| Vertex {
                point: [v.x, v.y, v.z],
                tolerance: v.tolerance,
            })
            .collect();
        let mut edges = Vec::with_capacity(t.edges.len());
        for (i, e) in t.edges.iter().enumerate() {
            let v0 = idx(e.v0, &format!("first vertex of edge {i}"))?;
            let v1 = idx(e.v1, &format!("last vertex of edge {i}"))?;
            edges.push(Edge {
                v0,
                v1,
                degenerate: e.degenerate,
                has_curve: e.has_curve,
                t_range: [e.first, e.last],
                closed: v0 == v1,
                tolerance: e.tolerance,
            });
        }
        let mut faces: Vec<Face> = t
            .faces
            .into_iter()
            .map(|f| Face {
                name: f.has_name.then_some(f.name),
                surface_kind: f.surface_kind,
                orientation_reversed: f.reversed,
                loops: Vec::new(),
                u_range: [f.u0, f.u1],
                v_range: [f.v0, f.v1],
                u_period: f.u_periodic.then_some(f.u_period),
                v_period: f.v_periodic.then_some(f.v_period),
                tolerance: f.tolerance,
            })
            .collect();
        for u in &t.uses {
            let face = &mut faces[idx(u.face, "face of an edge use")?];
            let l = idx(u.loop_index, "loop of an edge use")?;
            if face.loops.len() <= l {
                face.loops.resize(l + 1, Vec::new());
            }
            face.loops[l].push(EdgeUse {
                edge: idx(u.edge, "edge of an edge use")?,
                reversed: u.reversed,
                seam: u.seam,
            });
        }
        let mut shells = vec![
            Shell {
                faces: Vec::new(),
                closed: false,
                declared_open: false,
            };
            idx(t.shell_count, "shell count")?
        ];
        for &s in &t.shells_flagged_open {
            shells[idx(s, "shell")?].declared_open = true;
        }
        let mut in_shell = vec![false; faces.len()];
        for r in &t.shell_faces {
            let f = idx(r.face, "face of a shell")?;
            in_shell[f] = true;
            shells[idx(r.shell, "shell")?].faces.push((f, r.reversed));
        }
        let mut solids: Vec<Solid> = t
            .solids
            .into_iter()
            .map(|s| Solid {
                shells: Vec::new(),
                name: s.has_name.then_some(s.name),
            })
            .collect();
        for r in &t.solid_shells {
            solids[idx(r.solid, "solid")?]
                .shells
                .push(idx(r.shell, "shell of a solid")?);
        }
        let mut topo = CadTopology {
            vertices,
            edges,
            faces,
            shells,
            solids,
            free_faces: (0..in_shell.len()).filter(|&f| !in_shell[f]).collect(),
            free_edges: Vec::new(),
        };
        for s in 0..topo.shells.len() {
            topo.shells[s].closed =
                !topo.shells[s].faces.is_empty() && topo.shell_bad_edges(s).is_empty();
        }
        let n = topo.edge_use_counts(0..topo.faces.len());
        topo.free_edges = (0..n.len())
            .filter(|&e| n[e] == 1 && !topo.edges[e].degenerate)
            .collect();
        Ok(topo)
    }
}
