//! Native geometry mixed into a CAD model (`[mesh] cad` plus `[[replace_face]]` and
//! `[[wake]]`): the model then holds OCCT and native entities side by side, all behind the
//! same geometry traits. The model is validated and re-oriented afterwards, as any model.

mod chain;
mod replace;
mod wake;

use super::controls::Ctx;
use super::error::CaseError;
use super::schema::{CaseFile, EntityKey};
use crate::model::Model;
use glam::DVec3;
use toml::Spanned;

/// Grid points per direction of a replacement fit unless the entry says otherwise.
const DEFAULT_SAMPLES: usize = 17;

/// The first mixing entry of a case file without `[mesh] cad`, as an error: they only make
/// sense on a CAD model.
pub(super) fn first_entry(ctx: &Ctx, file: &CaseFile) -> Option<CaseError> {
    let msg = "needs `[mesh] cad`: it modifies a CAD model";
    if let Some(r) = file.replace_faces.first() {
        return Some(ctx.at(&r.face, "replace_face.face", msg));
    }
    file.wakes
        .first()
        .map(|w| ctx.at(&w.edges, "wake.edges", msg))
}

/// Applies every `[[replace_face]]`, then every `[[wake]]`, then validates and orients.
pub(super) fn apply(
    ctx: &Ctx,
    file: &CaseFile,
    model: &mut Model,
    tol: f64,
) -> Result<(), CaseError> {
    if file.replace_faces.is_empty() && file.wakes.is_empty() {
        return Ok(());
    }
    for r in &file.replace_faces {
        let key = "replace_face.face";
        let face = resolve_face(model, &r.face).map_err(|m| ctx.at(&r.face, key, m))?;
        let samples = match &r.samples {
            Some(s) if *s.get_ref() < 2 => {
                return Err(ctx.at(s, "replace_face.samples", "must be at least 2"))
            }
            Some(s) => *s.get_ref(),
            None => DEFAULT_SAMPLES,
        };
        let fit = replace::replace_face(model, face, samples, tol)
            .map_err(|m| ctx.at(&r.face, key, format!("{}: {m}", model.face_ref(face))))?;
        if fit.max_deviation > 10.0 * tol {
            log::warn!(
                "{}: the native fit ({samples}x{samples} points) is {:.3e} from the CAD surface at worst",
                model.face_ref(face),
                fit.max_deviation
            );
        }
    }
    for w in &file.wakes {
        let edges = w
            .edges
            .get_ref()
            .iter()
            .map(|k| resolve_edge(model, k))
            .collect::<Result<Vec<_>, _>>()
            .map_err(|m| ctx.at(&w.edges, "wake.edges", m))?;
        let direction = DVec3::from_array(*w.direction.get_ref());
        if !(direction.is_finite() && direction.length() > 0.0) {
            return Err(ctx.at(&w.direction, "wake.direction", "must be a non-zero vector"));
        }
        let length = *w.length.get_ref();
        if !(length.is_finite() && length > 0.0) {
            return Err(ctx.at(&w.length, "wake.length", "must be a positive number"));
        }
        let sheet = wake::WakeSpec {
            name: w.name.clone().unwrap_or_else(|| "wake".into()),
            edges,
            offset: direction.normalize() * length,
        };
        wake::add_wake(model, &sheet, tol).map_err(|m| ctx.at(&w.edges, "wake.edges", m))?;
    }
    let errors = model.validation_errors();
    if !errors.is_empty() {
        return Err(ctx.model(format!(
            "the mixed model is not valid:\n  {}",
            errors.join("\n  ")
        )));
    }
    model
        .orient()
        .map_err(|e| ctx.model(format!("the mixed model: {e}")))?;
    Ok(())
}

/// A face by id or by its (unique) name.
fn resolve_face(model: &Model, key: &Spanned<EntityKey>) -> Result<usize, String> {
    let names: Vec<Option<&str>> = model.faces.iter().map(|f| f.name.as_deref()).collect();
    resolve("face", &names, key.get_ref())
}

fn resolve_edge(model: &Model, key: &EntityKey) -> Result<usize, String> {
    let names: Vec<Option<&str>> = model.edges.iter().map(|e| e.name.as_deref()).collect();
    resolve("edge", &names, key)
}

fn resolve(what: &str, names: &[Option<&str>], key: &EntityKey) -> Result<usize, String> {
    match key {
        EntityKey::Id(i) if *i < names.len() => Ok(*i),
        EntityKey::Id(i) => Err(format!(
            "the CAD model has no {what} {i} ({} {what}s, ids from 0)",
            names.len()
        )),
        EntityKey::Name(n) => {
            let hits: Vec<usize> = (0..names.len())
                .filter(|&i| names[i] == Some(n.as_str()))
                .collect();
            match hits.as_slice() {
                [one] => Ok(*one),
                [] => Err(format!("the CAD model has no {what} named '{n}'")),
                many => Err(format!(
                    "{} {what}s are named '{n}' (ids {:?}): give the id",
                    many.len(),
                    many
                )),
            }
        }
    }
}
