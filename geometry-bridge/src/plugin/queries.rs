//! The OCCT plugin's entries: each checks its arguments, runs inside `guard` (a panic becomes
//! `TF_ERR_INTERNAL`, never an unwind into the caller) and answers through the interface's
//! buffers. Evaluation nudges inwards where OCCT refuses (`crate::nudge`); projection and
//! circle intersection are OCCT's own, and the core decides what to keep of them.

use super::model::PluginModel;
use crate::{CadModel, Farfield, OuterShape, SymmetryPlane};
use std::ffi::{c_char, CStr};
use std::panic::{catch_unwind, AssertUnwindSafe};
use tetrafoil_plugin_abi as abi;

/// Run `f`; a panic is an internal error naming where it happened.
fn guard(err: *mut abi::Error, what: &str, f: impl FnOnce() -> Result<(), Fail>) -> abi::Status {
    let result = catch_unwind(AssertUnwindSafe(f)).unwrap_or_else(|p| {
        let text = (p.downcast_ref::<&str>().map(|s| s.to_string()))
            .or_else(|| p.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "a panic".into());
        Err(Fail::new(
            abi::ERR_INTERNAL,
            0,
            -1,
            format!("{what}: {text}"),
        ))
    });
    match result {
        Ok(()) => abi::OK,
        Err(f) => {
            if let Some(e) = unsafe { err.as_mut() } {
                e.set(f.kind, f.entity, &f.message);
            }
            f.status
        }
    }
}

/// A failed entry: status, entity and message.
pub struct Fail {
    status: abi::Status,
    kind: i32,
    entity: i32,
    message: String,
}

impl Fail {
    fn new(status: abi::Status, kind: i32, entity: i32, message: String) -> Self {
        Fail {
            status,
            kind,
            entity,
            message,
        }
    }
    fn not_found() -> Self {
        Fail::new(abi::NOT_FOUND, 0, -1, String::new())
    }
}

/// The model behind a handle, and the entity's index checked against `len`.
///
/// # Safety
/// `m` is NULL or a model this plugin made and has not closed.
unsafe fn model_and<'a>(
    m: *const abi::Model,
    index: i32,
    len: impl Fn(&PluginModel) -> usize,
    kind: i32,
) -> Result<(&'a PluginModel, usize), Fail> {
    let model = (m as *const PluginModel)
        .as_ref()
        .ok_or_else(|| Fail::new(abi::ERR_INTERNAL, 0, -1, "no model given".into()))?;
    match usize::try_from(index).ok().filter(|&i| i < len(model)) {
        Some(i) => Ok((model, i)),
        None => Err(Fail::new(
            abi::ERR_ENTITY,
            kind,
            index,
            format!("there is no entity {index} (the model has {})", len(model)),
        )),
    }
}

/// `n` inputs of `k` values and room for `n` outputs of `o` values.
///
/// # Safety
/// The pointers hold at least that many values (the interface's contract).
unsafe fn buffers<'a>(
    n: usize,
    input: *const f64,
    k: usize,
    out: *mut f64,
    o: usize,
) -> Result<(&'a [f64], &'a mut [f64]), Fail> {
    if n == 0 {
        return Ok((&[], &mut []));
    }
    if input.is_null() || out.is_null() {
        return Err(Fail::new(abi::ERR_INTERNAL, 0, -1, "NULL buffer".into()));
    }
    Ok((
        std::slice::from_raw_parts(input, n * k),
        std::slice::from_raw_parts_mut(out, n * o),
    ))
}

fn eval_failed(kind: i32, entity: usize, what: String) -> Fail {
    Fail::new(
        abi::ERR_EVAL,
        kind,
        entity as i32,
        format!("OpenCASCADE cannot evaluate {what}, nor anywhere nearer the middle of its domain"),
    )
}

