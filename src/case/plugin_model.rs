//! A CAD file read by a geometry plugin (`tetrafoil mesh body.analytic`, `[mesh] cad = ...`):
//! opened by the first plugin claiming its extension, made ready as any kernel's file is
//! ([`super::kernel_file::prepare`]: sewn, healed, fused with the plugin's operations where
//! it has them), set in a far field by the plugin's booleans when asked, then imported,
//! validated and oriented.

use super::farfield::{build_domain, FarfieldSpec, FlowDomain};
use super::kernel_file::{prepare, FarfieldRequest, KernelFile};
use crate::geometry::plugin::{Plugin, PluginSource};
use crate::model::foreign::model_from_foreign;
use crate::model::Model;
use glam::DVec3;
use std::path::Path;
use std::sync::Arc;

/// The oriented model of `path` as `plugin` reads it, and the diagonal of its bounding box.
pub(crate) fn load_plugin_model(
    plugin: &Arc<Plugin>,
    path: &Path,
    farfield: Option<FarfieldSpec>,
) -> Result<(Model, f64, Option<FlowDomain>), String> {
    let (source, extent) = prepare(PluginSource::open(plugin, path)?)?;
    let (source, domain) = match farfield {
        Some(spec) => {
            let (domain, flow) = build_domain(source, spec, extent)?;
            (domain, Some(flow))
        }
        None => (source, None),
    };
    let model = model_from_foreign(&source).map_err(|e| e.to_string())?;
    Ok((model, extent, domain))
}

impl KernelFile for PluginSource {
    fn kernel(&self) -> String {
        self.plugin().label()
    }
    fn bounding_box(&self) -> Option<Result<[DVec3; 2], String>> {
        PluginSource::bounding_box(self).map(|b| b.map(|[lo, hi]| [lo, hi].map(DVec3::from_array)))
    }
    fn sew(&self, tolerance: f64) -> Option<Result<Self, String>> {
        PluginSource::sew(self, tolerance)
    }
    fn heal(&self, tolerance: f64) -> Option<Result<Self, String>> {
        PluginSource::heal(self, tolerance)
    }
    fn fuse(&self, tolerance: f64) -> Option<Result<Self, String>> {
        PluginSource::fuse(self, tolerance)
    }
    fn solids_only(&self) -> Option<Result<Self, String>> {
        PluginSource::solids_only(self)
    }
    fn farfield(&self, r: &FarfieldRequest) -> Option<Result<Self, String>> {
        PluginSource::farfield(self, r.sphere, r.centre, r.half, r.symmetry, r.fuzzy)
    }
}
