//! What a closed loop did (a rig whose body a controller positions): whether it settles on a
//! hunting limit cycle, with its period, amplitude and time stuck per cycle, or converges,
//! with its final error; and the tracking error over the run.
//!
//! The cycle is read off the position error `e = r − x` over the last half of the run, at
//! the evenly spaced output points: its period is the mean spacing of the times where x
//! passes the reference upwards (e falls through zero, located linearly between samples), its
//! amplitude half the range of e. The error holds still while the body sticks and changes
//! sign in each slip of a hunting cycle, so a slip shorter than the output spacing still
//! counts. The loop has **settled** when the two halves of that part each hold at least
//! [`MIN_CYCLES`] cycles whose periods and amplitudes agree within [`SETTLE_TOLERANCE`]
//! (it **hunts**), or when e's half range there is at most [`REST_AMPLITUDE`] and, under
//! integral action, e itself is (it has **converged**: a body stuck off the set point while
//! the integral winds up will move again). Otherwise the run ends in a transient: `hunting`
//! is undefined (null), never false.

use super::settled::{crossings, half_range, MIN_CYCLES, SETTLE_TOLERANCE};
use crate::run::{Outcome, Row};
use friction_systems::{Reference, STICK};
use serde::Serialize;

/// The half range of the error, m, at or below which the settled loop is at rest.
pub const REST_AMPLITUDE: f64 = 1e-9;

/// The speed, relative to the largest speed of the settled part, at or below which a body
/// counts as stuck although its contact slides: a law without a stick mode (LuGre) holds it
/// by creeping at micrometres per second.
pub const STUCK_SPEED: f64 = 1e-3;

/// The measures of one closed-loop run; `NaN` (written null) where a measure is undefined.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ClosedLoop {
    /// Whether the last half of the run has settled (on a cycle, or at rest).
    pub settled: bool,
    /// Whether the settled loop hunts (a limit cycle of the position error); `None` where the
    /// run has not settled.
    pub hunting: Option<bool>,
    /// The hunting cycle's period, s.
    pub period: f64,
    /// Its amplitude: half the range of the position error over the last half, m.
    pub amplitude: f64,
    /// The time the body is stuck per cycle, s: its contact in the stick mode, or its speed
    /// at most [`STUCK_SPEED`] of the largest speed of the last half.
    pub stick_time_per_cycle: f64,
    /// The position error r − x at the end, m.
    pub final_error: f64,
    /// The root mean square of r − x over the run's recorded points, m.
    pub rms_error: f64,
    /// The largest |r − x| over them, m.
    pub max_error: f64,
}

/// One part of the settled window: its cycles, their mean period and the error's half range.
struct Part {
    cycles: usize,
    period: f64,
    amplitude: f64,
}

impl Part {
    /// The part of the samples `k` (indices into t and d, the position's excess over the
    /// reference x − r): x passes the reference upwards where d crosses zero upwards.
    fn of(t: &[f64], d: &[f64], k: &[usize]) -> Part {
        let passes = crossings(t, d, k, 0.0);
        let cycles = passes.len().saturating_sub(1);
        Part {
            cycles,
            period: match cycles {
                0 => f64::NAN,
                n => (passes[n] - passes[0]) / n as f64,
            },
            amplitude: half_range(k, &|i| d[i]),
        }
    }
}

impl ClosedLoop {
    /// The measures of `outcome`, if a controller positions its body
    /// ([`Outcome::reference`]).
    pub fn of_outcome(outcome: &Outcome) -> Option<ClosedLoop> {
        (outcome.reference.as_ref()).map(|reference| ClosedLoop::of(outcome, reference))
    }

    /// The measures of `outcome`, whose body tracks `reference`.
    pub fn of(outcome: &Outcome, reference: &Reference) -> ClosedLoop {
        let events: Vec<f64> = outcome.events.iter().map(|e| e.t).collect();
        ClosedLoop::of_rows(&outcome.rows, &events, reference, outcome.integral_action)
    }

