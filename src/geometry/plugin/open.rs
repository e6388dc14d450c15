//! A file opened by a plugin: the plugin's model handle (closed on drop), its topology read
//! into [`ForeignTopology`] with every index checked, and the [`ForeignSource`] that hands
//! the model's entities to the import.

use super::entities::{PluginCurve, PluginPcurve, PluginSurface};
use super::handle::Handle;
use super::library::{CallError, Plugin};
use crate::geometry::{Curve, Curve2d, FaultLog, Surface, SurfaceBounds};
use crate::model::foreign::{
    ForeignEdge, ForeignFace, ForeignSolid, ForeignSource, ForeignTopology, ForeignUse,
    ForeignVertex,
};
use std::ffi::{c_char, CStr, CString};
use std::path::Path;
use std::sync::Arc;
use tetrafoil_plugin_abi as abi;

/// One use's place in the plugin's arrays and whether it has a pcurve.
#[derive(Clone, Copy)]
struct UseSlot {
    index: i32,
    pcurve: bool,
}

/// A file opened by a plugin, ready to import.
pub struct PluginSource {
    handle: Arc<Handle>,
    topology: ForeignTopology,
    bounds: Vec<SurfaceBounds>,
    uses: Vec<Vec<Vec<UseSlot>>>,
}

impl std::fmt::Debug for PluginSource {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.handle.context())
    }
}

/// The message of a failed call, naming the plugin, the file and what was asked.
fn failed(plugin: &Plugin, file: &str, what: &str, e: &CallError) -> String {
    let entity = match e.entity_kind {
        abi::ENTITY_VERTEX => format!(" (vertex {})", e.entity),
        abi::ENTITY_EDGE => format!(" (edge {})", e.entity),
        abi::ENTITY_FACE => format!(" (face {})", e.entity),
        abi::ENTITY_USE => format!(" (edge use {})", e.entity),
        abi::ENTITY_SHELL => format!(" (shell {})", e.entity),
        abi::ENTITY_SOLID => format!(" (solid {})", e.entity),
        abi::ENTITY_LINE => format!(" (line {})", e.entity),
        _ => String::new(),
    };
    format!(
        "{}: {file}: {what}: {}{entity}: {}",
        plugin.label(),
        e.kind(),
        e.message
    )
}

impl PluginSource {
    /// Open `path` with `plugin` and read its topology.
    pub fn open(plugin: &Arc<Plugin>, path: &Path) -> Result<PluginSource, String> {
        let file = path.display().to_string();
        let c_path = CString::new(path.as_os_str().as_encoded_bytes())
            .map_err(|_| format!("{file}: the path holds a NUL byte"))?;
        let open = plugin.table.open_file.expect("checked at load");
        let mut raw: *mut abi::Model = std::ptr::null_mut();
        // SAFETY: the header's open_file; `raw` is written on success.
        plugin
            .call(|err| unsafe { open(c_path.as_ptr(), &mut raw, err) })
            .map_err(|e| failed(plugin, &file, "cannot open it", &e))?;
        Self::adopt(plugin, raw, file)
    }

    /// Take ownership of a model the plugin made and read its topology.
    fn adopt(plugin: &Arc<Plugin>, raw: *mut abi::Model, file: String) -> Result<Self, String> {
        if raw.is_null() {
            return Err(format!(
                "{}: {file}: the plugin reported success but gave no model",
                plugin.label()
            ));
        }
        let handle = Arc::new(Handle {
            plugin: plugin.clone(),
            raw,
            file,
            faults: FaultLog::default(),
        });
        let get = plugin.table.topology.expect("checked at load");
        // SAFETY: zero is a valid `Topology` (counts 0, NULL arrays); the plugin fills it.
        let mut t: abi::Topology = unsafe { std::mem::zeroed() };
        plugin
            .call(|err| unsafe { get(raw, &mut t, err) })
            .map_err(|e| failed(plugin, &handle.file, "cannot give its topology", &e))?;
        // SAFETY: the arrays are the plugin's, valid until close, of the counts it gave.
        let read = unsafe { read_topology(&t) }
            .map_err(|m| format!("{}: its topology is not consistent: {m}", handle.context()))?;
        Ok(PluginSource {
            handle,
            topology: read.topology,
            bounds: read.bounds,
            uses: read.uses,
        })
    }

