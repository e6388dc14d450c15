//! A submission, read from its multipart body and checked before anything is stored: a
//! `geometry` part (STEP/IGES/BREP, known by its file name's extension) and/or a `case` part
//! (TOML), and the option fields `size`, `formats`, `threads`. The client's file names pick
//! the kind of file, never a path: the server stores `input/geometry.<ext>` and
//! `input/case.toml`. A case's `[mesh] cad` must be a bare file name naming the uploaded
//! geometry; it is pointed at the stored name in place (same line, so later messages keep
//! their line numbers).

use super::error::ApiError;
use super::job::{format_names, parse_format, Refine};
use super::run::cad_extension;
use crate::case::schema::CaseFile;
use axum::extract::multipart::{Multipart, MultipartError};
use axum::http::StatusCode;

/// A checked submission.
#[derive(Debug)]
pub struct Submission {
    /// The geometry's lower-case extension and bytes.
    pub geometry: Option<(String, Vec<u8>)>,
    /// The case text, `cad` already pointed at the stored geometry.
    pub case: Option<String>,
    pub size: Option<f64>,
    pub formats: Vec<String>,
    pub threads: Option<usize>,
    pub refine: Option<Refine>,
}

impl Submission {
    /// The file the worker loads, under the job's input folder.
    pub fn input_name(&self) -> String {
        match (&self.case, &self.geometry) {
            (Some(_), _) => "case.toml".to_string(),
            (None, Some((ext, _))) => format!("geometry.{ext}"),
            (None, None) => String::new(),
        }
    }
}

/// The formats a job gets when it names none.
pub const DEFAULT_FORMATS: [&str; 2] = ["su2", "vtu"];

fn multipart_error(e: MultipartError) -> ApiError {
    // A body over the limit shows up here when it came without a Content-Length.
    let status = e.status();
    let status = if status == StatusCode::PAYLOAD_TOO_LARGE {
        status
    } else {
        StatusCode::BAD_REQUEST
    };
    ApiError::new(
        status,
        format!("reading the multipart body: {}", e.body_text()),
    )
}

/// Read and check the whole submission.
pub async fn read(mut form: Multipart) -> Result<Submission, ApiError> {
    let mut geometry = None;
    let mut case: Option<String> = None;
    let (mut size, mut formats, mut threads) = (None, None, None);
    let mut refine = RefineFields::default();
    while let Some(field) = form.next_field().await.map_err(multipart_error)? {
        let name = field.name().unwrap_or("").to_string();
        let file_name = field.file_name().map(str::to_string);
        let bytes = field.bytes().await.map_err(multipart_error)?;
        let text = || {
            String::from_utf8(bytes.to_vec())
                .map_err(|_| ApiError::bad_request(format!("the `{name}` part is not UTF-8 text")))
        };
        let twice = || ApiError::bad_request(format!("the `{name}` part is given twice"));
        match name.as_str() {
            "geometry" => {
                let file_name = file_name.ok_or_else(|| {
                    ApiError::bad_request("the `geometry` part needs a file name (part.step …)")
                })?;
                let ext = cad_extension(&file_name).ok_or_else(|| {
                    ApiError::bad_request(format!(
                        "the geometry '{}' is not a STEP, IGES or BREP file (by its extension: \
                         .step .stp .iges .igs .brep .brp)",
                        printable(&file_name)
                    ))
                })?;
                if geometry.replace((ext, bytes.to_vec())).is_some() {
                    return Err(twice());
                }
            }
            "case" => {
                if case.replace(text()?).is_some() {
                    return Err(twice());
                }
            }
            "size" => {
                let v = text()?;
                let h: f64 = v.trim().parse().map_err(|_| {
                    ApiError::bad_request(format!("size: not a number: '{}'", printable(&v)))
                })?;
                if !(h.is_finite() && h > 0.0) {
                    return Err(ApiError::bad_request(format!(
                        "size must be a positive number, got {h}"
                    )));
                }
                if size.replace(h).is_some() {
                    return Err(twice());
                }
            }
            "formats" => {
                if formats.replace(parse_formats(&text()?)?).is_some() {
                    return Err(twice());
                }
            }
            "threads" => {
                let v = text()?;
                let n: usize = v.trim().parse().ok().filter(|&n| n >= 1).ok_or_else(|| {
                    ApiError::bad_request(format!(
                        "threads: expected a whole number >= 1, got '{}'",
                        printable(&v)
                    ))
                })?;
                if threads.replace(n).is_some() {
                    return Err(twice());
                }
            }
            "refine_faces" | "refine_curves" | "first" | "yplus" | "reynolds" | "chord"
            | "growth" | "constant" | "thickness" => {
                if refine.fields.insert(name.clone(), text()?).is_some() {
                    return Err(twice());
                }
            }
            other => {
                return Err(ApiError::bad_request(format!(
                    "unknown part `{}`: expected geometry, case, size, formats, threads, \
                     refine_faces, refine_curves, first, yplus, reynolds, chord, growth, \
                     constant or thickness",
                    printable(other)
                )))
            }
        }
    }
    let case = match case {
        Some(text) => Some(check_case(&text, geometry.as_ref().map(|g| g.0.as_str()))?),
        None => None,
    };
    if case.is_none() && geometry.is_none() {
        return Err(ApiError::bad_request(
            "no file: send a `geometry` part (STEP, IGES or BREP) and/or a `case` part (TOML)",
        ));
    }
    Ok(Submission {
        geometry,
        case,
        size,
        formats: formats.unwrap_or_else(|| DEFAULT_FORMATS.map(String::from).to_vec()),
        threads,
        refine: refine.check()?,
    })
}

