//! From the parsed schema to a [`Model`] and its sizing.

use super::controls::{
    curvature_segments_ok, AutoWakes, Case, ControlOverrides, Ctx, MeshControls, PROXIMITY_CELLS,
};
use super::error::CaseError;
use super::schema::{CaseFile, SourceKind, SurfaceEntry, P3};
use crate::geometry::{Curve, Line2d, Surface};
use crate::model::{Edge, EdgeUse, Face, FaceUse, Loop, Model, Region, Shell, Vertex};
use crate::sizing::{BackgroundMesh, SizingField, Source, SourceShape};
use glam::{DVec2, DVec3};
use std::collections::HashMap;
use std::sync::Arc;
use tetrafoil_native::{FergusonCurve, FergusonPatch, FergusonSurface};
use toml::Spanned;

fn v3(p: P3) -> DVec3 {
    DVec3::from_array(p)
}

/// Look a name up in a table, or say which key refers to what is missing.
fn lookup(
    ctx: &Ctx,
    table: &HashMap<String, usize>,
    name: &Spanned<String>,
    key: &str,
    what: &str,
) -> Result<usize, CaseError> {
    table
        .get(name.get_ref())
        .copied()
        .ok_or_else(|| ctx.at(name, key, format!("no {what} named '{}'", name.get_ref())))
}

/// Names must be unique within their kind.
fn index(
    ctx: &Ctx,
    names: &[&Spanned<String>],
    key: &str,
) -> Result<HashMap<String, usize>, CaseError> {
    let mut map = HashMap::new();
    for (i, n) in names.iter().enumerate() {
        if map.insert(n.get_ref().clone(), i).is_some() {
            return Err(ctx.at(n, key, format!("duplicate name '{}'", n.get_ref())));
        }
    }
    Ok(map)
}

/// Parse and build a case from its text; `path` is used in messages.
pub fn parse_case(text: &str, path: &str) -> Result<Case, CaseError> {
    parse_case_with(text, path, &ControlOverrides::default())
}

/// [`parse_case`] with some mesh controls replaced.
pub fn parse_case_with(
    text: &str,
    path: &str,
    overrides: &ControlOverrides,
) -> Result<Case, CaseError> {
    let ctx = Ctx { text, path };
    let mut file: CaseFile = toml::from_str(text).map_err(|e| CaseError::Syntax {
        path: path.to_string(),
        message: e.to_string().trim_end().replace('\n', "\n  "),
    })?;
    let (model, controls, domain) = match &file.mesh.cad {
        Some(cad) => {
            let native = !(file.vertices.is_empty()
                && file.curves.is_empty()
                && file.surfaces.is_empty()
                && file.edges.is_empty()
                && file.faces.is_empty()
                && file.regions.is_empty());
            if native {
                return Err(ctx.at(
                    cad,
                    "mesh.cad",
                    "native vertices, curves, surfaces, edges, faces and regions cannot be mixed with a CAD model (sources, background, [[replace_face]] and [[wake]] can)",
                ));
            }
            let cad_path = std::path::Path::new(path)
                .parent()
                .unwrap_or(std::path::Path::new(""))
                .join(cad.get_ref());
            let farfield = match (overrides.farfield, &file.mesh.farfield) {
                (Some(spec), _) => Some(spec),
                (None, Some(f)) => Some(farfield_spec(&ctx, f)?),
                (None, None) => None,
            };
            let (mut model, extent, domain) = super::cad::load_cad_model(&cad_path, farfield)
                .map_err(|message| ctx.at(cad, "mesh.cad", message))?;
            let controls = controls(&ctx, &file, extent, Some(extent / 20.0))?;
            super::mix::apply(&ctx, &file, &mut model, controls.tolerance)?;
            (model, controls, domain)
        }
        None => {
            if let Some(key) = super::mix::first_entry(&ctx, &file) {
                return Err(key);
            }
            let body_extent = model_extent(&file);
            let farfield = match (overrides.farfield, &file.mesh.farfield) {
                (Some(spec), _) => Some(spec),
                (None, Some(f)) => Some(farfield_spec(&ctx, f)?),
                (None, None) => None,
            };
            let Some(spec) = farfield else {
                let controls = controls(&ctx, &file, body_extent, None)?;
                let model = build_model(&ctx, &file, controls.tolerance)?;
                return finish(&ctx, &file, model, controls, None, overrides);
            };
            // The far field goes into the case as native entries; the body keeps the spacing
            // it would have alone, as a CAD body does.
            let key = file.mesh.farfield.as_ref().map(|f| f.span());
            let wrapped =
                super::farfield_native::wrap(&mut file, spec, key.clone().unwrap_or(0..0))
                    .map_err(|m| match &file.mesh.farfield {
                        Some(f) => ctx.at(f, "mesh.farfield", m),
                        None => ctx.model(format!("--farfield {}: {m}", spec.shape.name())),
                    })?;
            let controls = controls(&ctx, &file, body_extent, Some(body_extent / 20.0))?;
            let mut model = build_model(&ctx, &file, controls.tolerance)?;
            let domain = super::farfield_native::name_domain(&mut model, &wrapped);
            (model, controls, Some(domain))
        }
    };
    finish(&ctx, &file, model, controls, domain.as_ref(), overrides)
}

