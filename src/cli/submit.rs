//! `tetrafoil submit`: send a geometry and/or case to a `tetrafoil serve`, optionally follow
//! its events to the end and download the results. The HTTP client is `ureq` (blocking, no
//! async runtime of its own, small): a command that sends one request and reads one stream
//! needs nothing more.

use anyhow::{bail, Context};
use clap::Args;
use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};

#[derive(Args, Debug)]
pub struct SubmitArgs {
    /// A CAD file (.step/.stp, .iges/.igs, .brep) or a case file (.toml).
    pub file: PathBuf,
    /// A case file for the CAD file (its `[mesh] cad` names the CAD file).
    #[arg(long)]
    pub case: Option<PathBuf>,
    /// The service, e.g. http://127.0.0.1:8080.
    #[arg(long)]
    pub server: String,
    /// Follow the job to its end (implied by -o); exit non-zero if it fails.
    #[arg(long)]
    pub wait: bool,
    /// Download the result to this file (its extension picks the format); repeatable.
    #[arg(short, long)]
    pub output: Vec<PathBuf>,
    /// Override the background spacing.
    #[arg(long)]
    pub size: Option<f64>,
    /// Threads for the job (capped by the server).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Bearer token (default: the TETRAFOIL_TOKEN environment variable).
    #[arg(long)]
    pub token: Option<String>,
}

/// One multipart part: name, file name, bytes.
type Part = (String, Option<String>, Vec<u8>);

/// A multipart/form-data body and its boundary.
fn multipart(parts: &[Part]) -> (String, Vec<u8>) {
    // A boundary no file is likely to contain: seeded per process, checked against the parts.
    use std::hash::{BuildHasher, Hasher};
    let mut h = std::collections::hash_map::RandomState::new().build_hasher();
    h.write_u32(std::process::id());
    let mut boundary = format!("tetrafoil-{:016x}", h.finish());
    while parts.iter().any(|p| contains(&p.2, boundary.as_bytes())) {
        boundary.push('x');
    }
    let mut body = Vec::new();
    for (name, file, bytes) in parts {
        body.extend_from_slice(format!("--{boundary}\r\n").as_bytes());
        let disposition = match file {
            Some(f) => format!("form-data; name=\"{name}\"; filename=\"{f}\""),
            None => format!("form-data; name=\"{name}\""),
        };
        body.extend_from_slice(format!("Content-Disposition: {disposition}\r\n\r\n").as_bytes());
        body.extend_from_slice(bytes);
        body.extend_from_slice(b"\r\n");
    }
    body.extend_from_slice(format!("--{boundary}--\r\n").as_bytes());
    (boundary, body)
}

fn contains(haystack: &[u8], needle: &[u8]) -> bool {
    haystack.windows(needle.len()).any(|w| w == needle)
}

fn file_part(name: &str, path: &Path) -> anyhow::Result<Part> {
    let bytes = std::fs::read(path).with_context(|| format!("reading {}", path.display()))?;
    // Only the base name travels: the server takes the kind of file from it, nothing more.
    let base = path
        .file_name()
        .and_then(|n| n.to_str())
        .map(|n| n.replace('"', "_"));
    Ok((name.to_string(), base, bytes))
}

/// The error text of a refused request (the server's JSON `error`, with key and line).
fn refusal(e: ureq::Error) -> anyhow::Error {
    match e {
        ureq::Error::Status(code, response) => {
            let text = response.into_string().unwrap_or_default();
            let message = serde_json::from_str::<serde_json::Value>(&text)
                .ok()
                .and_then(|v| v["error"].as_str().map(str::to_string))
                .unwrap_or(text);
            anyhow::anyhow!("the server answered {code}: {message}")
        }
        e => anyhow::anyhow!("{e}"),
    }
}

