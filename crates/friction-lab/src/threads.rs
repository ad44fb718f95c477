//! The pool of worker threads a command's runs are evaluated on: results are collected in
//! order, so they do not depend on the number of threads.

use crate::error::AppError;
use std::sync::OnceLock;

/// The body of a pool's worker thread: its loop, which returns when the pool is dropped.
pub type WorkerLoop = Box<dyn FnOnce() + Send>;

/// How every pool's worker threads run their loops, where a front end set it
/// ([`set_worker_wrapper`]).
static WORKER_WRAPPER: OnceLock<fn(WorkerLoop)> = OnceLock::new();

/// Has every worker thread of the pools run its loop inside `wrap`, from now on; false (and
/// nothing changed) when a wrapper was set before. The Python package attaches each worker to
/// its interpreter for the worker's life and detaches it at once: a law written in Python then
/// takes the GIL on a thread state that lives as long as the worker, not one made and
/// destroyed per evaluation (docs/performance.md, "A friction law written in Python").
pub fn set_worker_wrapper(wrap: fn(WorkerLoop)) -> bool {
    WORKER_WRAPPER.set(wrap).is_ok()
}

/// Runs `f` on a pool of `threads` workers (all cores when `None`).
pub fn with_threads<T: Send>(
    threads: Option<usize>,
    f: impl FnOnce() -> T + Send,
) -> Result<T, AppError> {
    if threads == Some(0) {
        return Err(AppError::Invalid(crate::error::Invalid {
            field: "threads",
            value: "0".into(),
            allowed: "[1, inf)".into(),
            list: false,
        }));
    }
    let builder = rayon::ThreadPoolBuilder::new().num_threads(threads.unwrap_or(0));
    let pool = match WORKER_WRAPPER.get() {
        None => builder.build(),
        Some(&wrap) => builder
            .spawn_handler(move |worker| {
                std::thread::Builder::new()
                    .spawn(move || wrap(Box::new(move || worker.run())))
                    .map(drop)
            })
            .build(),
    }
    .map_err(|e| AppError::Usage(format!("cannot start {threads:?} threads: {e}")))?;
    Ok(pool.install(f))
}

/// The worker threads of the pool the caller runs in ([`with_threads`]'s), or of the global
/// pool outside any: all cores.
pub fn current() -> usize {
    rayon::current_num_threads()
}
