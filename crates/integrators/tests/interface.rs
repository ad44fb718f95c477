//! The shared interface: solvers by name, simultaneous events, and the errors that remain.

mod common;

use common::*;
use integrators::{
    Control, Crossing, EventSpec, Mode, OdeProblem, Options, Solver, SolverError, StepControl,
};

#[test]
fn every_solver_is_found_by_name_and_integrates_the_oscillator() {
    for solver in Solver::ALL {
        assert_eq!(Solver::from_name(solver.name()), Ok(solver));
        let options = if solver.is_fixed_step() {
            Options::fixed(0.0, 1.0, 1e-3)
        } else {
            Options::adaptive(0.0, 1.0, 1e-9, 1e-9)
        };
        let s = solver
            .solve(&Oscillator::plain(), &[1.0, 0.0], &[Mode(0)], options)
            .unwrap();
        let x = s.last().unwrap().1[0];
        // Implicit Euler is first order: its error at tol 1e-9 is about sqrt(tol).
        let tolerance = if solver == Solver::IMPLICIT_EULER {
            1e-3
        } else {
            1e-6
        };
        assert!((x - 1f64.cos()).abs() < tolerance, "{}: {x}", solver.name());
        assert_eq!(s.solver, solver.name());
    }
    assert_eq!(
        Solver::from_name("euler").unwrap_err(),
        "unknown solver `euler`; known solvers: rk4, dopri5, implicit-euler, bdf, tr-bdf2, esdirk34, tsit45, radau5, rodas, auto"
    );
}

#[test]
fn rk4_asks_for_a_fixed_step() {
    let f = Solver::RK4
        .solve(
            &Oscillator::plain(),
            &[1.0, 0.0],
            &[Mode(0)],
            Options::adaptive(0.0, 1.0, 1e-6, 1e-6),
        )
        .unwrap_err();
    assert_eq!(
        f.error.to_string(),
        "rk4 cannot integrate this problem: RK4 has no error estimate: give a fixed step h (dt)"
    );
}

/// x = cos t watched twice: both event functions vanish at π/2.
struct TwoWatchers;

impl OdeProblem for TwoWatchers {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], _m: &[Mode], f: &mut [f64]) {
        f[0] = y[1];
        f[1] = -y[0];
    }
    fn n_events(&self) -> usize {
        2
    }
    fn event_spec(&self, i: usize, _m: &[Mode]) -> Option<EventSpec> {
        Some(EventSpec {
            name: ["second", "first"][i],
            crossing: Crossing::Falling,
        })
    }
    fn event(&self, i: usize, _t: f64, y: &[f64], _m: &[Mode]) -> f64 {
        // The same root, seen through differently scaled functions.
        if i == 0 {
            y[0]
        } else {
            3.0 * y[0]
        }
    }
    fn on_events(&self, fired: &[usize], _t: f64, y: &mut [f64], _m: &mut [Mode]) -> Control {
        for &i in fired {
            y[1] *= 1.0 + i as f64; // index 0 multiplies v by 1, index 1 by 2
        }
        Control::Stop
    }
}

#[test]
fn simultaneous_events_are_handled_in_one_call() {
    let s = Solver::DOPRI5
        .solve(
            &TwoWatchers,
            &[1.0, 0.0],
            &[Mode(0)],
            Options::adaptive(0.0, 3.0, 1e-12, 1e-12),
        )
        .unwrap();
    // Both roots at the same instant: one event, both functions handed over at once.
    assert_eq!(s.events.len(), 1);
    assert_eq!(s.events[0].names, ["second", "first"]);
    assert_eq!(s.events[0].fired, [0, 1]);
    assert_eq!(s.stats.events, 2);
    // v = −1 at x = 0 (t = π/2), multiplied by 1 and by 2.
    let (_, y) = s.last().unwrap();
    assert!((y[1] + 2.0).abs() < 1e-10, "{}", y[1]);
}

#[test]
fn a_non_finite_state_and_a_step_size_underflow_are_reported() {
    // RK4 with h = 0.5 on y' = y² overflows to infinity: the step from t = 1.5 ends at a
    // finite y whose square is not.
    let f = Solver::RK4
        .solve(&BlowUp, &[1.0], &[Mode(0)], Options::fixed(0.0, 5.0, 0.5))
        .unwrap_err();
    let message = f.error.to_string();
    assert!(
        message.starts_with("non-finite state at t = 1.5 "),
        "{message}"
    );
    assert!(
        message.contains("RK4 f at the step's end, component 0 = inf"),
        "{message}"
    );
    assert!(!f.solution.is_empty());
    // Dormand–Prince approaches the singularity at t = 1 with ever smaller steps.
    let mut o = Options::adaptive(0.0, 2.0, 1e-6, 1e-6);
    o.step = StepControl::Adaptive {
        rtol: 1e-6,
        atol: 1e-6,
        h0: None,
    };
    let f = Solver::DOPRI5
        .solve(&BlowUp, &[1.0], &[Mode(0)], o)
        .unwrap_err();
    match f.error {
        SolverError::StepSizeUnderflow { t, h } => {
            // dopri5.f's test: 0.1·|h| <= UROUND·|t|, UROUND = 2.3e-16.
            assert!((t - 1.0).abs() < 1e-5, "t = {t}");
            assert!(0.1 * h <= 2.3e-16 * t, "h = {h}");
            assert!(
                f.error
                    .to_string()
                    .starts_with("step size underflow at t = 1.00000"),
                "{}",
                f.error
            );
        }
        ref e => panic!("expected an underflow, got: {e}"),
    }
}

