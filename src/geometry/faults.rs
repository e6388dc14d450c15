//! Where a foreign kernel's failed queries are recorded. The geometry traits answer plain
//! values (the mesher asks millions of questions and cannot thread a `Result` through each),
//! so a plugin entity that cannot answer returns a harmless value and records why here; the
//! pipeline looks at the log after each stage and stops the run with the first fault.

use std::sync::{Arc, Mutex};

/// The first fault of a model's kernel, shared by the model and its entities.
#[derive(Clone, Debug, Default)]
pub struct FaultLog(Arc<Mutex<Option<String>>>);

impl FaultLog {
    /// Keep `message` if it is the first fault.
    pub fn record(&self, message: impl FnOnce() -> String) {
        let mut first = self.0.lock().unwrap_or_else(|e| e.into_inner());
        if first.is_none() {
            *first = Some(message());
        }
    }

    /// The first fault recorded, if any.
    pub fn first(&self) -> Option<String> {
        self.0.lock().unwrap_or_else(|e| e.into_inner()).clone()
    }

    /// Whether nothing has failed yet (checked before recording costs a message).
    pub fn is_clear(&self) -> bool {
        self.0.lock().unwrap_or_else(|e| e.into_inner()).is_none()
    }
}
