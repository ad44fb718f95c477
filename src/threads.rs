//! The pool of worker threads a command's runs are evaluated on: results are collected in
//! order, so they do not depend on the number of threads.

use crate::error::AppError;

/// Runs `f` on a pool of `threads` workers (all cores when `None`).
pub fn with_threads<T: Send>(
    threads: Option<usize>,
    f: impl FnOnce() -> T + Send,
) -> Result<T, AppError> {
    if threads == Some(0) {
        return Err(AppError::Usage(
            "option `threads` = 0 is out of range: allowed [1, inf)".into(),
        ));
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(|e| AppError::Usage(format!("cannot start {threads:?} threads: {e}")))?;
    Ok(pool.install(f))
}
