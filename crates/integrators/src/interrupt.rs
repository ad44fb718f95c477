//! A process-wide request to stop every integration in progress, for a host that forwards
//! Ctrl-C to the solvers (the Python package): a run that sees it between two steps ends with
//! [`SolverError::Interrupted`](crate::SolverError::Interrupted) and keeps what it computed,
//! as a run that reaches its time limit does. Like the signal it carries, the request is one
//! for the whole process; whoever raises it lowers it once its own calls have returned.

use std::sync::atomic::{AtomicBool, Ordering};

static REQUESTED: AtomicBool = AtomicBool::new(false);

/// Asks every integration in progress, and every one that starts, to stop.
pub fn request() {
    REQUESTED.store(true, Ordering::Relaxed);
}

/// Withdraws the request.
pub fn clear() {
    REQUESTED.store(false, Ordering::Relaxed);
}

/// Whether a stop is requested: read by the drivers before each step (one relaxed load).
pub fn requested() -> bool {
    REQUESTED.load(Ordering::Relaxed)
}
