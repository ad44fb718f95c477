//! Greedy list scheduling of independent runs on rayon's pool: every worker takes the next
//! run of a priority list as soon as it is free, so the longest runs, listed first, start
//! first and the short ones fill the other cores around them (Graham 1969: a makespan of at
//! most the total work over the cores plus the longest run). rayon's `par_iter` splits the
//! list in halves instead, and can leave the longest run to start last.
//!
//! Each run's result depends only on the run, never on which worker took it, so the results
//! are the same for any number of threads.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Runs `job(i)` for every `i` of `order`, workers taking them in that order; returns the
/// results sorted by `i`, or the error of the smallest `i` that failed.
pub fn in_order<T: Send, E: Send>(
    order: &[usize],
    job: impl Fn(usize) -> Result<T, E> + Sync,
) -> Result<Vec<(usize, T)>, E> {
    let next = AtomicUsize::new(0);
    let done = Mutex::new(Vec::with_capacity(order.len()));
    let worker = || loop {
        let k = next.fetch_add(1, Ordering::Relaxed);
        let Some(&i) = order.get(k) else { break };
        let result = job(i);
        done.lock().expect("no worker panics").push((i, result));
    };
    rayon::scope(|s| {
        for _ in 0..rayon::current_num_threads().min(order.len()) {
            s.spawn(|_| worker());
        }
    });
    let mut done = done.into_inner().expect("no worker panics");
    done.sort_by_key(|(i, _)| *i);
    done.into_iter()
        .map(|(i, result)| result.map(|t| (i, t)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_job_runs_once_and_results_come_back_by_index() {
        let order = [3, 0, 2, 1];
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let out = pool
            .install(|| in_order(&order, |i| Ok::<_, ()>(10 * i)))
            .unwrap();
        assert_eq!(out, vec![(0, 0), (1, 10), (2, 20), (3, 30)]);
    }

    #[test]
    fn the_error_of_the_smallest_failing_index_is_returned() {
        let order = [3, 0, 2, 1];
        let err = in_order(&order, |i| if i >= 2 { Err(i) } else { Ok(i) }).unwrap_err();
        assert_eq!(err, 2);
    }
}