/// The case from its model: the command line's overrides, the sizing (kept fine on a flow
/// domain's body) and the refinement stages.
fn finish(
    ctx: &Ctx,
    file: &CaseFile,
    mut model: Model,
    mut controls: MeshControls,
    domain: Option<&super::farfield::FlowDomain>,
    overrides: &ControlOverrides,
) -> Result<Case, CaseError> {
    overrides.apply(&mut controls);
    // The command line's request, else the case file's (its errors then name the key).
    let from_file = auto_wakes(ctx, &file.mesh)?;
    let request = match (overrides.wakes, from_file) {
        (Some(r), _) => Some((r, None)),
        (None, file) => file.map(|(r, key)| (r, Some(key))),
    };
    if let Some((request, key)) = request {
        super::mix::auto_wakes(&mut model, domain, &request, controls.tolerance).map_err(|m| {
            match key {
                Some(k) => ctx.at(k, "mesh.wakes", m),
                None => ctx.model(m),
            }
        })?;
    }
    let mut sizing = sizing(ctx, file, &model, &controls)?;
    if let Some(domain) = domain {
        super::farfield::size_domain(&mut sizing, &model, domain, controls.size);
    }
    let refinement = super::refine::stages(ctx, &file.refine, &model, controls.size)?;
    if let Some(fault) = model.faults.first() {
        return Err(ctx.model(fault));
    }
    Ok(Case {
        model,
        controls,
        sizing,
        refinement,
    })
}

/// `[mesh] wakes = "auto"` with `alpha`, `beta` and `wake_length`, checked; the key to name
/// in errors beside it.
fn auto_wakes<'a>(
    ctx: &Ctx,
    m: &'a super::schema::MeshSection,
) -> Result<Option<(AutoWakes, &'a Spanned<String>)>, CaseError> {
    let angle = |v: &Option<Spanned<f64>>, key: &str| match v {
        Some(a) if !(a.get_ref().is_finite() && a.get_ref().abs() < 90.0) => Err(ctx.at(
            a,
            key,
            format!(
                "must be an angle in degrees between -90 and 90, got {}",
                a.get_ref()
            ),
        )),
        Some(a) => Ok(*a.get_ref()),
        None => Ok(0.0),
    };
    let alpha = angle(&m.alpha, "mesh.alpha")?;
    let beta = angle(&m.beta, "mesh.beta")?;
    let length = m
        .wake_length
        .as_ref()
        .map(|l| positive(ctx, l, "mesh.wake_length"))
        .transpose()?;
    match &m.wakes {
        Some(w) if w.get_ref() == "auto" => Ok(Some((
            AutoWakes {
                alpha,
                beta,
                length,
            },
            w,
        ))),
        Some(w) if w.get_ref() == "none" => Ok(None),
        Some(w) => Err(ctx.at(
            w,
            "mesh.wakes",
            format!("must be \"auto\" or \"none\", got \"{}\"", w.get_ref()),
        )),
        None => Ok(None),
    }
}