/// The refinement fields as sent, checked together.
#[derive(Default)]
struct RefineFields {
    fields: std::collections::HashMap<String, String>,
}

impl RefineFields {
    fn number(
        &self,
        key: &str,
        ok: impl Fn(f64) -> bool,
        what: &str,
    ) -> Result<Option<f64>, ApiError> {
        let Some(v) = self.fields.get(key) else {
            return Ok(None);
        };
        match v.trim().parse::<f64>() {
            Ok(x) if x.is_finite() && ok(x) => Ok(Some(x)),
            _ => Err(ApiError::bad_request(format!(
                "{key} must be {what}, got '{}'",
                printable(v)
            ))),
        }
    }

    fn list(&self, key: &str) -> Vec<String> {
        self.fields
            .get(key)
            .map(|v| {
                v.split(',')
                    .map(str::trim)
                    .filter(|s| !s.is_empty())
                    .map(String::from)
                    .collect()
            })
            .unwrap_or_default()
    }

    /// `None` when no refinement field was sent; the entity names are checked against the
    /// model when the job runs.
    fn check(&self) -> Result<Option<Refine>, ApiError> {
        if self.fields.is_empty() {
            return Ok(None);
        }
        let (faces, curves) = (self.list("refine_faces"), self.list("refine_curves"));
        if faces.is_empty() && curves.is_empty() {
            return Err(ApiError::bad_request(
                "first, growth, constant and thickness need refine_faces or refine_curves",
            ));
        }
        let first = self.number("first", |x| x > 0.0, "a positive number")?;
        let yplus = self.number("yplus", |x| x > 0.0, "a positive number")?;
        let reynolds = self.number("reynolds", |x| x > 0.0, "a positive number")?;
        let chord = self.number("chord", |x| x > 0.0, "a positive number")?;
        if first.is_none() && yplus.is_none() {
            return Err(ApiError::bad_request(
                "first (the first spacing), or yplus with reynolds and chord, is needed with \
                 refine_faces / refine_curves",
            ));
        }
        let growth = self
            .number("growth", |x| x >= 1.0, "a number >= 1")?
            .unwrap_or(1.2);
        let constant = self
            .number(
                "constant",
                |x| x >= 1.0 && x.fract() == 0.0,
                "a whole number >= 1",
            )?
            .map_or(3, |x| x as usize);
        let thickness = self.number("thickness", |x| x > 0.0, "a positive number")?;
        Ok(Some(Refine {
            faces,
            curves,
            first,
            yplus,
            reynolds,
            chord,
            growth,
            constant,
            thickness,
        }))
    }
}

