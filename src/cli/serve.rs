//! `tetrafoil serve`: the mesh service's command line (the service itself is
//! `crate::service`).

use crate::service::{self, Access, Config};
use clap::Args;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::time::Duration;

#[derive(Args, Debug)]
pub struct ServeArgs {
    /// Folder for the job database and files (created if missing).
    #[arg(long)]
    pub data: PathBuf,
    /// Address to listen on.
    #[arg(long, default_value = "127.0.0.1:8080")]
    pub listen: SocketAddr,
    /// Jobs meshing at once.
    #[arg(long, default_value_t = 1)]
    pub workers: usize,
    /// Threads per job (default: the cores shared among the workers).
    #[arg(long)]
    pub threads_per_job: Option<usize>,
    /// `NAME TOKEN` lines: clients then need `Authorization: Bearer TOKEN` and see only the
    /// jobs of their token. Without it only loopback connections are accepted.
    #[arg(long)]
    pub token_file: Option<PathBuf>,
    /// The largest upload, in bytes (refused from its Content-Length, before reading).
    #[arg(long, default_value_t = 256 << 20)]
    pub max_upload: u64,
    /// Jobs that may wait for a worker; more submissions answer 429.
    #[arg(long, default_value_t = 100)]
    pub max_queue: usize,
    /// A run longer than this many seconds is stopped and its job failed.
    #[arg(long, default_value_t = 3600)]
    pub time_limit: u64,
    /// A run holding more than this many MiB of heap is stopped and its job failed (0: no
    /// limit).
    #[arg(long, default_value_t = 8192)]
    pub memory_limit: u64,
}

pub fn run(a: ServeArgs) -> anyhow::Result<()> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let access = match &a.token_file {
        Some(path) => service::load_tokens(path)?,
        None => Access::Loopback,
    };
    anyhow::ensure!(a.time_limit >= 1, "--time-limit must be at least 1 s");
    service::serve(Config {
        data: a.data,
        listen: a.listen,
        workers: a.workers,
        threads_per_job: a
            .threads_per_job
            .unwrap_or((cores / a.workers.max(1)).max(1)),
        access,
        max_upload: a.max_upload,
        max_queue: a.max_queue,
        time_limit: Duration::from_secs(a.time_limit),
        memory_limit: a.memory_limit << 20,
    })
}
