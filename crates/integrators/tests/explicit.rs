//! RK4 and Dormand–Prince: parity with Hairer's dopri5.f, observed orders, landing on the
//! end time, event location, and every error.

mod common;

use approx::assert_abs_diff_eq;
use common::*;
use integrators::{
    Control, Crossing, Dopri5, Integrator, Mode, OdeProblem, Options, Output, Rk4, SolverError,
    StepControl, Stepper, StopReason,
};

fn dopri5(options: &Options, dim: usize) -> Box<dyn Stepper> {
    Box::new(Dopri5::new(
        options.step,
        options.h_max(),
        options.max_steps,
        dim,
    ))
}

fn run(
    problem: &dyn OdeProblem,
    stepper: Box<dyn Stepper + '_>,
    y0: &[f64],
    o: Options,
) -> integrators::Solution {
    Integrator::new(problem, stepper, y0, &[Mode(0)], o)
        .unwrap()
        .solve()
        .unwrap()
}

#[test]
fn dopri5_matches_hairers_arenstorf_run_with_given_initial_step() {
    // dopri5.f, RTOL = ATOL = 1e-7, H = 1e-4 (the run russell_ode reproduces): 238 steps,
    // 217 accepted, 21 rejected, 1 + 6·238 = 1429 evaluations (dopri5.f's NFCN prints 1430:
    // it adds 2 at the start even when HINIT is not called).
    let mut o = Options::adaptive(0.0, ARENSTORF_T_END, 1e-7, 1e-7);
    o.step = StepControl::Adaptive {
        rtol: 1e-7,
        atol: 1e-7,
        h0: Some(1e-4),
    };
    let s = run(&Arenstorf, dopri5(&o, 4), &ARENSTORF_Y0, o);
    assert_eq!(s.stats.steps, 217);
    assert_eq!(s.stats.rejected_error, 21);
    assert_eq!(s.stats.rhs_evals, 1429);
    let (t, y) = s.last().unwrap();
    assert_eq!(t, ARENSTORF_T_END);
    let reference = [
        0.9940021704037415,
        9.040893396741956e-06,
        0.0014597586885445324,
        -2.0012455157289244,
    ];
    for (a, b) in y.iter().zip(reference) {
        assert_abs_diff_eq!(*a, b, epsilon = 1e-9);
    }
}

#[test]
fn dopri5_matches_hairers_arenstorf_driver_with_hinit_and_dense_output() {
    // The output of Hairer's driver dr_dopri5.f (RTOL = ATOL = 1e-7, H = 0 so HINIT chooses):
    //   X = 2.00  Y = -0.5798781411E+00  0.6090775251E+00  NSTEP = 60   ...
    //   tol=0.10D-06  fcn= 1442 step= 240 accpt= 216 rejct= 22
    // dopri5.f counts no rejection before the first accepted step (IF(NACCPT.GE.1)), so
    // its 240 steps are 216 accepted + 24 rejected, two of them before the first acceptance.
    let printed = [
        (2.0, -0.5798781411, 0.6090775251, 60),
        (4.0, -0.1983335270, 0.1137638086e1, 73),
        (6.0, -0.4735743943, 0.2239068118, 91),
        (8.0, -0.1174553350e1, -0.2759466982, 110),
        (10.0, -0.8398073466, 0.4468302268, 122),
        (12.0, 0.1314712468e-1, -0.8385751499, 145),
        (14.0, -0.6031129504, -0.9912598031, 159),
        (16.0, 0.2427110999, -0.3899948833, 177),
    ];
    let mut o = Options::adaptive(0.0, ARENSTORF_T_END, 1e-7, 1e-7);
    o.output = Output::Grid(printed.iter().map(|p| p.0).collect());
    let mut run = Integrator::new(&Arenstorf, dopri5(&o, 4), &ARENSTORF_Y0, &[Mode(0)], o).unwrap();
    let mut accepted_at_output = Vec::new();
    let mut recorded = 0;
    while run.step().unwrap() != StopReason::EndReached {
        let s = run.solution();
        for _ in recorded..s.len() {
            accepted_at_output.push(s.stats.steps);
        }
        recorded = s.len();
    }
    let s = run.solution();
    for (i, (t, y1, y2, nstep)) in printed.into_iter().enumerate() {
        assert_eq!(s.t[i], t);
        assert_abs_diff_eq!(s.y_at(i)[0], y1, epsilon = 1e-9);
        assert_abs_diff_eq!(s.y_at(i)[1], y2, epsilon = 1e-9);
        assert_eq!(
            accepted_at_output[i], nstep,
            "accepted steps when X = {t} was passed"
        );
    }
    assert_eq!(s.stats.rhs_evals, 1442);
    assert_eq!(s.stats.steps, 216);
    assert_eq!(s.stats.rejected_error, 24);
}