/// `[mesh] farfield`, checked.
fn farfield_spec(
    ctx: &Ctx,
    f: &Spanned<super::schema::FarfieldTable>,
) -> Result<super::farfield::FarfieldSpec, CaseError> {
    let t = f.get_ref();
    let shape = super::farfield::FarfieldShape::parse(&t.shape)
        .map_err(|m| ctx.at(f, "mesh.farfield.shape", m))?;
    super::farfield::FarfieldSpec::new(shape, t.size)
        .map_err(|m| ctx.at(f, "mesh.farfield.size", m))
}

fn positive(ctx: &Ctx, v: &Spanned<f64>, key: &str) -> Result<f64, CaseError> {
    let x = *v.get_ref();
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(ctx.at(v, key, format!("must be a positive number, got {x}")))
    }
}

/// Mesh controls after defaults; `extent` is the model's size (tolerance default),
/// `default_size` the spacing when the file gives none (CAD cases).
fn controls(
    ctx: &Ctx,
    file: &CaseFile,
    extent: f64,
    default_size: Option<f64>,
) -> Result<MeshControls, CaseError> {
    let m = &file.mesh;
    let size = match (&m.size, default_size) {
        (Some(s), _) => positive(ctx, s, "mesh.size")?,
        (None, Some(s)) => s,
        (None, None) => {
            return Err(ctx.model(
                "[mesh]: missing key `size` (the background spacing; required unless `cad` gives the model)",
            ))
        }
    };
    let curvature_segments = match &m.curvature_segments {
        Some(n) if !curvature_segments_ok(*n.get_ref()) => {
            return Err(ctx.at(
                n,
                "mesh.curvature_segments",
                format!("must be 0 (off) or at least 3, got {}", n.get_ref()),
            ))
        }
        Some(n) => *n.get_ref(),
        None => 12.0,
    };
    let proximity_cells = match &m.proximity_cells {
        Some(n) if *n.get_ref() < 0.0 || !n.get_ref().is_finite() => {
            return Err(ctx.at(
                n,
                "mesh.proximity_cells",
                format!("must be 0 (off) or positive, got {}", n.get_ref()),
            ))
        }
        Some(n) => *n.get_ref(),
        None => PROXIMITY_CELLS,
    };
    let min_size = match &m.min_size {
        Some(v) => positive(ctx, v, "mesh.min_size")?,
        None => size / 100.0,
    };
    let tolerance = match &m.tolerance {
        Some(v) => positive(ctx, v, "mesh.tolerance")?,
        None => 1e-6 * extent.max(1e-300),
    };
    let prism_warp = match &m.prism_warp {
        Some(w) if !super::controls::prism_warp_ok(*w.get_ref()) => {
            return Err(ctx.at(
                w,
                "mesh.prism_warp",
                format!("must be between 0 and 90 degrees, got {}", w.get_ref()),
            ))
        }
        Some(w) => *w.get_ref(),
        None => crate::prisms::DEFAULT_MAX_WARP_DEGREES,
    };
    Ok(MeshControls {
        size,
        curvature_segments,
        proximity_cells,
        min_size,
        tolerance,
        prisms: m.prisms.as_ref().is_some_and(|p| *p.get_ref()),
        prism_warp,
    })
}

