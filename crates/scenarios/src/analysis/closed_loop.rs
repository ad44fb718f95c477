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
//!
//! A body asked to move that **never moved** (its travel from the start within
//! [`STUCK_TRAVEL`] of the largest distance |r − x0| its reference asked, which is above
//! [`REST_AMPLITUDE`]) is **stuck**, not hunting whatever its error does (a sinusoidal
//! reference it never followed crosses it), and settled unless integral action winds up to
//! free it. A body that moved and came to rest off its set point (without integral action)
//! stopped in the friction's **dead zone**, |e| ≤ F_s/k_p.

use super::settled::{crossings, half_range, MIN_CYCLES, SETTLE_TOLERANCE};
use crate::run::{Outcome, Row};
use friction_systems::{Reference, Run, System, SLIP_POSITIVE, STICK};
use serde::Serialize;

/// The half range of the error, m, at or below which the settled loop is at rest.
pub const REST_AMPLITUDE: f64 = 1e-9;

/// The travel from the start, relative to the largest distance |r − x0| the reference asks
/// of the body, at or below which it never followed it: a law without a stick mode lets a body
/// held by friction creep, and a reference that starts moving jolts it (5 mm against a
/// sinusoid of 1 m under the servo's PID and CS, after which it sticks for good).
pub const STUCK_TRAVEL: f64 = 1e-2;

/// The speed, relative to the largest speed of the settled part, at or below which a body
/// counts as stuck although its contact slides: a law without a stick mode (LuGre) holds it
/// by creeping at micrometres per second.
pub const STUCK_SPEED: f64 = 1e-3;

/// The measures of one closed-loop run; `NaN` (written null) where a measure is undefined.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ClosedLoop {
    /// Whether the last half of the run has settled (on a cycle, or at rest).
    pub settled: bool,
    /// Whether the body never moved although its reference asked it to: the largest distance
    /// |r − x0| asked is above [`REST_AMPLITUDE`], and the body's travel from the start stays
    /// within [`STUCK_TRAVEL`] of it at every recorded point.
    pub stuck: bool,
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

    /// The closed loop of `system`'s first controller, read off its body's recorded states in
    /// `run` (up to the first that is not finite); `None` for a system without a controller.
    pub fn of_run(run: &Run, system: &System) -> Option<ClosedLoop> {
        let c = system.controllers.first()?;
        let rows: Vec<Row> = (run.body(c.body).into_iter())
            .map(|b| Row {
                t: b.t,
                x: b.x,
                v: b.v,
                friction: b.friction,
                // A body without a contact never sticks.
                mode: b.mode.unwrap_or(SLIP_POSITIVE),
                z: b.z,
            })
            .take_while(Row::is_finite)
            .collect();
        let events: Vec<f64> = (run.contact_events().iter())
            .filter(|e| e.body == c.body)
            .map(|e| e.t)
            .collect();
        Some(ClosedLoop::of_rows(
            &rows,
            &events,
            &c.reference,
            c.ki > 0.0,
        ))
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
        let x0 = recorded.first().map_or(0.0, |r| r.x);
        let asked =
            (recorded.iter()).fold(0.0, |m: f64, r| m.max((reference.at(r.t).0 - x0).abs()));
        let travel = (recorded.iter()).fold(0.0, |m: f64, r| m.max((r.x - x0).abs()));
        let never_moved = asked > REST_AMPLITUDE && travel <= STUCK_TRAVEL * asked;
        let (settled, cycling) = if never_moved {
            (!integral_action, false)
        } else {
            (at_rest || cycling, cycling)
        };
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
            stuck: never_moved,
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

impl ClosedLoop {
    /// Whether the loop is at rest off its reference: |r − x| at the end above
    /// [`REST_AMPLITUDE`].
    pub fn off_reference(&self) -> bool {
        self.final_error.abs() > REST_AMPLITUDE
    }

    /// Hunting, converged or not settled, as [`ClosedLoop`]'s one line says it.
    fn fmt_regime(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
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
        }
    }
}

/// One line: `closed loop: hunting, period 24.45 s, amplitude 6.390e-2 m, stuck 18.75 s a
/// cycle`, or converged with the final error, at rest in the dead zone, stuck, or not
/// settled; then the tracking error.
impl std::fmt::Display for ClosedLoop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match (self.stuck, self.hunting) {
            (true, Some(_)) => write!(
                f,
                "closed loop: stuck, the body never moved (by more than 1 % of what its \
                 reference asks), final error {:.3e} m",
                self.final_error
            ),
            (true, None) => write!(
                f,
                "closed loop: stuck so far, the body never moved (by more than 1 % of what its \
                 reference asks), and integral action may yet free it: run longer (a later end \
                 time t_end); final error {:.3e} m",
                self.final_error
            ),
            (false, Some(false)) if self.off_reference() => write!(
                f,
                "closed loop: at rest in the friction's dead zone, off its set point by {:.3e} m",
                self.final_error
            ),
            _ => self.fmt_regime(f),
        }?;
        write!(
            f,
            " (tracking error: RMS {:.3e} m, largest {:.3e} m)",
            self.rms_error, self.max_error
        )
    }
}