/// Error at t = 2 of x'' = −x (x = cos t) with fixed step h.
fn oscillator_error(stepper: Box<dyn Stepper>, h: f64) -> f64 {
    let s = run(
        &Oscillator::plain(),
        stepper,
        &[1.0, 0.0],
        Options::fixed(0.0, 2.0, h),
    );
    let (_, y) = s.last().unwrap();
    ((y[0] - 2f64.cos()).powi(2) + (y[1] + 2f64.sin()).powi(2)).sqrt()
}

fn observed_order(errors: &[f64], steps: &[f64]) -> Vec<f64> {
    errors
        .windows(2)
        .zip(steps.windows(2))
        .map(|(e, h)| (e[0] / e[1]).ln() / (h[0] / h[1]).ln())
        .collect()
}

#[test]
fn rk4_converges_with_order_four() {
    let steps = [0.2, 0.1, 0.05, 0.025];
    let errors: Vec<f64> = steps
        .iter()
        .map(|&h| oscillator_error(Box::new(Rk4::new(h, 2)), h))
        .collect();
    for p in observed_order(&errors, &steps) {
        assert!(
            (p - 4.0).abs() < 0.1,
            "observed order {p}, errors {errors:?}"
        );
    }
}

#[test]
fn dopri5_fixed_step_converges_with_order_five() {
    let steps = [0.4, 0.2, 0.1, 0.05];
    let errors: Vec<f64> = steps
        .iter()
        .map(|&h| oscillator_error(dopri5(&Options::fixed(0.0, 2.0, h), 2), h))
        .collect();
    for p in observed_order(&errors, &steps) {
        assert!(
            (p - 5.0).abs() < 0.25,
            "observed order {p}, errors {errors:?}"
        );
    }
}

#[test]
fn dopri5_error_is_proportional_to_the_tolerance() {
    let tols = [1e-5, 1e-7, 1e-9, 1e-11];
    let errors: Vec<f64> = tols
        .iter()
        .map(|&tol| {
            let o = Options::adaptive(0.0, 10.0, tol, tol);
            let s = run(&Oscillator::plain(), dopri5(&o, 2), &[1.0, 0.0], o);
            (s.last().unwrap().1[0] - 10f64.cos()).abs()
        })
        .collect();
    // log(error) against log(tol): slope near 1 (Hairer's controller aims at tolerance
    // proportionality; its slope for dopri5 is typically 0.8–1.1).
    for w in errors.windows(2) {
        let slope = (w[0] / w[1]).log10() / 2.0;
        assert!(
            (0.7..1.2).contains(&slope),
            "slope {slope}, errors {errors:?}"
        );
    }
}

#[test]
fn rk4_lands_exactly_on_the_end_time() {
    let s = run(
        &Oscillator::plain(),
        Box::new(Rk4::new(0.3, 2)),
        &[1.0, 0.0],
        Options::fixed(0.0, 1.0, 0.3),
    );
    assert_eq!(s.t, vec![0.0, 0.3, 0.6, 0.8999999999999999, 1.0]);
    assert_eq!(s.stats.steps, 4);
    assert_eq!(s.stats.rhs_evals, 1 + 4 * 4);
}

#[test]
fn events_are_located_on_the_dense_output_to_1e_10() {
    // x = cos t crosses zero falling at π/2.
    let p = Oscillator::watching(Crossing::Falling, Control::Stop);
    let o = Options::adaptive(0.0, 3.0, 1e-12, 1e-12);
    let s = run(&p, dopri5(&o, 2), &[1.0, 0.0], o);
    assert_eq!(s.events.len(), 1);
    assert!(
        (s.events[0].t - std::f64::consts::FRAC_PI_2).abs() < 1e-10,
        "{}",
        s.events[0].t
    );
    assert_eq!(
        s.last().unwrap().0,
        s.events[0].t,
        "Stop ends the run at the event"
    );
    let s = run(
        &p,
        Box::new(Rk4::new(1e-3, 2)),
        &[1.0, 0.0],
        Options::fixed(0.0, 3.0, 1e-3),
    );
    assert!(
        (s.events[0].t - std::f64::consts::FRAC_PI_2).abs() < 1e-10,
        "{}",
        s.events[0].t
    );
}

