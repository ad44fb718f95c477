//! The settled-state measures of a sweep against a trace whose answers are known.

use scenarios::analysis::settled::{Settled, Trace};
use std::f64::consts::PI;

/// x = v̄·t + A·sin(ωt) sampled densely over 20 periods, friction c·v, one switch into stick
/// at the top of every period.
fn harmonic(v_bar: f64, a: f64, omega: f64, c: f64) -> Trace {
    let period = 2.0 * PI / omega;
    let n = 20_000;
    let t_end = 20.0 * period;
    let t: Vec<f64> = (0..=n).map(|i| t_end * i as f64 / n as f64).collect();
    let x = t
        .iter()
        .map(|&t| v_bar * t + a * (omega * t).sin())
        .collect();
    let v: Vec<f64> = t
        .iter()
        .map(|&t| v_bar + a * omega * (omega * t).cos())
        .collect();
    Trace {
        friction: v.iter().map(|v| c * v).collect(),
        stick_entries: (0..20).map(|k| (k as f64 + 0.25) * period).collect(),
        t,
        x,
        v,
    }
}

#[test]
fn a_harmonic_trace_gives_its_period_amplitudes_means_and_one_stick_per_cycle() {
    let (v_bar, a, omega, c) = (0.3, 0.02, 7.0, 2.0);
    let s = Settled::of(&harmonic(v_bar, a, omega, c), 0.5);
    let period = 2.0 * PI / omega;
    assert!((s.from - 10.0 * period).abs() < 1e-12, "{}", s.from);
    assert!((s.period - period).abs() < 1e-6 * period, "{}", s.period);
    assert!((s.x_amplitude - a).abs() < 1e-6, "{}", s.x_amplitude);
    assert!(
        (s.v_amplitude - a * omega).abs() < 1e-6,
        "{}",
        s.v_amplitude
    );
    assert!((s.v_mean - v_bar).abs() < 1e-9, "{}", s.v_mean);
    assert!(
        (s.friction_mean - c * v_bar).abs() < 1e-8,
        "{}",
        s.friction_mean
    );
    assert!((s.friction_peak - c * (v_bar + a * omega)).abs() < 1e-9);
    assert_eq!(s.stick_phases, 10);
    assert!(
        (s.stick_per_cycle - 1.0).abs() < 1e-6,
        "{}",
        s.stick_per_cycle
    );
}

#[test]
fn steady_sliding_has_no_period_and_no_stick() {
    let mut trace = harmonic(0.3, 0.0, 7.0, 2.0);
    trace.stick_entries.clear();
    let s = Settled::of(&trace, 0.5);
    assert!(s.period.is_nan());
    assert!(s.stick_per_cycle.is_nan());
    assert_eq!(s.stick_phases, 0);
    assert!(s.x_amplitude.abs() < 1e-12 && s.v_amplitude.abs() < 1e-12);
}

#[test]
fn a_motion_that_starts_late_in_the_window_has_no_decay_ratio() {
    // Stuck at v̄ over the first half of the settled window, oscillating in the second: the
    // ratio of the halves' amplitudes is undefined (it was infinite, and sweep.csv refused
    // to write it).
    let mut trace = harmonic(0.3, 0.02, 7.0, 2.0);
    let t_mid = 0.75 * trace.t.last().unwrap();
    for (t, v) in trace.t.iter().zip(trace.v.iter_mut()) {
        if *t < t_mid {
            *v = 0.3;
        }
    }
    let s = Settled::of(&trace, 0.5);
    assert!(s.v_amplitude > 0.1, "{}", s.v_amplitude);
    assert!(s.v_amplitude_ratio.is_nan(), "{}", s.v_amplitude_ratio);
    // A decaying one keeps its ratio below one.
    let mut decaying = harmonic(0.3, 0.02, 7.0, 2.0);
    let t_end = *decaying.t.last().unwrap();
    for (t, v) in decaying.t.iter().zip(decaying.v.iter_mut()) {
        *v = 0.3 + (*v - 0.3) * (-t / t_end).exp();
    }
    let r = Settled::of(&decaying, 0.5).v_amplitude_ratio;
    assert!(r > 0.5 && r < 1.0, "{r}");
}

/// A sustained oscillation has settled: its two half windows agree (drift near 0); one that
/// dies out by a few per cent a cycle has not, whatever its ratio of amplitudes once allowed.
#[test]
fn a_run_has_settled_when_its_returns_agree_and_not_while_it_decays() {
    let s = Settled::of(&harmonic(0.3, 0.02, 7.0, 2.0), 0.5);
    assert!(s.settled && s.drift < 1e-3, "{s:?}");
    let mut decaying = harmonic(0.3, 0.02, 7.0, 2.0);
    let t_end = *decaying.t.last().unwrap();
    for (i, t) in decaying.t.clone().iter().enumerate() {
        let fade = (-0.5 * t / t_end).exp();
        decaying.v[i] = 0.3 + (decaying.v[i] - 0.3) * fade;
        decaying.x[i] = 0.3 * t + (decaying.x[i] - 0.3 * t) * fade;
    }
    let s = Settled::of(&decaying, 0.5);
    assert!(!s.settled && s.drift > 0.1, "{s:?}");
    // No oscillation at all has settled (at rest about its mean motion).
    let mut still = harmonic(0.3, 0.0, 7.0, 2.0);
    still.stick_entries.clear();
    let s = Settled::of(&still, 0.5);
    assert!(s.settled && s.drift.is_nan(), "{s:?}");
}

#[test]
fn a_run_that_stopped_at_its_start_measures_nothing_and_has_not_settled() {
    // One instant (a run stopped at t = 0), and two at the same time: no window at all.
    for t in [vec![0.0], vec![0.0, 0.0]] {
        let n = t.len();
        let trace = Trace {
            t,
            x: vec![0.0; n],
            v: vec![0.0; n],
            friction: vec![-28.9; n],
            stick_entries: Vec::new(),
        };
        let s = Settled::of(&trace, 0.5);
        assert!(!s.settled, "{s:?}");
        for m in [
            s.x_amplitude,
            s.v_amplitude,
            s.v_mean,
            s.friction_mean,
            s.friction_peak,
        ] {
            assert!(m.is_nan(), "{s:?}");
        }
    }
}

#[test]
fn a_rigs_trace_is_its_evenly_spaced_rows_without_those_recorded_at_events() {
    use friction_models::{FrictionParams, ModelId};
    use integrators::even_grid;
    use scenarios::run;
    use scenarios::stick_slip::belt_run;
    let spec = scenarios::RunSpec {
        t_end: Some(20.0),
        output_points: 201,
        ..belt_run(ModelId::Cvs, &FrictionParams::paper())
    };
    let o = run(&spec, &mut |_| {}).unwrap();
    let trace = Trace::of_outcome(&o);
    // Stick–slip: the rows at the switches come on top of the grid's 201.
    assert!(o.events.len() > 10, "{} events", o.events.len());
    assert_eq!(o.rows.len(), 201 + o.events.len());
    assert_eq!(trace.t, even_grid(0.0, 20.0, 201));
    let stick = o.events.iter().filter(|e| e.to == friction_systems::STICK);
    assert_eq!(trace.stick_entries.len(), stick.count());
}
