//! Event location: after each accepted step the event functions watched in the current
//! modes are checked for a sign change in their requested direction; the earliest root is
//! found on the method's dense output by the Illinois variant of regula falsi (Dahlquist &
//! Björck, *Numerical Methods*, sec. 6.2.3) to a time tolerance of 1e-12 relative, and every
//! function whose root lies within that tolerance of it fires with it (simultaneous events).
//!
//! Re-trigger guard: after an event, an event function that fired, sits at zero and is
//! watched as before does not fire again from zero: it takes as its reference the first sign
//! it shows in the next step, sampled on the dense output at [`REARM_SAMPLES`] interior points
//! (so that an excursion and return within that step, a short bounce, is still caught). Any
//! other event function that starts at zero is taken to be on the side *before* the crossing
//! it watches, so that a state that immediately moves across it (an inconsistent mode switch)
//! is caught at once; until it leaves zero it has not crossed (a step at whose end it is still
//! exactly zero fires nothing). Else a grazing switch chatters: a stuck body whose force reaches
//! a bound of its stick interval and stays there to the last bit breaks away with zero
//! acceleration, its velocity stays exactly zero, and an exact zero read as an arrival sends
//! it back to stick, once per shortest step.
//!
//! The watch keeps its buffers between steps: checking a step allocates nothing.

use crate::error::SolverError;
use crate::options::ZenoGuard;
use crate::problem::{Crossing, EventSpec, Mode, OdeProblem};
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

/// An event function that changed sign in the step being checked.
#[derive(Clone, Copy, Debug)]
struct Candidate {
    index: usize,
    crossing: Crossing,
    /// Start of its bracket and its value there.
    ta: f64,
    ga: f64,
    /// Its value at the step's end.
    g1: f64,
}

/// Locates the root of candidate `c` on `[c.ta, tb]` (the step ends at `t1`, where its value
/// is known) by Illinois on the dense output.
#[allow(clippy::too_many_arguments)]
fn locate(
    problem: &dyn OdeProblem,
    modes: &[Mode],
    dense: &mut dyn FnMut(f64, &mut [f64]),
    y: &mut [f64],
    c: &Candidate,
    tb: f64,
    t1: f64,
    tol: f64,
) -> f64 {
    let mut g = |t: f64| {
        dense(t, y);
        problem.event(c.index, t, y, modes)
    };
    let gb = if tb == t1 { c.g1 } else { g(tb) };
    illinois(&mut g, c.ta, c.ga, tb, gb, tol)
}

/// The state of the event functions in the current modes.
#[derive(Clone, Debug, Default)]
pub struct EventWatch {
    specs: Vec<Option<EventSpec>>,
    last: Vec<f64>,
    disarmed: Vec<bool>,
    /// Started at zero, taken to be on the side before, and not yet left zero.
    at_zero: Vec<bool>,
    now: Vec<f64>,
    candidates: Vec<Candidate>,
    y: Vec<f64>,
    recent: VecDeque<f64>,
}

impl EventWatch {
    /// (Re)starts watching at (t, y) in `modes`; `rearm` are the indices that just fired and
    /// are watched as before (they start disarmed if they sit at zero).
    pub fn start(
        &mut self,
        problem: &dyn OdeProblem,
        modes: &[Mode],
        t: f64,
        y: &[f64],
        rearm: &[usize],
    ) {
        let n = problem.n_events();
        self.specs.clear();
        self.last.clear();
        self.disarmed.clear();
        self.at_zero.clear();
        self.y.resize(y.len(), 0.0);
        for i in 0..n {
            let spec = problem.event_spec(i, modes);
            let (g, disarmed, at_zero) = match spec {
                None => (0.0, false, false),
                Some(spec) => {
                    let g = problem.event(i, t, y, modes);
                    if g.abs() <= ZERO {
                        let rearmed = rearm.contains(&i);
                        (spec.crossing.side_before() * ZERO, rearmed, !rearmed)
                    } else {
                        (g, false, false)
                    }
                }
            };
            self.specs.push(spec);
            self.last.push(g);
            self.disarmed.push(disarmed);
            self.at_zero.push(at_zero);
        }
    }

    /// How event function `index` is watched now.
    pub fn spec(&self, index: usize) -> Option<EventSpec> {
        self.specs[index]
    }

