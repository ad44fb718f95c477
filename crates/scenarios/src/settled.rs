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

use crate::run::Outcome;
use friction_systems::STICK;
use serde::Serialize;

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
        for r in o
            .rows
            .iter()
            .filter(|r| !o.events.iter().any(|e| e.t == r.t))
        {
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
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Settled {
    /// Start of the measured window, s.
    pub from: f64,
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
    /// The measures of `trace` over the last `settle` fraction (0, 1] of its time span.
    pub fn of(trace: &Trace, settle: f64) -> Settled {
        let t = &trace.t;
        let (t0, t1) = match (t.first(), t.last()) {
            (Some(&a), Some(&b)) => (a, b),
            _ => (0.0, 0.0),
        };
        let from = t1 - settle * (t1 - t0);
        let k: Vec<usize> = (0..t.len()).filter(|&i| t[i] >= from).collect();
        if k.is_empty() {
            return Settled {
                from,
                stick_phases: 0,
                stick_per_cycle: f64::NAN,
                period: f64::NAN,
                x_amplitude: f64::NAN,
                v_amplitude: f64::NAN,
                v_amplitude_ratio: f64::NAN,
                v_mean: f64::NAN,
                friction_mean: f64::NAN,
                friction_peak: f64::NAN,
            };
        }
        let v_mean = time_mean(t, &trace.v, &k);
        let half_range = |k: &[usize], f: &dyn Fn(usize) -> f64| {
            let (lo, hi) = k
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &i| {
                    (lo.min(f(i)), hi.max(f(i)))
                });
            0.5 * (hi - lo)
        };
        let range = |f: &dyn Fn(usize) -> f64| half_range(&k, f);
        let (first, second) = k.split_at(k.len() / 2);
        let v_of = |i: usize| trace.v[i];
        let crossings: Vec<f64> = k
            .windows(2)
            .filter(|w| trace.v[w[0]] < v_mean && trace.v[w[1]] >= v_mean)
            .map(|w| {
                let (a, b) = (trace.v[w[0]] - v_mean, trace.v[w[1]] - v_mean);
                t[w[0]] + (t[w[1]] - t[w[0]]) * a / (a - b)
            })
            .collect();
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
        Settled {
            from,
            stick_phases,
            stick_per_cycle: stick_phases as f64 * period / (t1 - from),
            period,
            x_amplitude: range(&|i| trace.x[i] - v_mean * t[i]),
            v_amplitude: range(&v_of),
            v_amplitude_ratio: ratio(half_range(second, &v_of), half_range(first, &v_of)),
            v_mean,
            friction_mean: time_mean(t, &trace.friction, &k),
            friction_peak: k
                .iter()
                .map(|&i| trace.friction[i].abs())
                .fold(0.0, f64::max),
        }
    }
}
