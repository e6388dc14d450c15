//! A plugin's curves, pcurves and surfaces behind the geometry traits. Each query is one call
//! through the table (the batched entries with n = 1). A call that fails, or answers a value
//! that is not finite, records a fault naming the plugin, the file, the entity and the query
//! in the model's [`FaultLog`](crate::geometry::FaultLog) and answers zeros, which stop
//! Newton iterations rather than send them astray; the pipeline then stops the run with the
//! fault. The optional queries (closest point, circle) fall back to the generic Newton
//! methods when the plugin leaves them out or finds nothing.

use super::handle::Handle;
use crate::geometry::{
    kernel, Circle, CircleHint, CircleHit, Curve, Curve2d, CurveDerivs, Range1, Surface,
    SurfaceBounds, SurfaceDerivs,
};
use glam::{DVec2, DVec3};
use std::sync::Arc;
use tetrafoil_plugin_abi as abi;

/// Most hits asked of a plugin's circle intersection.
const MAX_CIRCLE_HITS: usize = 16;

fn v3(a: &[f64]) -> DVec3 {
    DVec3::new(a[0], a[1], a[2])
}

fn label(kind: &str, index: usize, name: &Option<String>) -> String {
    match name {
        Some(n) => format!("{kind} {index} '{n}'"),
        None => format!("{kind} {index}"),
    }
}

/// A plugin edge's 3-D curve.
pub struct PluginCurve {
    handle: Arc<Handle>,
    edge: usize,
    range: Range1,
}

impl PluginCurve {
    pub(super) fn new(handle: Arc<Handle>, edge: usize, range: Range1) -> Self {
        PluginCurve {
            handle,
            edge,
            range,
        }
    }
}

impl Curve for PluginCurve {
    fn range(&self) -> Range1 {
        self.range
    }
    fn point(&self, t: f64) -> DVec3 {
        let what = || format!("edge {}: curve_points at t = {t}", self.edge);
        let answer = match self.handle.plugin.table.curve_points {
            Some(f) => self
                .handle
                .eval::<3>(f, self.edge as i32, &[t], what)
                .map(|o| v3(&o)),
            None => return self.derivs(t).p,
        };
        answer.unwrap_or(DVec3::ZERO)
    }
    fn derivs(&self, t: f64) -> CurveDerivs {
        let f = self
            .handle
            .plugin
            .table
            .curve_derivs
            .expect("checked at load");
        let what = || format!("edge {}: curve_derivs at t = {t}", self.edge);
        let o = self
            .handle
            .eval::<9>(f, self.edge as i32, &[t], what)
            .unwrap_or([0.0; 9]);
        CurveDerivs {
            p: v3(&o[0..3]),
            d1: v3(&o[3..6]),
            d2: v3(&o[6..9]),
        }
    }
    /// The plugin's closest point when it has one, checked by [`kernel::closest_parameter`].
    fn closest_parameter(&self, p: DVec3, hint: Option<f64>) -> Option<f64> {
        let found = self.handle.plugin.table.curve_closest.and_then(|f| {
            let hint_ptr = hint.as_ref().map_or(std::ptr::null(), |h| h as *const f64);
            let what = || format!("edge {}: curve_closest to {p}", self.edge);
            let (raw, edge, q) = (self.handle.raw, self.edge as i32, p.to_array());
            // SAFETY: the header's curve_closest: p is 3 doubles, hint 1 or NULL, out 1.
            self.handle.optional::<1>(
                |out, err| unsafe { f(raw, edge, q.as_ptr(), hint_ptr, out.as_mut_ptr(), err) },
                what,
            )
        });
        kernel::closest_parameter(self, p, hint, found.map(|[t]| t))
    }
}

/// A plugin edge use's pcurve, in the edge's parameter.
pub struct PluginPcurve {
    handle: Arc<Handle>,
    index: i32,
    face: usize,
    range: Range1,
}

impl PluginPcurve {
    pub(super) fn new(handle: Arc<Handle>, index: i32, face: usize, range: Range1) -> Self {
        PluginPcurve {
            handle,
            index,
            face,
            range,
        }
    }
}

impl Curve2d for PluginPcurve {
    fn range(&self) -> Range1 {
        self.range
    }
    fn point(&self, t: f64) -> DVec2 {
        self.derivs(t).0
    }
    fn derivs(&self, t: f64) -> (DVec2, DVec2, DVec2) {
        let f = self
            .handle
            .plugin
            .table
            .pcurve_derivs
            .expect("checked at load");
        let what = || {
            format!(
                "face {}: edge use {}: pcurve_derivs at t = {t}",
                self.face, self.index
            )
        };
        let o = self
            .handle
            .eval::<6>(f, self.index, &[t], what)
            .unwrap_or([0.0; 6]);
        (
            DVec2::new(o[0], o[1]),
            DVec2::new(o[2], o[3]),
            DVec2::new(o[4], o[5]),
        )
    }
}