pub unsafe extern "C" fn open_file(
    path: *const c_char,
    out: *mut *mut abi::Model,
    err: *mut abi::Error,
) -> abi::Status {
    guard(err, "open_file", || {
        if path.is_null() || out.is_null() {
            return Err(Fail::new(
                abi::ERR_INTERNAL,
                0,
                -1,
                "no path or no output".into(),
            ));
        }
        let bytes = CStr::from_ptr(path).to_bytes();
        let path = std::path::Path::new(
            std::str::from_utf8(bytes)
                .map_err(|_| Fail::new(abi::ERR_IO, 0, -1, "the path is not UTF-8".into()))?,
        );
        let cad = CadModel::read(path).map_err(|e| Fail::new(abi::ERR_IO, 0, -1, e.to_string()))?;
        adopt(cad, out)
    })
}

/// Hand a new model to the caller.
unsafe fn adopt(cad: CadModel, out: *mut *mut abi::Model) -> Result<(), Fail> {
    let model = PluginModel::new(cad).map_err(|m| Fail::new(abi::ERR_FORMAT, 0, -1, m))?;
    *out = Box::into_raw(Box::new(model)) as *mut abi::Model;
    Ok(())
}

pub unsafe extern "C" fn close(m: *mut abi::Model) {
    if !m.is_null() {
        let _ = catch_unwind(|| drop(Box::from_raw(m as *mut PluginModel)));
    }
}

pub unsafe extern "C" fn topology(
    m: *const abi::Model,
    out: *mut abi::Topology,
    err: *mut abi::Error,
) -> abi::Status {
    guard(err, "topology", || {
        let (model, _) = model_and(m, 0, |_| 1, 0)?;
        let out = out
            .as_mut()
            .ok_or_else(|| Fail::new(abi::ERR_INTERNAL, 0, -1, "no output".into()))?;
        *out = model.topology();
        Ok(())
    })
}

pub unsafe extern "C" fn curve_derivs(
    m: *const abi::Model,
    edge: i32,
    n: usize,
    t: *const f64,
    out: *mut f64,
    err: *mut abi::Error,
) -> abi::Status {
    guard(err, "curve_derivs", || {
        let (model, e) = model_and(m, edge, |x| x.curves.len(), abi::ENTITY_EDGE)?;
        let curve = model.curves[e].as_ref().ok_or_else(|| {
            Fail::new(
                abi::ERR_ENTITY,
                abi::ENTITY_EDGE,
                edge,
                "a degenerate edge has no curve".into(),
            )
        })?;
        let (t, out) = buffers(n, t, 1, out, 9)?;
        for (&t, o) in t.iter().zip(out.chunks_exact_mut(9)) {
            let d = curve
                .derivs_nudged(t)
                .ok_or_else(|| eval_failed(abi::ENTITY_EDGE, e, format!("edge {e} at t = {t}")))?;
            o[0..3].copy_from_slice(&d.p);
            o[3..6].copy_from_slice(&d.d1);
            o[6..9].copy_from_slice(&d.d2);
        }
        Ok(())
    })
}

pub unsafe extern "C" fn pcurve_derivs(
    m: *const abi::Model,
    edge_use: i32,
    n: usize,
    t: *const f64,
    out: *mut f64,
    err: *mut abi::Error,
) -> abi::Status {
    guard(err, "pcurve_derivs", || {
        let (model, u) = model_and(m, edge_use, |x| x.pcurves.len(), abi::ENTITY_USE)?;
        let (pcurve, edge) = &model.pcurves[u];
        let same = pcurve.same_parameter(*edge);
        let (t, out) = buffers(n, t, 1, out, 6)?;
        for (&t, o) in t.iter().zip(out.chunks_exact_mut(6)) {
            let (s, k) = if same {
                (t, 1.0)
            } else {
                pcurve.edge_parameter(*edge, t)
            };
            let d = pcurve.derivs_nudged(s).ok_or_else(|| {
                eval_failed(abi::ENTITY_USE, u, format!("edge use {u} at t = {t}"))
            })?;
            o[0..2].copy_from_slice(&d.p);
            o[2..4].copy_from_slice(&[d.d1[0] * k, d.d1[1] * k]);
            o[4..6].copy_from_slice(&[d.d2[0] * k * k, d.d2[1] * k * k]);
        }
        Ok(())
    })
}