/// Diagonal of the box around every point the file gives.
fn model_extent(file: &CaseFile) -> f64 {
    let mut lo = DVec3::INFINITY;
    let mut hi = DVec3::NEG_INFINITY;
    let mut add = |p: P3| {
        lo = lo.min(v3(p));
        hi = hi.max(v3(p));
    };
    file.vertices.iter().for_each(|v| add(v.point));
    file.curves
        .iter()
        .flat_map(|c| &c.points)
        .for_each(|&p| add(p));
    for s in &file.surfaces {
        let s = s.get_ref();
        s.grid.iter().flatten().flatten().for_each(|&p| add(p));
        s.corners.iter().flatten().flatten().for_each(|&p| add(p));
    }
    if lo.x > hi.x {
        0.0
    } else {
        lo.distance(hi)
    }
}

fn surface(ctx: &Ctx, s: &Spanned<SurfaceEntry>) -> Result<Arc<dyn Surface>, CaseError> {
    let e = s.get_ref();
    let key = format!("surface '{}'", e.name.get_ref());
    match (&e.grid, &e.corners) {
        (Some(grid), None) => {
            let grid: Vec<Vec<DVec3>> = grid
                .iter()
                .map(|r| r.iter().map(|&p| v3(p)).collect())
                .collect();
            let surf = FergusonSurface::interpolate(&grid)
                .map_err(|err| ctx.at(&e.name, &format!("{key}.grid"), err.to_string()))?;
            Ok(Arc::new(surf))
        }
        (None, Some(c)) => {
            let p = c.map(|r| r.map(v3));
            let patch = match (&e.u_tangents, &e.v_tangents, &e.twists) {
                (None, None, None) => FergusonPatch::bilinear(p),
                (Some(pu), Some(pv), tw) => FergusonPatch::new(
                    p,
                    pu.map(|r| r.map(v3)),
                    pv.map(|r| r.map(v3)),
                    tw.map(|t| t.map(|r| r.map(v3))).unwrap_or([[DVec3::ZERO; 2]; 2]),
                ),
                _ => {
                    return Err(ctx.at(
                        &e.name,
                        &key,
                        "give both u_tangents and v_tangents (twists optional), or none for a bilinear patch",
                    ))
                }
            };
            Ok(Arc::new(patch))
        }
        _ => Err(ctx.at(
            &e.name,
            &key,
            "give exactly one of `grid` (points to interpolate) or `corners` (one patch)",
        )),
    }
}

