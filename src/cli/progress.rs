//! Stage timings on stderr (silenced by `--quiet`) and collected for `--report`.

use serde::Serialize;
use std::cell::RefCell;
use std::time::Instant;

#[derive(Clone, Debug, Serialize)]
pub struct StageTime {
    pub stage: String,
    pub seconds: f64,
}

pub struct Progress {
    verbose: bool,
    stages: RefCell<Vec<StageTime>>,
}

impl Progress {
    pub fn new(verbose: bool) -> Self {
        Progress {
            verbose,
            stages: RefCell::new(Vec::new()),
        }
    }

    /// Run one stage, time it, and say so.
    pub fn stage<T>(&self, name: &str, f: impl FnOnce() -> T) -> T {
        let start = Instant::now();
        let out = f();
        let seconds = start.elapsed().as_secs_f64();
        if self.verbose {
            eprintln!("{name:<12} {seconds:>9.3} s");
        }
        self.stages.borrow_mut().push(StageTime {
            stage: name.to_string(),
            seconds,
        });
        out
    }

    /// Record a stage that ran elsewhere (inside another stage), and say so.
    pub fn record(&self, name: &str, seconds: f64, note: &str) {
        if self.verbose {
            eprintln!("{name:<12} {seconds:>9.3} s {note}");
        }
        self.stages.borrow_mut().push(StageTime {
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
        self.stages.borrow().clone()
    }
}