pub unsafe extern "C" fn surface_derivs(
    m: *const abi::Model,
    face: i32,
    n: usize,
    uv: *const f64,
    out: *mut f64,
    err: *mut abi::Error,
) -> abi::Status {
    guard(err, "surface_derivs", || {
        let (model, f) = model_and(m, face, |x| x.surfaces.len(), abi::ENTITY_FACE)?;
        let surface = &model.surfaces[f];
        let (uv, out) = buffers(n, uv, 2, out, 18)?;
        for (uv, o) in uv.chunks_exact(2).zip(out.chunks_exact_mut(18)) {
            let d = surface.derivs_nudged(uv[0], uv[1]).ok_or_else(|| {
                eval_failed(
                    abi::ENTITY_FACE,
                    f,
                    format!("face {f} at (u, v) = ({}, {})", uv[0], uv[1]),
                )
            })?;
            for (k, v) in [d.p, d.du, d.dv, d.duu, d.duv, d.dvv].iter().enumerate() {
                o[3 * k..3 * k + 3].copy_from_slice(v);
            }
        }
        Ok(())
    })
}

pub unsafe extern "C" fn curve_closest(
    m: *const abi::Model,
    edge: i32,
    p: *const f64,
    hint: *const f64,
    t: *mut f64,
    err: *mut abi::Error,
) -> abi::Status {
    guard(err, "curve_closest", || {
        let (model, e) = model_and(m, edge, |x| x.curves.len(), abi::ENTITY_EDGE)?;
        let curve = model.curves[e].as_ref().ok_or_else(Fail::not_found)?;
        let (p, out) = buffers(1, p, 3, t, 1)?;
        let hint = hint.as_ref().copied();
        let (found, _) = curve
            .project([p[0], p[1], p[2]], hint)
            .filter(|(t, d)| t.is_finite() && d.is_finite())
            .ok_or_else(Fail::not_found)?;
        out[0] = found;
        Ok(())
    })
}

pub unsafe extern "C" fn surface_closest(
    m: *const abi::Model,
    face: i32,
    p: *const f64,
    hint: *const f64,
    uv: *mut f64,
    err: *mut abi::Error,
) -> abi::Status {
    guard(err, "surface_closest", || {
        let (model, f) = model_and(m, face, |x| x.surfaces.len(), abi::ENTITY_FACE)?;
        let (p, out) = buffers(1, p, 3, uv, 2)?;
        let hint = (!hint.is_null()).then(|| [*hint, *hint.add(1)]);
        let found = model.surfaces[f]
            .project([p[0], p[1], p[2]], hint)
            .filter(|uv| uv.iter().all(|x| x.is_finite()))
            .ok_or_else(Fail::not_found)?;
        out.copy_from_slice(&found);
        Ok(())
    })
}

/// GeomAPI_IntCS on plane, cylinder, cone, sphere and torus, where it is closed-form and cheap;
/// on other surfaces it sorts boxes over the whole surface on every call, so the plugin answers
/// `TF_NOT_FOUND` and the core's Newton search from the front's hint answers instead.
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn surface_circle(
    m: *const abi::Model,
    face: i32,
    centre: *const f64,
    axis: *const f64,
    x_axis: *const f64,
    radius: f64,
    max_hits: usize,
    hits: *mut f64,
    n_hits: *mut usize,
    err: *mut abi::Error,
) -> abi::Status {
    guard(err, "surface_circle", || {
        let (model, f) = model_and(m, face, |x| x.surfaces.len(), abi::ENTITY_FACE)?;
        let surface = &model.surfaces[f];
        if !surface.is_elementary() {
            return Err(Fail::not_found());
        }
        let v3 = |p: *const f64| [*p, *p.add(1), *p.add(2)];
        if centre.is_null() || axis.is_null() || x_axis.is_null() || n_hits.is_null() {
            return Err(Fail::new(abi::ERR_INTERNAL, 0, -1, "NULL argument".into()));
        }
        let found = surface
            .intersect_circle(v3(centre), v3(axis), v3(x_axis), radius)
            .unwrap_or_default();
        let n = found.len().min(max_hits);
        if n > 0 && hits.is_null() {
            return Err(Fail::new(abi::ERR_INTERNAL, 0, -1, "NULL hits".into()));
        }
        for (k, h) in found.iter().take(n).enumerate() {
            let o = std::slice::from_raw_parts_mut(hits.add(6 * k), 6);
            o.copy_from_slice(&[
                h.theta, h.uv[0], h.uv[1], h.point[0], h.point[1], h.point[2],
            ]);
        }
        *n_hits = n;
        Ok(())
    })
}