fn build_model(ctx: &Ctx, file: &CaseFile, tol: f64) -> Result<Model, CaseError> {
    let vnames = index(
        ctx,
        &file.vertices.iter().map(|v| &v.name).collect::<Vec<_>>(),
        "vertex.name",
    )?;
    let cnames = index(
        ctx,
        &file.curves.iter().map(|c| &c.name).collect::<Vec<_>>(),
        "curve.name",
    )?;
    let snames = index(
        ctx,
        &file
            .surfaces
            .iter()
            .map(|s| &s.get_ref().name)
            .collect::<Vec<_>>(),
        "surface.name",
    )?;
    let enames = index(
        ctx,
        &file.edges.iter().map(|e| &e.name).collect::<Vec<_>>(),
        "edge.name",
    )?;
    let fnames = index(
        ctx,
        &file.faces.iter().map(|f| &f.name).collect::<Vec<_>>(),
        "face.name",
    )?;

    let mut model = Model {
        vertices: file
            .vertices
            .iter()
            .map(|v| Vertex {
                name: Some(v.name.get_ref().clone()),
                point: v3(v.point),
            })
            .collect(),
        ..Model::default()
    };
    let mut curves: Vec<Arc<FergusonCurve>> = Vec::new();
    for c in &file.curves {
        let pts: Vec<DVec3> = c.points.iter().map(|&p| v3(p)).collect();
        let key = format!("curve '{}'", c.name.get_ref());
        let curve = match &c.tangents {
            Some(t) => {
                FergusonCurve::with_tangents(&pts, &t.iter().map(|&p| v3(p)).collect::<Vec<_>>())
            }
            None => FergusonCurve::interpolate(&pts),
        }
        .map_err(|err| ctx.at(&c.name, &key, err.to_string()))?;
        curves.push(Arc::new(curve));
    }
    let surfaces: Vec<Arc<dyn Surface>> = file
        .surfaces
        .iter()
        .map(|s| surface(ctx, s))
        .collect::<Result<_, _>>()?;

    for e in &file.edges {
        let key = format!("edge '{}'", e.name.get_ref());
        let start = lookup(ctx, &vnames, &e.start, &format!("{key}.start"), "vertex")?;
        let end = lookup(ctx, &vnames, &e.end, &format!("{key}.end"), "vertex")?;
        let (a, b) = (model.vertices[start].point, model.vertices[end].point);
        let edge = if e.degenerate {
            if start != end {
                return Err(ctx.at(
                    &e.name,
                    &key,
                    "a degenerate edge starts and ends at the same vertex",
                ));
            }
            Edge {
                name: Some(e.name.get_ref().clone()),
                curve: None,
                range: (0.0, 1.0),
                start,
                end,
            }
        } else {
            let curve: Arc<dyn Curve> = match &e.curve {
                Some(cn) => {
                    curves[lookup(ctx, &cnames, cn, &format!("{key}.curve"), "curve")?].clone()
                }
                None => {
                    if a.distance(b) <= tol {
                        return Err(ctx.at(
                            &e.name,
                            &key,
                            "a straight edge (no `curve`) needs two distinct vertices",
                        ));
                    }
                    Arc::new(
                        FergusonCurve::interpolate(&[a, b])
                            .map_err(|err| ctx.at(&e.name, &key, err.to_string()))?,
                    )
                }
            };
            let range = curve.range();
            let (ca, cb) = (curve.point(range.0), curve.point(range.1));
            if ca.distance(a) > tol || cb.distance(b) > tol {
                let hint = if ca.distance(b) <= tol && cb.distance(a) <= tol {
                    " (the curve runs the other way: swap start and end)"
                } else {
                    ""
                };
                return Err(ctx.at(
                    &e.name,
                    &key,
                    format!(
                        "curve ends {} and {} do not meet vertices '{}' and '{}' within tolerance {tol:e}{hint}",
                        crate::geometry::Xyz(ca),
                        crate::geometry::Xyz(cb),
                        e.start.get_ref(),
                        e.end.get_ref()
                    ),
                ));
            }
            Edge {
                name: Some(e.name.get_ref().clone()),
                curve: Some(curve),
                range,
                start,
                end,
            }
        };
        model.edges.push(edge);
    }

    for f in &file.faces {
        let key = format!("face '{}'", f.name.get_ref());
        let s = lookup(
            ctx,
            &snames,
            &f.surface,
            &format!("{key}.surface"),
            "surface",
        )?;
        let mut loops = Vec::new();
        for names in &f.loops {
            let ids = names
                .iter()
                .map(|n| lookup(ctx, &enames, n, &format!("{key}.loops"), "edge"))
                .collect::<Result<Vec<_>, _>>()?;
            loops.push(Loop {
                uses: chain(&model, &ids),
                vertex: None,
            });
        }
        model.faces.push(Face {
            name: Some(f.name.get_ref().clone()),
            surface: surfaces[s].clone(),
            loops,
        });
    }
    for (fi, f) in file.faces.iter().enumerate() {
        attach_pcurves(ctx, &mut model, fi, &f.name, tol)?;
    }

    for r in &file.regions {
        let key = format!("region '{}'", r.name.get_ref());
        let faces = r
            .faces
            .iter()
            .map(|n| lookup(ctx, &fnames, n, &format!("{key}.faces"), "face"))
            .collect::<Result<Vec<_>, _>>()?;
        let embedded_faces = r
            .embedded_faces
            .iter()
            .map(|n| lookup(ctx, &fnames, n, &format!("{key}.embedded_faces"), "face"))
            .collect::<Result<Vec<_>, _>>()?;
        let embedded_edges = r
            .embedded_edges
            .iter()
            .map(|n| lookup(ctx, &enames, n, &format!("{key}.embedded_edges"), "edge"))
            .collect::<Result<Vec<_>, _>>()?;
        let shells = connected_shells(&model, &faces);
        model.regions.push(Region {
            name: Some(r.name.get_ref().clone()),
            shells,
            embedded_faces,
            embedded_edges,
        });
    }

    let errors = model.validation_errors();
    if !errors.is_empty() {
        return Err(ctx.model(format!(
            "the model is not valid:\n  {}",
            errors.join("\n  ")
        )));
    }
    model.orient().map_err(|e| ctx.model(e.to_string()))?;
    Ok(model)
}

