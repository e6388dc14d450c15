//! `tetrafoil serve`: the mesh service. Jobs come in over HTTP (JSON API under `/v1`), are
//! stored before they are acknowledged (SQLite for jobs and events, files under
//! `DATA/jobs/<id>/`), mesh on a pool of worker threads with progress from the pipeline's
//! observer, and survive a killed server: at start, jobs that were running are queued again
//! and queued jobs run. The entry point is [`serve`]; `docs/service.md` is the API.
//!
//! - `page.rs` — the web page at `/`;
//! - `api.rs` — the routes and handlers; `upload.rs` — reading and checking a submission;
//!   `events.rs` — server-sent events; `metrics.rs` — Prometheus text.
//! - `auth.rs` — tokens and the loopback rule; `error.rs` — the JSON error answers.
//! - `store.rs` — the database; `files.rs` — the data folder; `job.rs` — the job's shape.
//! - `queue.rs`, `worker.rs`, `observer.rs`, `run.rs` — the work: queue, threads, progress,
//!   and one run of the pipeline; `memory.rs` — the per-job memory accounting.

mod api;
mod auth;
mod error;
mod events;
mod files;
mod job;
pub mod memory;
mod metrics;
mod observer;
mod page;
mod queue;
mod run;
mod store;
mod upload;
mod worker;

pub use auth::{load_tokens, Access};
pub use job::State;

use anyhow::Context;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::watch;

/// How the service runs.
#[derive(Clone, Debug)]
pub struct Config {
    pub data: PathBuf,
    pub listen: SocketAddr,
    /// Jobs meshing at once.
    pub workers: usize,
    /// Threads each job may use (its `threads` option is capped to this).
    pub threads_per_job: usize,
    pub access: Access,
    /// The largest request body accepted (refused from its Content-Length, before reading).
    pub max_upload: u64,
    /// Jobs waiting at most; a submission beyond answers `429`.
    pub max_queue: usize,
    /// A run past this is stopped and its job failed.
    pub time_limit: Duration,
    /// A run holding more than this many bytes is stopped and its job failed (0: no limit;
    /// counted only where the binary installs [`memory::Counting`]).
    pub memory_limit: u64,
}

/// What the handlers and workers share.
pub(crate) struct Shared {
    config: Config,
    layout: files::Layout,
    store: store::Store,
    queue: queue::Queue,
    /// Bumped after every stored event; the event streams wait on it.
    changed: watch::Sender<u64>,
}

/// Open the data folder, recover the jobs of an earlier run, start the workers and serve
/// until the process is stopped (Ctrl-C or SIGTERM: running jobs then run again at the next
/// start).
pub fn serve(config: Config) -> anyhow::Result<()> {
    let shared = Arc::new(open(config)?);
    worker::spawn(&shared, shared.config.workers).context("starting the workers")?;
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .context("starting the async runtime")?;
    runtime.block_on(async move {
        let listen = shared.config.listen;
        let listener = tokio::net::TcpListener::bind(listen)
            .await
            .with_context(|| format!("listening on {listen}"))?;
        let local = listener.local_addr()?;
        log::info!(
            "tetrafoil serve: listening on http://{local}, data in {}, {} worker(s) × {} thread(s)",
            shared.config.data.display(),
            shared.config.workers,
            shared.config.threads_per_job
        );
        let app = api::router(shared.clone()).into_make_service_with_connect_info::<SocketAddr>();
        // On a stop signal new connections end at once; open event streams get a moment,
        // then the process goes (the jobs it was running are re-run at the next start).
        let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
        let signal = async move {
            shutdown().await;
            let _ = stop.send(());
        };
        let server = axum::serve(listener, app).with_graceful_shutdown(signal);
        tokio::select! {
            r = server => r.context("serving"),
            _ = async {
                let _ = stopped.await;
                tokio::time::sleep(Duration::from_secs(2)).await;
            } => Ok(()),
        }
    })
}

async fn shutdown() {
    let ctrl_c = async {
        let _ = tokio::signal::ctrl_c().await;
    };
    #[cfg(unix)]
    let term = async {
        match tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate()) {
            Ok(mut s) => {
                s.recv().await;
            }
            Err(_) => std::future::pending::<()>().await,
        }
    };
    #[cfg(not(unix))]
    let term = std::future::pending::<()>();
    tokio::select! { _ = ctrl_c => {}, _ = term => {} }
    log::info!("tetrafoil serve: stopping");
}

/// The data folder and database, with the jobs of an earlier run recovered and queued.
fn open(config: Config) -> anyhow::Result<Shared> {
    anyhow::ensure!(config.workers >= 1, "--workers must be at least 1");
    anyhow::ensure!(
        config.threads_per_job >= 1,
        "--threads-per-job must be at least 1"
    );
    let layout = files::Layout {
        data: config.data.clone(),
    };
    std::fs::create_dir_all(layout.jobs())
        .with_context(|| format!("creating {}", layout.jobs().display()))?;
    let store = store::Store::open(&layout.database())
        .with_context(|| format!("opening {}", layout.database().display()))?;
    let (rerun, queued) = store.recover().context("recovering the jobs")?;
    let swept = files::sweep_orphans(&layout, &store.ids()?)?;
    let queue = queue::Queue::default();
    for id in &queued {
        queue.push(id);
    }
    if !queued.is_empty() || swept > 0 {
        log::info!(
            "tetrafoil serve: {} job(s) queued again ({} were running), {swept} unfinished \
             upload(s) removed",
            queued.len(),
            rerun.len()
        );
    }
    let (changed, _) = watch::channel(0);
    Ok(Shared {
        config,
        layout,
        store,
        queue,
        changed,
    })
}