    /// Checks the step from `t0` to `t1` (state `y1`), locating roots on `dense`, which
    /// evaluates the method's dense output. Updates the stored values when nothing fires.
    ///
    /// Only the earliest root is located by Illinois: the function whose secant estimate is
    /// earliest is located first, and every other function that crossed in the step is then
    /// classified by its sign at `t* − tol` and `t* + tol` (two dense outputs for all of them):
    /// crossed before `t* − tol`, it is located and becomes the new earliest; crossed by
    /// `t* + tol`, it fires with it; otherwise its root lies later and is found in a later step.
    pub fn check(
        &mut self,
        problem: &dyn OdeProblem,
        modes: &[Mode],
        t0: f64,
        t1: f64,
        y1: &[f64],
        dense: &mut dyn FnMut(f64, &mut [f64]),
    ) -> Option<Found> {
        let tol = TIME_TOLERANCE * t1.abs().max(t1 - t0).max(f64::MIN_POSITIVE);
        self.candidates.clear();
        self.now.clear();
        let y = &mut self.y;
        for (i, spec) in self.specs.iter().enumerate() {
            let Some(spec) = spec else {
                self.now.push(0.0);
                continue;
            };
            let g1 = problem.event(i, t1, y1, modes);
            self.now.push(g1);
            if self.at_zero[i] && g1 == 0.0 {
                // Still on zero: not crossed, and still on the side before.
                continue;
            }
            let (mut ta, mut ga) = (t0, self.last[i]);
            if self.disarmed[i] {
                // The first sign the function shows after leaving zero is its reference.
                let samples =
                    (1..REARM_SAMPLES).map(|k| t0 + (t1 - t0) * k as f64 / REARM_SAMPLES as f64);
                let mut first = None;
                for t in samples {
                    dense(t, y);
                    let v = problem.event(i, t, y, modes);
                    if v != 0.0 {
                        first = Some((t, v));
                        break;
                    }
                }
                match first {
                    Some((t, v)) => (ta, ga) = (t, v),
                    None if g1 != 0.0 => (ta, ga) = (t1, g1),
                    None => continue,
                }
            }
            if ta < t1 && spec.crossing.crossed(ga, g1) {
                self.candidates.push(Candidate {
                    index: i,
                    crossing: spec.crossing,
                    ta,
                    ga,
                    g1,
                });
            } else if self.disarmed[i] {
                self.now[i] = if ta < t1 { g1 } else { ga };
            }
        }
        if self.candidates.is_empty() {
            for (i, &g) in self.now.iter().enumerate() {
                if g != 0.0 || !(self.disarmed[i] || self.at_zero[i]) {
                    self.disarmed[i] = false;
                    self.at_zero[i] = false;
                    self.last[i] = g;
                }
            }
            return None;
        }
        let secant = |c: &Candidate| c.ta - c.ga * (t1 - c.ta) / (c.g1 - c.ga);
        let mut earliest = *self
            .candidates
            .iter()
            .min_by(|a, b| secant(a).total_cmp(&secant(b)))
            .expect("there are candidates");
        let mut t = locate(problem, modes, dense, y, &earliest, t1, t1, tol);
        // A candidate already crossed at t* − tol has an earlier root: it becomes the earliest.
        loop {
            let before = (t - tol).max(t0);
            dense(before, y);
            let crossed_before = self.candidates.iter().find(|c| {
                c.ta < before
                    && c.crossing
                        .crossed(c.ga, problem.event(c.index, before, y, modes))
            });
            match crossed_before {
                Some(&c) => {
                    earliest = c;
                    t = locate(problem, modes, dense, y, &c, before, t1, tol);
                }
                None => break,
            }
        }
        // Every candidate crossed by t* + tol fires with the earliest.
        let after = (t + tol).min(t1);
        dense(after, y);
        let mut indices: Vec<usize> = self
            .candidates
            .iter()
            .filter(|c| {
                c.index == earliest.index
                    || c.crossing
                        .crossed(c.ga, problem.event(c.index, after, y, modes))
            })
            .map(|c| c.index)
            .collect();
        indices.sort_unstable();
        self.candidates.clear();
        Some(Found { t, indices })
    }

    /// Records an event instant at `t` and fails if more than `guard.max_events` instants
    /// fall within `window` seconds (the guard's window in the problem's time scale).
    pub fn record(
        &mut self,
        t: f64,
        name: &str,
        guard: &ZenoGuard,
        window: f64,
    ) -> Result<(), SolverError> {
        self.recent.push_back(t);
        while self.recent.front().is_some_and(|&t0| t0 < t - window) {
            self.recent.pop_front();
        }
        if self.recent.len() > guard.max_events {
            return Err(SolverError::TooManyEvents {
                t,
                count: self.recent.len(),
                window,
                last: name.to_string(),
            });
        }
        Ok(())
    }
}