/// Edge uses for a loop given as a chain of edge names: each use's direction is whatever makes
/// it start where the previous one ended (users never orient by hand). A chain that does not
/// connect keeps the edges forward; validation then reports the open loop.
fn chain(model: &Model, ids: &[usize]) -> Vec<EdgeUse> {
    let n = ids.len();
    let ends = |e: usize| (model.edges[e].start, model.edges[e].end);
    let mut uses: Vec<EdgeUse> = Vec::with_capacity(n);
    for (k, &e) in ids.iter().enumerate() {
        let (s, t) = ends(e);
        let reversed = if k == 0 {
            // Forward if our end touches the next edge (or there is no next edge).
            match ids.get(1) {
                Some(&next) => {
                    let (ns, nt) = ends(next);
                    !(t == ns || t == nt)
                }
                None => false,
            }
        } else {
            let prev = &uses[k - 1];
            let at = if prev.reversed {
                model.edges[prev.edge].start
            } else {
                model.edges[prev.edge].end
            };
            at != s && at == t
        };
        uses.push(EdgeUse {
            edge: e,
            reversed,
            pcurve: None,
        });
    }
    uses
}

/// Give every use on face `fi` a pcurve by projecting its edge; degenerate edges get the
/// straight (u,v) segment between their neighbours.
fn attach_pcurves(
    ctx: &Ctx,
    model: &mut Model,
    fi: usize,
    name: &Spanned<String>,
    tol: f64,
) -> Result<(), CaseError> {
    let surface = model.faces[fi].surface.clone();
    let key = format!("face '{}'", name.get_ref());
    let mut loops = std::mem::take(&mut model.faces[fi].loops);
    for lp in &mut loops {
        for u in &mut lp.uses {
            let e = &model.edges[u.edge];
            if let Some(c) = &e.curve {
                let pc =
                    crate::model::project_pcurve(surface.as_ref(), c.as_ref(), e.range, 10.0 * tol)
                        .map_err(|off| {
                            ctx.at(
                                name,
                                &key,
                                format!(
                            "{} does not lie on the face's surface: {:e} away at parameter {}",
                            model.edge_ref(u.edge),
                            off.distance,
                            off.t
                        ),
                            )
                        })?;
                u.pcurve = Some(Arc::new(pc));
            }
        }
        let n = lp.uses.len();
        for k in 0..n {
            if !model.edges[lp.uses[k].edge].is_degenerate() {
                continue;
            }
            let end_uv = |u: &EdgeUse, at_end: bool| -> Option<DVec2> {
                let pc = u.pcurve.as_ref()?;
                let e = &model.edges[u.edge];
                let t = if at_end != u.reversed {
                    e.range.1
                } else {
                    e.range.0
                };
                Some(pc.point(t))
            };
            let prev = end_uv(&lp.uses[(k + n - 1) % n], true);
            let next = end_uv(&lp.uses[(k + 1) % n], false);
            let (Some(a), Some(b)) = (prev, next) else {
                return Err(ctx.at(
                    name,
                    &key,
                    format!(
                        "{} is degenerate and has no neighbours to place it in (u,v)",
                        model.edge_ref(lp.uses[k].edge)
                    ),
                ));
            };
            let e = &model.edges[lp.uses[k].edge];
            let (a, b) = if lp.uses[k].reversed { (b, a) } else { (a, b) };
            lp.uses[k].pcurve = Some(Arc::new(Line2d {
                a,
                b,
                range: e.range,
            }));
        }
    }
    model.faces[fi].loops = loops;
    Ok(())
}

