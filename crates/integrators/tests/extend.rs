//! A run continued to a later end ([`Integrator::extend`]) is the run from the start to that
//! end, bit for bit, and one that cannot be continued so says `false`.

mod common;

use common::Oscillator;
use integrators::testset::VanDerPol;
use integrators::{
    even_grid, Control, Crossing, Integrator, Mode, OdeProblem, Options, Output, Solution, Solver,
    StepControl,
};

/// The options of a run to `t_end` at `tol` recording `points` evenly spaced points a unit
/// of time.
fn options(t_end: f64, tol: f64, points: usize) -> Options {
    Options {
        output: Output::Grid(even_grid(0.0, t_end, (points as f64 * t_end) as usize + 1)),
        ..Options::adaptive(0.0, t_end, tol, tol)
    }
}

fn integrator<'a>(
    solver: Solver,
    problem: &'a dyn OdeProblem,
    y0: &[f64],
    options: Options,
) -> Integrator<'a> {
    let stepper = solver.method().stepper(&options, problem.dim()).unwrap();
    Integrator::new(problem, stepper, y0, &[], options)
        .unwrap()
        .resumable()
}

/// `problem` run to `ends[0]` and extended to each later end, against the run from the start
/// to the last end: whether every extension was made, and the two solutions.
fn extended(
    solver: Solver,
    problem: &dyn OdeProblem,
    y0: &[f64],
    ends: &[f64],
    tol: f64,
) -> (bool, Solution, Solution) {
    let mut run = integrator(solver, problem, y0, options(ends[0], tol, 4));
    run.advance(&mut |_| {}).unwrap();
    let mut all = true;
    for &t_end in &ends[1..] {
        all &= run.extend(options(t_end, tol, 4));
        run.advance(&mut |_| {}).unwrap();
    }
    let last = *ends.last().unwrap();
    let fresh = integrator(solver, problem, y0, options(last, tol, 4));
    (all, run.solve().unwrap(), fresh.solve().unwrap())
}

fn assert_same(a: &Solution, b: &Solution) {
    assert_eq!(a.t, b.t);
    assert_eq!(a.y, b.y);
    assert_eq!(a.stats, b.stats);
    let times = |s: &Solution| s.events.iter().map(|e| e.t).collect::<Vec<_>>();
    assert_eq!(times(a), times(b));
}

#[test]
fn an_oscillator_watched_at_x_zero_extended_twice_is_the_run_to_the_last_end() {
    let problem = Oscillator::watching(Crossing::Either, Control::Continue);
    for solver in [Solver::DOPRI5, Solver::RADAU5, Solver::AUTO] {
        let (all, extended, fresh) =
            extended(solver, &problem, &[1.0, 0.0], &[6.25, 12.5, 25.0], 1e-8);
        assert!(all, "{solver}: an extension was refused");
        // x = cos t crosses zero at (k + 1/2)π: eight times by t = 25.
        assert_eq!(fresh.events.len(), 8, "{solver}");
        assert_eq!(fresh.t.last(), Some(&25.0));
        assert_same(&extended, &fresh);
    }
}

#[test]
fn auto_on_van_der_pol_switched_to_radau_and_extended_is_the_run_to_the_last_end() {
    let (all, extended, fresh) = extended(
        Solver::AUTO,
        &VanDerPol,
        &[2.0, 0.0],
        &[0.5, 1.0, 2.0],
        1e-6,
    );
    assert!(all, "an extension was refused");
    // Radau IIA takes the run over at the first layer.
    assert_eq!(
        fresh.method_switches.len(),
        1,
        "{:?}",
        fresh.method_switches
    );
    assert_same(&extended, &fresh);
}

/// `y' = 1`: Dormand–Prince is exact on it, and its steps grow until the largest step bounds
/// them.
struct Drift;

impl OdeProblem for Drift {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&self, _t: f64, _y: &[f64], _m: &[Mode], f: &mut [f64]) {
        f[0] = 1.0;
    }
}

#[test]
fn a_run_whose_steps_the_old_span_bounded_is_not_extended() {
    let start = |t_end| Options {
        step: StepControl::Adaptive {
            rtol: 1e-8,
            atol: 1e-8,
            h0: Some(0.3),
        },
        ..options(t_end, 1e-8, 1)
    };
    let mut run = integrator(Solver::DOPRI5, &Drift, &[0.0], start(10.0));
    run.advance(&mut |_| {}).unwrap();
    // Steps of 0.3 and 3, then 30 bounded by the largest step, the span 10: a run to 20
    // steps otherwise.
    assert_eq!(run.solution().stats.steps, 3);
    assert!(!run.extend(start(20.0)));
}

#[test]
fn other_tolerances_an_earlier_end_or_a_run_not_at_its_end_are_not_extended() {
    let problem = Oscillator::watching(Crossing::Either, Control::Continue);
    let mut run = integrator(
        Solver::DOPRI5,
        &problem,
        &[1.0, 0.0],
        options(5.0, 1e-8, 10),
    );
    assert!(!run.extend(options(10.0, 1e-8, 10)), "not at its end");
    run.advance(&mut |_| {}).unwrap();
    assert!(!run.extend(options(10.0, 1e-6, 10)), "other tolerances");
    assert!(!run.extend(options(4.0, 1e-8, 10)), "an earlier end");
    assert!(!run.extend(options(10.0, 1e-8, 20)), "another grid");
    assert!(run.extend(options(10.0, 1e-8, 10)));
}

#[test]
fn a_method_that_cannot_be_copied_is_not_extended() {
    let problem = Oscillator::plain();
    let options = |t_end| Options {
        output: Output::Steps,
        ..Options::fixed(0.0, t_end, 0.1)
    };
    let mut run = integrator(Solver::RK4, &problem, &[1.0, 0.0], options(5.0));
    run.advance(&mut |_| {}).unwrap();
    assert!(!run.extend(options(10.0)));
}