#[test]
fn the_crossing_direction_filters_events() {
    // Rising crossings of cos t only: 3π/2 and 7π/2 in [0, 12].
    let p = Oscillator::watching(Crossing::Rising, Control::Continue);
    let o = Options::adaptive(0.0, 12.0, 1e-10, 1e-10);
    let s = run(&p, dopri5(&o, 2), &[1.0, 0.0], o);
    let times: Vec<f64> = s.events.iter().map(|e| e.t).collect();
    assert_eq!(times.len(), 2, "{times:?}");
    assert!((times[0] - 1.5 * std::f64::consts::PI).abs() < 1e-9);
    assert!((times[1] - 3.5 * std::f64::consts::PI).abs() < 1e-9);
    assert_eq!(s.stats.events, 2);
    assert_eq!(s.stats.cut_at_event, 2);
}

#[test]
fn an_event_that_fired_does_not_fire_again_at_once() {
    // Starting on x = 0 (sin t with x'' = −x from (0, 1)): the start is no event; each of the
    // three crossings in (0, 10) fires exactly once although the method restarts on it.
    let p = Oscillator::watching(Crossing::Either, Control::Continue);
    let o = Options::adaptive(0.0, 10.0, 1e-10, 1e-10);
    let s = run(&p, dopri5(&o, 2), &[0.0, 1.0], o);
    let times: Vec<f64> = s.events.iter().map(|e| e.t).collect();
    assert_eq!(times.len(), 3, "{times:?}");
    for (k, t) in times.iter().enumerate() {
        assert!((t - (k + 1) as f64 * std::f64::consts::PI).abs() < 1e-9);
    }
}

#[test]
fn accumulating_events_end_with_an_error_and_keep_the_solution() {
    // Bounces at t_k accumulate at t* = t_1·(1 + 2·(1/2)/(1 − 1/2)) = 3·sqrt(2/9.81).
    let o = Options::adaptive(0.0, 5.0, 1e-10, 1e-10);
    let failure = Integrator::new(&BouncingBall, dopri5(&o, 2), &[1.0, 0.0], &[Mode(0)], o)
        .unwrap()
        .solve()
        .unwrap_err();
    let SolverError::TooManyEvents { t, count, .. } = failure.error else {
        panic!("{failure}");
    };
    let zeno = 3.0 * (2.0 / 9.81f64).sqrt();
    assert!((t - zeno).abs() < 1e-5, "stopped at {t}, Zeno point {zeno}");
    assert_eq!(count, 101);
    assert!(failure.solution.events.len() > 100);
    assert!(failure
        .to_string()
        .starts_with("too many events: 101 events within"));
}

#[test]
fn chattering_is_detected_relative_to_the_problems_own_time_scale() {
    // The same Zeno point at time scales 1e-9 s, 1 s and 100 s: the guard's window follows
    // the scale, so it fires after the same bounces at the same scaled time.
    let zeno = 3.0 * (2.0 / 9.81f64).sqrt();
    let mut counts = Vec::new();
    for scale in [1e-9, 1.0, 1e2] {
        let o = Options::adaptive(0.0, 5.0 * scale, 1e-10, 1e-10);
        let failure = Integrator::new(
            &ScaledBall { scale },
            dopri5(&o, 2),
            &[1.0, 0.0],
            &[Mode(0)],
            o,
        )
        .unwrap()
        .solve()
        .unwrap_err();
        let SolverError::TooManyEvents { t, window, .. } = failure.error else {
            panic!("scale {scale}: {failure}");
        };
        assert!(
            (t / scale - zeno).abs() < 1e-5,
            "scale {scale}: stopped at {t}"
        );
        assert_eq!(window, 1e-6 * scale);
        counts.push(failure.solution.events.len());
    }
    assert!(
        counts.iter().all(|&c| c.abs_diff(counts[1]) <= 2),
        "bounces before the guard fired: {counts:?}"
    );
}