    /// The plugin that opened the file.
    pub fn plugin(&self) -> &Arc<Plugin> {
        &self.handle.plugin
    }

    /// A new model with the faces sewn into solids at `tolerance`; `None` when the plugin
    /// does not sew.
    pub fn sew(&self, tolerance: f64) -> Option<Result<PluginSource, String>> {
        let sew = self.handle.plugin.table.sew?;
        Some(self.derived("sew", |m, out, err| unsafe { sew(m, tolerance, out, err) }))
    }

    /// A new model of the solids alone (faces outside them dropped); `None` when the plugin
    /// cannot.
    pub fn solids_only(&self) -> Option<Result<PluginSource, String>> {
        let solids_only = self.handle.plugin.table.solids_only?;
        Some(self.derived("solids_only", |m, out, err| unsafe {
            solids_only(m, out, err)
        }))
    }

    /// A new model with the plugin's repairs at `tolerance`; `None` when it does not heal.
    pub fn heal(&self, tolerance: f64) -> Option<Result<PluginSource, String>> {
        let heal = self.handle.plugin.table.heal?;
        Some(self.derived("heal", |m, out, err| unsafe {
            heal(m, tolerance, out, err)
        }))
    }

    /// The plugin's bounding box (low and high corners); `None` when it gives none.
    pub fn bounding_box(&self) -> Option<Result<[[f64; 3]; 2], String>> {
        let f = self.handle.plugin.table.bounding_box?;
        let plugin = &self.handle.plugin;
        let mut out = [0.0; 6];
        // SAFETY: the header's bounding_box: room for 6 doubles.
        let result = plugin.call(|err| unsafe { f(self.handle.raw, out.as_mut_ptr(), err) });
        Some(match result {
            Ok(abi::OK) if out.iter().all(|x| x.is_finite()) => {
                Ok([[out[0], out[1], out[2]], [out[3], out[4], out[5]]])
            }
            Ok(abi::OK) => Err(format!(
                "{}: bounding_box answered a value that is not finite",
                self.handle.context()
            )),
            Ok(_) => Err(format!(
                "{}: the model is empty (no bounding box)",
                self.handle.context()
            )),
            Err(e) => Err(failed(plugin, &self.handle.file, "bounding_box", &e)),
        })
    }

    /// A new model whose touching solids share their contact faces; `None` when the plugin
    /// has no booleans.
    pub fn fuse(&self, tolerance: f64) -> Option<Result<PluginSource, String>> {
        let fuse = self.handle.plugin.table.fuse?;
        Some(self.derived("fuse", |m, out, err| unsafe {
            fuse(m, tolerance, out, err)
        }))
    }

    /// The flow domain around the solids: a box about `centre` with half extents `half` (or a
    /// sphere of radius `half[0]`), on one side of a symmetry plane (axis, coordinate, the
    /// positive side or not) for a half model; `None` when the plugin has no booleans.
    pub fn farfield(
        &self,
        sphere: bool,
        centre: [f64; 3],
        half: [f64; 3],
        symmetry: Option<(usize, f64, bool)>,
        fuzzy: f64,
    ) -> Option<Result<PluginSource, String>> {
        let farfield = self.handle.plugin.table.farfield?;
        let spec = abi::Farfield {
            shape: if sphere {
                abi::FARFIELD_SPHERE
            } else {
                abi::FARFIELD_BOX
            },
            symmetry_axis: symmetry.map_or(-1, |s| s.0 as i32),
            symmetry_side: match symmetry {
                Some((_, _, true)) => 1,
                Some((_, _, false)) => -1,
                None => 0,
            },
            reserved: 0,
            centre,
            half,
            symmetry_at: symmetry.map_or(0.0, |s| s.1),
            fuzzy,
        };
        Some(self.derived("farfield", |m, out, err| unsafe {
            farfield(m, &spec, out, err)
        }))
    }

