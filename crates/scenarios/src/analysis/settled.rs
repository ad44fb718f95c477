//! The settled state of one body's run, as a sweep measures it: after the transient, how often
//! the body sticks per cycle, the amplitude and period of its oscillation, and its friction.
//!
//! With the window `[t_s, t_end]`, `t_s = (1 − settle)·t_end`, and v̄ the mean velocity over
//! it (time-weighted, trapezoidal):
//!
//! - the **period** is the mean spacing of the upward crossings of v through v̄ (linearly
//!   located between samples), defined from two crossings on;
//! - the **amplitudes** are half the ranges of v and of the detrended displacement x − v̄·t;
//! - the **stick phases** are the switches into stick in the window (from the switching log),
//!   and per cycle they are divided by window / period;
//! - the **friction** is its time mean over the window and the largest |F| in it.
//!
//! A run has **settled** when its cycle-to-cycle return has converged: the two halves of the
//! window each hold at least [`MIN_CYCLES`] cycles, and their periods, their half ranges of
//! x − v̄·t and of v, and their stick phases per cycle agree within [`SETTLE_TOLERANCE`]
//! ([`Settled::drift`], the largest relative difference). A run with no oscillation left (v's
//! half range at most [`REST_AMPLITUDE`] of the run's largest speed, or of 1e-3 m/s, and the
//! friction's at most [`REST_AMPLITUDE`] of its peak) has settled too.
//! A transient (an oscillation still growing or decaying, a first stick phase that fills half
//! the window) has not: the map, the bifurcation diagram and `sweep` say so instead of calling
//! it a regime.

use crate::run::{Outcome, RunSpec};
use friction_systems::STICK;
use serde::Serialize;

/// The relative difference between the two halves of the window (period, amplitudes, stick
/// phases per cycle) up to which a run has settled: 1 %.
pub const SETTLE_TOLERANCE: f64 = 1e-2;

/// The fewest complete cycles each half of the window must hold for its returns to be
/// compared.
pub const MIN_CYCLES: usize = 2;

/// v's half range, relative to the run's largest speed (or to 1e-3 m/s, whichever is larger),
/// at or below which no oscillation is left, and the friction's half range relative to its
/// peak: the run has settled at rest relative to its mean motion, under a constant force.
pub const REST_AMPLITUDE: f64 = 1e-6;

/// How far a run that has not settled in its base span is extended: its span doubled until it
/// settles, up to this many times the base (40 s → 320 s on the map).
pub const MAX_EXTENSION: u32 = 8;

/// The result of `run(factor)` for factor = 1, 2, 4, … up to [`MAX_EXTENSION`], stopping at
/// the first that `settled` accepts (or at the bound): a run extended until it settles.
pub fn until_settled<T, E>(
    mut run: impl FnMut(u32) -> Result<T, E>,
    mut settled: impl FnMut(&T) -> bool,
) -> Result<T, E> {
    let mut factor = 1;
    loop {
        let result = run(factor)?;
        if factor >= MAX_EXTENSION || settled(&result) {
            return Ok(result);
        }
        factor *= 2;
    }
}

/// `spec` over `factor` times its span (its end time, or its scenario's default), with
/// `factor` times its output intervals: the same output spacing.
pub fn spanned(spec: &RunSpec, factor: u32) -> RunSpec {
    let base = spec.end_time();
    let mut longer = spec.clone();
    longer.t_end = Some(base * f64::from(factor));
    longer.output_points = (spec.output_points - 1) * factor as usize + 1;
    longer
}

/// One body's sampled run: times, displacement, velocity, friction, and the times at which
/// its contact switched into stick.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trace {
    /// Sample times, increasing, s.
    pub t: Vec<f64>,
    /// Displacement, m.
    pub x: Vec<f64>,
    /// Velocity, m/s.
    pub v: Vec<f64>,
    /// Friction force, N.
    pub friction: Vec<f64>,
    /// Times of the switches into stick, s.
    pub stick_entries: Vec<f64>,
}

impl Trace {
    /// The trace of a rig's outcome: its evenly spaced rows (the rows recorded at events are
    /// left out) and its switches into stick.
    pub fn of_outcome(o: &Outcome) -> Trace {
        let mut trace = Trace::default();
        // The event times sorted once (−0 read as 0, as `==` reads it): a row is left out when
        // its time is one of them, found by bisection, not by a scan of every event per row.
        let mut at_events: Vec<f64> = o.events.iter().map(|e| e.t + 0.0).collect();
        at_events.sort_by(f64::total_cmp);
        let at_event = |t: f64| {
            at_events
                .binary_search_by(|e| e.total_cmp(&(t + 0.0)))
                .is_ok()
        };
        for r in o.rows.iter().filter(|r| !at_event(r.t)) {
            trace.t.push(r.t);
            trace.x.push(r.x);
            trace.v.push(r.v);
            trace.friction.push(r.friction);
        }
        trace.stick_entries = o
            .events
            .iter()
            .filter(|e| e.to == STICK)
            .map(|e| e.t)
            .collect();
        trace
    }
}

