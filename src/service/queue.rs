//! The queue of job ids the workers take from, bounded (a full queue answers `429`), and the
//! cancel flags of the running jobs. The database is the truth about a job's state; this
//! only orders the work of this process and is rebuilt from the database at start.

use std::collections::{HashMap, VecDeque};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};

#[derive(Default)]
pub struct Queue {
    waiting: Mutex<VecDeque<String>>,
    ready: Condvar,
    running: Mutex<HashMap<String, Arc<AtomicBool>>>,
}

/// The queue already holds its bound of jobs.
#[derive(Debug)]
pub struct Full;

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

impl Queue {
    /// Queue `id` unless `max` jobs wait already; `accept` (storing the job) runs under the
    /// queue's lock, so two submissions cannot both take the last place.
    pub fn try_push<E>(
        &self,
        id: &str,
        max: usize,
        accept: impl FnOnce() -> Result<(), E>,
    ) -> Result<Result<(), E>, Full> {
        let mut waiting = lock(&self.waiting);
        if waiting.len() >= max {
            return Err(Full);
        }
        if let Err(e) = accept() {
            return Ok(Err(e));
        }
        waiting.push_back(id.to_string());
        self.ready.notify_one();
        Ok(Ok(()))
    }

    /// Queue a job recovered at start (no bound: it was accepted before).
    pub fn push(&self, id: &str) {
        lock(&self.waiting).push_back(id.to_string());
        self.ready.notify_one();
    }

    /// The next job id; blocks until there is one.
    pub fn pop(&self) -> String {
        let mut waiting = lock(&self.waiting);
        loop {
            if let Some(id) = waiting.pop_front() {
                return id;
            }
            waiting = self.ready.wait(waiting).unwrap_or_else(|e| e.into_inner());
        }
    }

    /// Drop a queued id (cancelled before it ran).
    pub fn remove(&self, id: &str) {
        lock(&self.waiting).retain(|x| x != id);
    }

    pub fn len(&self) -> usize {
        lock(&self.waiting).len()
    }

    /// A running job's cancel flag, registered for [`Queue::cancel`].
    pub fn start(&self, id: &str) -> Arc<AtomicBool> {
        let flag = Arc::new(AtomicBool::new(false));
        lock(&self.running).insert(id.to_string(), flag.clone());
        flag
    }

    pub fn stop(&self, id: &str) {
        lock(&self.running).remove(id);
    }

    /// Ask a running job to stop; `false` if it is not running here.
    pub fn cancel(&self, id: &str) -> bool {
        match lock(&self.running).get(id) {
            Some(flag) => {
                flag.store(true, Ordering::Relaxed);
                true
            }
            None => false,
        }
    }

    pub fn running(&self) -> usize {
        lock(&self.running).len()
    }
}
