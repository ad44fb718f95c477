//! The solver studies: convergence order, step-size independence, work–precision, the
//! explicit/implicit crossover and cost against size. Every study is a list of independent
//! runs evaluated on rayon's pool and collected in order, so its results do not depend on the
//! thread count. This module holds what the studies share (the methods, a run against the
//! reference and its errors); each study is in a file of its own.

mod convergence;
mod independence;
mod scaling;
mod stiffness;
mod work_precision;

use crate::batch;
pub use crate::batch::reference;
pub use crate::cases::{Case, Measured, Measures, StudyCase, SystemCase, GRID_POINTS};
use crate::run::{ScenarioError, SwitchingKind};
pub use convergence::{convergence, observed_order, orders, Convergence, OrderTable, PairOrder};
pub use independence::{independence, FailedLevel, Independence, OutputCheck};
use integrators::{Solver, Stats, StepControl};
pub use scaling::{scaling, Scaling, ScalingRun};
use serde::Serialize;
pub use stiffness::{crossover, stiffness, Cost, Stiffness, StiffnessPoint, Sweep};
pub use work_precision::{work_precision, WorkPrecision};

/// How a study integrates its case: a solver under the case's own treatment of v = 0, or a
/// peer under another one (regularised BDF, or Moreau–Jean time-stepping, beside event-driven
/// solvers: one system, several schemes, as Siconos runs one declared system event-driven or
/// time-stepped).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Method {
    /// The solver (not used under time-stepping).
    pub solver: Solver,
    /// The treatment of v = 0; `None` for the case's own.
    pub switching: Option<SwitchingKind>,
}

impl Method {
    /// `solver` under the case's own treatment.
    pub fn of(solver: Solver) -> Method {
        Method {
            solver,
            switching: None,
        }
    }

    /// The solvers of `methods` that run under the case's own treatment of v = 0: those its
    /// reference must be independent of (a peer's or time-stepping's placeholder solver is
    /// not one).
    pub fn own_solvers(methods: &[Method]) -> Vec<Solver> {
        methods
            .iter()
            .filter(|m| m.switching.is_none())
            .map(|m| m.solver)
            .collect()
    }

    /// The methods a study of `solvers` runs on `case`: each solver under the case's own
    /// treatment of v = 0, or, for a time-stepped case, the one scheme that treatment is
    /// (Moreau–Jean takes no solver: every solver would name the same runs), labelled
    /// `moreau-jean (timestepping)` and stepped over the study's step sizes.
    pub fn studied(case: &dyn StudyCase, solvers: &[Solver]) -> Vec<Method> {
        match case.switching() {
            s @ SwitchingKind::TimeStepping { .. } => vec![Method {
                solver: Solver::Rk4,
                switching: Some(s),
            }],
            _ => solvers.iter().map(|&s| Method::of(s)).collect(),
        }
    }

    /// The name tables and legends give it: the solver's (`dopri5`), or a peer's with its
    /// treatment (`bdf (regularized)`, `moreau-jean (timestepping)`).
    pub fn label(&self) -> String {
        match self.switching {
            None => self.solver.name().to_string(),
            Some(s) => format!("{} ({})", s.method(self.solver), s.name()),
        }
    }

    /// Whether it takes the study's step sizes rather than its tolerances.
    pub fn is_fixed_step(&self) -> bool {
        self.solver.is_fixed_step() || self.switching.is_some_and(|s| s.is_time_stepping())
    }

    /// The order at which its error can fall with its resolution: the formal order in the
    /// step size of a method with fixed steps (Moreau–Jean's: 2 at θ = 1/2, else 1), and 1 in
    /// the tolerance of an adaptive one (tolerance proportionality, the aim of its error
    /// control).
    pub fn order_bound(&self) -> f64 {
        match self.switching {
            Some(SwitchingKind::TimeStepping { theta: 0.5 }) => 2.0,
            Some(SwitchingKind::TimeStepping { .. }) => 1.0,
            _ if self.is_fixed_step() => self.solver.order() as f64,
            _ => 1.0,
        }
    }

    /// Whether it solves an implicit problem per step (time-stepping does).
    pub fn is_implicit(&self) -> bool {
        self.solver.is_implicit() || self.switching.is_some_and(|s| s.is_time_stepping())
    }

    /// One run of `case` by this method with `step`.
    pub fn measure(
        &self,
        case: &dyn StudyCase,
        step: StepControl,
    ) -> Result<Measured, ScenarioError> {
        match self.switching {
            None => case.measure(self.solver, step),
            Some(s) => case.with_switching(s).measure(self.solver, step),
        }
    }

    /// The steps or tolerances a study runs it at (see [`steps_for`]).
    pub fn steps(&self, step_sizes: &[f64], tolerances: &[f64], fixed: bool) -> Vec<StepControl> {
        if self.switching.is_some_and(|s| s.is_time_stepping()) {
            step_sizes
                .iter()
                .map(|&h| StepControl::Fixed { h })
                .collect()
        } else {
            steps_for(self.solver, step_sizes, tolerances, fixed)
        }
    }

    /// Every (method, step) of a study of `methods`.
    pub fn jobs(
        methods: &[Method],
        step_sizes: &[f64],
        tolerances: &[f64],
        fixed: bool,
    ) -> Vec<(Method, StepControl)> {
        methods
            .iter()
            .flat_map(|&m| {
                m.steps(step_sizes, tolerances, fixed)
                    .into_iter()
                    .map(move |c| (m, c))
            })
            .collect()
    }
}

