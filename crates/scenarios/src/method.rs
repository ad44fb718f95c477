//! How a study integrates its case: a [`Method`] (a scheme, studied or drawn beside the
//! studied ones as a peer), and the steps or tolerances it runs at.

use friction_systems::{Scheme, Switching};
use integrators::{Solver, StepControl};
use serde::Serialize;

/// How a study integrates its case: a scheme (a solver under a treatment of v = 0, or
/// Moreau–Jean time-stepping), either one of those studied or a peer drawn beside them (the
/// regularised BDF or time-stepping beside event-driven solvers: one system, several schemes,
/// as Siconos runs one declared system event-driven or time-stepped).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Method {
    /// The scheme.
    pub scheme: Scheme,
    /// Whether it is a peer: drawn beside the studied methods, not studied.
    pub peer: bool,
}

impl Method {
    /// `scheme`, studied.
    pub fn of(scheme: Scheme) -> Method {
        Method {
            scheme,
            peer: false,
        }
    }

    /// `solver` event-driven with event location at v = 0 ([`Scheme::events`]), studied.
    pub fn events(solver: Solver) -> Method {
        Method::of(Scheme::events(solver))
    }

    /// `scheme`, as a peer of the studied methods.
    pub fn peer(scheme: Scheme) -> Method {
        Method { scheme, peer: true }
    }

    /// Each of `schemes`, studied.
    pub fn studied(schemes: &[Scheme]) -> Vec<Method> {
        schemes.iter().map(|&s| Method::of(s)).collect()
    }

    /// The solvers of the studied methods of `methods`: those a reference must be
    /// independent of (time-stepping and the peers have none).
    pub fn own_solvers(methods: &[Method]) -> Vec<Solver> {
        (methods.iter())
            .filter(|m| !m.peer)
            .filter_map(|m| m.scheme.solver())
            .collect()
    }

    /// The first studied method of `methods`: the one whose treatment of v = 0 a study
    /// names and computes its reference under.
    pub fn first_studied(methods: &[Method]) -> Option<Method> {
        methods.iter().find(|m| !m.peer).copied()
    }

    /// The treatment of v = 0 of the studied methods of `methods` (of the first; event
    /// location when none is studied), time-stepping's modes being event switching's.
    pub fn studied_switching(methods: &[Method]) -> Switching {
        Method::first_studied(methods).map_or(Switching::Event, |m| m.scheme.switching())
    }

    /// The name of the treatment of v = 0 of the studied methods of `methods` (of the
    /// first; `event` when none is studied): `event`, `regularized`, `naive` or
    /// `timestepping`.
    pub fn treatment_name(methods: &[Method]) -> &'static str {
        Method::first_studied(methods).map_or("event", |m| m.scheme.treatment_name())
    }

    /// Whether it reads the regularisation width ε: under regularised switching.
    pub fn reads_epsilon(&self) -> bool {
        matches!(self.scheme.parameter(), Some(("epsilon", _)))
    }

    /// The same method with the regularisation width `epsilon` (m/s), if it reads one
    /// ([`Method::reads_epsilon`]); unchanged otherwise.
    pub fn regularised_at(self, epsilon: f64) -> Method {
        match self.scheme {
            Scheme::EventDriven {
                solver,
                switching: Switching::Regularized { .. },
            } => Method {
                scheme: Scheme::EventDriven {
                    solver,
                    switching: Switching::Regularized { epsilon },
                },
                ..self
            },
            _ => self,
        }
    }

    /// The name tables and legends give it: a studied solver's (`dopri5`), or the method's
    /// with its treatment (`bdf (regularized)`, `moreau-jean (timestepping)`).
    pub fn label(&self) -> String {
        match (self.peer, self.scheme) {
            (false, Scheme::EventDriven { solver, .. }) => solver.name().to_string(),
            (_, s) => format!("{} ({})", s.method_name(), s.treatment_name()),
        }
    }

    /// Whether it takes the study's step sizes rather than its tolerances.
    pub fn is_fixed_step(&self) -> bool {
        self.scheme.solver().is_none_or(|s| s.is_fixed_step())
    }

    /// The order at which its error can fall with its resolution: the formal order in the
    /// step size of a method with fixed steps (Moreau–Jean's: 2 at θ = 1/2, else 1), and 1 in
    /// the tolerance of an adaptive one (tolerance proportionality, the aim of its error
    /// control).
    pub fn order_bound(&self) -> f64 {
        match self.scheme {
            Scheme::TimeStepping { theta: 0.5 } => 2.0,
            Scheme::TimeStepping { .. } => 1.0,
            Scheme::EventDriven { solver, .. } if solver.is_fixed_step() => solver.order() as f64,
            Scheme::EventDriven { .. } => 1.0,
        }
    }

    /// The order that orders the expected cost of its runs: its solver's, 1 for
    /// time-stepping.
    pub fn order(&self) -> usize {
        self.scheme.solver().map_or(1, |s| s.order())
    }

    /// Whether it solves an implicit problem per step (time-stepping does).
    pub fn is_implicit(&self) -> bool {
        self.scheme.solver().is_none_or(|s| s.is_implicit())
    }

    /// The steps or tolerances a study runs it at (see [`steps_for`]); time-stepping takes
    /// the step sizes.
    pub fn steps(&self, step_sizes: &[f64], tolerances: &[f64], fixed: bool) -> Vec<StepControl> {
        match self.scheme.solver() {
            Some(solver) => steps_for(solver, step_sizes, tolerances, fixed),
            None => step_sizes
                .iter()
                .map(|&h| StepControl::Fixed { h })
                .collect(),
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
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize)]
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
