//! `GET /metrics`: Prometheus text exposition: jobs by state, the queue, and per pipeline
//! stage the runs finished and their seconds (a counter pair, so rates and means come from
//! the scraper).

use super::error::ApiError;
use super::Shared;
use axum::extract::State as Ctx;
use axum::http::header;
use axum::response::IntoResponse;
use std::fmt::Write;
use std::sync::Arc;

pub async fn metrics(Ctx(shared): Ctx<Arc<Shared>>) -> Result<impl IntoResponse, ApiError> {
    let mut out = String::new();
    let _ = writeln!(out, "# HELP tetrafoil_jobs Jobs by state.");
    let _ = writeln!(out, "# TYPE tetrafoil_jobs gauge");
    for (state, n) in shared.store.counts()? {
        let _ = writeln!(out, "tetrafoil_jobs{{state=\"{}\"}} {n}", state.as_str());
    }
    let _ = writeln!(
        out,
        "# HELP tetrafoil_queue_length Jobs waiting for a worker."
    );
    let _ = writeln!(out, "# TYPE tetrafoil_queue_length gauge");
    let _ = writeln!(out, "tetrafoil_queue_length {}", shared.queue.len());
    let _ = writeln!(out, "# HELP tetrafoil_workers_busy Workers running a job.");
    let _ = writeln!(out, "# TYPE tetrafoil_workers_busy gauge");
    let _ = writeln!(out, "tetrafoil_workers_busy {}", shared.queue.running());
    let totals = shared.store.stage_totals()?;
    let _ = writeln!(
        out,
        "# HELP tetrafoil_stage_seconds_total Seconds spent in each pipeline stage."
    );
    let _ = writeln!(out, "# TYPE tetrafoil_stage_seconds_total counter");
    for (stage, _, seconds) in &totals {
        let _ = writeln!(
            out,
            "tetrafoil_stage_seconds_total{{stage=\"{}\"}} {seconds}",
            label(stage)
        );
    }
    let _ = writeln!(
        out,
        "# HELP tetrafoil_stage_runs_total Pipeline stages finished."
    );
    let _ = writeln!(out, "# TYPE tetrafoil_stage_runs_total counter");
    for (stage, runs, _) in &totals {
        let _ = writeln!(
            out,
            "tetrafoil_stage_runs_total{{stage=\"{}\"}} {runs}",
            label(stage)
        );
    }
    Ok(([(header::CONTENT_TYPE, "text/plain; version=0.0.4")], out))
}

/// A label value with `\`, `"` and newlines escaped.
fn label(s: &str) -> String {
    s.replace('\\', "\\\\")
        .replace('"', "\\\"")
        .replace('\n', "\\n")
}