    fn derived(
        &self,
        what: &str,
        f: impl FnOnce(*const abi::Model, *mut *mut abi::Model, *mut abi::Error) -> abi::Status,
    ) -> Result<PluginSource, String> {
        let plugin = &self.handle.plugin;
        let mut raw: *mut abi::Model = std::ptr::null_mut();
        plugin
            .call(|err| f(self.handle.raw, &mut raw, err))
            .map_err(|e| failed(plugin, &self.handle.file, what, &e))?;
        Self::adopt(plugin, raw, self.handle.file.clone())
    }
}

impl ForeignSource for PluginSource {
    fn file(&self) -> &str {
        &self.handle.file
    }
    fn topology(&self) -> &ForeignTopology {
        &self.topology
    }
    fn curve(&self, edge: usize) -> Result<Arc<dyn Curve>, String> {
        let t = self.topology.edges[edge].t_range;
        Ok(Arc::new(PluginCurve::new(
            self.handle.clone(),
            edge,
            (t[0], t[1]),
        )))
    }
    fn surface(&self, face: usize) -> Result<Arc<dyn Surface>, String> {
        let name = self.topology.faces[face].name.clone();
        Ok(Arc::new(PluginSurface::new(
            self.handle.clone(),
            face,
            name,
            self.bounds[face],
        )))
    }
    fn pcurve(&self, face: usize, lp: usize, k: usize) -> Result<Option<Arc<dyn Curve2d>>, String> {
        let slot = self.uses[face][lp][k];
        if !slot.pcurve {
            return Ok(None);
        }
        let edge = &self.topology.edges[self.topology.faces[face].loops[lp][k].edge];
        Ok(Some(Arc::new(PluginPcurve::new(
            self.handle.clone(),
            slot.index,
            face,
            (edge.t_range[0], edge.t_range[1]),
        ))))
    }
    fn faults(&self) -> FaultLog {
        self.handle.faults.clone()
    }
}

/// The topology, each face's parameter bounds and each use's slot.
struct Read {
    topology: ForeignTopology,
    bounds: Vec<SurfaceBounds>,
    uses: Vec<Vec<Vec<UseSlot>>>,
}

/// `n` elements at `p`, or an empty slice; refuses a negative count or a NULL array.
///
/// # Safety
/// `p` points to at least `n` elements valid while the result is used.
unsafe fn slice<'a, T>(p: *const T, n: i32, what: &str) -> Result<&'a [T], String> {
    match n {
        0 => Ok(&[]),
        n if n < 0 => Err(format!("{what}: negative count {n}")),
        n if p.is_null() => Err(format!("{what}: {n} announced, array missing")),
        n => Ok(std::slice::from_raw_parts(p, n as usize)),
    }
}

/// `first .. first + n` inside `0 .. len`.
fn span(first: i32, n: i32, len: usize, what: &str) -> Result<std::ops::Range<usize>, String> {
    let (a, b) = (first as i64, first as i64 + n as i64);
    if first < 0 || n < 0 || b > len as i64 {
        return Err(format!("{what} {a}..{b} is outside 0..{len}"));
    }
    Ok(a as usize..b as usize)
}

fn index(i: i32, len: usize, what: &str) -> Result<usize, String> {
    usize::try_from(i)
        .ok()
        .filter(|&i| i < len)
        .ok_or_else(|| format!("{what} {i} is outside 0..{len}"))
}

fn finite(values: &[f64], what: &str) -> Result<(), String> {
    match values.iter().all(|x| x.is_finite()) {
        true => Ok(()),
        false => Err(format!("{what} is not finite: {values:?}")),
    }
}

/// A name given by the plugin (NULL: none).
///
/// # Safety
/// `p` is NULL or a NUL-terminated string valid during the call.
unsafe fn name(p: *const c_char, what: &str) -> Result<Option<String>, String> {
    if p.is_null() {
        return Ok(None);
    }
    CStr::from_ptr(p)
        .to_str()
        .map(|s| Some(s.to_string()))
        .map_err(|_| format!("{what}: its name is not UTF-8"))
}

