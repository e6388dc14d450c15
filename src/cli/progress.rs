//! Stage timings on stderr (silenced by `--quiet`) and collected for `--report`; on a terminal
//! also a progress bar for the running stage, fed by the pipeline's [`Observer`] calls
//! (faces meshed of faces, interior points of those expected). Piped or `--quiet`, no bar.

use crate::progress::Observer;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde::Serialize;
use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::{Duration, Instant};

#[derive(Clone, Debug, Serialize)]
pub struct StageTime {
    pub stage: String,
    pub seconds: f64,
}

pub struct Progress {
    verbose: bool,
    /// Bars are drawn at all: stderr is a terminal and not `--quiet`.
    bars: bool,
    stages: Mutex<Vec<StageTime>>,
    /// The running top-level stage's bar, and whether it shows a count (else a spinner).
    bar: Mutex<Option<(ProgressBar, bool)>>,
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

impl Progress {
    pub fn new(verbose: bool) -> Self {
        Progress {
            verbose,
            bars: verbose && std::io::stderr().is_terminal(),
            stages: Mutex::new(Vec::new()),
            bar: Mutex::new(None),
        }
    }

    /// Run one stage, time it, and say so.
    /// Run `f` as the stage `name` (loading, writing): spinner, timing line, recorded time.
    pub fn stage<T>(&self, name: &str, f: impl FnOnce() -> T) -> T {
        self.begin(name);
        let start = Instant::now();
        let out = f();
        self.end(name, start.elapsed().as_secs_f64());
        out
    }

    /// A stage starts: its spinner on a terminal.
    fn begin(&self, name: &str) {
        if self.bars {
            let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
            bar.set_style(spinner_style());
            bar.set_message(name.to_string());
            bar.enable_steady_tick(Duration::from_millis(120));
            *lock(&self.bar) = Some((bar, false));
        }
    }

    /// A stage ended after `seconds`: the bar cleared, the timing line, the time recorded.
    fn end(&self, name: &str, seconds: f64) {
        if let Some((bar, _)) = lock(&self.bar).take() {
            bar.finish_and_clear();
        }
        if self.verbose {
            eprintln!("{name:<12} {seconds:>9.3} s");
        }
        lock(&self.stages).push(StageTime {
            stage: name.to_string(),
            seconds,
        });
    }

    pub fn record(&self, name: &str, seconds: f64, note: &str) {
        if self.verbose {
            eprintln!("{name:<12} {seconds:>9.3} s {note}");
        }
        lock(&self.stages).push(StageTime {
            stage: name.to_string(),
            seconds,
        });
    }

    pub fn say(&self, msg: &str) {
        if self.verbose {
            eprintln!("{msg}");
        }
    }

    pub fn stages(&self) -> Vec<StageTime> {
        lock(&self.stages).clone()
    }
}

fn spinner_style() -> ProgressStyle {
    ProgressStyle::with_template("{spinner} {msg:<12} {elapsed}").unwrap_or_else(|_| {
        // The template is fixed; a default style is only the fallback of a typo.
        ProgressStyle::default_spinner()
    })
}

fn bar_style() -> ProgressStyle {
    ProgressStyle::with_template("{spinner} {msg:<12} [{bar:32}] {pos}/{len} {elapsed}")
        .map(|s| s.progress_chars("=> "))
        .unwrap_or_else(|_| ProgressStyle::default_bar())
}

impl Observer for Progress {
    /// A count of the running stage or step: the spinner becomes a bar.
    fn progress(&self, stage: &str, done: u64, total: u64) {
        if let Some((bar, counting)) = lock(&self.bar).as_mut() {
            if !*counting || bar.message() != stage {
                bar.set_style(bar_style());
                bar.set_message(stage.to_string());
                bar.set_position(0);
                *counting = true;
            }
            // Surface jobs finish out of order on the threads: the count only grows.
            let len = total.max(done);
            bar.set_length(len);
            bar.set_position(done.max(bar.position()).min(len));
        }
    }

    /// A pipeline stage begins; a step inside the running stage (a volume step) shows as the
    /// bar's message.
    fn stage_started(&self, stage: &str) {
        if PIPELINE_STAGES.contains(&stage) {
            self.begin(stage);
        } else if let Some((bar, counting)) = lock(&self.bar).as_mut() {
            bar.set_style(spinner_style());
            bar.set_message(stage.to_string());
            *counting = false;
        }
    }

    /// A pipeline stage ends with its timing line; the volume's steps are told afterwards
    /// from its report.
    fn stage_finished(&self, stage: &str, seconds: f64) {
        if PIPELINE_STAGES.contains(&stage) {
            self.end(stage, seconds);
        }
    }
}

/// The stages [`crate::pipeline`] reports that get a timing line of their own.
const PIPELINE_STAGES: [&str; 4] = ["curves", "surfaces", "volume", "prisms"];
