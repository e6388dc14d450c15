//! The plugin's handle of one open file: closed on drop, shared by the file's entities, and
//! the two ways they query it ([`Handle::eval`] for the required queries, [`Handle::optional`]
//! for those that may find nothing), each recording a failure in the model's fault log.

use super::library::{CallError, Plugin};
use crate::geometry::FaultLog;
use std::sync::Arc;
use tetrafoil_plugin_abi as abi;

/// The plugin's handle of one open file.
pub(super) struct Handle {
    pub plugin: Arc<Plugin>,
    pub raw: *mut abi::Model,
    /// The file as messages name it.
    pub file: String,
    pub faults: FaultLog,
}

// SAFETY: the plugin contract lets queries on one model run on several threads at once
// (`Plugin::call` serialises a plugin that says otherwise); open, topology and close are only
// made by the one owner of the handle.
unsafe impl Send for Handle {}
unsafe impl Sync for Handle {}

impl Drop for Handle {
    fn drop(&mut self) {
        if let Some(close) = self.plugin.table.close {
            // SAFETY: `raw` came from this plugin's open and is closed once.
            let _ = self.plugin.call(|_| {
                unsafe { close(self.raw) };
                abi::OK
            });
        }
    }
}

impl Handle {
    /// "plugin 'name' (path): file: ", the start of every message about this model.
    pub fn context(&self) -> String {
        format!("{}: {}", self.plugin.label(), self.file)
    }
}

type EvalFn = unsafe extern "C" fn(
    *const abi::Model,
    i32,
    usize,
    *const f64,
    *mut f64,
    *mut abi::Error,
) -> abi::Status;

impl Handle {
    /// One batched evaluation of `N` outputs at `input`; `None` (and a fault) when it fails
    /// or answers a non-finite value.
    pub(super) fn eval<const N: usize>(
        &self,
        f: EvalFn,
        entity: i32,
        input: &[f64],
        what: impl Fn() -> String,
    ) -> Option<[f64; N]> {
        let mut out = [0.0; N];
        // SAFETY: `input` holds one parameter set, `out` room for one answer (n = 1).
        let result = self
            .plugin
            .call(|err| unsafe { f(self.raw, entity, 1, input.as_ptr(), out.as_mut_ptr(), err) });
        match result {
            Ok(abi::OK) if out.iter().all(|x| x.is_finite()) => Some(out),
            Ok(abi::OK) => {
                self.faults.record(|| {
                    format!(
                        "{}: {}: answered a value that is not finite",
                        self.context(),
                        what()
                    )
                });
                None
            }
            Ok(_) => {
                self.faults.record(|| {
                    format!(
                        "{}: {}: answered 'not found', which it may not",
                        self.context(),
                        what()
                    )
                });
                None
            }
            Err(e) => {
                self.record_failure(what, &e);
                None
            }
        }
    }

    /// An optional query's answer: `None` when it is absent, finds nothing, or fails (a
    /// failure is also a fault).
    pub(super) fn optional<const N: usize>(
        &self,
        call: impl FnOnce(&mut [f64; N], *mut abi::Error) -> abi::Status,
        what: impl Fn() -> String,
    ) -> Option<[f64; N]> {
        let mut out = [0.0; N];
        match self.plugin.call(|err| call(&mut out, err)) {
            Ok(abi::OK) if out.iter().all(|x| x.is_finite()) => Some(out),
            Ok(_) => None,
            Err(e) => {
                self.record_failure(what, &e);
                None
            }
        }
    }

    /// Record a failed call as the model's fault: the plugin, the file, what was asked, and
    /// what the plugin said.
    pub(super) fn record_failure(&self, what: impl Fn() -> String, e: &CallError) {
        self.faults.record(|| {
            format!(
                "{}: {}: {}: {}",
                self.context(),
                what(),
                e.kind(),
                e.message
            )
        });
    }
}
