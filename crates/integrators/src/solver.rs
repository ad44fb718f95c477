//! Every solver by the name the command line uses, behind one call.

use crate::diffsol_backend::{self, DiffsolMethod};
use crate::error::SolverError;
use crate::integrator::Integrator;
use crate::newton::NewtonKind;
use crate::options::{Options, StepControl};
use crate::problem::{Mode, OdeProblem};
use crate::solution::{Failure, Solution};
use crate::stepper::Stepper;
use crate::{Dopri5, ImplicitEuler, Rk4};

/// A solver of friction-lab.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Solver {
    /// Classical Runge–Kutta, fixed step.
    Rk4,
    /// Dormand–Prince 5(4), adaptive (or fixed with `--dt` only).
    Dopri5,
    /// Implicit Euler with modified Newton, fixed or adaptive.
    ImplicitEuler,
    /// One of diffsol's methods (adaptive).
    Diffsol(DiffsolMethod),
}

impl Solver {
    /// Every solver, in listing order.
    pub const ALL: [Solver; 7] = [
        Solver::Rk4,
        Solver::Dopri5,
        Solver::ImplicitEuler,
        Solver::Diffsol(DiffsolMethod::Bdf),
        Solver::Diffsol(DiffsolMethod::TrBdf2),
        Solver::Diffsol(DiffsolMethod::Esdirk34),
        Solver::Diffsol(DiffsolMethod::Tsit45),
    ];

    /// The name the command line takes.
    pub fn name(self) -> &'static str {
        match self {
            Solver::Rk4 => "rk4",
            Solver::Dopri5 => "dopri5",
            Solver::ImplicitEuler => "implicit-euler",
            Solver::Diffsol(m) => m.name(),
        }
    }

    /// The solver called `name`.
    pub fn from_name(name: &str) -> Result<Solver, String> {
        Solver::ALL
            .into_iter()
            .find(|s| s.name() == name)
            .ok_or_else(|| {
                let known: Vec<_> = Solver::ALL.iter().map(|s| s.name()).collect();
                format!(
                    "unknown solver `{name}`; known solvers: {}",
                    known.join(", ")
                )
            })
    }

    /// Whether the method is implicit (solves a nonlinear system per step).
    pub fn is_implicit(self) -> bool {
        !matches!(
            self,
            Solver::Rk4 | Solver::Dopri5 | Solver::Diffsol(DiffsolMethod::Tsit45)
        )
    }

    /// The order p of the method: its global error ∝ h^p (BDF: its highest order, 5).
    pub fn order(self) -> usize {
        match self {
            Solver::Rk4 => 4,
            Solver::Dopri5 | Solver::Diffsol(DiffsolMethod::Tsit45) => 5,
            Solver::ImplicitEuler => 1,
            Solver::Diffsol(DiffsolMethod::Bdf) => 5,
            Solver::Diffsol(DiffsolMethod::TrBdf2) => 2,
            Solver::Diffsol(DiffsolMethod::Esdirk34) => 3,
        }
    }

    /// Whether the method needs a fixed step (`--dt`) rather than tolerances.
    pub fn is_fixed_step(self) -> bool {
        self == Solver::Rk4
    }

    /// Integrates `problem` from `y0` in `modes` with `options`.
    pub fn solve(
        self,
        problem: &dyn OdeProblem,
        y0: &[f64],
        modes: &[Mode],
        options: Options,
    ) -> Result<Solution, Failure> {
        self.solve_observed(problem, y0, modes, options, &mut |_| {})
    }

    /// As [`Solver::solve`], telling `observe` the time reached after every step.
    pub fn solve_observed(
        self,
        problem: &dyn OdeProblem,
        y0: &[f64],
        modes: &[Mode],
        options: Options,
        observe: &mut dyn FnMut(f64),
    ) -> Result<Solution, Failure> {
        let n = problem.dim();
        let stepper: Box<dyn Stepper> = match (self, options.step) {
            (Solver::Rk4, StepControl::Fixed { h }) => Box::new(Rk4::new(h, n)),
            (Solver::Rk4, StepControl::Adaptive { .. }) => {
                return Err(Failure {
                    error: SolverError::Unsupported {
                        solver: "rk4",
                        why: "RK4 has no error estimate: give a fixed step (--dt)".into(),
                    },
                    solution: Box::new(Solution::new("rk4", n, modes.len())),
                })
            }
            (Solver::Dopri5, step) => {
                Box::new(Dopri5::new(step, options.h_max(), options.max_steps, n))
            }
            (Solver::ImplicitEuler, step) => Box::new(ImplicitEuler::new(
                step,
                NewtonKind::Modified,
                options.h_max(),
                options.max_steps,
                n,
            )),
            (Solver::Diffsol(method), _) => {
                return diffsol_backend::solve_observed(
                    problem, method, y0, modes, options, observe,
                )
            }
        };
        Integrator::new(problem, stepper, y0, modes, options)
            .map_err(|error| Failure {
                error,
                solution: Box::new(Solution::new(self.name(), n, modes.len())),
            })?
            .solve_observed(observe)
    }
}

impl std::str::FromStr for Solver {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Solver::from_name(s)
    }
}
