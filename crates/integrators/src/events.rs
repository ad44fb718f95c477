//! Event location: after each accepted step the event functions of the current mode are
//! checked for a sign change in their requested direction; the earliest root is found on
//! the method's dense output by the Illinois variant of regula falsi (Dahlquist & Björck,
//! *Numerical Methods*, sec. 6.2.3) to a time tolerance of 1e-12 relative.
//!
//! Re-trigger guard: after an event, an event function that fired and sits at zero does not
//! fire again from zero: it takes as its reference the first sign it shows in the next step,
//! sampled on the dense output at [`REARM_SAMPLES`] interior points (so that an excursion and
//! return within that step, a short bounce, is still caught). Any other event function that
//! starts at zero is taken to be on the side *before* the crossing it watches, so that a state
//! that immediately moves across it (an inconsistent mode switch) is caught at once.

use crate::error::SolverError;
use crate::options::ZenoGuard;
use crate::problem::{Mode, OdeProblem};
use std::collections::VecDeque;

/// Relative time tolerance of event location.
pub const TIME_TOLERANCE: f64 = 1e-12;
/// An event function with |g| at or below this at a restart counts as sitting on zero.
pub const ZERO: f64 = 1e-12;
/// Interior points of the first step after an event at which a fired event function is
/// sampled for its first sign.
pub const REARM_SAMPLES: usize = 8;
/// Most Illinois iterations; the bracket shrinks at least linearly, so this is never the
/// limit in practice.
const MAX_ITERATIONS: usize = 200;

/// Events found in one step: the earliest root and every event function whose root lies
/// within the time tolerance of it, in index order.
#[derive(Clone, Debug, PartialEq)]
pub struct Found {
    /// Time of the event(s).
    pub t: f64,
    /// Indices of the event functions that fire there, ascending.
    pub indices: Vec<usize>,
}

/// The state of the event functions of the current mode.
#[derive(Clone, Debug, Default)]
pub struct EventWatch {
    last: Vec<f64>,
    disarmed: Vec<bool>,
    recent: VecDeque<f64>,
}

impl EventWatch {
    /// (Re)starts watching the events of `mode` at (t, y); `fired` are the indices that just
    /// fired in this same mode (empty after a mode switch).
    pub fn start(
        &mut self,
        problem: &dyn OdeProblem,
        mode: Mode,
        t: f64,
        y: &[f64],
        fired: &[usize],
    ) {
        let specs = problem.events(mode);
        self.last.clear();
        self.disarmed.clear();
        for (i, spec) in specs.iter().enumerate() {
            let g = problem.event(i, t, y, mode);
            let at_zero = g.abs() <= ZERO;
            self.disarmed.push(at_zero && fired.contains(&i));
            self.last.push(if at_zero {
                spec.crossing.side_before() * ZERO
            } else {
                g
            });
        }
    }

    /// Checks the step from `t0` to `t1` (state `y1`), locating roots on `dense`, which
    /// evaluates the method's dense output. Updates the stored values when nothing fires.
    pub fn check(
        &mut self,
        problem: &dyn OdeProblem,
        mode: Mode,
        t0: f64,
        t1: f64,
        y1: &[f64],
        dense: &mut dyn FnMut(f64, &mut [f64]),
    ) -> Option<Found> {
        let specs = problem.events(mode);
        let mut y = vec![0.0; y1.len()];
        let tol = TIME_TOLERANCE * t1.abs().max(t1 - t0).max(f64::MIN_POSITIVE);
        let mut roots: Vec<(f64, usize)> = Vec::new();
        let mut now = Vec::with_capacity(specs.len());
        for (i, spec) in specs.iter().enumerate() {
            let g1 = problem.event(i, t1, y1, mode);
            now.push(g1);
            let mut g = |t: f64| {
                dense(t, &mut y);
                problem.event(i, t, &y, mode)
            };
            let (mut ta, mut ga) = (t0, self.last[i]);
            if self.disarmed[i] {
                // The first sign the function shows after leaving zero is its reference.
                let samples =
                    (1..REARM_SAMPLES).map(|k| t0 + (t1 - t0) * k as f64 / REARM_SAMPLES as f64);
                match samples.map(|t| (t, g(t))).find(|&(_, v)| v != 0.0) {
                    Some((t, v)) => (ta, ga) = (t, v),
                    None if g1 != 0.0 => (ta, ga) = (t1, g1),
                    None => continue,
                }
            }
            if ta < t1 && spec.crossing.crossed(ga, g1) {
                roots.push((illinois(&mut g, ta, ga, t1, g1, tol), i));
            } else if self.disarmed[i] {
                now[i] = if ta < t1 { g1 } else { ga };
            }
        }
        if roots.is_empty() {
            for (i, g) in now.into_iter().enumerate() {
                if g != 0.0 || !self.disarmed[i] {
                    self.disarmed[i] = false;
                    self.last[i] = g;
                }
            }
            return None;
        }
        let t = roots.iter().map(|r| r.0).fold(f64::INFINITY, f64::min);
        let mut indices: Vec<usize> = roots
            .iter()
            .filter(|r| r.0 - t <= tol)
            .map(|r| r.1)
            .collect();
        indices.sort_unstable();
        Some(Found { t, indices })
    }

    /// Records an event at `t` and fails if more than `guard.max_events` fall within
    /// `guard.window` seconds.
    pub fn record(&mut self, t: f64, name: &str, guard: &ZenoGuard) -> Result<(), SolverError> {
        self.recent.push_back(t);
        while self.recent.front().is_some_and(|&t0| t0 < t - guard.window) {
            self.recent.pop_front();
        }
        if self.recent.len() > guard.max_events {
            return Err(SolverError::TooManyEvents {
                t,
                count: self.recent.len(),
                window: guard.window,
                last: name.to_string(),
            });
        }
        Ok(())
    }
}

/// The Illinois method on `[a, b]` with `g(a) = ga` and `g(b) = gb` of opposite signs (or
/// `gb = 0`): returns the end of the final bracket on the side of `b`'s sign (the state
/// there has crossed), once the bracket is narrower than `tol`.
pub fn illinois(g: &mut dyn FnMut(f64) -> f64, a: f64, ga: f64, b: f64, gb: f64, tol: f64) -> f64 {
    let after = gb.signum();
    if gb == 0.0 {
        return b;
    }
    let (mut a, mut ga, mut b, mut gb) = (a, ga, b, gb);
    for _ in 0..MAX_ITERATIONS {
        if (b - a).abs() <= tol {
            break;
        }
        let c = b - gb * (b - a) / (gb - ga);
        // Guard against a secant point outside the bracket through round-off.
        let c = if c > a.min(b) && c < a.max(b) {
            c
        } else {
            0.5 * (a + b)
        };
        let gc = g(c);
        if gc == 0.0 {
            return c;
        }
        if gc.signum() == gb.signum() {
            ga *= 0.5;
        } else {
            a = b;
            ga = gb;
        }
        b = c;
        gb = gc;
    }
    if gb.signum() == after {
        b
    } else {
        a
    }
}
