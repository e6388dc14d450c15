//! The routes: the job API under `/v1`, `/healthz` and `/metrics`. Two layers run before any
//! handler reads a body: the size check (a declared Content-Length over the limit is refused
//! with `413` at once) and the access check (token or loopback). Anything not routed is a JSON
//! `404`/`405`.

use super::auth::{self, owned, Access, Owner};
use super::error::ApiError;
use super::files;
use super::job::{parse_format, Job, Options, State};
use super::upload::{self, Submission};
use super::Shared;
use axum::body::Body;
use axum::extract::{ConnectInfo, DefaultBodyLimit, Multipart, Path, Request, State as Ctx};
use axum::http::{header, StatusCode};
use axum::middleware::{self, Next};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use axum::{Extension, Json, Router};
use serde_json::json;
use std::net::SocketAddr;
use std::sync::Arc;

pub fn router(shared: Arc<Shared>) -> Router {
    let limit = usize::try_from(shared.config.max_upload).unwrap_or(usize::MAX);
    let v1 = Router::new()
        .route("/jobs", get(list).post(create))
        .route("/jobs/{id}", get(one).delete(remove))
        .route("/jobs/{id}/events", get(super::events::stream))
        .route("/jobs/{id}/result/{format}", get(result))
        .route("/jobs/{id}/result/{format}/mapbc", get(result_mapbc))
        .route("/jobs/{id}/surface", get(surface));
    let guarded = Router::new()
        .nest("/v1", v1)
        .route("/metrics", get(super::metrics::metrics))
        .layer(middleware::from_fn_with_state(shared.clone(), access));
    Router::new()
        .route("/", get(super::page::index))
        .route("/healthz", get(healthz))
        .merge(guarded)
        .fallback(not_found)
        .method_not_allowed_fallback(not_allowed)
        .layer(DefaultBodyLimit::max(limit))
        .layer(middleware::from_fn_with_state(shared.clone(), size_limit))
        .layer(middleware::from_fn_with_state(shared.clone(), loopback))
        .with_state(shared)
}

async fn not_found() -> ApiError {
    ApiError::not_found("no such route (the API is under /v1: see docs/service.md)")
}

async fn not_allowed() -> ApiError {
    ApiError::new(
        StatusCode::METHOD_NOT_ALLOWED,
        "method not allowed on this route",
    )
}

/// Without a token file, only loopback peers, on every route.
async fn loopback(
    Ctx(shared): Ctx<Arc<Shared>>,
    ConnectInfo(peer): ConnectInfo<SocketAddr>,
    request: Request,
    next: Next,
) -> Response {
    if matches!(shared.config.access, Access::Loopback) && !peer.ip().is_loopback() {
        return ApiError::new(StatusCode::FORBIDDEN, auth::LOOPBACK_ONLY).into_response();
    }
    next.run(request).await
}

/// A body declared larger than the limit is refused before a byte of it is read.
async fn size_limit(Ctx(shared): Ctx<Arc<Shared>>, request: Request, next: Next) -> Response {
    let declared = request
        .headers()
        .get(header::CONTENT_LENGTH)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.parse::<u64>().ok());
    if let Some(n) = declared {
        let max = shared.config.max_upload;
        if n > max {
            let mut response = ApiError::new(
                StatusCode::PAYLOAD_TOO_LARGE,
                format!("the upload is {n} bytes; this server takes at most {max}"),
            )
            .into_response();
            // The client is mid-upload: tell it the connection ends here.
            response.headers_mut().insert(
                header::CONNECTION,
                header::HeaderValue::from_static("close"),
            );
            return response;
        }
    }
    next.run(request).await
}

/// The owner from the token (or the loopback rule), into the request's extensions.
async fn access(
    Ctx(shared): Ctx<Arc<Shared>>,
    ConnectInfo(peer): ConnectInfo<SocketAddr>,
    mut request: Request,
    next: Next,
) -> Response {
    match auth::owner(&shared.config.access, request.headers(), peer) {
        Ok(owner) => {
            request.extensions_mut().insert(Owner(owner));
            next.run(request).await
        }
        Err(e) => e.into_response(),
    }
}

async fn healthz(Ctx(shared): Ctx<Arc<Shared>>) -> Result<Json<serde_json::Value>, ApiError> {
    let queued = shared.store.queued()?;
    Ok(Json(json!({
        "status": "ok",
        "queued": queued,
        "running": shared.queue.running(),
        "workers": shared.config.workers,
    })))
}