/// The Illinois method on `[a, b]` with `g(a) = ga` on the side before the crossing and
/// `g(b) = gb` on the side after it or zero: returns the end of the final bracket on the side
/// the function arrives at (the state there has crossed), once the bracket is narrower than
/// `tol`.
///
/// A value of exactly zero counts as arrived, as in [`Crossing::crossed`]. An event function
/// can reach zero and stay there (a body that comes to rest on its surface and is held there by
/// nothing), and the root sought is where it arrives, the earliest zero: a zero at the end of
/// the bracket is not taken as the root, and a zero inside it only if the function is still
/// before the crossing a tolerance earlier (one more evaluation). Where the secant point would
/// be a bracket end (a zero end), the step is a bisection.
pub fn illinois(g: &mut dyn FnMut(f64) -> f64, a: f64, ga: f64, b: f64, gb: f64, tol: f64) -> f64 {
    // The sign of the side the function arrives at; a zero is on it.
    let after = -ga.signum();
    let side = |g: f64| if g == 0.0 { after } else { g.signum() };
    let (mut a, mut ga, mut b, mut gb) = (a, ga, b, gb);
    for _ in 0..MAX_ITERATIONS {
        if (b - a).abs() <= tol {
            break;
        }
        let c = b - gb * (b - a) / (gb - ga);
        // Guard against a secant point outside the bracket through round-off, or at its end.
        let c = if c > a.min(b) && c < a.max(b) {
            c
        } else {
            0.5 * (a + b)
        };
        let gc = g(c);
        // An exact zero is the root if the function is still before the crossing a time
        // tolerance earlier (or the bracket ends there): an isolated root, as a secant step
        // lands on a linear function's. Otherwise it sits at zero there too, and the earliest
        // zero lies before c.
        if gc == 0.0 && (c - tol <= a.min(b) || side(g(c - tol)) != after) {
            return c;
        }
        if side(gc) == side(gb) {
            ga *= 0.5;
        } else {
            a = b;
            ga = gb;
        }
        b = c;
        gb = gc;
    }
    if side(gb) == after {
        b
    } else {
        a
    }
}

#[cfg(test)]
mod tests {
    use super::illinois;

    /// Falls through zero at t = 0.3 and stays there: the arrival is 0.3, not the end of the
    /// bracket where the function is also zero.
    fn arrives_and_rests(t: f64) -> f64 {
        (0.3 - t).max(0.0)
    }

    #[test]
    fn a_function_that_arrives_at_zero_and_stays_is_located_where_it_arrives() {
        let tol = 1e-12;
        let mut evaluations = 0;
        let mut g = |t: f64| {
            evaluations += 1;
            arrives_and_rests(t)
        };
        let root = illinois(&mut g, 0.0, 0.3, 1.0, 0.0, tol);
        assert!(
            root >= 0.3 && root - 0.3 <= tol,
            "located at {root}, the arrival is at 0.3"
        );
        assert_eq!(
            arrives_and_rests(root),
            0.0,
            "the state at the root has arrived"
        );
        // Bisection halves 1 s to below 1e-12 s in 40 steps, and each zero it meets is probed
        // once a tolerance earlier.
        assert!(evaluations <= 80, "{evaluations} evaluations");
    }

    #[test]
    fn a_secant_step_onto_a_linear_functions_root_ends_the_iteration_there() {
        // The bracket of an event at t = 10 s of a force ramp (as `reproduce` meets it): the
        // secant lands on the root exactly; one probe a tolerance earlier confirms it.
        let (a, b) = (9.437152000000003, 10.485728000000003);
        let mut evaluations = 0;
        let mut g = |t: f64| {
            evaluations += 1;
            10.0 - t
        };
        let root = illinois(&mut g, a, 10.0 - a, b, 10.0 - b, 1e-11);
        assert_eq!((root, evaluations), (10.0, 2));
    }

    #[test]
    fn a_function_that_sits_at_zero_from_the_start_is_located_at_the_start() {
        // A placeholder on the side before at a, zero everywhere after it.
        let root = illinois(&mut |_| 0.0, 2.0, 1e-12, 3.0, 0.0, 1e-12);
        assert!(root > 2.0 && root - 2.0 <= 1e-12, "located at {root}");
    }

    #[test]
    fn a_rising_crossing_is_located_by_illinois_to_the_tolerance() {
        // g = t² − 2 rises through zero at √2.
        let mut evaluations = 0;
        let mut g = |t: f64| {
            evaluations += 1;
            t * t - 2.0
        };
        let root = illinois(&mut g, 1.0, -1.0, 2.0, 2.0, 1e-12);
        assert!(root >= std::f64::consts::SQRT_2 && root - std::f64::consts::SQRT_2 <= 1e-12);
        // Illinois converges superlinearly (order about 1.44): far fewer than bisection's 40.
        assert!(evaluations <= 12, "{evaluations} evaluations");
    }
}
