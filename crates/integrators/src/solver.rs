//! Every solver by the name the command line uses, behind one call, and the [`OneStepMethod`] trait
//! through which a method written outside friction-lab joins them ([`Solver::Own`]).

use crate::diffsol_backend::{self, DiffsolMethod};
use crate::error::SolverError;
use crate::integrator::Integrator;
use crate::newton::NewtonKind;
use crate::options::{Options, StepControl};
use crate::problem::{Mode, OdeProblem};
use crate::solution::{Failure, Solution};
use crate::stepper::Stepper;
use crate::{Dopri5, ImplicitEuler, Rk4};

/// A one-step method written in a user's own crate, run and studied like a built-in one: it
/// names itself, says its order and how it takes its steps, and makes a [`Stepper`] that the
/// [`Integrator`] drives (event location on its dense output, mode switching, output grid,
/// step cap and wall-clock limit included). Wrapped as [`Solver::Own`], it goes wherever a
/// [`Solver`] goes: `simulate`, the rigs and every study (see `examples/own_solver.rs`).
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

    /// A fresh stepper for `dim` unknowns under `options` (their step control, largest step
    /// and step cap), or why the options do not suit the method.
    fn stepper(&self, options: &Options, dim: usize) -> Result<Box<dyn Stepper>, SolverError>;
}

/// A solver of friction-lab.
#[derive(Clone, Copy, Debug)]
pub enum Solver {
    /// Classical Runge–Kutta, fixed step.
    Rk4,
    /// Dormand–Prince 5(4), adaptive (or fixed with `--dt` only).
    Dopri5,
    /// Implicit Euler with modified Newton, fixed or adaptive.
    ImplicitEuler,
    /// One of diffsol's methods (adaptive).
    Diffsol(DiffsolMethod),
    /// A method of the user's own (not named on the command line).
    Own(&'static dyn OneStepMethod),
}

/// Built-in solvers are equal when they are the same variant; an own method is equal to an
/// own method of the same name (its identity in a study's tables), never to a built-in one.
impl PartialEq for Solver {
    fn eq(&self, other: &Solver) -> bool {
        match (self, other) {
            (Solver::Own(a), Solver::Own(b)) => a.name() == b.name(),
            (Solver::Own(_), _) | (_, Solver::Own(_)) => false,
            (a, b) => a.name() == b.name(),
        }
    }
}

impl Eq for Solver {}

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
            Solver::Own(m) => m.name(),
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

    /// The stability polynomial `R(z)` (ascending powers) of an explicit method that can take
    /// a fixed step: RK4's and Dormand–Prince's ([`crate::stability`]); `None` for the
    /// implicit methods, for Tsit45 (adaptive only) and for an own method.
    pub fn stability_polynomial(self) -> Option<&'static [f64]> {
        match self {
            Solver::Rk4 => Some(&crate::stability::RK4_POLYNOMIAL),
            Solver::Dopri5 => Some(&crate::stability::DOPRI5_POLYNOMIAL),
            _ => None,
        }
    }

    /// Whether the method is implicit (solves a nonlinear system per step).
    pub fn is_implicit(self) -> bool {
        match self {
            Solver::Own(m) => m.is_implicit(),
            _ => !matches!(
                self,
                Solver::Rk4 | Solver::Dopri5 | Solver::Diffsol(DiffsolMethod::Tsit45)
            ),
        }
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
            Solver::Own(m) => m.order(),
        }
    }

    /// Whether the method needs a fixed step (`--dt`) rather than tolerances.
    pub fn is_fixed_step(self) -> bool {
        match self {
            Solver::Own(m) => m.is_fixed_step(),
            _ => self == Solver::Rk4,
        }
    }

    /// Whether the method takes fixed steps when a study asks for observed orders (every
    /// hand-written method; diffsol's take tolerances only).
    pub fn takes_fixed_steps(self) -> bool {
        match self {
            Solver::Own(m) => m.takes_fixed_steps(),
            _ => !matches!(self, Solver::Diffsol(_)),
        }
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
            (Solver::Own(method), _) => method.stepper(&options, n).map_err(|error| Failure {
                error,
                solution: Box::new(Solution::new(method.name(), n, modes.len())),
            })?,
        };
        // The solution carries the solver's name, whatever its stepper calls itself (an own
        // method may wrap a built-in stepper).
        let named = |mut s: Solution| {
            s.solver = self.name();
            s
        };
        Integrator::new(problem, stepper, y0, modes, options)
            .map_err(|error| Failure {
                error,
                solution: Box::new(Solution::new(self.name(), n, modes.len())),
            })?
            .solve_observed(observe)
            .map(named)
            .map_err(|f| Failure {
                error: f.error,
                solution: Box::new(named(*f.solution)),
            })
    }
}

impl std::str::FromStr for Solver {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Solver::from_name(s)
    }
}
