//! The [`OneStepMethod`] trait: what every method, built-in or a user's own, says of itself
//! and how it is run. `solve_observed` is provided on top of [`OneStepMethod::stepper`] (the
//! [`Integrator`] drives the stepper); a method with a driver of its own (diffsol's) provides
//! `solve_observed` instead.

use crate::error::SolverError;
use crate::integrator::Integrator;
use crate::options::{Options, StepControl};
use crate::problem::{Mode, OdeProblem};
use crate::solution::{Failure, Solution};
use crate::stepper::Stepper;

/// A one-step method, run and studied through [`crate::Solver`]: it names itself, says its
/// order and how it takes its steps, and makes a [`Stepper`] that the [`Integrator`] drives
/// (event location on its dense output, mode switching, output grid, step cap and wall-clock
/// limit included). The built-in methods implement it, and so does a method written in a
/// user's own crate (see `examples/own_solver.rs`), which [`crate::Solver::own`] then takes
/// wherever a built-in method goes: `simulate`, the rigs and every study.
pub trait OneStepMethod: std::fmt::Debug + Send + Sync {
    /// The method's name in solutions, files and tables; unique among the methods of a study.
    fn name(&self) -> &'static str;

    /// The order p of the method: its global error ∝ h^p (the studies order their runs by
    /// the expected number of steps, T·tol^(−1/(p+1)) at a tolerance).
    fn order(&self) -> usize;

    /// Whether a step solves a nonlinear system (the studies report explicit and implicit
    /// methods apart).
    fn is_implicit(&self) -> bool;

    /// Whether the method takes only fixed steps (`--dt`), as RK4.
    fn is_fixed_step(&self) -> bool;

    /// Whether the method also takes fixed steps when a study asks for observed orders.
    fn takes_fixed_steps(&self) -> bool {
        self.is_fixed_step()
    }

    /// The stability polynomial `R(z)` (ascending powers) of an explicit method that can take
    /// a fixed step, for judging a fixed step against the Jacobian's eigenvalues
    /// ([`crate::stability`]); `None` (the default) where there is none to check.
    fn stability_polynomial(&self) -> Option<&'static [f64]> {
        None
    }

    /// A fresh stepper for `dim` unknowns under `options` (their step control, largest step
    /// and step cap), or why the options do not suit the method.
    fn stepper(&self, options: &Options, dim: usize) -> Result<Box<dyn Stepper>, SolverError>;

    /// Integrates `problem` from `y0` in `modes` with `options`, telling `observe` the time
    /// reached after every step: the method's [`OneStepMethod::stepper`] driven by an
    /// [`Integrator`], the solution named by [`OneStepMethod::name`] whatever its stepper
    /// calls itself (an own method may wrap a built-in stepper).
    fn solve_observed(
        &self,
        problem: &dyn OdeProblem,
        y0: &[f64],
        modes: &[Mode],
        options: Options,
        observe: &mut dyn FnMut(f64),
    ) -> Result<Solution, Failure> {
        let (n, name) = (problem.dim(), self.name());
        let failed = |error| Failure {
            error,
            solution: Box::new(Solution::new(name, n, modes.len())),
        };
        let stepper = self.stepper(&options, n).map_err(failed)?;
        let named = |mut s: Solution| {
            s.solver = name;
            s
        };
        Integrator::new(problem, stepper, y0, modes, options)
            .map_err(failed)?
            .solve_observed(observe)
            .map(named)
            .map_err(|f| Failure {
                error: f.error,
                solution: Box::new(named(*f.solution)),
            })
    }
}

/// The tolerances `(rtol, atol, h0)` of `step` for a method that takes adaptive steps only,
/// or why a fixed step does not suit `solver`.
pub fn adaptive_only(
    solver: &'static str,
    step: StepControl,
) -> Result<(f64, f64, Option<f64>), SolverError> {
    match step {
        StepControl::Adaptive { rtol, atol, h0 } => Ok((rtol, atol, h0)),
        StepControl::Fixed { .. } => Err(SolverError::Unsupported {
            solver,
            why: "it takes adaptive steps only: give tolerances, not a fixed step".into(),
        }),
    }
}