pub fn run(a: SubmitArgs, quiet: bool) -> anyhow::Result<()> {
    let server = a.server.trim_end_matches('/').to_string();
    let token = a
        .token
        .clone()
        .or_else(|| std::env::var("TETRAFOIL_TOKEN").ok());
    let is_case = a
        .file
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"));
    let mut parts = Vec::new();
    match (&a.case, is_case) {
        (Some(_), true) => bail!(
            "{} is a case file: --case goes with a CAD file",
            a.file.display()
        ),
        (Some(case), false) => {
            parts.push(file_part("geometry", &a.file)?);
            parts.push(file_part("case", case)?);
        }
        (None, true) => parts.push(file_part("case", &a.file)?),
        (None, false) => parts.push(file_part("geometry", &a.file)?),
    }
    let mut formats: Vec<String> = Vec::new();
    for o in &a.output {
        let f = crate::io::MeshFormat::from_path(o).with_context(|| {
            format!(
                "cannot tell the format of {} from its extension",
                o.display()
            )
        })?;
        let name = match f {
            crate::io::MeshFormat::Msh41 => "msh",
            other => other.extension(),
        };
        formats.push(name.to_string());
    }
    if !formats.is_empty() {
        parts.push(("formats".into(), None, formats.join(",").into_bytes()));
    }
    if let Some(h) = a.size {
        parts.push(("size".into(), None, h.to_string().into_bytes()));
    }
    if let Some(n) = a.threads {
        parts.push(("threads".into(), None, n.to_string().into_bytes()));
    }
    let (boundary, body) = multipart(&parts);
    let with_token = |r: ureq::Request| match &token {
        Some(t) => r.set("Authorization", &format!("Bearer {t}")),
        None => r,
    };
    let response = with_token(ureq::post(&format!("{server}/v1/jobs")))
        .set(
            "Content-Type",
            &format!("multipart/form-data; boundary={boundary}"),
        )
        .send_bytes(&body)
        .map_err(refusal)?;
    let text = response
        .into_string()
        .context("reading the server's answer")?;
    let job: serde_json::Value = serde_json::from_str(&text).context("the server's answer")?;
    let id = job["id"]
        .as_str()
        .context("the server's answer has no job id")?
        .to_string();
    println!("{id}");
    if !a.wait && a.output.is_empty() {
        return Ok(());
    }
    let events = with_token(ureq::get(&format!("{server}/v1/jobs/{id}/events")))
        .call()
        .map_err(refusal)?;
    let mut last_stage = String::new();
    let mut end = None;
    for line in BufReader::new(events.into_reader()).lines() {
        let line = line.context("reading the event stream")?;
        let Some(data) = line.strip_prefix("data:") else {
            continue;
        };
        let event: serde_json::Value = serde_json::from_str(data.trim())?;
        let kind = event["kind"].as_str().unwrap_or("");
        if let Some(stage) = event["stage"].as_str() {
            if !quiet && kind == "stage" && stage != last_stage {
                eprintln!("{id}: {stage}");
                last_stage = stage.to_string();
            }
        }
        if matches!(kind, "done" | "failed" | "cancelled") {
            end = Some((
                kind.to_string(),
                event["message"].as_str().map(str::to_string),
            ));
            break;
        }
    }
    match end {
        Some((kind, _)) if kind == "done" => {}
        Some((kind, message)) => bail!("job {id} {kind}: {}", message.unwrap_or_default()),
        None => bail!("the event stream of job {id} ended before the job did"),
    }
    for (o, f) in a.output.iter().zip(&formats) {
        let mut files = vec![(format!("{server}/v1/jobs/{id}/result/{f}"), o.clone())];
        if crate::io::MeshFormat::from_path(o).is_some_and(|f| f.has_mapbc()) {
            let mapbc = crate::io::mapbc_path(o);
            files.push((format!("{server}/v1/jobs/{id}/result/{f}/mapbc"), mapbc));
        }
        for (url, path) in files {
            download(with_token(ureq::get(&url)), &path)?;
            if !quiet {
                eprintln!("{id}: wrote {}", path.display());
            }
        }
    }
    Ok(())
}

/// The body of `request`'s answer into `path` (temporary file, then rename).
fn download(request: ureq::Request, path: &Path) -> anyhow::Result<()> {
    let response = request.call().map_err(refusal)?;
    let mut reader = response.into_reader();
    crate::io::write_atomic(path, |w| std::io::copy(&mut reader.by_ref(), w).map(|_| ()))
        .with_context(|| format!("writing {}", path.display()))
}