/// The settled-state measures of a [`Trace`]; `NaN` where a measure is not defined (no
/// oscillation: fewer than two crossings).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Settled {
    /// Start of the measured window, s.
    pub from: f64,
    /// Its end: the end of the run, s.
    pub to: f64,
    /// Switches into stick in the window.
    pub stick_phases: usize,
    /// Stick phases per cycle of the oscillation.
    pub stick_per_cycle: f64,
    /// Period of the settled oscillation, s.
    pub period: f64,
    /// Half the range of x − v̄·t, m.
    pub x_amplitude: f64,
    /// Half the range of v, m/s.
    pub v_amplitude: f64,
    /// Half the range of v over the second half of the window over that over the first: 1
    /// for a sustained oscillation, below 1 for one that dies out; undefined (NaN) when v is
    /// constant over the first half (a motion that starts there is no decay).
    pub v_amplitude_ratio: f64,
    /// Mean velocity v̄, m/s.
    pub v_mean: f64,
    /// Time mean of the friction force, N.
    pub friction_mean: f64,
    /// Largest |friction|, N.
    pub friction_peak: f64,
    /// The largest relative difference between the window's two halves in period, half
    /// range of x − v̄·t, half range of v and stick phases per cycle (the last relative to
    /// one); NaN where a half holds fewer than [`MIN_CYCLES`] cycles.
    pub drift: f64,
    /// Whether the run has settled: no oscillation left, or a `drift` of at most
    /// [`SETTLE_TOLERANCE`].
    pub settled: bool,
}

/// The measures of one half of the window that its returns are compared by.
struct Half {
    cycles: usize,
    period: f64,
    x_amplitude: f64,
    v_amplitude: f64,
    stick_per_cycle: f64,
}

/// Half the range of `f` over the samples `k`.
pub(crate) fn half_range(k: &[usize], f: &dyn Fn(usize) -> f64) -> f64 {
    let (lo, hi) = k
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &i| {
            (lo.min(f(i)), hi.max(f(i)))
        });
    0.5 * (hi - lo)
}

/// The upward crossings of `v` through `level` among the samples `k` of `t`, located
/// linearly between samples.
pub(crate) fn crossings(t: &[f64], v: &[f64], k: &[usize], level: f64) -> Vec<f64> {
    k.windows(2)
        .filter(|w| v[w[0]] < level && v[w[1]] >= level)
        .map(|w| {
            let (a, b) = (v[w[0]] - level, v[w[1]] - level);
            t[w[0]] + (t[w[1]] - t[w[0]]) * a / (a - b)
        })
        .collect()
}

impl Half {
    /// The measures of the samples `k` of `trace`, about the mean velocity `v_mean`.
    fn of(trace: &Trace, k: &[usize], v_mean: f64) -> Half {
        let c = crossings(&trace.t, &trace.v, k, v_mean);
        let cycles = c.len().saturating_sub(1);
        let period = if cycles > 0 {
            (c[cycles] - c[0]) / cycles as f64
        } else {
            f64::NAN
        };
        let half_range = |f: &dyn Fn(usize) -> f64| half_range(k, f);
        let sticks = match (c.first(), c.last()) {
            (Some(&a), Some(&b)) if cycles > 0 => trace
                .stick_entries
                .iter()
                .filter(|&&s| s >= a && s < b)
                .count(),
            _ => 0,
        };
        Half {
            cycles,
            period,
            x_amplitude: half_range(&|i| trace.x[i] - v_mean * trace.t[i]),
            v_amplitude: half_range(&|i| trace.v[i]),
            stick_per_cycle: sticks as f64 / cycles.max(1) as f64,
        }
    }

    /// The largest relative difference to `other` ([`Settled::drift`]); NaN where either
    /// holds fewer than [`MIN_CYCLES`] cycles.
    fn drift(&self, other: &Half) -> f64 {
        if self.cycles < MIN_CYCLES || other.cycles < MIN_CYCLES {
            return f64::NAN;
        }
        let relative = |a: f64, b: f64| (a - b).abs() / a.abs().max(b.abs()).max(f64::MIN_POSITIVE);
        [
            relative(self.period, other.period),
            relative(self.x_amplitude, other.x_amplitude),
            relative(self.v_amplitude, other.v_amplitude),
            (self.stick_per_cycle - other.stick_per_cycle).abs(),
        ]
        .into_iter()
        .fold(0.0, f64::max)
    }
}

/// `late / early`, undefined (NaN) where `early` is zero.
fn ratio(late: f64, early: f64) -> f64 {
    if early > 0.0 {
        late / early
    } else {
        f64::NAN
    }
}

