//! Greedy list scheduling of independent runs on rayon's pool: every worker takes the next
//! run of a priority list as soon as it is free, so the longest runs, listed first, start
//! first and the short ones fill the other cores around them (Graham 1969: a makespan of at
//! most the total work over the cores plus the longest run). rayon's `par_iter` splits the
//! list in halves instead, and can leave the longest run to start last.
//!
//! Each run's result depends only on the run, never on which worker took it, so the results
//! are the same for any number of threads.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Mutex;

/// Runs `job(i)` for every `i` of `order`, workers taking them in that order; returns the
/// results sorted by `i`, or the error of the smallest `i` that failed. Once a job `i` with
/// `fatal(i)` has failed (one whose result every other needs, such as a study's reference),
/// the workers take no further job: those in progress finish, the rest never start. The
/// error returned is the same for any number of threads as long as the fatal jobs come first
/// in `order` and have the smallest indices: a fatal job that fails is then the smallest
/// index that failed, whichever jobs ran beside it.
pub fn in_order<T: Send, E: Send>(
    order: &[usize],
    fatal: impl Fn(usize) -> bool + Sync,
    job: impl Fn(usize) -> Result<T, E> + Sync,
) -> Result<Vec<(usize, T)>, E> {
    let next = AtomicUsize::new(0);
    let stopped = AtomicBool::new(false);
    let done = Mutex::new(Vec::with_capacity(order.len()));
    let worker = || loop {
        if stopped.load(Ordering::Relaxed) {
            break;
        }
        let k = next.fetch_add(1, Ordering::Relaxed);
        let Some(&i) = order.get(k) else { break };
        let result = job(i);
        if result.is_err() && fatal(i) {
            stopped.store(true, Ordering::Relaxed);
        }
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
            .install(|| in_order(&order, |_| false, |i| Ok::<_, ()>(10 * i)))
            .unwrap();
        assert_eq!(out, vec![(0, 0), (1, 10), (2, 20), (3, 30)]);
    }

    #[test]
    fn the_error_of_the_smallest_failing_index_is_returned() {
        let order = [3, 0, 2, 1];
        let err = in_order(&order, |_| false, |i| if i >= 2 { Err(i) } else { Ok(i) }).unwrap_err();
        assert_eq!(err, 2);
    }

    #[test]
    fn no_job_starts_after_a_fatal_one_failed() {
        // Job 0 (first in the order) fails after 10 ms and is fatal; the others take 50 ms: on
        // one thread nothing else runs, on two at most the job taken beside it. The error is
        // job 0's either way.
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let ran = AtomicUsize::new(0);
            let err = pool
                .install(|| {
                    in_order(
                        &[0, 1, 2, 3, 4, 5],
                        |i| i == 0,
                        |i| {
                            ran.fetch_add(1, Ordering::Relaxed);
                            let ms = if i == 0 { 10 } else { 50 };
                            std::thread::sleep(std::time::Duration::from_millis(ms));
                            if i == 0 {
                                Err(i)
                            } else {
                                Ok(i)
                            }
                        },
                    )
                })
                .unwrap_err();
            assert_eq!(err, 0);
            let ran = ran.into_inner();
            // (Without the stop, all six would run.)
            assert!((1..=threads).contains(&ran), "{threads} threads: {ran} ran");
        }
    }
}