/// A plugin face's surface.
pub struct PluginSurface {
    handle: Arc<Handle>,
    face: usize,
    name: Option<String>,
    bounds: SurfaceBounds,
}

impl PluginSurface {
    pub(super) fn new(
        handle: Arc<Handle>,
        face: usize,
        name: Option<String>,
        bounds: SurfaceBounds,
    ) -> Self {
        PluginSurface {
            handle,
            face,
            name,
            bounds,
        }
    }

    fn what(&self, query: &str, uv: DVec2) -> String {
        format!(
            "{}: {query} at (u, v) = ({}, {})",
            label("face", self.face, &self.name),
            uv.x,
            uv.y
        )
    }
}

impl Surface for PluginSurface {
    fn bounds(&self) -> SurfaceBounds {
        self.bounds
    }
    fn point(&self, uv: DVec2) -> DVec3 {
        match self.handle.plugin.table.surface_points {
            Some(f) => (self.handle)
                .eval::<3>(f, self.face as i32, &uv.to_array(), || {
                    self.what("surface_points", uv)
                })
                .map_or(DVec3::ZERO, |o| v3(&o)),
            None => self.derivs(uv).p,
        }
    }
    fn derivs(&self, uv: DVec2) -> SurfaceDerivs {
        let f = self
            .handle
            .plugin
            .table
            .surface_derivs
            .expect("checked at load");
        let o = (self.handle)
            .eval::<18>(f, self.face as i32, &uv.to_array(), || {
                self.what("surface_derivs", uv)
            })
            .unwrap_or([0.0; 18]);
        SurfaceDerivs {
            p: v3(&o[0..3]),
            du: v3(&o[3..6]),
            dv: v3(&o[6..9]),
            duu: v3(&o[9..12]),
            duv: v3(&o[12..15]),
            dvv: v3(&o[15..18]),
        }
    }
    /// The plugin's closest point when it has one, checked by [`kernel::closest_uv`].
    fn closest_uv(&self, p: DVec3, hint: Option<DVec2>) -> Option<DVec2> {
        let found = self.handle.plugin.table.surface_closest.and_then(|f| {
            let h = hint.map(|h| h.to_array());
            let hint_ptr = h.as_ref().map_or(std::ptr::null(), |h| h.as_ptr());
            let (raw, face, q) = (self.handle.raw, self.face as i32, p.to_array());
            // SAFETY: the header's surface_closest: p 3 doubles, hint 2 or NULL, out 2.
            self.handle.optional::<2>(
                |out, err| unsafe { f(raw, face, q.as_ptr(), hint_ptr, out.as_mut_ptr(), err) },
                || {
                    format!(
                        "{}: surface_closest to {p}",
                        label("face", self.face, &self.name)
                    )
                },
            )
        });
        kernel::closest_uv(self, p, hint, found.map(DVec2::from_array))
    }
    /// The plugin's hits on the whole circle when it has them, through
    /// [`kernel::intersect_circle`]; `TF_NOT_FOUND` means it does not intersect this surface.
    fn intersect_circle(&self, circle: &Circle, hint: &CircleHint) -> Option<CircleHit> {
        kernel::intersect_circle(self, circle, hint, || self.circle_hits(circle))
    }
}

impl PluginSurface {
    /// Every hit of the plugin's `surface_circle`; `None` when it has none or says
    /// `TF_NOT_FOUND`, or fails (a fault).
    fn circle_hits(&self, circle: &Circle) -> Option<Vec<CircleHit>> {
        let f = self.handle.plugin.table.surface_circle?;
        let mut hits = [0.0; 6 * MAX_CIRCLE_HITS];
        let mut n = 0usize;
        let (c, a, x) = (
            circle.centre.to_array(),
            circle.axis().to_array(),
            circle.x_axis.to_array(),
        );
        let (raw, face) = (self.handle.raw, self.face as i32);
        // SAFETY: the header's surface_circle: three 3-vectors in, room for MAX_CIRCLE_HITS.
        let result = self.handle.plugin.call(|err| unsafe {
            f(
                raw,
                face,
                c.as_ptr(),
                a.as_ptr(),
                x.as_ptr(),
                circle.radius,
                MAX_CIRCLE_HITS,
                hits.as_mut_ptr(),
                &mut n,
                err,
            )
        });
        match result {
            Ok(abi::OK) => Some(
                hits.chunks_exact(6)
                    .take(n.min(MAX_CIRCLE_HITS))
                    .map(|h| CircleHit {
                        theta: h[0],
                        uv: DVec2::new(h[1], h[2]),
                        point: v3(&h[3..6]),
                    })
                    .collect(),
            ),
            Ok(_) => None,
            Err(e) => {
                let what = || format!("{}: surface_circle", label("face", self.face, &self.name));
                self.handle.record_failure(what, &e);
                None
            }
        }
    }
}
