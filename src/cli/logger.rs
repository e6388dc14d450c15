//! Where the library's log records go: stderr, as the command line decides. Notes (the
//! library's `log::warn!`: a file sewn, a wake that cannot conform) show unless `--quiet`;
//! debug records (the parallel kernel's passes, a stuck front) only with `--verbose`.

use log::{Level, LevelFilter, Log, Metadata, Record};

struct Stderr;

impl Log for Stderr {
    fn enabled(&self, metadata: &Metadata) -> bool {
        metadata.level() <= log::max_level()
    }

    fn log(&self, record: &Record) {
        if !self.enabled(record.metadata()) {
            return;
        }
        match record.level() {
            Level::Error => eprintln!("error: {}", record.args()),
            Level::Warn => eprintln!("note: {}", record.args()),
            Level::Info => eprintln!("{}", record.args()),
            Level::Debug | Level::Trace => eprintln!("debug: {}", record.args()),
        }
    }

    fn flush(&self) {}
}

static STDERR: Stderr = Stderr;

/// Send the library's records to stderr: nothing with `quiet`, debug records too with
/// `verbose`, notes otherwise. Safe to call more than once (the level follows the last call).
pub fn init(quiet: bool, verbose: bool) {
    let _ = log::set_logger(&STDERR);
    log::set_max_level(if quiet {
        LevelFilter::Off
    } else if verbose {
        LevelFilter::Debug
    } else {
        LevelFilter::Info
    });
}
