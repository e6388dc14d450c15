//! Progress and cancellation: the one interface the pipeline's stages report through. The
//! command line draws it as progress bars, the service stores it as job events; the stages
//! themselves know neither. A stage says when it starts and finishes and how far it is
//! (`done` of `total`: faces meshed of faces, interior points inserted of the expected count),
//! and its long loops ask [`Reporter::cancelled`] so that a cancelled or timed-out job stops
//! within one face or one round of insertion instead of running to the end.

use std::fmt;
use std::time::Instant;

/// What the pipeline tells whoever runs it. Called from worker threads (a face finishes on
/// whichever rayon thread meshed it), so implementations are `Sync` and cheap: a counter,
/// a channel send, never a blocking wait.
pub trait Observer: Sync {
    /// A stage (`"curves"`, `"surfaces"`, `"interior"` …) started.
    fn stage_started(&self, _stage: &str) {}
    /// A stage finished after `seconds`.
    fn stage_finished(&self, _stage: &str, _seconds: f64) {}
    /// `done` of `total` units of the stage's work (`total` is an estimate for some stages,
    /// and `done` may pass it).
    fn progress(&self, _stage: &str, _done: u64, _total: u64) {}
    /// Whether the run should stop: polled between stages and inside the long loops.
    fn cancelled(&self) -> bool {
        false
    }
}

/// The run was stopped through [`Observer::cancelled`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("cancelled")]
pub struct Cancelled;

/// An optional observer, small enough to sit in the stages' `Copy` option structs: no
/// observer (the default) reports nothing and never cancels.
#[derive(Clone, Copy, Default)]
pub struct Reporter<'a>(Option<&'a dyn Observer>);

impl fmt::Debug for Reporter<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let state = if self.0.is_some() { "observed" } else { "none" };
        f.debug_tuple("Reporter").field(&state).finish()
    }
}

impl<'a> Reporter<'a> {
    pub fn new(observer: &'a dyn Observer) -> Self {
        Reporter(Some(observer))
    }

    pub fn started(&self, stage: &str) {
        if let Some(o) = self.0 {
            o.stage_started(stage);
        }
    }

    pub fn finished(&self, stage: &str, seconds: f64) {
        if let Some(o) = self.0 {
            o.stage_finished(stage, seconds);
        }
    }

    pub fn progress(&self, stage: &str, done: u64, total: u64) {
        if let Some(o) = self.0 {
            o.progress(stage, done, total);
        }
    }

    pub fn cancelled(&self) -> bool {
        self.0.is_some_and(|o| o.cancelled())
    }

    /// `Err(Cancelled)` once the run should stop: for `?` between stages.
    pub fn check(&self) -> Result<(), Cancelled> {
        if self.cancelled() {
            Err(Cancelled)
        } else {
            Ok(())
        }
    }

    /// Run `f` as the stage `name`: started, timed, finished.
    pub fn stage<T>(&self, name: &str, f: impl FnOnce() -> T) -> T {
        self.started(name);
        let start = Instant::now();
        let out = f();
        self.finished(name, start.elapsed().as_secs_f64());
        out
    }
}
