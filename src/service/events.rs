//! `GET /v1/jobs/{id}/events`: the job's events as server-sent events, from the first (or
//! after `Last-Event-ID`, so a client that reconnects misses nothing) and then live, until
//! the job ends. Each SSE message has the event's id, its kind as the SSE event name, and the
//! event as JSON. Live events are read from the store when the workers signal a change, so
//! the stream shows exactly what `GET /v1/jobs/{id}` would.

use super::auth::{owned, Owner};
use super::error::ApiError;
use super::store::Event;
use super::Shared;
use axum::extract::{Path, State as Ctx};
use axum::http::HeaderMap;
use axum::response::sse::{Event as Sse, KeepAlive, Sse as SseResponse};
use axum::Extension;
use futures_util::stream::{self, Stream};
use std::convert::Infallible;
use std::sync::Arc;
use std::time::Duration;

/// Events read from the store at a time.
const BATCH: usize = 256;

struct Cursor {
    shared: Arc<Shared>,
    id: String,
    after: i64,
    pending: std::collections::VecDeque<Event>,
    changed: tokio::sync::watch::Receiver<u64>,
    ended: bool,
}

pub async fn stream(
    Ctx(shared): Ctx<Arc<Shared>>,
    Extension(owner): Extension<Owner>,
    Path(id): Path<String>,
    headers: HeaderMap,
) -> Result<SseResponse<impl Stream<Item = Result<Sse, Infallible>>>, ApiError> {
    owned(&shared, &owner, &id)?;
    let after = headers
        .get("last-event-id")
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.trim().parse::<i64>().ok())
        .unwrap_or(0);
    let changed = shared.changed.subscribe();
    let cursor = Cursor {
        shared,
        id,
        after,
        pending: Default::default(),
        changed,
        ended: false,
    };
    let events = stream::unfold(cursor, |mut c| async move {
        loop {
            if c.ended {
                return None;
            }
            if let Some(event) = c.pending.pop_front() {
                c.after = event.id;
                c.ended = event.is_final();
                let data = serde_json::to_string(&event).unwrap_or_default();
                let sse = Sse::default()
                    .id(event.id.to_string())
                    .event(event.kind.clone())
                    .data(data);
                return Some((Ok(sse), c));
            }
            // Mark what we have seen before reading, so no change slips between.
            c.changed.borrow_and_update();
            match c.shared.store.events_after(&c.id, c.after, BATCH) {
                Ok(batch) if !batch.is_empty() => c.pending.extend(batch),
                Ok(_) => {
                    // Nothing new: wait for a change (or look again after a while, in case
                    // the job was deleted and no event will come).
                    let wait = tokio::time::timeout(Duration::from_secs(5), c.changed.changed());
                    if let Ok(Err(_)) = wait.await {
                        return None; // the server is stopping
                    }
                    if !matches!(c.shared.store.get(&c.id), Ok(Some(_))) {
                        return None;
                    }
                }
                Err(e) => {
                    log::error!("events of job {}: {e}", c.id);
                    return None;
                }
            }
        }
    });
    Ok(SseResponse::new(events).keep_alive(KeepAlive::default()))
}
