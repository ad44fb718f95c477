//! A periodic orbit's starting guess from a long run that has settled onto a cycle: the
//! period from the recurrence of its switches, the state from the middle of the cycle's
//! longest smooth segment (far from every switch, where the section is transversal).

use crate::OrbitError;
use integrators::{Mode, Solution};

/// How close, relative to the run's scale, the states at two occurrences of a switch must be
/// for the time between them to be taken as the period.
pub const RECURRENCE_TOLERANCE: f64 = 1e-3;

/// A starting guess.
#[derive(Clone, Debug, PartialEq)]
pub struct Guess {
    /// The time of the guessed state, s.
    pub t: f64,
    /// The state.
    pub y: Vec<f64>,
    /// Its modes.
    pub modes: Vec<Mode>,
    /// The period, s.
    pub period: f64,
}

/// The guess from `run`'s last cycle over its first `n` unknowns (the dynamic ones): the last
/// switch and the latest earlier occurrence of the same switch (the same event, the same modes
/// on each side) whose state lies within [`RECURRENCE_TOLERANCE`] of it give the period; the
/// recorded point nearest the middle of the cycle's longest segment gives the state.
pub fn guess_from_run(run: &Solution, n: usize) -> Result<Guess, OrbitError> {
    let none = |why: &str| OrbitError::NoGuess(why.to_string());
    let last = run
        .events
        .last()
        .ok_or_else(|| none("the run has no switch"))?;
    let state_at = |t: f64| {
        let k = run.t.partition_point(|&s| s < t).min(run.len() - 1);
        &run.y_at(k)[..n]
    };
    let scale = (0..run.len())
        .flat_map(|k| run.y_at(k)[..n].iter().copied())
        .fold(0.0_f64, |a, v| a.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    let end_state = state_at(last.t).to_vec();
    let earlier = run.events[..run.events.len() - 1]
        .iter()
        .rev()
        .filter(|e| e.fired == last.fired && e.switches == last.switches)
        .find(|e| {
            let gap = (state_at(e.t).iter().zip(&end_state))
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            gap <= RECURRENCE_TOLERANCE * scale
        })
        .ok_or_else(|| none("its last switch does not recur within the run"))?;
    let period = last.t - earlier.t;
    // The cycle's switch times, and its longest segment's middle.
    let times: Vec<f64> = (run.events.iter())
        .map(|e| e.t)
        .filter(|&t| t >= earlier.t && t <= last.t)
        .collect();
    let (a, b) = times
        .windows(2)
        .map(|w| (w[0], w[1]))
        .max_by(|x, y| (x.1 - x.0).total_cmp(&(y.1 - y.0)))
        .unwrap_or((earlier.t, last.t));
    let middle = 0.5 * (a + b);
    let k = (0..run.len())
        .filter(|&k| run.t[k] > a && run.t[k] < b)
        .min_by(|&i, &j| {
            (run.t[i] - middle)
                .abs()
                .total_cmp(&(run.t[j] - middle).abs())
        })
        .ok_or_else(|| none("no recorded point inside the cycle's longest segment"))?;
    Ok(Guess {
        t: run.t[k],
        y: run.y_at(k).to_vec(),
        modes: run.modes_at(k).to_vec(),
        period,
    })
}
