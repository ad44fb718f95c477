//! How a study integrates its case: a [`Method`] (a solver under the case's treatment of
//! v = 0, or a peer under another), and the steps or tolerances it runs at.

use crate::run::SwitchingKind;
use integrators::{Solver, StepControl};
use serde::Serialize;

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

    /// The methods a study of `solvers` runs on a case whose treatment of v = 0 is
    /// `switching`: each solver under that treatment, or, for a time-stepped case, the one scheme that treatment is
    /// (Moreau–Jean takes no solver: every solver would name the same runs), labelled
    /// `moreau-jean (timestepping)` and stepped over the study's step sizes.
    pub fn studied(switching: SwitchingKind, solvers: &[Solver]) -> Vec<Method> {
        match switching {
            s @ SwitchingKind::TimeStepping { .. } => vec![Method {
                solver: Solver::RK4,
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

/// The resolution of a run: its step size (fixed steps, s) or its tolerance (adaptive: rtol,
/// equal to atol in the studies).
pub fn resolution(step: StepControl) -> f64 {
    match step {
        StepControl::Fixed { h } => h,
        StepControl::Adaptive { rtol, .. } => rtol,
    }
}

/// Which a resolution is: a step size (fixed steps, s) or a tolerance (adaptive steps,
/// rtol = atol); written `fixed` and `adaptive`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum StepKind {
    /// A step size.
    Fixed,
    /// A tolerance.
    Adaptive,
}

impl StepKind {
    /// The kind of `step`.
    pub fn of(step: StepControl) -> StepKind {
        match step {
            StepControl::Fixed { .. } => StepKind::Fixed,
            StepControl::Adaptive { .. } => StepKind::Adaptive,
        }
    }

    /// Its name, as tables write it.
    pub fn name(self) -> &'static str {
        match self {
            StepKind::Fixed => "fixed",
            StepKind::Adaptive => "adaptive",
        }
    }
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