#[test]
fn each_error_says_where_and_why() {
    let p = Oscillator::plain();
    let err = |o: Options| {
        Integrator::new(&p, dopri5(&o, 2), &[1.0, 0.0], &[Mode(0)], o)
            .err()
            .unwrap()
    };
    assert_eq!(
        err(Options::adaptive(1.0, 0.5, 1e-6, 1e-6)).to_string(),
        "t_end = 0.5 lies before t0 = 1: integration runs forward in time"
    );
    assert_eq!(
        err(Options::adaptive(0.0, 1.0, 0.0, 1e-6)).to_string(),
        "invalid option `rtol` = 0: allowed (0, inf)"
    );
    assert_eq!(
        err(Options::fixed(0.0, 1.0, f64::NAN)).to_string(),
        "invalid option `dt` = NaN: allowed (0, inf)"
    );
    assert_eq!(
        err(Options::fixed(0.0, 1.0, -0.1)).to_string(),
        "invalid option `dt` = -0.1: allowed (0, inf)"
    );
    // Too many steps, with the solution so far kept.
    let mut o = Options::adaptive(0.0, 100.0, 1e-10, 1e-10);
    o.max_steps = 10;
    let f = Integrator::new(&p, dopri5(&o, 2), &[1.0, 0.0], &[Mode(0)], o)
        .unwrap()
        .solve()
        .unwrap_err();
    assert!(
        matches!(f.error, SolverError::TooManySteps { max: 10, .. }),
        "{f}"
    );
    assert_eq!(f.solution.len(), 1 + 10);
    // Blow-up of y' = y² at t = 1: the step size underflows just before it.
    let o = Options::adaptive(0.0, 2.0, 1e-8, 1e-8);
    let f = Integrator::new(&BlowUp, dopri5(&o, 1), &[1.0], &[Mode(0)], o)
        .unwrap()
        .solve()
        .unwrap_err();
    let t = match f.error {
        SolverError::StepSizeUnderflow { t, .. } | SolverError::NonFinite { t, .. } => t,
        ref e => panic!("{e}"),
    };
    assert!((t - 1.0).abs() < 1e-3, "failed at t = {t}: {f}");
    assert!(f.solution.len() > 10);
}

#[test]
fn an_even_grid_ends_at_t_end_and_every_point_is_recorded() {
    // 319 periods of ω = 100/6: computed as t_end·i/(n − 1), the last of 2001 points lands
    // one rounding above t_end, and a run that stops at t_end never recorded it (the
    // hysteresis protocol then read its integrals at the wrong time).
    let t_end = 319.0 * 2.0 * std::f64::consts::PI / (100.0 / 6.0);
    let n = 2001;
    assert!(
        t_end * (n - 1) as f64 / (n - 1) as f64 > t_end,
        "the case still shows it"
    );
    let grid = integrators::even_grid(0.0, t_end, n);
    assert_eq!((grid[0], grid[n - 1], grid.len()), (0.0, t_end, n));
    let mut o = Options::adaptive(0.0, t_end, 1e-8, 1e-10);
    o.output = Output::Grid(grid.clone());
    let s = run(&Oscillator::plain(), dopri5(&o, 2), &[1.0, 0.0], o);
    assert_eq!(s.t, grid);
}

/// y' = 1 from y = 0 with an event at y = 1 whose action sets y to 5: with RK4's steps of
/// 1/4 the event lands on t = 1 exactly, a point of the output grid.
struct JumpAtOne;

impl OdeProblem for JumpAtOne {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&self, _t: f64, _y: &[f64], _m: &[Mode], f: &mut [f64]) {
        f[0] = 1.0;
    }
    fn n_events(&self) -> usize {
        1
    }
    fn event_spec(&self, _i: usize, _m: &[Mode]) -> Option<integrators::EventSpec> {
        Some(integrators::EventSpec {
            name: "jump",
            crossing: Crossing::Rising,
        })
    }
    fn event(&self, _i: usize, _t: f64, y: &[f64], _m: &[Mode]) -> f64 {
        y[0] - 1.0
    }
    fn on_events(&self, _i: &[usize], _t: f64, y: &mut [f64], _m: &mut [Mode]) -> Control {
        y[0] = 5.0;
        Control::Continue
    }
}

#[test]
fn a_grid_point_at_an_event_holds_the_state_after_it_once() {
    // An event on the last grid point: a grid-only run (a system's) never recorded t_end and
    // ended one point short, status ok. Where events are recorded, a grid point at an event
    // was written twice.
    let grid_run = |t_end: f64, output: fn(Vec<f64>) -> Output| {
        let mut o = Options::adaptive(0.0, t_end, 1e-8, 1e-10);
        o.step = StepControl::Fixed { h: 0.25 };
        o.output = output(integrators::even_grid(
            0.0,
            t_end,
            (2.0 * t_end) as usize + 1,
        ));
        run(&JumpAtOne, Box::new(Rk4::new(0.25, 1)), &[0.0], o)
    };
    for output in [Output::GridOnly as fn(Vec<f64>) -> Output, Output::Grid] {
        let s = grid_run(1.0, output);
        assert_eq!(s.t, [0.0, 0.5, 1.0]);
        assert_eq!(s.y, [0.0, 0.5, 5.0]);
        assert_eq!(s.events.len(), 1);
        let s = grid_run(2.0, output);
        assert_eq!(s.t, [0.0, 0.5, 1.0, 1.5, 2.0]);
        assert_eq!(s.y, [0.0, 0.5, 5.0, 5.5, 6.0]);
    }
}