/// A client's text in a message: at most 80 characters, control characters dropped.
fn printable(s: &str) -> String {
    s.chars().filter(|c| !c.is_control()).take(80).collect()
}

/// `su2,vtu` → the names, each a known format.
pub fn parse_formats(list: &str) -> Result<Vec<String>, ApiError> {
    let mut out: Vec<String> = Vec::new();
    for name in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        if parse_format(name).is_none() {
            return Err(ApiError::bad_request(format!(
                "unknown format '{}'; known: {}",
                printable(name),
                format_names().join(", ")
            )));
        }
        if !out.iter().any(|n| n == name) {
            out.push(name.to_string());
        }
    }
    if out.is_empty() {
        return Err(ApiError::bad_request("formats: the list is empty"));
    }
    Ok(out)
}

/// 1-based line of a byte offset.
fn line_of(text: &str, offset: usize) -> usize {
    text.as_bytes()[..offset.min(text.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// The key written on `line` (the text before its `=`), if any.
fn key_on_line(text: &str, line: usize) -> Option<String> {
    let l = text.lines().nth(line.checked_sub(1)?)?;
    let (key, _) = l.split_once('=')?;
    let key = key.trim();
    (!key.is_empty()).then(|| key.to_string())
}

/// Check a case's schema and its `cad` name; return the text to store.
pub fn check_case(text: &str, geometry_ext: Option<&str>) -> Result<String, ApiError> {
    let file: CaseFile = toml::from_str(text).map_err(|e| {
        let line = e.span().map(|s| line_of(text, s.start));
        let key = line.and_then(|l| key_on_line(text, l));
        ApiError::case(
            format!(
                "case.toml{}: {}",
                line.map(|l| format!(":{l}")).unwrap_or_default(),
                e.message().trim_end()
            ),
            key,
            line,
        )
    })?;
    let Some(cad) = &file.mesh.cad else {
        if geometry_ext.is_some() {
            return Err(ApiError::case(
                "a geometry was sent with a case whose [mesh] has no `cad` key: set \
                 `cad = \"<the geometry's file name>\"`, or send the geometry alone",
                Some("mesh.cad".into()),
                None,
            ));
        }
        return Ok(text.to_string());
    };
    let span = cad.span();
    let line = line_of(text, span.start);
    let refuse =
        |message: String| Err(ApiError::case(message, Some("mesh.cad".into()), Some(line)));
    let name = cad.get_ref();
    let bare = !name.is_empty()
        && !name.contains(['/', '\\', '\0', ':'])
        && name != "."
        && name != ".."
        && !std::path::Path::new(name).is_absolute();
    if !bare {
        return refuse(format!(
            "case.toml:{line}: mesh.cad: '{}' is not a bare file name: the service takes no \
             paths, only the name of the geometry uploaded with the case",
            printable(name)
        ));
    }
    let Some(ext) = geometry_ext else {
        return refuse(format!(
            "case.toml:{line}: mesh.cad names '{}' but no `geometry` part was sent",
            printable(name)
        ));
    };
    if cad_extension(name).as_deref() != Some(ext) {
        return refuse(format!(
            "case.toml:{line}: mesh.cad names '{}', which is not the uploaded .{ext} geometry",
            printable(name)
        ));
    }
    let literal = &text[span.clone()];
    if !(literal.starts_with('"') || literal.starts_with('\'')) {
        return refuse(format!("case.toml:{line}: mesh.cad: expected a string"));
    }
    Ok(format!(
        "{}\"geometry.{ext}\"{}",
        &text[..span.start],
        &text[span.end..]
    ))
}
