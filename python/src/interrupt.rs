//! Long calls release the GIL and stop on Ctrl-C.
//!
//! Python runs a signal's handler only when the main thread checks for it, and a
//! thread inside Rust never does. So a long call runs without the GIL and the
//! library's progress reports (after each OLS pick, each stage) are the
//! checkpoints: on the thread that made the call, each one takes the GIL back for
//! `PyErr_CheckSignals`. If the handler raised (KeyboardInterrupt), the checkpoint
//! unwinds out of the library with [`std::panic::resume_unwind`], which runs no
//! panic hook and prints nothing, and [`detached`] returns the handler's exception.
//! Everything the interrupted call allocated is dropped on the way.

use std::panic::{AssertUnwindSafe, catch_unwind, resume_unwind};
use std::sync::Mutex;
use std::thread::{self, ThreadId};

use pyo3::exceptions::PyKeyboardInterrupt;
use pyo3::prelude::*;

/// The unwind payload of an interrupted call.
struct Interrupted;

/// Where a long call may be stopped: [`Checkpoint::check`] between its steps.
pub struct Checkpoint {
    /// Signals are handled on the main thread only; other threads' checks are free.
    caller: ThreadId,
    /// The exception the signal handler raised.
    raised: Mutex<Option<PyErr>>,
}

impl Checkpoint {
    /// Runs pending signal handlers; unwinds out of the call if one raised.
    pub fn check(&self) {
        if thread::current().id() != self.caller {
            return;
        }
        if let Err(e) = Python::attach(|py| py.check_signals()) {
            if let Ok(mut slot) = self.raised.lock() {
                *slot = Some(e);
            }
            resume_unwind(Box::new(Interrupted));
        }
    }
}

/// Runs `work` without the GIL, handing it a [`Checkpoint`]; a signal whose
/// handler raises stops it at its next check and is returned as the exception.
pub fn detached<T, F>(py: Python<'_>, work: F) -> PyResult<T>
where
    T: Send,
    F: FnOnce(&Checkpoint) -> T + Send,
{
    let checkpoint = Checkpoint {
        caller: thread::current().id(),
        raised: Mutex::new(None),
    };
    let result = py.detach(|| catch_unwind(AssertUnwindSafe(|| work(&checkpoint))));
    match result {
        Ok(value) => Ok(value),
        Err(payload) if payload.is::<Interrupted>() => Err(checkpoint
            .raised
            .lock()
            .ok()
            .and_then(|mut slot| slot.take())
            .unwrap_or_else(|| PyKeyboardInterrupt::new_err(()))),
        Err(payload) => resume_unwind(payload),
    }
}