/// A user's method that is RK4 under another name, or that refuses adaptive steps.
#[derive(Debug)]
struct Renamed;

impl integrators::OneStepMethod for Renamed {
    fn name(&self) -> &'static str {
        "my-rk4"
    }
    fn order(&self) -> usize {
        4
    }
    fn is_implicit(&self) -> bool {
        false
    }
    fn is_fixed_step(&self) -> bool {
        true
    }
    fn stepper(
        &self,
        options: &Options,
        dim: usize,
    ) -> Result<Box<dyn integrators::Stepper>, SolverError> {
        match options.step {
            StepControl::Fixed { h } => Ok(Box::new(integrators::Rk4::new(h, dim))),
            StepControl::Adaptive { .. } => Err(SolverError::Unsupported {
                solver: "my-rk4",
                why: "fixed steps only".into(),
            }),
        }
    }
}

static RENAMED: Renamed = Renamed;

#[test]
fn an_own_method_is_driven_like_a_built_in_one() {
    let own = Solver::own(&RENAMED);
    assert_eq!(own.name(), "my-rk4");
    assert_eq!((own.order(), own.is_implicit()), (4, false));
    assert!(own.is_fixed_step() && own.takes_fixed_steps());
    assert_eq!(own, Solver::own(&RENAMED));
    assert_ne!(own, Solver::RK4);
    // The same steps, events and dense output as the built-in RK4 it wraps, bit for bit.
    let problem = Oscillator::watching(Crossing::Either, Control::Continue);
    let run = |solver: Solver| {
        solver
            .solve(
                &problem,
                &[1.0, 0.0],
                &[Mode(0)],
                Options::fixed(0.0, 5.0, 0.01),
            )
            .unwrap()
    };
    let (mine, theirs) = (run(own), run(Solver::RK4));
    assert_eq!(mine.solver, "my-rk4");
    assert_eq!(
        (mine.t.clone(), mine.stats),
        (theirs.t.clone(), theirs.stats)
    );
    let t_events: Vec<f64> = mine.events.iter().map(|e| e.t).collect();
    assert_eq!(t_events.len(), 2);
    for (t, exact) in t_events.iter().zip([0.5, 1.5]) {
        assert!((t - exact * std::f64::consts::PI).abs() < 1e-8, "{t}");
    }
    // What the method refuses comes back as its error, with an empty solution.
    let refused = own
        .solve(
            &problem,
            &[1.0, 0.0],
            &[Mode(0)],
            Options::adaptive(0.0, 1.0, 1e-6, 1e-6),
        )
        .unwrap_err();
    assert!(
        matches!(
            refused.error,
            SolverError::Unsupported {
                solver: "my-rk4",
                ..
            }
        ),
        "{:?}",
        refused.error
    );
    assert_eq!(refused.solution.solver, "my-rk4");
    assert!(refused.solution.t.is_empty());
}

/// y' = 1, except that evaluation number `nan_at` (counted from 1) returns NaN.
struct NanAt {
    nan_at: usize,
    calls: std::sync::atomic::AtomicUsize,
}

impl OdeProblem for NanAt {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&self, _t: f64, _y: &[f64], _m: &[Mode], f: &mut [f64]) {
        let call = 1 + self
            .calls
            .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        f[0] = if call == self.nan_at { f64::NAN } else { 1.0 };
    }
}

#[test]
fn a_finite_step_end_whose_derivative_is_not_is_refused_where_it_is_made() {
    // Evaluation 1 is f at the start. Dormand–Prince's first step makes evaluations 2 to 7,
    // the seventh f at its end (FSAL); RK4's makes 2 to 4 and then f at its end, the fifth.
    // The end value y1 = 0.5 uses neither, so it is finite, but the dense output (read by the
    // event location) and the next step would read the NaN.
    for (solver, nan_at, what) in [
        (Solver::DOPRI5, 7, "Dormand-Prince f at the step's end"),
        (Solver::RK4, 5, "RK4 f at the step's end"),
    ] {
        let problem = NanAt {
            nan_at,
            calls: 0.into(),
        };
        let f = solver
            .solve(&problem, &[0.0], &[Mode(0)], Options::fixed(0.0, 5.0, 0.5))
            .unwrap_err();
        let message = f.error.to_string();
        assert!(
            message.contains(&format!("{what}, component 0 = NaN")),
            "{message}"
        );
        // The run keeps its start and no step.
        assert_eq!(f.solution.t, [0.0], "{solver:?}");
        assert_eq!(f.solution.stats.steps, 0, "{solver:?}");
    }
}
