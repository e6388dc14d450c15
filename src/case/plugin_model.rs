//! A CAD file read by a geometry plugin (`tetrafoil mesh body.analytic`, `[mesh] cad = ...`):
//! opened by the first plugin claiming its extension, sewn by the plugin when it has faces
//! but no solid and the plugin can sew, its touching solids imprinted when the plugin has
//! booleans, then imported, validated and oriented as any kernel's model.

use super::controls::SEW_STEPS;
use super::farfield::{FarfieldSpec, FlowDomain};
use crate::geometry::plugin::{Plugin, PluginSource};
use crate::model::foreign::{model_from_foreign, ForeignSource};
use crate::model::Model;
use glam::{DVec2, DVec3};
use std::path::Path;
use std::sync::Arc;

/// The oriented model of `path` as `plugin` reads it, and the diagonal of its bounding box.
pub(crate) fn load_plugin_model(
    plugin: &Arc<Plugin>,
    path: &Path,
    farfield: Option<FarfieldSpec>,
) -> Result<(Model, f64, Option<FlowDomain>), String> {
    if let Some(spec) = farfield {
        return Err(format!(
            "{}: a {} far field is built with OpenCASCADE's booleans, which the plugin \
             interface does not carry: give the flow domain in the file, or read a STEP file",
            path.display(),
            spec.shape.name()
        ));
    }
    let source = PluginSource::open(plugin, path)?;
    let source = if source.topology().solids.is_empty() {
        sew(source, path)?
    } else {
        source
    };
    let source = if source.topology().solids.len() >= 2 {
        match source.fuse(1e-6 * vertex_extent(&source)) {
            Some(fused) => fused?,
            None => {
                log::warn!(
                    "{}: {} solids, and {} has no booleans: solids that touch must already \
                     share their contact faces",
                    path.display(),
                    source.topology().solids.len(),
                    plugin.label()
                );
                source
            }
        }
    } else {
        source
    };
    let model = model_from_foreign(&source).map_err(|e| e.to_string())?;
    let extent = model_extent(&model);
    if !(extent.is_finite() && extent > 0.0) {
        return Err(format!(
            "{}: the model is empty (no extent)",
            path.display()
        ));
    }
    Ok((model, extent, None))
}

/// Sew a file without solids at the tolerances of [`SEW_STEPS`], when the plugin sews.
fn sew(source: PluginSource, path: &Path) -> Result<PluginSource, String> {
    let faces = source.topology().faces.len();
    let extent = vertex_extent(&source);
    for step in SEW_STEPS {
        match source.sew(step * extent) {
            None => {
                return Err(format!(
                    "{}: contains no solid ({faces} faces), and {} does not sew",
                    path.display(),
                    source.plugin().label()
                ))
            }
            Some(Ok(sewn)) if !sewn.topology().solids.is_empty() => {
                log::warn!(
                    "{} has no solid: sewed its {faces} faces at tolerance {:.3e} into {} solid(s)",
                    path.display(),
                    step * extent,
                    sewn.topology().solids.len()
                );
                return Ok(sewn);
            }
            Some(Ok(_)) => {}
            Some(Err(e)) => return Err(e),
        }
    }
    Err(format!(
        "{}: contains no solid ({faces} faces), and sewing at {} of its size closes none",
        path.display(),
        SEW_STEPS.map(|s| format!("{s:e}")).join(", ")
    ))
}

/// The diagonal of the vertices' bounding box.
fn vertex_extent(source: &PluginSource) -> f64 {
    let points = source
        .topology()
        .vertices
        .iter()
        .map(|v| DVec3::from_array(v.point));
    diagonal(points)
}

/// The diagonal of the model's bounding box, from its vertices and a 5 × 5 grid of points on
/// each face's parameter rectangle (a sphere has one vertex).
fn model_extent(model: &Model) -> f64 {
    let on_faces = model.faces.iter().flat_map(|f| {
        let b = f.surface.bounds();
        (0..5).flat_map(move |i| {
            (0..5).map(move |j| {
                let s = DVec2::new(i as f64 / 4.0, j as f64 / 4.0);
                f.surface.point(DVec2::new(
                    b.u.0 + s.x * (b.u.1 - b.u.0),
                    b.v.0 + s.y * (b.v.1 - b.v.0),
                ))
            })
        })
    });
    diagonal(model.vertices.iter().map(|v| v.point).chain(on_faces))
}

fn diagonal(points: impl Iterator<Item = DVec3>) -> f64 {
    let (lo, hi) = points.fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    );
    if lo.x > hi.x {
        0.0
    } else {
        lo.distance(hi)
    }
}