/// The time mean of `y` over the samples `k` of `t` (trapezoidal).
fn time_mean(t: &[f64], y: &[f64], k: &[usize]) -> f64 {
    let (mut area, mut span) = (0.0, 0.0);
    for w in k.windows(2) {
        let dt = t[w[1]] - t[w[0]];
        area += 0.5 * (y[w[0]] + y[w[1]]) * dt;
        span += dt;
    }
    if span > 0.0 {
        area / span
    } else {
        y.get(k[0]).copied().unwrap_or(f64::NAN)
    }
}

impl Settled {
    /// The window of these measures with every measure undefined (NaN, no stick phase) and not
    /// settled: what a window measures where the run in it is no measure of the problem (it
    /// failed, or it diverged) or where it holds fewer than two instants.
    pub fn undefined(self) -> Settled {
        Settled {
            from: self.from,
            to: self.to,
            stick_phases: 0,
            stick_per_cycle: f64::NAN,
            period: f64::NAN,
            x_amplitude: f64::NAN,
            v_amplitude: f64::NAN,
            v_amplitude_ratio: f64::NAN,
            v_mean: f64::NAN,
            friction_mean: f64::NAN,
            friction_peak: f64::NAN,
            drift: f64::NAN,
            settled: false,
        }
    }

    /// The measures of `trace` over the last `settle` fraction (0, 1] of its time span; all
    /// undefined (NaN), and not settled, where the window holds fewer than two instants.
    pub fn of(trace: &Trace, settle: f64) -> Settled {
        let t = &trace.t;
        let (t0, t1) = match (t.first(), t.last()) {
            (Some(&a), Some(&b)) => (a, b),
            _ => (0.0, 0.0),
        };
        let from = t1 - settle * (t1 - t0);
        let k: Vec<usize> = (0..t.len()).filter(|&i| t[i] >= from).collect();
        // A window of one instant (a run that stopped at its start) measures nothing: at rest
        // there only because no time passed, it is not settled.
        if k.len() < 2 || t1 <= t0 {
            return Settled {
                from,
                to: t1,
                ..Settled::default().undefined()
            };
        }
        let v_mean = time_mean(t, &trace.v, &k);
        let range = |f: &dyn Fn(usize) -> f64| half_range(&k, f);
        let (first, second) = k.split_at(k.len() / 2);
        let v_of = |i: usize| trace.v[i];
        let crossings = crossings(t, &trace.v, &k, v_mean);
        let period = match crossings.len() {
            0 | 1 => f64::NAN,
            n => (crossings[n - 1] - crossings[0]) / (n - 1) as f64,
        };
        // Over whole cycles (first to last crossing) the mean velocity is exactly the mean
        // motion: Δx/Δt, with x interpolated linearly at the crossings.
        let x_at = |tc: f64| {
            let j = t.partition_point(|&s| s < tc).clamp(1, t.len() - 1);
            let w = (tc - t[j - 1]) / (t[j] - t[j - 1]);
            trace.x[j - 1] + w * (trace.x[j] - trace.x[j - 1])
        };
        let v_mean = match crossings.len() {
            0 | 1 => v_mean,
            n => (x_at(crossings[n - 1]) - x_at(crossings[0])) / (crossings[n - 1] - crossings[0]),
        };
        let stick_phases = trace
            .stick_entries
            .iter()
            .filter(|&&s| s >= from && s <= t1)
            .count();
        let v_amplitude = range(&v_of);
        // At rest about the mean motion, and under a constant force: a body carried by a
        // belt while a spring loads it is at rest too, but its friction still ramps (a first
        // stick phase longer than the window), and that is a transient.
        let friction_peak = k
            .iter()
            .map(|&i| trace.friction[i].abs())
            .fold(0.0, f64::max);
        let speed = trace
            .v
            .iter()
            .fold(v_mean.abs().max(1e-3), |a, v| a.max(v.abs()));
        let at_rest = v_amplitude <= REST_AMPLITUDE * speed
            && range(&|i| trace.friction[i]) <= REST_AMPLITUDE * friction_peak;
        let drift = Half::of(trace, first, v_mean).drift(&Half::of(trace, second, v_mean));
        Settled {
            from,
            to: t1,
            stick_phases,
            stick_per_cycle: stick_phases as f64 * period / (t1 - from),
            period,
            x_amplitude: range(&|i| trace.x[i] - v_mean * t[i]),
            v_amplitude,
            v_amplitude_ratio: ratio(half_range(second, &v_of), half_range(first, &v_of)),
            v_mean,
            friction_mean: time_mean(t, &trace.friction, &k),
            friction_peak,
            drift,
            settled: at_rest || drift <= SETTLE_TOLERANCE,
        }
    }
}
