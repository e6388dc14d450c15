//! `[[refine]]` stages of a case file (and the command line's shortcut): sources named by face
//! or edge name or CAD id, checked against the model, with their distributions checked against
//! the case's spacing.

use super::controls::Ctx;
use super::error::CaseError;
use super::schema::{EntityKey, RefineEntry};
use crate::model::{EdgeId, FaceId, Model};
use crate::refine::{Distribution, DistributionError, Refinement, SourceSpec, Stage};

/// A face of `model` by name or 0-based id.
pub fn face_by_key(model: &Model, key: &EntityKey) -> Result<FaceId, String> {
    let found = match key {
        EntityKey::Id(i) => (*i < model.faces.len()).then_some(*i),
        EntityKey::Name(n) => model
            .faces
            .iter()
            .position(|f| f.name.as_deref() == Some(n.as_str())),
    };
    let f =
        found.ok_or_else(|| format!("no face {key} in the model ({} faces)", model.faces.len()))?;
    let in_region = model.regions.iter().any(|r| {
        r.embedded_faces.contains(&f)
            || r.shells.iter().any(|s| s.faces.iter().any(|u| u.face == f))
    });
    if !in_region {
        return Err(format!(
            "{} bounds no region and lies in none",
            model.face_ref(f)
        ));
    }
    Ok(f)
}

/// An edge of `model` by name or 0-based id.
pub fn edge_by_key(model: &Model, key: &EntityKey) -> Result<EdgeId, String> {
    let found = match key {
        EntityKey::Id(i) => (*i < model.edges.len()).then_some(*i),
        EntityKey::Name(n) => model
            .edges
            .iter()
            .position(|e| e.name.as_deref() == Some(n.as_str())),
    };
    found.ok_or_else(|| format!("no edge {key} in the model ({} edges)", model.edges.len()))
}

/// The model's refinement stages from the case file's entries; `size` is the case's isotropic
/// spacing (the layers must start finer).
pub(super) fn stages(
    ctx: &Ctx,
    entries: &[RefineEntry],
    model: &Model,
    size: f64,
) -> Result<Refinement, CaseError> {
    let mut refinement = Refinement::default();
    for entry in entries {
        let mut stage = Stage::default();
        for src in &entry.sources {
            let s = src.get_ref();
            if s.faces.is_empty() && s.curves.is_empty() {
                return Err(ctx.at(src, "refine.source", "names no faces and no curves"));
            }
            let mut faces = Vec::new();
            for k in &s.faces {
                faces.push(
                    face_by_key(model, k.get_ref())
                        .map_err(|m| ctx.at(k, "refine.source.faces", m))?,
                );
            }
            let mut edges = Vec::new();
            for k in &s.curves {
                edges.push(
                    edge_by_key(model, k.get_ref())
                        .map_err(|m| ctx.at(k, "refine.source.curves", m))?,
                );
            }
            let constant = match &s.constant {
                Some(c) if *c.get_ref() < 1 => {
                    return Err(ctx.at(
                        c,
                        "refine.source.constant",
                        format!("must be at least 1, got {}", c.get_ref()),
                    ))
                }
                Some(c) => *c.get_ref() as usize,
                None => 1,
            };
            let d = Distribution::new(
                *s.first.get_ref(),
                *s.growth.get_ref(),
                constant,
                s.thickness.as_ref().map(|t| *t.get_ref()),
                size,
            )
            .map_err(|e| match e {
                DistributionError::First(_) | DistributionError::NotFiner { .. } => {
                    ctx.at(&s.first, "refine.source.first", e.to_string())
                }
                DistributionError::Growth(_) | DistributionError::NeverEnds => {
                    ctx.at(&s.growth, "refine.source.growth", e.to_string())
                }
                DistributionError::Thickness(_) => match &s.thickness {
                    Some(t) => ctx.at(t, "refine.source.thickness", e.to_string()),
                    None => ctx.at(src, "refine.source", e.to_string()),
                },
            })?;
            let label = s
                .faces
                .iter()
                .chain(&s.curves)
                .map(|k| k.get_ref().to_string())
                .collect::<Vec<_>>()
                .join(", ");
            stage.sources.push(SourceSpec {
                label,
                faces,
                edges,
                distribution: d,
            });
        }
        refinement.stages.push(stage);
    }
    Ok(refinement)
}

/// One more refinement stage from plain arguments, after the case's own: the command line's
/// `--refine-faces … --first …` and the service's `refine_faces`, `first` … fields. Faces and
/// edges by name or 0-based id.
#[derive(Clone, Debug, Default)]
pub struct ExtraStage {
    pub faces: Vec<String>,
    pub edges: Vec<String>,
    pub first: Option<f64>,
    pub growth: f64,
    pub constant: usize,
    pub thickness: Option<f64>,
}

impl ExtraStage {
    /// Whether it asks for anything.
    pub fn is_empty(&self) -> bool {
        self.faces.is_empty() && self.edges.is_empty()
    }

    /// Append the stage to `case`'s refinement; `name` spells an option as the caller's users
    /// know it (`"refine-faces"` → `--refine-faces` or `refine_faces`).
    pub fn add_to(
        &self,
        case: &mut super::Case,
        name: impl Fn(&str) -> String,
    ) -> Result<(), String> {
        if self.is_empty() {
            if self.first.is_some() || self.thickness.is_some() {
                return Err(format!(
                    "{} and {} need {} or {}",
                    name("first"),
                    name("thickness"),
                    name("refine-faces"),
                    name("refine-curves")
                ));
            }
            return Ok(());
        }
        let key = |s: &str| match s.parse::<usize>() {
            Ok(i) => EntityKey::Id(i),
            Err(_) => EntityKey::Name(s.to_string()),
        };
        let faces = self
            .faces
            .iter()
            .map(|s| {
                face_by_key(&case.model, &key(s))
                    .map_err(|m| format!("{}: {m}", name("refine-faces")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let edges = self
            .edges
            .iter()
            .map(|s| {
                edge_by_key(&case.model, &key(s))
                    .map_err(|m| format!("{}: {m}", name("refine-curves")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let first = self.first.ok_or_else(|| {
            format!(
                "{} is needed with {} / {}",
                name("first"),
                name("refine-faces"),
                name("refine-curves")
            )
        })?;
        if self.constant < 1 {
            return Err(format!("{} must be at least 1", name("constant")));
        }
        let distribution = Distribution::new(
            first,
            self.growth,
            self.constant,
            self.thickness,
            case.controls.size,
        )
        .map_err(|e| format!("the refinement stage of {}: {e}", name("refine-faces")))?;
        let label = self
            .faces
            .iter()
            .chain(&self.edges)
            .cloned()
            .collect::<Vec<_>>()
            .join(", ");
        case.refinement.stages.push(Stage {
            sources: vec![SourceSpec {
                label,
                faces,
                edges,
                distribution,
            }],
        });
        Ok(())
    }
}