/// Split a region's faces into shells: faces connected through shared edges.
fn connected_shells(model: &Model, faces: &[usize]) -> Vec<Shell> {
    let mut parent: Vec<usize> = (0..faces.len()).collect();
    fn find(p: &mut [usize], i: usize) -> usize {
        let mut r = i;
        while p[r] != r {
            r = p[r];
        }
        p[i] = r;
        r
    }
    let mut owner: HashMap<usize, usize> = HashMap::new();
    for (k, &f) in faces.iter().enumerate() {
        for u in model.faces[f].loops.iter().flat_map(|l| &l.uses) {
            if let Some(&other) = owner.get(&u.edge) {
                let (a, b) = (find(&mut parent, k), find(&mut parent, other));
                parent[a] = b;
            } else {
                owner.insert(u.edge, k);
            }
        }
    }
    let mut groups: HashMap<usize, Shell> = HashMap::new();
    let mut order = Vec::new();
    for (k, &f) in faces.iter().enumerate() {
        let root = find(&mut parent, k);
        let shell = groups.entry(root).or_insert_with(|| {
            order.push(root);
            Shell::default()
        });
        shell.faces.push(FaceUse {
            face: f,
            reversed: false,
        });
    }
    order
        .into_iter()
        .filter_map(|r| groups.remove(&r))
        .collect()
}

fn sizing(
    ctx: &Ctx,
    file: &CaseFile,
    model: &Model,
    c: &MeshControls,
) -> Result<SizingField, CaseError> {
    let mut field = SizingField::uniform(c.size);
    for s in &file.sources {
        let e = s.get_ref();
        let pts: Vec<DVec3> = e.points.iter().map(|&p| v3(p)).collect();
        let shape = match (&e.kind, pts.as_slice()) {
            (SourceKind::Point, [a]) => SourceShape::Point(*a),
            (SourceKind::Line, [a, b]) => SourceShape::Line(*a, *b),
            (SourceKind::Triangle, [a, b, c]) => SourceShape::Triangle([*a, *b, *c]),
            (kind, _) => {
                return Err(ctx.at(
                    s,
                    "source.points",
                    format!(
                        "a {kind:?} source needs {} points, got {}",
                        match kind {
                            SourceKind::Point => 1,
                            SourceKind::Line => 2,
                            SourceKind::Triangle => 3,
                        },
                        pts.len()
                    ),
                ))
            }
        };
        if !(e.delta > 0.0 && e.r1 >= 0.0 && e.r2 > e.r1) {
            return Err(ctx.at(
                s,
                "source",
                format!(
                    "need delta > 0 and 0 <= r1 < r2, got delta {}, r1 {}, r2 {}",
                    e.delta, e.r1, e.r2
                ),
            ));
        }
        field.sources.push(Source {
            shape,
            delta1: e.delta,
            r1: e.r1,
            r2: e.r2,
        });
    }
    if let Some(bg) = &file.background {
        let nodes = bg
            .nodes
            .iter()
            .map(|n| DVec3::new(n[0], n[1], n[2]))
            .collect();
        let spacing = bg.nodes.iter().map(|n| n[3]).collect();
        field.background = Some(
            BackgroundMesh::new(nodes, spacing, bg.tets.clone()).map_err(|e| {
                match &file.mesh.size {
                    Some(s) => ctx.at(s, "background", e.to_string()),
                    None => ctx.model(format!("background: {e}")),
                }
            })?,
        );
    }
    field.set_local_limits(model, c);
    Ok(field)
}
