//! The case file's TOML schema. Unknown keys are errors (`deny_unknown_fields`); names that
//! refer to other entries keep their source span so a bad reference can name its line. It also
//! serialises (absent options and empty lists left out), so the sample cases are built as
//! this very schema and written by the `toml` crates (`samples/case_file.rs`).

use serde::{Deserialize, Serialize};
use toml::Spanned;

pub type P3 = [f64; 3];

#[derive(Debug, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CaseFile {
    pub mesh: MeshSection,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub background: Option<BackgroundSection>,
    #[serde(default, rename = "source", skip_serializing_if = "Vec::is_empty")]
    pub sources: Vec<Spanned<SourceEntry>>,
    #[serde(default, rename = "vertex", skip_serializing_if = "Vec::is_empty")]
    pub vertices: Vec<VertexEntry>,
    #[serde(default, rename = "curve", skip_serializing_if = "Vec::is_empty")]
    pub curves: Vec<CurveEntry>,
    #[serde(default, rename = "surface", skip_serializing_if = "Vec::is_empty")]
    pub surfaces: Vec<Spanned<SurfaceEntry>>,
    #[serde(default, rename = "edge", skip_serializing_if = "Vec::is_empty")]
    pub edges: Vec<EdgeEntry>,
    #[serde(default, rename = "face", skip_serializing_if = "Vec::is_empty")]
    pub faces: Vec<FaceEntry>,
    #[serde(default, rename = "region", skip_serializing_if = "Vec::is_empty")]
    pub regions: Vec<RegionEntry>,
    /// With `[mesh] cad`: CAD faces whose surface is replaced by a native fit.
    #[serde(
        default,
        rename = "replace_face",
        skip_serializing_if = "Vec::is_empty"
    )]
    pub replace_faces: Vec<ReplaceFaceEntry>,
    /// With `[mesh] cad`: native wake sheets attached to CAD edges.
    #[serde(default, rename = "wake", skip_serializing_if = "Vec::is_empty")]
    pub wakes: Vec<WakeEntry>,
    /// Directional refinement stages, run in order.
    #[serde(default, rename = "refine", skip_serializing_if = "Vec::is_empty")]
    pub refine: Vec<RefineEntry>,
}

/// A directional refinement stage: its sources combine by the minimum of their distributions.
#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RefineEntry {
    #[serde(rename = "source")]
    pub sources: Vec<Spanned<RefineSourceEntry>>,
}

/// A refinement source: model faces and/or edges (by name or CAD id) and the 1-D distribution
/// away from them.
#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RefineSourceEntry {
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub faces: Vec<Spanned<EntityKey>>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub curves: Vec<Spanned<EntityKey>>,
    /// The first layer's height; or `yplus` with `reynolds` and `chord` for the flat-plate
    /// estimate of it (`refine/viscous.rs`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub first: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub yplus: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reynolds: Option<Spanned<f64>>,
    /// The length the Reynolds number is based on, in the model's unit.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub chord: Option<Spanned<f64>>,
    pub growth: Spanned<f64>,
    /// Layers of spacing `first` next to the source (1 by default).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub constant: Option<Spanned<i64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub thickness: Option<Spanned<f64>>,
}

/// A CAD entity by 0-based id or by name.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(untagged)]
pub enum EntityKey {
    Id(usize),
    Name(String),
}

impl std::fmt::Display for EntityKey {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EntityKey::Id(i) => write!(f, "{i}"),
            EntityKey::Name(n) => write!(f, "'{n}'"),
        }
    }
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ReplaceFaceEntry {
    pub face: Spanned<EntityKey>,
    /// Grid points per parameter direction of the fit (default 17).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub samples: Option<Spanned<usize>>,
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct WakeEntry {
    /// Name of the wake face (boundary marker); "wake" by default.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// A chain of CAD edges (e.g. a trailing edge), in any order and direction.
    pub edges: Spanned<Vec<EntityKey>>,
    pub direction: Spanned<P3>,
    pub length: Spanned<f64>,
}

#[derive(Debug, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSection {
    /// Required for native cases; for a CAD case 1/20 of the model's bounding-box diagonal
    /// by default.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub size: Option<Spanned<f64>>,
    /// A CAD file (STEP, IGES, BREP) giving the whole model, relative to the case file.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cad: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub curvature_segments: Option<Spanned<f64>>,
    /// n in δ ≤ w/n across faces only w wide (1 by default; 0 turns it off).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub proximity_cells: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_size: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<Spanned<f64>>,
    /// Merge the stretched layers' tets into prisms (needs a `[[refine]]` stage).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub prisms: Option<Spanned<bool>>,
    /// A prism side quad warped more than this (degrees between its two triangles) stays two
    /// triangles (20 by default).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub prism_warp: Option<Spanned<f64>>,
    /// A flow domain around the body: `{ shape = "box" | "sphere" | "half-box" |
    /// "half-sphere", size = body lengths }` (a native body: box and half-box).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub farfield: Option<Spanned<FarfieldTable>>,
    /// `"auto"`: a wake sheet from every trailing edge found on the body, along the free
    /// stream (`alpha`, `beta`), to the far field or `wake_length` long.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wakes: Option<Spanned<String>>,
    /// Angle of attack in degrees (the free stream tilts from +x towards +z).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub alpha: Option<Spanned<f64>>,
    /// Sideslip in degrees (the free stream turns from +x towards +y).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub beta: Option<Spanned<f64>>,
    /// The automatic wakes' length in the model's unit (to the far field by default).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wake_length: Option<Spanned<f64>>,
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct FarfieldTable {
    pub shape: String,
    pub size: f64,
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BackgroundSection {
    /// `[x, y, z, spacing]` per node.
    pub nodes: Vec<[f64; 4]>,
    pub tets: Vec<[usize; 4]>,
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields, rename_all = "lowercase")]
pub enum SourceKind {
    Point,
    Line,
    Triangle,
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SourceEntry {
    pub kind: SourceKind,
    pub points: Vec<P3>,
    pub delta: f64,
    pub r1: f64,
    pub r2: f64,
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct VertexEntry {
    pub name: Spanned<String>,
    pub point: P3,
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CurveEntry {
    pub name: Spanned<String>,
    pub points: Vec<P3>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tangents: Option<Vec<P3>>,
}

/// A surface: either a grid of points to interpolate, or one patch by its corner data.
#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SurfaceEntry {
    pub name: Spanned<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grid: Option<Vec<Vec<P3>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub corners: Option<[[P3; 2]; 2]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub u_tangents: Option<[[P3; 2]; 2]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub v_tangents: Option<[[P3; 2]; 2]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub twists: Option<[[P3; 2]; 2]>,
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct EdgeEntry {
    pub name: Spanned<String>,
    pub start: Spanned<String>,
    pub end: Spanned<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub curve: Option<Spanned<String>>,
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub degenerate: bool,
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct FaceEntry {
    pub name: Spanned<String>,
    pub surface: Spanned<String>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub loops: Vec<Vec<Spanned<String>>>,
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RegionEntry {
    pub name: Spanned<String>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub faces: Vec<Spanned<String>>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub embedded_faces: Vec<Spanned<String>>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub embedded_edges: Vec<Spanned<String>>,
}