pub unsafe extern "C" fn bounding_box(
    m: *const abi::Model,
    out: *mut f64,
    err: *mut abi::Error,
) -> abi::Status {
    guard(err, "bounding_box", || {
        let (model, _) = model_and(m, 0, |_| 1, 0)?;
        let b = model
            .cad
            .bounding_box()
            .map_err(|e| Fail::new(abi::ERR_EVAL, 0, -1, e.to_string()))?
            .ok_or_else(Fail::not_found)?;
        let (_, o) = buffers(1, out, 0, out, 6)?;
        o.copy_from_slice(&[b.min[0], b.min[1], b.min[2], b.max[0], b.max[1], b.max[2]]);
        Ok(())
    })
}

/// A new model from an operation on `m`'s `CadModel`.
unsafe fn derived(
    m: *const abi::Model,
    out: *mut *mut abi::Model,
    err: *mut abi::Error,
    what: &str,
    op: impl FnOnce(&CadModel) -> Result<CadModel, crate::CadError>,
) -> abi::Status {
    guard(err, what, || {
        let (model, _) = model_and(m, 0, |_| 1, 0)?;
        if out.is_null() {
            return Err(Fail::new(abi::ERR_INTERNAL, 0, -1, "no output".into()));
        }
        let cad = op(&model.cad).map_err(|e| Fail::new(abi::ERR_EVAL, 0, -1, e.to_string()))?;
        adopt(cad, out)
    })
}

pub unsafe extern "C" fn sew(
    m: *const abi::Model,
    tolerance: f64,
    out: *mut *mut abi::Model,
    err: *mut abi::Error,
) -> abi::Status {
    derived(m, out, err, "sew", |c| c.sew(tolerance).map(|r| r.0))
}

pub unsafe extern "C" fn heal(
    m: *const abi::Model,
    tolerance: f64,
    out: *mut *mut abi::Model,
    err: *mut abi::Error,
) -> abi::Status {
    derived(m, out, err, "heal", |c| c.heal(tolerance).map(|r| r.0))
}

pub unsafe extern "C" fn solids_only(
    m: *const abi::Model,
    out: *mut *mut abi::Model,
    err: *mut abi::Error,
) -> abi::Status {
    derived(m, out, err, "solids_only", |c| c.solids_only())
}

pub unsafe extern "C" fn fuse(
    m: *const abi::Model,
    tolerance: f64,
    out: *mut *mut abi::Model,
    err: *mut abi::Error,
) -> abi::Status {
    derived(m, out, err, "fuse", |c| {
        c.fuse_solids(tolerance).map(|r| r.0)
    })
}

pub unsafe extern "C" fn farfield(
    m: *const abi::Model,
    spec: *const abi::Farfield,
    out: *mut *mut abi::Model,
    err: *mut abi::Error,
) -> abi::Status {
    let Some(spec) = spec.as_ref().copied() else {
        return guard(err, "farfield", || {
            Err(Fail::new(
                abi::ERR_INTERNAL,
                0,
                -1,
                "no far-field spec".into(),
            ))
        });
    };
    let shape = match spec.shape {
        abi::FARFIELD_SPHERE => OuterShape::Sphere,
        _ => OuterShape::Box,
    };
    let symmetry = (0..3)
        .contains(&spec.symmetry_axis)
        .then_some(SymmetryPlane {
            axis: spec.symmetry_axis as usize,
            at: spec.symmetry_at,
            positive: spec.symmetry_side >= 0,
        });
    let f = Farfield {
        shape,
        centre: spec.centre,
        half: spec.half,
        symmetry,
        fuzzy: spec.fuzzy,
    };
    derived(m, out, err, "farfield", |c| c.farfield_domain(&f))
}
