//! The pipeline's [`Observer`] for one run of a job: stage starts and ends become events in
//! the store, counts become progress events (at most a few per second, so a face-by-face
//! count does not flood the database), and `cancelled` answers true once the job was
//! cancelled through the API or ran past the server's time or memory limit.

use super::memory::Account;
use super::store::{NewEvent, Store};
use crate::progress::Observer;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use tokio::sync::watch;

/// The shortest time between two stored progress events of a job.
const PROGRESS_EVERY: Duration = Duration::from_millis(250);

pub struct JobObserver<'a> {
    pub store: &'a Store,
    pub id: &'a str,
    pub attempt: u32,
    /// Set by `DELETE /v1/jobs/{id}`.
    pub cancel: Arc<AtomicBool>,
    pub deadline: Instant,
    /// What the run holds (the worker's account).
    pub memory: &'static Account,
    /// Bumped after every stored event: the event streams wait on it.
    pub changed: &'a watch::Sender<u64>,
    last_progress: Mutex<Option<(String, Instant)>>,
}

impl<'a> JobObserver<'a> {
    pub fn new(
        store: &'a Store,
        id: &'a str,
        attempt: u32,
        cancel: Arc<AtomicBool>,
        deadline: Instant,
        memory: &'static Account,
        changed: &'a watch::Sender<u64>,
    ) -> Self {
        JobObserver {
            store,
            id,
            attempt,
            cancel,
            deadline,
            memory,
            changed,
            last_progress: Mutex::new(None),
        }
    }

    /// Whether the time limit (not a user) stopped the run.
    pub fn timed_out(&self) -> bool {
        Instant::now() >= self.deadline
    }

    fn record(&self, event: NewEvent<'_>) {
        // A lost progress event is not worth failing a run over: log it and go on.
        if let Err(e) = self.store.event(self.id, self.attempt, &event) {
            log::error!("job {}: storing a {} event: {e}", self.id, event.kind);
        }
        self.changed.send_modify(|n| *n += 1);
    }
}

impl Observer for JobObserver<'_> {
    fn stage_started(&self, stage: &str) {
        self.record(NewEvent {
            stage: Some(stage),
            ..NewEvent::kind("stage")
        });
    }

    fn stage_finished(&self, stage: &str, seconds: f64) {
        self.record(NewEvent {
            stage: Some(stage),
            seconds: Some(seconds),
            ..NewEvent::kind("stage_done")
        });
    }

    fn progress(&self, stage: &str, done: u64, total: u64) {
        {
            let mut last = self.last_progress.lock().unwrap_or_else(|e| e.into_inner());
            let now = Instant::now();
            let due = match last.as_ref() {
                Some((s, at)) => s != stage || now - *at >= PROGRESS_EVERY || done >= total,
                None => true,
            };
            if !due {
                return;
            }
            *last = Some((stage.to_string(), now));
        }
        self.record(NewEvent {
            stage: Some(stage),
            done: Some(done),
            total: Some(total),
            ..NewEvent::kind("progress")
        });
    }

    fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed) || self.timed_out() || self.memory.over_limit()
    }
}