/// Errors of a run against the reference.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Errors {
    /// max |Δx|, |Δv| over every body at the end.
    pub final_state: f64,
    /// max |Δx|, |Δv| of the measured bodies over the common grid.
    pub grid_max: f64,
    /// max |Δt| over the events (NaN when the numbers of events differ).
    pub event_times: f64,
    /// max |Δ| over the stick durations (NaN when their numbers differ).
    pub stick_durations: f64,
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    if a.len() != b.len() {
        return f64::NAN;
    }
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

impl Errors {
    /// Not measured (yet): every error NaN.
    pub const UNMEASURED: Errors = Errors {
        final_state: f64::NAN,
        grid_max: f64::NAN,
        event_times: f64::NAN,
        stick_durations: f64::NAN,
    };

    /// The errors of `m` against `reference`.
    pub fn between(m: &Measures, reference: &Measures) -> Errors {
        let grid_max = if m.grid.len() == reference.grid.len() {
            m.grid
                .iter()
                .zip(&reference.grid)
                .map(|(a, b)| max_diff(a, b))
                .fold(0.0, f64::max)
        } else {
            f64::NAN
        };
        Errors {
            final_state: max_diff(&m.final_state, &reference.final_state),
            grid_max,
            event_times: max_diff(&m.event_times, &reference.event_times),
            stick_durations: max_diff(&m.stick_durations, &reference.stick_durations),
        }
    }
}

/// Where the reference comes from.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Reference {
    /// An exact solution, by name.
    ClosedForm(String),
    /// A much tighter run of a solver.
    Run {
        /// The solver.
        solver: &'static str,
        /// Its step control.
        step: StepControl,
        /// A second tight run by an independent solver, where the first one is also studied:
        /// the solver, and the largest difference of the two on the time grid (a bound on the
        /// reference's own error).
        cross_check: Option<(&'static str, f64)>,
    },
}

/// The tolerance of a reference run, rtol = atol.
pub const REFERENCE_TOLERANCE: f64 = 1e-13;

/// The resolution of a run: its step size (fixed steps, s) or its tolerance (adaptive: rtol,
/// equal to atol in the studies).
pub fn resolution(step: StepControl) -> f64 {
    match step {
        StepControl::Fixed { h } => h,
        StepControl::Adaptive { rtol, .. } => rtol,
    }
}

/// Which a resolution is: `fixed` (a step size) or `adaptive` (a tolerance).
pub fn step_kind(step: StepControl) -> &'static str {
    match step {
        StepControl::Fixed { .. } => "fixed",
        StepControl::Adaptive { .. } => "adaptive",
    }
}

/// One run of a study.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StudyRun {
    /// The method's label ([`Method::label`]): the solver, or a peer with its treatment.
    pub solver: String,
    /// The step size (fixed-step runs) or the tolerance (adaptive runs).
    pub resolution: f64,
    /// Which the resolution is: `fixed` (a step size, s) or `adaptive` (rtol = atol).
    pub step: &'static str,
    /// Errors against the reference.
    pub errors: Errors,
    /// The run's measures.
    #[serde(skip)]
    pub measures: Measures,
    /// Work done.
    pub stats: Stats,
    /// Work in right-hand-side evaluations ([`Stats::work`] at the problem's dimension).
    pub work: usize,
    /// The solver's error, if it failed.
    pub failure: Option<String>,
    /// Whether it failed as an explicit method with a fixed step past its stability limit
    /// ([`crate::run::diverged`]).
    #[serde(skip)]
    pub diverged: bool,
    /// Wall time of the run, s: the median over it and its timing repeats (not
    /// deterministic: kept out of the study's main files).
    #[serde(skip)]
    pub wall_time_s: f64,
}

/// Runs `case` with each (method, step) against its reference for a study of `studied`
/// solvers, the reference runs and the runs in one list ([`batch`]).
pub fn run_against_reference(
    case: &dyn StudyCase,
    studied: &[Solver],
    jobs: &[(Method, StepControl)],
    progress: &(dyn Fn() + Sync),
) -> Result<(Reference, Measures, Vec<StudyRun>), ScenarioError> {
    let c = batch::run_cases(&[case], Some(studied), jobs, 0, progress)?.remove(0);
    let (reference, measures) = c.reference.expect("a reference was asked for");
    Ok((reference, measures, c.runs))
}

/// The steps or tolerances a study runs a solver at: a fixed-step method (RK4) always takes
/// the step sizes; with `fixed`, so does every method that can (Dormand–Prince, implicit Euler,
/// for observed orders); otherwise they and diffsol's methods take the tolerances.
pub fn steps_for(
    solver: Solver,
    step_sizes: &[f64],
    tolerances: &[f64],
    fixed: bool,
) -> Vec<StepControl> {
    let steps = solver.is_fixed_step() || (fixed && solver.takes_fixed_steps());
    match steps {
        true => step_sizes
            .iter()
            .map(|&h| StepControl::Fixed { h })
            .collect(),
        false => tolerances
            .iter()
            .map(|&tol| StepControl::Adaptive {
                rtol: tol,
                atol: tol,
                h0: None,
            })
            .collect(),
    }
}

/// The least-squares slope of `points` (NaN for fewer than two).
pub fn slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    if points.len() < 2 {
        return f64::NAN;
    }
    let (mx, my) = (
        points.iter().map(|p| p.0).sum::<f64>() / n,
        points.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    sxy / sxx
}
