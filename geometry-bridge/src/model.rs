//! `CadModel`: a shape read from a file, its numbered topology, and entry points to geometry.
use std::path::Path;

use cxx::UniquePtr;
use opencascade_sys::{b_rep_bnd_lib, b_rep_g_prop, b_rep_tools, bnd, g_prop};
use opencascade_sys::{if_select::IFSelect_ReturnStatus, iges_control, message};

use crate::curve::{OccCurve, OccPcurve};
use crate::error::{CadError, CadWarning};
use crate::ffi::bridge as ffi;
use crate::surface::OccSurface;
use crate::topology::CadTopology;

/// A CAD model held by OpenCASCADE. Not `Send`: the shape's topology is shared OCCT data. Ask
/// it for geometry handles (`surface`, `curve`, `pcurve`), which are independent and `Send + Sync`.
pub struct CadModel {
    file: String,
    pub(crate) index: UniquePtr<ffi::ShapeIndex>,
    topology: CadTopology,
}

/// An axis-aligned box (BRepBndLib, enlarged by the shapes' tolerances).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundingBox {
    pub min: [f64; 3],
    pub max: [f64; 3],
}

impl BoundingBox {
    /// Length of the diagonal: the model's length scale.
    pub fn diagonal(&self) -> f64 {
        (0..3)
            .map(|k| (self.max[k] - self.min[k]).powi(2))
            .sum::<f64>()
            .sqrt()
    }
}

/// Sub-shape kinds as the shim numbers them.
#[derive(Clone, Copy)]
pub(crate) enum Kind {
    Face = 2,
    Solid = 4,
    Whole = 5,
}