    /// The measures of a body recorded as `recorded` (evenly spaced rows, and rows at the
    /// times `events` of its contact's switches), tracking `reference` under a controller
    /// with integral action or not.
    pub fn of_rows(
        recorded: &[Row],
        events: &[f64],
        reference: &Reference,
        integral_action: bool,
    ) -> ClosedLoop {
        let error = |r: &Row| reference.at(r.t).0 - r.x;
        let all: Vec<f64> = recorded.iter().map(error).collect();
        // The evenly spaced rows (those recorded at events left out), the last half.
        let rows: Vec<&Row> = (recorded.iter())
            .filter(|r| !events.contains(&r.t))
            .collect();
        let t: Vec<f64> = rows.iter().map(|r| r.t).collect();
        // x − r, whose upward crossings of zero are the passes of the reference.
        let d: Vec<f64> = rows.iter().map(|r| -error(r)).collect();
        let (t0, t1) = (
            t.first().copied().unwrap_or(0.0),
            t.last().copied().unwrap_or(0.0),
        );
        let from = 0.5 * (t0 + t1);
        let k: Vec<usize> = (0..t.len()).filter(|&i| t[i] >= from).collect();
        let (first, second) = k.split_at(k.len() / 2);
        let (whole, a, b) = (
            Part::of(&t, &d, &k),
            Part::of(&t, &d, first),
            Part::of(&t, &d, second),
        );
        let relative = |x: f64, y: f64| (x - y).abs() / x.abs().max(y.abs()).max(f64::MIN_POSITIVE);
        let last = d.last().copied().unwrap_or(f64::NAN);
        let at_rest = k.len() >= 2
            && whole.amplitude <= REST_AMPLITUDE
            && (!integral_action || last.abs() <= REST_AMPLITUDE);
        let cycling = !at_rest
            && a.cycles >= MIN_CYCLES
            && b.cycles >= MIN_CYCLES
            && relative(a.period, b.period) <= SETTLE_TOLERANCE
            && relative(a.amplitude, b.amplitude) <= SETTLE_TOLERANCE;
        let settled = at_rest || cycling;
        let hunting = settled.then_some(cycling);
        let fastest = (k.iter()).fold(0.0, |m: f64, &i| m.max(rows[i].v.abs()));
        let stuck: f64 = (k.windows(2))
            .filter(|w| rows[w[0]].mode == STICK || rows[w[0]].v.abs() <= STUCK_SPEED * fastest)
            .map(|w| t[w[1]] - t[w[0]])
            .sum();
        let undefined = |defined: bool, x: f64| if defined { x } else { f64::NAN };
        let n = all.len().max(1) as f64;
        ClosedLoop {
            settled,
            hunting,
            period: undefined(cycling, whole.period),
            amplitude: undefined(settled, whole.amplitude),
            stick_time_per_cycle: undefined(cycling, stuck / (t1 - from) * whole.period),
            final_error: all.last().copied().unwrap_or(f64::NAN),
            rms_error: (all.iter().map(|e| e * e).sum::<f64>() / n).sqrt(),
            max_error: all.iter().fold(0.0, |m: f64, e| m.max(e.abs())),
        }
    }
}

/// One line: `closed loop: hunting, period 24.45 s, amplitude 6.390e-2 m, stuck 18.75 s a
/// cycle`, or converged with the final error, or not settled; then the tracking error.
impl std::fmt::Display for ClosedLoop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.hunting {
            Some(true) => write!(
                f,
                "closed loop: hunting, period {:.4} s, amplitude {:.3e} m, stuck {:.4} s a cycle",
                self.period, self.amplitude, self.stick_time_per_cycle
            ),
            Some(false) => write!(
                f,
                "closed loop: converged, final error {:.3e} m",
                self.final_error
            ),
            None => write!(
                f,
                "closed loop: not settled over the last half of the run (neither hunting nor \
                 converged yet): run longer (a later end time t_end); final error {:.3e} m",
                self.final_error
            ),
        }?;
        write!(
            f,
            " (tracking error: RMS {:.3e} m, largest {:.3e} m)",
            self.rms_error, self.max_error
        )
    }
}
