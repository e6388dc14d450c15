//! Sewing, healing and the general fuse of solids, each returning a new model and a short report of what changed.
use crate::error::CadError;
use crate::ffi::bridge as ffi;
use crate::model::{occt, CadModel};
use crate::topology::Counts;

/// What the general fuse did: the counts before and after.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FuseReport {
    pub before: Counts,
    pub after: Counts,
}

/// What sewing did (BRepBuilderAPI_Sewing, then closed shells made into solids).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SewReport {
    pub before: Counts,
    pub after: Counts,
    /// Edges still bounding only one face after sewing.
    pub free_edges: usize,
    /// Edges shared by more than two faces after sewing.
    pub multiple_edges: usize,
    pub degenerated: usize,
    pub closed_shells: usize,
    pub open_shells: usize,
    pub solids_made: usize,
}

/// What ShapeFix_Shape changed, as entity counts before and after.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HealReport {
    pub before: Counts,
    pub after: Counts,
    /// Free (single-use) edges before and after.
    pub free_edges: (usize, usize),
}

impl HealReport {
    pub fn changed(&self) -> bool {
        self.before != self.after || self.free_edges.0 != self.free_edges.1
    }
}

impl CadModel {
    /// Sews faces closer than `tolerance` into shells; closed shells become (outward oriented)
    /// solids. Face and solid names are carried over.
    pub fn sew(&self, tolerance: f64) -> Result<(CadModel, SewReport), CadError> {
        let _guard = crate::model::translator_lock();
        let mut s = ffi::SewStats::default();
        let idx = ffi::sew_shape(&self.index, tolerance, &mut s)
            .map_err(|e| occt(self.file(), "sewing", e))?;
        let model = CadModel::new(self.file().to_string(), idx)?;
        let n = |x: i32| x.max(0) as usize;
        let report = SewReport {
            before: self.topology().counts(),
            after: model.topology().counts(),
            free_edges: n(s.free_edges),
            multiple_edges: n(s.multiple_edges),
            degenerated: n(s.degenerated),
            closed_shells: n(s.closed_shells),
            open_shells: n(s.open_shells),
            solids_made: n(s.solids_made),
        };
        Ok((model, report))
    }

    /// Imprints the contacts of the model's solids on each other (OCCT's general fuse, with
    /// `fuzzy` as the gap treated as contact; 0 for exact): touching solids then share the
    /// faces along their contact, and overlapping ones are split into the pieces inside one,
    /// the other or both. Names go to the pieces.
    pub fn fuse_solids(&self, fuzzy: f64) -> Result<(CadModel, FuseReport), CadError> {
        let _guard = crate::model::translator_lock();
        let idx = ffi::fuse_solids(&self.index, fuzzy)
            .map_err(|e| occt(self.file(), "the general fuse", e))?;
        let model = CadModel::new(self.file().to_string(), idx)?;
        let report = FuseReport {
            before: self.topology().counts(),
            after: model.topology().counts(),
        };
        Ok((model, report))
    }

    /// The model's solids alone: faces and open shells that belong to no solid (construction
    /// surfaces a CAD system wrote beside the part) are left out. Ids are those of the new
    /// model.
    pub fn solids_only(&self) -> Result<CadModel, CadError> {
        let _guard = crate::model::translator_lock();
        let idx = ffi::solids_only(&self.index)
            .map_err(|e| occt(self.file(), "keeping the solids", e))?;
        CadModel::new(self.file().to_string(), idx)
    }

    /// Faces that belong to no solid's shells, in id order.
    pub fn faces_outside_solids(&self) -> Vec<usize> {
        let t = self.topology();
        let mut inside = vec![false; t.faces.len()];
        for s in &t.solids {
            for &sh in &s.shells {
                for &(f, _) in &t.shells[sh].faces {
                    inside[f] = true;
                }
            }
        }
        (0..t.faces.len()).filter(|&f| !inside[f]).collect()
    }

    /// Runs ShapeFix_Shape with working precision `tolerance` (tolerances may grow up to
    /// 100 × that).
    pub fn heal(&self, tolerance: f64) -> Result<(CadModel, HealReport), CadError> {
        let _guard = crate::model::translator_lock();
        let idx =
            ffi::heal_shape(&self.index, tolerance).map_err(|e| occt(self.file(), "healing", e))?;
        let model = CadModel::new(self.file().to_string(), idx)?;
        let report = HealReport {
            before: self.topology().counts(),
            after: model.topology().counts(),
            free_edges: (
                self.topology().free_edges.len(),
                model.topology().free_edges.len(),
            ),
        };
        Ok((model, report))
    }
}