impl CadModel {
    /// Reads STEP (.step/.stp), IGES (.iges/.igs) or OCCT BREP (.brep/.brp) by extension.
    pub fn read(path: impl AsRef<Path>) -> Result<Self, CadError> {
        let path = path.as_ref();
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("step" | "stp") => Self::read_step(path),
            Some("iges" | "igs") => Self::read_iges(path),
            Some("brep" | "brp") => Self::read_brep(path),
            _ => Err(CadError::UnknownFormat {
                file: path.display().to_string(),
            }),
        }
    }

    /// Reads STEP through XDE, keeping the names of faces and solids.
    pub fn read_step(path: impl AsRef<Path>) -> Result<Self, CadError> {
        let file = existing(path.as_ref())?;
        let _guard = translator_lock();
        ffi::quiet_messages();
        let mut status = 0;
        let index =
            ffi::read_step_xde(&file, &mut status).map_err(|e| occt(&file, "STEP read", e))?;
        match status {
            0 => Self::new(file, index),
            1 => Err(CadError::Unreadable {
                file,
                format: "STEP",
            }),
            _ => Err(CadError::Empty { file }),
        }
    }

    /// Reads IGES (all roots transferred into one shape).
    pub fn read_iges(path: impl AsRef<Path>) -> Result<Self, CadError> {
        let file = existing(path.as_ref())?;
        let _guard = translator_lock();
        ffi::quiet_messages();
        let mut reader = iges_control::IGESControl_Reader_new();
        let status = iges_control::read_iges(reader.pin_mut(), file.clone());
        if status != IFSelect_ReturnStatus::IFSelect_RetDone {
            return Err(CadError::Unreadable {
                file,
                format: "IGES",
            });
        }
        let progress = message::Message_ProgressRange_new();
        if reader.pin_mut().TransferRoots(&progress) == 0 {
            return Err(CadError::Empty { file });
        }
        let shape = iges_control::one_shape_iges(&reader);
        Self::from_shape(file, &shape)
    }

    /// Reads an OCCT BREP file.
    pub fn read_brep(path: impl AsRef<Path>) -> Result<Self, CadError> {
        let file = existing(path.as_ref())?;
        let _guard = translator_lock();
        let shape = b_rep_tools::read(file.clone());
        if shape.is_null() {
            return Err(CadError::Unreadable {
                file,
                format: "BREP",
            });
        }
        Self::from_shape(file, &shape)
    }

    fn from_shape(
        file: String,
        shape: &UniquePtr<opencascade_sys::topo_ds::TopoDS_Shape>,
    ) -> Result<Self, CadError> {
        let Some(shape) = shape.as_ref().filter(|s| !s.IsNull()) else {
            return Err(CadError::Empty { file });
        };
        let index = ffi::index_shape(shape).map_err(|e| occt(&file, "indexing", e))?;
        Self::new(file, index)
    }

    pub(crate) fn new(file: String, index: UniquePtr<ffi::ShapeIndex>) -> Result<Self, CadError> {
        let mut raw = ffi::Topology::default();
        ffi::extract_topology(&index, &mut raw).map_err(|e| occt(&file, "topology", e))?;
        let topology = CadTopology::from_ffi(raw).map_err(|message| CadError::Topology {
            file: file.clone(),
            message,
        })?;
        if topology.faces.is_empty() && topology.edges.is_empty() {
            return Err(CadError::Empty { file });
        }
        Ok(Self {
            file,
            index,
            topology,
        })
    }

    /// The file this model came from (as given), for messages.
    pub fn file(&self) -> &str {
        &self.file
    }

    pub fn topology(&self) -> &CadTopology {
        &self.topology
    }

    /// Geometry of face `face` (independent copy).
    pub fn surface(&self, face: usize) -> Result<OccSurface, CadError> {
        self.check(face, self.topology.faces.len(), "face")?;
        let g = ffi::face_surface(&self.index, face as i32)
            .map_err(|e| occt(&self.file, "face surface", e))?;
        Ok(OccSurface::new(g))
    }

    /// 3-D curve of edge `edge`; `None` for an edge without one (degenerate edges).
    pub fn curve(&self, edge: usize) -> Result<Option<OccCurve>, CadError> {
        self.check(edge, self.topology.edges.len(), "edge")?;
        let g = ffi::edge_curve(&self.index, edge as i32)
            .map_err(|e| occt(&self.file, "edge curve", e))?;
        Ok((!g.is_null()).then(|| OccCurve::new(g)))
    }

    /// Pcurve of use `use_index` of loop `loop_index` of face `face` (as in `Face::loops`).
    pub fn pcurve(
        &self,
        face: usize,
        loop_index: usize,
        use_index: usize,
    ) -> Result<OccPcurve, CadError> {
        self.check(face, self.topology.faces.len(), "face")?;
        let g = ffi::use_pcurve(
            &self.index,
            face as i32,
            loop_index as i32,
            use_index as i32,
        )
        .map_err(|e| occt(&self.file, "pcurve", e))?;
        Ok(OccPcurve::new(g))
    }

    /// Area of face `face` (BRepGProp).
    pub fn face_area(&self, face: usize) -> Result<f64, CadError> {
        self.check(face, self.topology.faces.len(), "face")?;
        let shape = self.sub(Kind::Face, face)?;
        let mut props = g_prop::GProps_new();
        b_rep_g_prop::BRepGProp::SurfaceProperties(&shape, props.pin_mut(), false, false);
        Ok(props.Mass())
    }

    /// Volume enclosed by solid `solid` (BRepGProp; negative if the solid is inside out).
    pub fn solid_volume(&self, solid: usize) -> Result<f64, CadError> {
        self.check(solid, self.topology.solids.len(), "solid")?;
        let shape = self.sub(Kind::Solid, solid)?;
        let mut props = g_prop::GProps_new();
        b_rep_g_prop::BRepGProp::VolumeProperties(&shape, props.pin_mut(), false, false, false);
        Ok(props.Mass())
    }

    /// Area of face `face` by BRepGProp's adaptive integration to relative error `eps`:
    /// slower than [`Self::face_area`], and right where the fixed-order rule is not (faces
    /// bounded by dense B-spline pcurves).
    pub fn face_area_adaptive(&self, face: usize, eps: f64) -> Result<f64, CadError> {
        self.check(face, self.topology.faces.len(), "face")?;
        ffi::adaptive_measure(&self.index, Kind::Face as i32, face as i32, eps)
            .map_err(|e| occt(&self.file, "face area", e))
    }

    /// Volume of solid `solid` by BRepGProp's adaptive integration (see
    /// [`Self::face_area_adaptive`]).
    pub fn solid_volume_adaptive(&self, solid: usize, eps: f64) -> Result<f64, CadError> {
        self.check(solid, self.topology.solids.len(), "solid")?;
        ffi::adaptive_measure(&self.index, Kind::Solid as i32, solid as i32, eps)
            .map_err(|e| occt(&self.file, "solid volume", e))
    }

    /// Axis-aligned bounding box (min, max) of the whole shape, or None when it is empty.
    pub fn bounding_box(&self) -> Result<Option<BoundingBox>, CadError> {
        let shape = self.sub(Kind::Whole, 0)?;
        let mut bb = bnd::Bnd_Box_new();
        b_rep_bnd_lib::BRepBndLib::Add(&shape, bb.pin_mut(), false);
        if bb.IsVoid() {
            return Ok(None);
        }
        let (lo, hi) = (bnd::Bnd_Box_CornerMin(&bb), bnd::Bnd_Box_CornerMax(&bb));
        Ok(Some(BoundingBox {
            min: [lo.X(), lo.Y(), lo.Z()],
            max: [hi.X(), hi.Y(), hi.Z()],
        }))
    }

    /// Checks that the model is a set of solids bounded by closed shells, the precondition of
    /// volume meshing. The error says what is wrong (no solid, or which shell is open).
    pub fn check_solids(&self) -> Result<(), CadError> {
        let t = &self.topology;
        if t.solids.is_empty() {
            return Err(CadError::NoSolid {
                file: self.file.clone(),
                faces: t.faces.len(),
                open_shells: t.shells.iter().filter(|s| !s.closed).count(),
            });
        }
        for (solid, s) in t.solids.iter().enumerate() {
            for &shell in &s.shells {
                if !t.shells[shell].closed {
                    return Err(CadError::OpenShell {
                        file: self.file.clone(),
                        solid,
                        shell,
                        free_edges: t.shell_bad_edges(shell).len(),
                    });
                }
            }
        }
        Ok(())
    }

    /// Problems that do not stop meshing but that a user should hear about.
    pub fn warnings(&self) -> Vec<CadWarning> {
        let t = &self.topology;
        let mut w = Vec::new();
        for (shell, s) in t.shells.iter().enumerate() {
            if s.closed && s.declared_open {
                w.push(CadWarning::ShellDeclaredOpen { shell });
            }
        }
        if !t.free_faces.is_empty() {
            w.push(CadWarning::FacesOutsideShells {
                faces: t.free_faces.len(),
            });
        }
        w
    }

    fn sub(
        &self,
        kind: Kind,
        i: usize,
    ) -> Result<UniquePtr<opencascade_sys::topo_ds::TopoDS_Shape>, CadError> {
        ffi::sub_shape(&self.index, kind as i32, i as i32)
            .map_err(|e| occt(&self.file, "sub-shape", e))
    }

    fn check(&self, i: usize, n: usize, what: &'static str) -> Result<(), CadError> {
        if i < n {
            Ok(())
        } else {
            Err(CadError::NoSuchEntity {
                file: self.file.clone(),
                what,
                index: i,
            })
        }
    }
}

fn existing(path: &Path) -> Result<String, CadError> {
    let file = path.display().to_string();
    if path.is_file() {
        Ok(file)
    } else {
        Err(CadError::NotFound { file })
    }
}

pub(crate) fn occt(file: &str, operation: &'static str, e: cxx::Exception) -> CadError {
    CadError::Occt {
        file: file.to_string(),
        operation,
        message: e.what().to_string(),
    }
}

/// OCCT's translators (STEP/IGES/BREP readers, sewing, healing) share process-wide state —
/// static parameter tables, message gravity settings, controller registration — and are not
/// safe to run from two threads at once: two tests reading files concurrently crashed with
/// SIGSEGV. Every such call holds this lock; geometry queries on the per-entity copies do not.
pub(crate) fn translator_lock() -> std::sync::MutexGuard<'static, ()> {
    static LOCK: std::sync::Mutex<()> = std::sync::Mutex::new(());
    LOCK.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}
