//! `[[refine]]` stages of a case file (and the command line's shortcut): sources named by face
//! or edge name or CAD id, checked against the model, with their distributions checked against
//! the case's spacing.

use super::controls::Ctx;
use super::error::CaseError;
use super::schema::{EntityKey, RefineEntry};
use crate::model::{EdgeId, FaceId, Model};
use crate::refine::{Distribution, DistributionError, Refinement, SourceSpec, Stage};

/// The faces of `model` a key names: the face of a 0-based id, or every face of a name (a CAD
/// file often gives one name to all the faces of a part: a wing's skin, its far field).
pub fn faces_by_key(model: &Model, key: &EntityKey) -> Result<Vec<FaceId>, String> {
    let names: Vec<Option<&str>> = model.faces.iter().map(|f| f.name.as_deref()).collect();
    let found = by_key("face", &names, key)?;
    for &f in &found {
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
    }
    Ok(found)
}

/// The edges of `model` a key names: the edge of a 0-based id, or every edge of a name.
pub fn edges_by_key(model: &Model, key: &EntityKey) -> Result<Vec<EdgeId>, String> {
    let names: Vec<Option<&str>> = model.edges.iter().map(|e| e.name.as_deref()).collect();
    by_key("edge", &names, key)
}

/// The entities (`names` per id) a key names, or an error saying what there is.
fn by_key(what: &str, names: &[Option<&str>], key: &EntityKey) -> Result<Vec<usize>, String> {
    let found: Vec<usize> = match key {
        EntityKey::Id(i) => (*i < names.len()).then_some(*i).into_iter().collect(),
        EntityKey::Name(n) => (0..names.len())
            .filter(|&i| names[i] == Some(n.as_str()))
            .collect(),
    };
    if found.is_empty() {
        return Err(format!(
            "no {what} {key} in the model ({})",
            known(what, names)
        ));
    }
    Ok(found)
}

/// What a user may name instead: the count, the id range and the first names.
fn known(what: &str, names: &[Option<&str>]) -> String {
    const SHOWN: usize = 12;
    let n = names.len();
    let mut named: Vec<&str> = Vec::new();
    for name in names.iter().flatten().copied() {
        if !named.contains(&name) {
            named.push(name);
        }
    }
    let ids = format!("{n} {what}s, CAD ids 0 to {}", n.saturating_sub(1));
    match named.len() {
        0 => format!("{ids}, none named"),
        k if k <= SHOWN => format!("{ids}; named {}", named.join(", ")),
        k => format!(
            "{ids}; named {}, … ({} more)",
            named[..SHOWN].join(", "),
            k - SHOWN
        ),
    }
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
                faces.extend(
                    faces_by_key(model, k.get_ref())
                        .map_err(|m| ctx.at(k, "refine.source.faces", m))?,
                );
            }
            let mut edges = Vec::new();
            for k in &s.curves {
                edges.extend(
                    edges_by_key(model, k.get_ref())
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
                faces_by_key(&case.model, &key(s))
                    .map_err(|m| format!("{}: {m}", name("refine-faces")))
            })
            .collect::<Result<Vec<Vec<_>>, _>>()?
            .concat();
        let edges = self
            .edges
            .iter()
            .map(|s| {
                edges_by_key(&case.model, &key(s))
                    .map_err(|m| format!("{}: {m}", name("refine-curves")))
            })
            .collect::<Result<Vec<Vec<_>>, _>>()?
            .concat();
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