async fn list(
    Ctx(shared): Ctx<Arc<Shared>>,
    Extension(owner): Extension<Owner>,
) -> Result<Json<serde_json::Value>, ApiError> {
    let jobs = shared.store.list(&owner.0)?;
    Ok(Json(json!({ "jobs": jobs })))
}

async fn one(
    Ctx(shared): Ctx<Arc<Shared>>,
    Extension(owner): Extension<Owner>,
    Path(id): Path<String>,
) -> Result<Json<Job>, ApiError> {
    Ok(Json(owned(&shared, &owner, &id)?))
}

async fn create(
    Ctx(shared): Ctx<Arc<Shared>>,
    Extension(owner): Extension<Owner>,
    form: Result<Multipart, axum::extract::multipart::MultipartRejection>,
) -> Result<Response, ApiError> {
    let form = form.map_err(|e| {
        ApiError::bad_request(format!(
            "expected a multipart/form-data body with a `geometry` and/or `case` part: {}",
            e.body_text()
        ))
    })?;
    let submission = upload::read(form).await?;
    let id = files::new_id();
    let options = Options {
        input: submission.input_name(),
        size: submission.size,
        formats: submission.formats.clone(),
        threads: submission
            .threads
            .unwrap_or(shared.config.threads_per_job)
            .min(shared.config.threads_per_job),
        refine: submission.refine.clone(),
    };
    // Files first (durably), then the row: a crash between leaves an orphan folder that the
    // next start removes, never a job without its input.
    let stored = {
        let shared = shared.clone();
        let id = id.clone();
        tokio::task::spawn_blocking(move || store_input(&shared, &id, &submission))
            .await
            .map_err(ApiError::internal)?
    };
    if let Err(e) = stored {
        let _ = files::remove_job(&shared.layout, &id);
        return Err(e);
    }
    let accepted = shared.queue.try_push(&id, shared.config.max_queue, || {
        shared.store.insert(&id, &owner.0, &options)
    });
    match accepted {
        Ok(Ok(())) => {}
        Ok(Err(e)) => {
            let _ = files::remove_job(&shared.layout, &id);
            return Err(e.into());
        }
        Err(_full) => {
            let _ = files::remove_job(&shared.layout, &id);
            return Err(ApiError::new(
                StatusCode::TOO_MANY_REQUESTS,
                format!(
                    "the queue is full ({} jobs waiting): try again later",
                    shared.config.max_queue
                ),
            ));
        }
    }
    shared.changed.send_modify(|n| *n += 1);
    log::info!("job {id}: queued ({})", options.input);
    let job = owned(&shared, &owner, &id)?;
    let location = format!("/v1/jobs/{id}");
    Ok((
        StatusCode::CREATED,
        [(header::LOCATION, location)],
        Json(job),
    )
        .into_response())
}

fn store_input(shared: &Shared, id: &str, s: &Submission) -> Result<(), ApiError> {
    let input = shared.layout.input(id);
    std::fs::create_dir_all(&input)?;
    std::fs::create_dir_all(shared.layout.out(id))?;
    if let Some((ext, bytes)) = &s.geometry {
        files::write_file(&input.join(format!("geometry.{ext}")), bytes)?;
    }
    if let Some(text) = &s.case {
        files::write_file(&input.join("case.toml"), text.as_bytes())?;
    }
    Ok(())
}

/// Cancel a live job (`202`), or delete a finished one with its files (`204`).
async fn remove(
    Ctx(shared): Ctx<Arc<Shared>>,
    Extension(owner): Extension<Owner>,
    Path(id): Path<String>,
) -> Result<Response, ApiError> {
    let job = owned(&shared, &owner, &id)?;
    if job.state == State::Queued && shared.store.cancel_queued(&id)? {
        shared.queue.remove(&id);
        shared.changed.send_modify(|n| *n += 1);
        return Ok((StatusCode::ACCEPTED, Json(owned(&shared, &owner, &id)?)).into_response());
    }
    if job.state.is_final() {
        shared.store.delete(&id)?;
        let layout = shared.layout.clone();
        tokio::task::spawn_blocking(move || files::remove_job(&layout, &id))
            .await
            .map_err(ApiError::internal)??;
        return Ok(StatusCode::NO_CONTENT.into_response());
    }
    // Running (or claimed by a worker since the read): its run stops at its next check.
    shared.queue.cancel(&id);
    Ok((StatusCode::ACCEPTED, Json(job)).into_response())
}

