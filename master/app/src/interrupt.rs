//! Ctrl-C stops a run at the next step boundary instead of killing it mid-row:
//! a killed run left a torn last CSV row (16 of 19 fields) that pandas read
//! without complaint and no `summary.json` (issue 27). The first SIGINT only
//! sets a flag the step loop reads; the run then writes its rows whole, its
//! figures and a summary with status "interrupted" and the time reached. A
//! second SIGINT ends the process at once (exit 130), for a step that hangs.

use std::sync::atomic::{AtomicBool, Ordering};

static REQUESTED: AtomicBool = AtomicBool::new(false);

/// Whether an interruption was asked for (Ctrl-C, or [`request`]).
pub fn requested() -> bool {
    REQUESTED.load(Ordering::Relaxed)
}

/// Asks the running scenes to stop at their next step boundary (what SIGINT
/// does; also for tests and embedding programs).
pub fn request() {
    REQUESTED.store(true, Ordering::Relaxed);
}

/// `Err(AppError::Interrupted)` when Ctrl-C stopped a study whose runs'
/// outcomes are `outcomes` (`finished` tells a run that finished): a study
/// stopped part-way fits and tables nothing (its finished runs are kept).
pub(crate) fn stop_if_requested<T>(
    outcomes: &[T],
    finished: impl Fn(&T) -> bool,
) -> Result<(), crate::AppError> {
    if !requested() {
        return Ok(());
    }
    Err(crate::AppError::Interrupted {
        finished: outcomes.iter().filter(|o| finished(o)).count(),
        total: outcomes.len(),
    })
}

/// Installs the SIGINT handler (Unix; elsewhere Ctrl-C keeps its default).
pub fn install() {
    #[cfg(unix)]
    {
        extern "C" fn on_interrupt(_: libc::c_int) {
            // Async-signal-safe: an atomic swap, and _exit.
            if REQUESTED.swap(true, Ordering::Relaxed) {
                unsafe { libc::_exit(130) };
            }
        }
        let handler: extern "C" fn(libc::c_int) = on_interrupt;
        // SAFETY: the handler only touches an atomic and calls _exit, both
        // async-signal-safe; installed from the main thread at start-up.
        unsafe {
            libc::signal(libc::SIGINT, handler as libc::sighandler_t);
        }
    }
}
