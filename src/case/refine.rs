//! `[[refine]]` stages of a case file (and the command line's shortcut): sources named by face
//! or edge name or CAD id, checked against the model, with their distributions checked against
//! the case's spacing.

use super::controls::Ctx;
use super::error::CaseError;
use super::schema::{EntityKey, RefineEntry, RefineSourceEntry};
use crate::model::{EdgeId, FaceId, Model};
use crate::refine::viscous::WallTarget;
use crate::refine::{Distribution, DistributionError, Refinement, SourceSpec, Stage};
use toml::Spanned;

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
            let (first, first_span, note) = first_of(ctx, src, s)?;
            let d = Distribution::new(
                first,
                *s.growth.get_ref(),
                constant,
                s.thickness.as_ref().map(|t| *t.get_ref()),
                size,
            )
            .map_err(|e| match e {
                DistributionError::First(_) | DistributionError::NotFiner { .. } => {
                    let (span, key) = first_span;
                    ctx.at(span, key, e.to_string())
                }
                DistributionError::Growth(_) | DistributionError::NeverEnds => {
                    ctx.at(&s.growth, "refine.source.growth", e.to_string())
                }
                DistributionError::Thickness(_) => match &s.thickness {
                    Some(t) => ctx.at(t, "refine.source.thickness", e.to_string()),
                    None => ctx.at(src, "refine.source", e.to_string()),
                },
            })?;
            let mut label = s
                .faces
                .iter()
                .chain(&s.curves)
                .map(|k| k.get_ref().to_string())
                .collect::<Vec<_>>()
                .join(", ");
            if let Some(note) = note {
                log::info!("refinement source {label}: {note}");
                label = format!("{label} ({note})");
            }
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

/// A source's first-layer height: `first`, or the flat-plate estimate from `yplus`,
/// `reynolds` and `chord` (with what was estimated); and the key to blame should the height
/// not suit the distribution.
#[allow(clippy::type_complexity)]
fn first_of<'a>(
    ctx: &Ctx,
    src: &Spanned<RefineSourceEntry>,
    s: &'a RefineSourceEntry,
) -> Result<(f64, (&'a Spanned<f64>, &'static str), Option<String>), CaseError> {
    match (&s.first, &s.yplus) {
        (Some(first), None) => {
            for (other, key) in [(&s.reynolds, "reynolds"), (&s.chord, "chord")] {
                if let Some(o) = other {
                    return Err(ctx.at(
                        o,
                        &format!("refine.source.{key}"),
                        "goes with yplus (the first layer from a y+ target), not with first",
                    ));
                }
            }
            Ok((*first.get_ref(), (first, "refine.source.first"), None))
        }
        (Some(_), Some(y)) => Err(ctx.at(
            y,
            "refine.source.yplus",
            "give first or yplus (with reynolds and chord), not both",
        )),
        (None, Some(y)) => {
            let (Some(re), Some(chord)) = (&s.reynolds, &s.chord) else {
                return Err(ctx.at(
                    y,
                    "refine.source.yplus",
                    "needs reynolds (the Reynolds number) and chord (the length it is based \
                     on, in the model's unit) for the flat-plate estimate of the first layer",
                ));
            };
            let target = WallTarget::new(*y.get_ref(), *re.get_ref(), *chord.get_ref()).map_err(
                |(key, m)| {
                    let span = match key {
                        "yplus" => y,
                        "reynolds" => re,
                        _ => chord,
                    };
                    ctx.at(span, &format!("refine.source.{key}"), m)
                },
            )?;
            Ok((
                target.first(),
                (y, "refine.source.yplus"),
                Some(target.describe()),
            ))
        }
        (None, None) => Err(ctx.at(
            src,
            "refine.source",
            "needs first (the first layer's height), or yplus with reynolds and chord",
        )),
    }
}

/// One more refinement stage from plain arguments, after the case's own: the command line's
/// `--refine-faces … --first …` and the service's `refine_faces`, `first` … fields. Faces and
/// edges by name or 0-based id.
#[derive(Clone, Debug, Default)]
pub struct ExtraStage {
    pub faces: Vec<String>,
    pub edges: Vec<String>,
    pub first: Option<f64>,
    /// The first layer from a y⁺ target instead of `first` (with `reynolds` and `chord`).
    pub yplus: Option<f64>,
    pub reynolds: Option<f64>,
    pub chord: Option<f64>,
    pub growth: f64,
    pub constant: usize,
    pub thickness: Option<f64>,
}

impl ExtraStage {
    /// Whether it asks for anything.
    pub fn is_empty(&self) -> bool {
        self.faces.is_empty() && self.edges.is_empty()
    }

    /// The first layer's height: `first`, or the flat-plate estimate from `yplus` (with what
    /// was estimated).
    fn first_layer(&self, name: &impl Fn(&str) -> String) -> Result<(f64, Option<String>), String> {
        match (self.first, self.yplus) {
            (Some(first), None) => {
                if self.reynolds.is_some() || self.chord.is_some() {
                    return Err(format!(
                        "{} and {} go with {}, not with {}",
                        name("reynolds"),
                        name("chord"),
                        name("yplus"),
                        name("first")
                    ));
                }
                Ok((first, None))
            }
            (Some(_), Some(_)) => Err(format!(
                "give {} or {}, not both",
                name("first"),
                name("yplus")
            )),
            (None, Some(yplus)) => {
                let (Some(re), Some(chord)) = (self.reynolds, self.chord) else {
                    return Err(format!(
                        "{} needs {} (the Reynolds number) and {} (the length it is based on, \
                         in the model's unit) for the flat-plate estimate of the first layer",
                        name("yplus"),
                        name("reynolds"),
                        name("chord")
                    ));
                };
                let t = WallTarget::new(yplus, re, chord)
                    .map_err(|(key, m)| format!("{} {m}", name(key)))?;
                Ok((t.first(), Some(t.describe())))
            }
            (None, None) => Err(format!(
                "{} (or {} with {} and {}) is needed with {} / {}",
                name("first"),
                name("yplus"),
                name("reynolds"),
                name("chord"),
                name("refine-faces"),
                name("refine-curves")
            )),
        }
    }

    /// Append the stage to `case`'s refinement; `name` spells an option as the caller's users
    /// know it (`"refine-faces"` → `--refine-faces` or `refine_faces`).
    pub fn add_to(
        &self,
        case: &mut super::Case,
        name: impl Fn(&str) -> String,
    ) -> Result<(), String> {
        if self.is_empty() {
            if self.first.is_some() || self.thickness.is_some() || self.yplus.is_some() {
                return Err(format!(
                    "{}, {} and {} need {} or {}",
                    name("first"),
                    name("yplus"),
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
        let (first, note) = self.first_layer(&name)?;
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
        let mut label = self
            .faces
            .iter()
            .chain(&self.edges)
            .cloned()
            .collect::<Vec<_>>()
            .join(", ");
        if let Some(note) = note {
            log::info!("refinement source {label}: {note}");
            label = format!("{label} ({note})");
        }
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
