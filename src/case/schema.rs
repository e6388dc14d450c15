//! The case file's TOML schema. Unknown keys are errors (`deny_unknown_fields`); names that
//! refer to other entries keep their source span so a bad reference can name its line.

use serde::Deserialize;
use toml::Spanned;

pub type P3 = [f64; 3];

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CaseFile {
    pub mesh: MeshSection,
    #[serde(default)]
    pub background: Option<BackgroundSection>,
    #[serde(default, rename = "source")]
    pub sources: Vec<Spanned<SourceEntry>>,
    #[serde(default, rename = "vertex")]
    pub vertices: Vec<VertexEntry>,
    #[serde(default, rename = "curve")]
    pub curves: Vec<CurveEntry>,
    #[serde(default, rename = "surface")]
    pub surfaces: Vec<Spanned<SurfaceEntry>>,
    #[serde(default, rename = "edge")]
    pub edges: Vec<EdgeEntry>,
    #[serde(default, rename = "face")]
    pub faces: Vec<FaceEntry>,
    #[serde(default, rename = "region")]
    pub regions: Vec<RegionEntry>,
    /// With `[mesh] cad`: CAD faces whose surface is replaced by a native fit.
    #[serde(default, rename = "replace_face")]
    pub replace_faces: Vec<ReplaceFaceEntry>,
    /// With `[mesh] cad`: native wake sheets attached to CAD edges.
    #[serde(default, rename = "wake")]
    pub wakes: Vec<WakeEntry>,
    /// Directional refinement stages, run in order.
    #[serde(default, rename = "refine")]
    pub refine: Vec<RefineEntry>,
}

/// A directional refinement stage: its sources combine by the minimum of their distributions.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RefineEntry {
    #[serde(rename = "source")]
    pub sources: Vec<Spanned<RefineSourceEntry>>,
}

/// A refinement source: model faces and/or edges (by name or CAD id) and the 1-D distribution
/// away from them.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RefineSourceEntry {
    #[serde(default)]
    pub faces: Vec<Spanned<EntityKey>>,
    #[serde(default)]
    pub curves: Vec<Spanned<EntityKey>>,
    pub first: Spanned<f64>,
    pub growth: Spanned<f64>,
    /// Layers of spacing `first` next to the source (1 by default).
    pub constant: Option<Spanned<i64>>,
    pub thickness: Option<Spanned<f64>>,
}

/// A CAD entity by 0-based id or by name.
#[derive(Debug, Clone, Deserialize)]
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

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReplaceFaceEntry {
    pub face: Spanned<EntityKey>,
    /// Grid points per parameter direction of the fit (default 17).
    pub samples: Option<Spanned<usize>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WakeEntry {
    /// Name of the wake face (boundary marker); "wake" by default.
    pub name: Option<String>,
    /// A chain of CAD edges (e.g. a trailing edge), in any order and direction.
    pub edges: Spanned<Vec<EntityKey>>,
    pub direction: Spanned<P3>,
    pub length: Spanned<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSection {
    /// Required for native cases; for a CAD case 1/20 of the model's bounding-box diagonal
    /// by default.
    pub size: Option<Spanned<f64>>,
    /// A CAD file (STEP, IGES, BREP) giving the whole model, relative to the case file.
    pub cad: Option<Spanned<String>>,
    pub curvature_segments: Option<Spanned<f64>>,
    /// n in δ ≤ w/n across faces only w wide (1 by default; 0 turns it off).
    pub proximity_cells: Option<Spanned<f64>>,
    pub min_size: Option<Spanned<f64>>,
    pub tolerance: Option<Spanned<f64>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BackgroundSection {
    /// `[x, y, z, spacing]` per node.
    pub nodes: Vec<[f64; 4]>,
    pub tets: Vec<[usize; 4]>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "lowercase")]
pub enum SourceKind {
    Point,
    Line,
    Triangle,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SourceEntry {
    pub kind: SourceKind,
    pub points: Vec<P3>,
    pub delta: f64,
    pub r1: f64,
    pub r2: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VertexEntry {
    pub name: Spanned<String>,
    pub point: P3,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CurveEntry {
    pub name: Spanned<String>,
    pub points: Vec<P3>,
    pub tangents: Option<Vec<P3>>,
}

/// A surface: either a grid of points to interpolate, or one patch by its corner data.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SurfaceEntry {
    pub name: Spanned<String>,
    pub grid: Option<Vec<Vec<P3>>>,
    pub corners: Option<[[P3; 2]; 2]>,
    pub u_tangents: Option<[[P3; 2]; 2]>,
    pub v_tangents: Option<[[P3; 2]; 2]>,
    pub twists: Option<[[P3; 2]; 2]>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EdgeEntry {
    pub name: Spanned<String>,
    pub start: Spanned<String>,
    pub end: Spanned<String>,
    pub curve: Option<Spanned<String>>,
    #[serde(default)]
    pub degenerate: bool,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FaceEntry {
    pub name: Spanned<String>,
    pub surface: Spanned<String>,
    #[serde(default)]
    pub loops: Vec<Vec<Spanned<String>>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RegionEntry {
    pub name: Spanned<String>,
    #[serde(default)]
    pub faces: Vec<Spanned<String>>,
    #[serde(default)]
    pub embedded_faces: Vec<Spanned<String>>,
    #[serde(default)]
    pub embedded_edges: Vec<Spanned<String>>,
}