/// Copy the plugin's arrays, checking every count and index.
///
/// # Safety
/// The pointers of `t` point to arrays of the counts given, valid during the call.
unsafe fn read_topology(t: &abi::Topology) -> Result<Read, String> {
    let vertices = slice(t.vertices, t.n_vertices, "vertices")?;
    let edges = slice(t.edges, t.n_edges, "edges")?;
    let faces = slice(t.faces, t.n_faces, "faces")?;
    let loops = slice(t.loops, t.n_loops, "loops")?;
    let uses = slice(t.uses, t.n_uses, "edge uses")?;
    let shells = slice(t.shells, t.n_shells, "shells")?;
    let face_refs = slice(t.face_refs, t.n_face_refs, "face references")?;
    let solids = slice(t.solids, t.n_solids, "solids")?;
    let solid_shells = slice(t.solid_shells, t.n_solid_shells, "solid shells")?;
    let mut out = ForeignTopology::default();
    for (i, v) in vertices.iter().enumerate() {
        finite(&v.point, &format!("vertex {i}'s point"))?;
        out.vertices.push(ForeignVertex {
            point: v.point,
            tolerance: v.tolerance.max(0.0),
        });
    }
    for (i, e) in edges.iter().enumerate() {
        let what = format!("edge {i}");
        finite(&e.t_range, &format!("{what}'s parameter range"))?;
        out.edges.push(ForeignEdge {
            v0: index(e.v0, vertices.len(), &format!("{what}'s start vertex"))?,
            v1: index(e.v1, vertices.len(), &format!("{what}'s end vertex"))?,
            degenerate: e.flags & abi::EDGE_DEGENERATE != 0,
            t_range: e.t_range,
            tolerance: e.tolerance.max(0.0),
        });
    }
    let mut bounds = Vec::with_capacity(faces.len());
    let mut slots = Vec::with_capacity(faces.len());
    for (i, f) in faces.iter().enumerate() {
        let what = format!("face {i}");
        finite(
            &[f.u_range[0], f.u_range[1], f.v_range[0], f.v_range[1]],
            &format!("{what}'s parameter ranges"),
        )?;
        let period = |p: f64| (p.is_finite() && p > 0.0).then_some(p);
        bounds.push(SurfaceBounds {
            u: (f.u_range[0], f.u_range[1]),
            v: (f.v_range[0], f.v_range[1]),
            u_period: period(f.u_period),
            v_period: period(f.v_period),
        });
        let mut face_loops = Vec::new();
        let mut face_slots = Vec::new();
        for l in span(
            f.first_loop,
            f.n_loops,
            loops.len(),
            &format!("{what}'s loops"),
        )? {
            let lp = loops[l];
            let mut chain = Vec::new();
            let mut chain_slots = Vec::new();
            for u in span(
                lp.first_use,
                lp.n_uses,
                uses.len(),
                &format!("loop {l}'s uses"),
            )? {
                let eu = uses[u];
                chain.push(ForeignUse {
                    edge: index(eu.edge, edges.len(), &format!("edge use {u}'s edge"))?,
                    reversed: eu.flags & abi::USE_REVERSED != 0,
                });
                chain_slots.push(UseSlot {
                    index: u as i32,
                    pcurve: eu.flags & abi::USE_PCURVE != 0,
                });
            }
            face_loops.push(chain);
            face_slots.push(chain_slots);
        }
        out.faces.push(ForeignFace {
            name: name(f.name, &what)?,
            loops: face_loops,
        });
        slots.push(face_slots);
    }
    for (s, sh) in shells.iter().enumerate() {
        let faces = span(
            sh.first_face,
            sh.n_faces,
            face_refs.len(),
            &format!("shell {s}'s faces"),
        )?
        .map(|r| index(face_refs[r].face, faces.len(), &format!("shell {s}'s face")))
        .collect::<Result<Vec<_>, _>>()?;
        out.shells.push(faces);
    }
    for (i, s) in solids.iter().enumerate() {
        let what = format!("solid {i}");
        let solid_shell_ids = span(
            s.first_shell,
            s.n_shells,
            solid_shells.len(),
            &format!("{what}'s shells"),
        )?
        .map(|k| index(solid_shells[k], shells.len(), &format!("{what}'s shell")))
        .collect::<Result<Vec<_>, _>>()?;
        out.solids.push(ForeignSolid {
            name: name(s.name, &what)?,
            shells: solid_shell_ids,
        });
    }
    Ok(Read {
        topology: out,
        bounds,
        uses: slots,
    })
}
