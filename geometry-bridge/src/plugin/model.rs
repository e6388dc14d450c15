//! One file open in the OCCT plugin: the `CadModel`, its topology as the flat arrays of the
//! plugin interface, and a geometry handle for every face, edge and edge use, made once at
//! open so that queries only read.

use crate::{CadModel, OccCurve, OccPcurve, OccSurface};
use std::ffi::{c_char, CString};
use tetrafoil_plugin_abi as abi;

/// The plugin's `tf_model`.
pub struct PluginModel {
    pub cad: CadModel,
    pub surfaces: Vec<OccSurface>,
    pub curves: Vec<Option<OccCurve>>,
    /// Per edge use (global index): its pcurve and its edge's range.
    pub pcurves: Vec<(OccPcurve, [f64; 2])>,
    arrays: Arrays,
}

/// The topology arrays and the names they point to.
#[derive(Default)]
struct Arrays {
    vertices: Vec<abi::TfVertex>,
    edges: Vec<abi::TfEdge>,
    faces: Vec<abi::TfFace>,
    loops: Vec<abi::TfLoop>,
    uses: Vec<abi::TfEdgeUse>,
    shells: Vec<abi::TfShell>,
    face_refs: Vec<abi::TfFaceRef>,
    solids: Vec<abi::TfSolid>,
    solid_shells: Vec<i32>,
    names: Vec<CString>,
}

fn count(n: usize) -> i32 {
    i32::try_from(n).unwrap_or(i32::MAX)
}

/// A name for the interface (interior NUL bytes dropped).
fn c_name(names: &mut Vec<CString>, name: &Option<String>) -> *const c_char {
    match name {
        None => std::ptr::null(),
        Some(n) => {
            let c = CString::new(n.replace('\0', "")).unwrap_or_default();
            names.push(c);
            names.last().map_or(std::ptr::null(), |c| c.as_ptr())
        }
    }
}

impl PluginModel {
    /// The model of `cad` with every geometry handle made.
    pub fn new(cad: CadModel) -> Result<Self, String> {
        let t = cad.topology();
        let e = |x: crate::CadError| x.to_string();
        let surfaces = (0..t.faces.len())
            .map(|f| cad.surface(f).map_err(e))
            .collect::<Result<Vec<_>, _>>()?;
        let mut curves = Vec::with_capacity(t.edges.len());
        for (i, edge) in t.edges.iter().enumerate() {
            curves.push(if edge.degenerate {
                None
            } else {
                match cad.curve(i).map_err(e)? {
                    Some(c) => Some(c),
                    None => {
                        return Err(format!(
                            "{}: edge {i} has no 3-D curve and is not degenerate",
                            cad.file()
                        ))
                    }
                }
            });
        }
        let mut a = Arrays::default();
        let mut pcurves = Vec::new();
        a.vertices = (t.vertices.iter())
            .map(|v| abi::TfVertex {
                point: v.point,
                tolerance: v.tolerance,
            })
            .collect();
        a.edges = (t.edges.iter())
            .map(|x| abi::TfEdge {
                v0: count(x.v0),
                v1: count(x.v1),
                flags: if x.degenerate {
                    abi::EDGE_DEGENERATE
                } else {
                    0
                },
                reserved: 0,
                t_range: x.t_range,
                tolerance: x.tolerance,
            })
            .collect();
        for (f, face) in t.faces.iter().enumerate() {
            let first_loop = count(a.loops.len());
            for (l, lp) in face.loops.iter().enumerate() {
                a.loops.push(abi::TfLoop {
                    first_use: count(a.uses.len()),
                    n_uses: count(lp.len()),
                });
                for (k, u) in lp.iter().enumerate() {
                    let mut flags = abi::USE_PCURVE;
                    if u.reversed {
                        flags |= abi::USE_REVERSED;
                    }
                    if u.seam {
                        flags |= abi::USE_SEAM;
                    }
                    a.uses.push(abi::TfEdgeUse {
                        edge: count(u.edge),
                        flags,
                    });
                    pcurves.push((cad.pcurve(f, l, k).map_err(e)?, t.edges[u.edge].t_range));
                }
            }
            let s = &surfaces[f];
            let name = c_name(&mut a.names, &face.name);
            a.faces.push(abi::TfFace {
                name,
                flags: if face.orientation_reversed {
                    abi::FACE_REVERSED
                } else {
                    0
                },
                first_loop,
                n_loops: count(face.loops.len()),
                reserved: 0,
                u_range: s.u_range(),
                v_range: s.v_range(),
                u_period: s.u_period().unwrap_or(0.0),
                v_period: s.v_period().unwrap_or(0.0),
                tolerance: face.tolerance,
            });
        }
        for shell in &t.shells {
            a.shells.push(abi::TfShell {
                first_face: count(a.face_refs.len()),
                n_faces: count(shell.faces.len()),
            });
            a.face_refs
                .extend(shell.faces.iter().map(|&(face, reversed)| abi::TfFaceRef {
                    face: count(face),
                    reversed: reversed as u32,
                }));
        }
        for solid in &t.solids {
            let name = c_name(&mut a.names, &solid.name);
            a.solids.push(abi::TfSolid {
                name,
                first_shell: count(a.solid_shells.len()),
                n_shells: count(solid.shells.len()),
            });
            a.solid_shells
                .extend(solid.shells.iter().map(|&s| count(s)));
        }
        Ok(PluginModel {
            cad,
            surfaces,
            curves,
            pcurves,
            arrays: a,
        })
    }

    /// The arrays as the interface's `tf_topology` (valid while the model lives).
    pub fn topology(&self) -> abi::Topology {
        let a = &self.arrays;
        abi::Topology {
            n_vertices: count(a.vertices.len()),
            n_edges: count(a.edges.len()),
            n_faces: count(a.faces.len()),
            n_loops: count(a.loops.len()),
            n_uses: count(a.uses.len()),
            n_shells: count(a.shells.len()),
            n_face_refs: count(a.face_refs.len()),
            n_solids: count(a.solids.len()),
            n_solid_shells: count(a.solid_shells.len()),
            vertices: a.vertices.as_ptr(),
            edges: a.edges.as_ptr(),
            faces: a.faces.as_ptr(),
            loops: a.loops.as_ptr(),
            uses: a.uses.as_ptr(),
            shells: a.shells.as_ptr(),
            face_refs: a.face_refs.as_ptr(),
            solids: a.solids.as_ptr(),
            solid_shells: a.solid_shells.as_ptr(),
        }
    }
}