/// A result file, streamed from disk.
async fn result(
    Ctx(shared): Ctx<Arc<Shared>>,
    Extension(owner): Extension<Owner>,
    Path((id, format)): Path<(String, String)>,
) -> Result<Response, ApiError> {
    let (path, mesh_format) = done_result(&shared, &owner, &id, &format)?;
    let name = format!("{id}.{}", mesh_format.extension());
    stream_file(&path, "application/octet-stream", Some(&name)).await
}

/// The `.mapbc` beside a UGRID result (FUN3D's boundary conditions by surface id).
async fn result_mapbc(
    Ctx(shared): Ctx<Arc<Shared>>,
    Extension(owner): Extension<Owner>,
    Path((id, format)): Path<(String, String)>,
) -> Result<Response, ApiError> {
    let (path, mesh_format) = done_result(&shared, &owner, &id, &format)?;
    if !mesh_format.has_mapbc() {
        return Err(ApiError::not_found(format!(
            "a {format} result has no .mapbc; the UGRID formats have one"
        )));
    }
    let name = format!("{id}.mapbc");
    stream_file(&crate::io::mapbc_path(&path), "text/plain", Some(&name)).await
}

/// The file of job `id`'s result in `format`, once the job is done and was asked for it.
fn done_result(
    shared: &Shared,
    owner: &Owner,
    id: &str,
    format: &str,
) -> Result<(std::path::PathBuf, crate::io::MeshFormat), ApiError> {
    let job = owned(shared, owner, id)?;
    let Some(mesh_format) = parse_format(format) else {
        return Err(ApiError::bad_request(format!(
            "unknown format '{}'; known: {}",
            format.chars().take(40).collect::<String>(),
            super::job::format_names().join(", ")
        )));
    };
    if job.state != State::Done {
        return Err(ApiError::new(
            StatusCode::CONFLICT,
            format!(
                "job {id} is {}: results come when it is done",
                job.state.as_str()
            ),
        ));
    }
    if !job.results.iter().any(|r| r == format) {
        return Err(ApiError::not_found(format!(
            "job {id} was not asked for {format}; it has: {}",
            job.results.join(", ")
        )));
    }
    let path = shared.layout.result(id, format, mesh_format.extension());
    Ok((path, mesh_format))
}

/// A done job's boundary triangles and markers as JSON, for the web page's viewer.
async fn surface(
    Ctx(shared): Ctx<Arc<Shared>>,
    Extension(owner): Extension<Owner>,
    Path(id): Path<String>,
) -> Result<Response, ApiError> {
    let job = owned(&shared, &owner, &id)?;
    if job.state != State::Done {
        return Err(ApiError::new(
            StatusCode::CONFLICT,
            format!(
                "job {id} is {}: its surface comes when it is done",
                job.state.as_str()
            ),
        ));
    }
    stream_file(&shared.layout.surface(&id), "application/json", None).await
}

/// A file streamed from disk, optionally as a download under `name`.
async fn stream_file(
    path: &std::path::Path,
    content_type: &str,
    name: Option<&str>,
) -> Result<Response, ApiError> {
    let file = match tokio::fs::File::open(path).await {
        Ok(f) => f,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(ApiError::not_found("the file is gone (deleted meanwhile)"))
        }
        Err(e) => return Err(e.into()),
    };
    let length = file.metadata().await?.len();
    // 64 KiB reads: the default 4 KiB made a 2 MB SU2 download a few hundred small writes.
    let body = Body::from_stream(tokio_util::io::ReaderStream::with_capacity(file, 64 << 10));
    let mut response = (
        [
            (header::CONTENT_TYPE, content_type.to_string()),
            (header::CONTENT_LENGTH, length.to_string()),
        ],
        body,
    )
        .into_response();
    if let Some(name) = name {
        let disposition = format!("attachment; filename=\"{name}\"");
        if let Ok(v) = header::HeaderValue::from_str(&disposition) {
            response
                .headers_mut()
                .insert(header::CONTENT_DISPOSITION, v);
        }
    }
    Ok(response)
}
