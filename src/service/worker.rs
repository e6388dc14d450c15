//! The meshing workers: plain threads (never the async runtime's), each taking a job id from
//! the queue, claiming it in the store, running it in a rayon pool of the job's threads, and
//! storing how it ended. A panic inside the pipeline fails that job, not the worker. Each
//! worker has one memory account, charged by its own thread and its job's pool threads.

use super::job::State;
use super::memory::{charge_thread_to, Account};
use super::observer::JobObserver;
use super::run::{run, Outcome};
use super::store::NewEvent;
use super::Shared;
use crate::progress::Reporter;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::Ordering;
use std::sync::Arc;
use std::time::Instant;

/// Start `n` workers.
pub fn spawn(shared: &Arc<Shared>, n: usize) -> std::io::Result<()> {
    for k in 0..n {
        let shared = shared.clone();
        std::thread::Builder::new()
            .name(format!("mesh-worker-{k}"))
            .spawn(move || {
                let account = Account::leaked();
                loop {
                    let id = shared.queue.pop();
                    if let Err(e) = run_one(&shared, &id, account) {
                        log::error!("job {id}: {e}");
                    }
                }
            })?;
    }
    Ok(())
}

fn run_one(shared: &Shared, id: &str, account: &'static Account) -> anyhow::Result<()> {
    let Some(job) = shared.store.get(id)? else {
        return Ok(()); // deleted while queued
    };
    if job.state != State::Queued {
        return Ok(());
    }
    // Partial files of an interrupted run go before the claim (which starts the new run).
    super::files::clear_out(&shared.layout, id)?;
    let Some(attempt) = shared.store.claim(id)? else {
        return Ok(()); // cancelled meanwhile
    };
    shared.changed.send_modify(|n| *n += 1);
    let cancel = shared.queue.start(id);
    let deadline = Instant::now() + shared.config.time_limit;
    account.reset(shared.config.memory_limit);
    let observer = JobObserver::new(
        &shared.store,
        id,
        attempt,
        cancel.clone(),
        deadline,
        account,
        &shared.changed,
    );
    let threads = job.options.threads.clamp(1, shared.config.threads_per_job);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .thread_name(move |k| format!("mesh-{k}"))
        .start_handler(move |_| charge_thread_to(Some(account)))
        .build()?;
    let started = Instant::now();
    charge_thread_to(Some(account));
    let outcome = pool.install(|| {
        catch_unwind(AssertUnwindSafe(|| {
            run(&shared.layout, id, &job.options, Reporter::new(&observer))
        }))
    });
    drop(pool);
    charge_thread_to(None);
    shared.queue.stop(id);
    let outcome = outcome.unwrap_or_else(|panic| {
        let what = panic
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| panic.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".into());
        Outcome::Failed(format!("internal error while meshing: {what}"))
    });
    let seconds = started.elapsed().as_secs_f64();
    let store = &shared.store;
    match outcome {
        Outcome::Done {
            mut report,
            results,
        } => {
            // Heap only: what OpenCASCADE holds in C++ is not counted.
            report["memory_peak_mib"] = serde_json::json!(account.peak() as f64 / 1048576.0);
            store.finish(id, attempt, State::Done, Some(&report), None, &results)?;
            log::info!("job {id}: done in {seconds:.2} s");
        }
        Outcome::Failed(message) => {
            store.finish(id, attempt, State::Failed, None, Some(&message), &[])?;
            log::info!("job {id}: failed after {seconds:.2} s: {message}");
        }
        Outcome::Cancelled if account.over_limit() && !cancel.load(Ordering::Relaxed) => {
            let message = format!(
                "stopped at the memory limit of {} MiB (the run held {} MiB)",
                shared.config.memory_limit >> 20,
                account.peak() >> 20
            );
            super::files::clear_out(&shared.layout, id)?;
            store.finish(id, attempt, State::Failed, None, Some(&message), &[])?;
            log::info!("job {id}: {message}");
        }
        Outcome::Cancelled if observer.timed_out() && !cancel.load(Ordering::Relaxed) => {
            let message = format!(
                "stopped at the time limit of {} s",
                shared.config.time_limit.as_secs()
            );
            super::files::clear_out(&shared.layout, id)?;
            store.finish(id, attempt, State::Failed, None, Some(&message), &[])?;
            log::info!("job {id}: {message}");
        }
        Outcome::Cancelled => {
            super::files::clear_out(&shared.layout, id)?;
            let event = NewEvent {
                message: Some("stopped by the cancel request"),
                ..NewEvent::kind("stopping")
            };
            store.event(id, attempt, &event)?;
            store.finish(id, attempt, State::Cancelled, None, None, &[])?;
            log::info!("job {id}: cancelled after {seconds:.2} s");
        }
    }
    shared.changed.send_modify(|n| *n += 1);
    Ok(())
}
