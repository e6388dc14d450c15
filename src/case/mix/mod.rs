//! Native geometry mixed into a CAD model (`[mesh] cad` plus `[[replace_face]]` and
//! `[[wake]]`): the model then holds OCCT and native entities side by side, all behind the
//! same geometry traits. The model is validated and re-oriented afterwards, as any model.

mod chain;
mod replace;
mod trailing;
mod wake;

use super::controls::{AutoWakes, Ctx};
use super::error::CaseError;
use super::farfield::FlowDomain;
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
    settle(model, "the mixed model").map_err(|m| ctx.model(m))
}

/// Validate and orient `model` again after native entities joined it; errors start with
/// `what`.
fn settle(model: &mut Model, what: &str) -> Result<(), String> {
    let errors = model.validation_errors();
    if !errors.is_empty() {
        return Err(format!("{what} is not valid:\n  {}", errors.join("\n  ")));
    }
    model.orient().map_err(|e| format!("{what}: {e}"))?;
    Ok(())
}

/// `--wakes auto`: a wake sheet from every trailing-edge chain of the body (the flow domain's
/// body faces, or every boundary face of a model without one), named `wake_1`, `wake_2`, …
/// in chain order, then validation and orientation again. Returns the wakes' names.
pub(super) fn auto_wakes(
    model: &mut Model,
    domain: Option<&FlowDomain>,
    request: &AutoWakes,
    tol: f64,
) -> Result<Vec<String>, String> {
    let stream = request.stream();
    if let Some((axis, at)) = domain.and_then(|d| d.symmetry) {
        if stream[axis].abs() > 1e-12 {
            return Err(format!(
                "--wakes auto: the free stream (alpha {}°, beta {}°) leaves the symmetry plane \
                 {} = {at:.6}: a half model takes no flow across its plane",
                request.alpha,
                request.beta,
                ["x", "y", "z"][axis]
            ));
        }
    }
    let mut names = Vec::new();
    for region in 0..model.regions.len() {
        let faces: Vec<usize> = match domain {
            Some(d) => d.body_faces.clone(),
            None => model.region_faces(region).map(|fu| fu.face).collect(),
        };
        for chain in trailing::trailing_chains(model, region, &faces, stream) {
            let name = format!("wake_{}", names.len() + 1);
            if model.faces.iter().any(|f| f.name.as_deref() == Some(&name)) {
                return Err(format!(
                    "--wakes auto: the model has a face named '{name}' already"
                ));
            }
            let edges: Vec<usize> = chain.uses.iter().map(|&(e, _)| e).collect();
            let length = match (request.length, domain) {
                (Some(l), _) => l,
                (None, Some(d)) => {
                    let reach = wake::chain_points(model, &chain)
                        .into_iter()
                        .map(|p| d.outer.exit_distance(p, stream))
                        .fold(f64::INFINITY, f64::min);
                    reach - d.far_spacing()
                }
                (None, None) => {
                    return Err(
                        "--wakes auto without a far field built by tetrafoil needs the wakes'                          length (--wake-length, or [mesh] wake_length)"
                            .into(),
                    )
                }
            };
            if !(length.is_finite() && length > 0.0) {
                return Err(format!(
                    "--wakes auto: the trailing edge {} has no room for a wake before the far \
                     field (length {length:.4e})",
                    model.edge_ref(edges[0])
                ));
            }
            log::info!(
                "{name}: shed from {} trailing edge(s) from {} to {}, {length:.4} long",
                edges.len(),
                crate::geometry::Xyz(model.vertices[chain.first].point),
                crate::geometry::Xyz(model.vertices[chain.last].point),
            );
            let spec = wake::WakeSpec {
                name: name.clone(),
                edges,
                offset: stream * length,
            };
            wake::add_wake(model, &spec, tol).map_err(|m| format!("{name}: {m}"))?;
            names.push(name);
        }
    }
    if names.is_empty() {
        log::warn!(
            "--wakes auto: no trailing edge found (two faces meeting in a wedge under {}° \
             facing downstream)",
            trailing::MAX_WEDGE_DEGREES
        );
        return Ok(names);
    }
    settle(model, "the model with its wakes")?;
    Ok(names)
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
