//! Every solver by the name the command line uses, behind one call: a [`Solver`] is a
//! [`OneStepMethod`], the built-in ones listed in [`Solver::ALL`] and a user's own through
//! [`Solver::own`].

use crate::auto::AutoMethod;
use crate::diffsol_backend::DiffsolMethod;
use crate::dopri5::Dopri5Method;
use crate::implicit_euler::ImplicitEulerMethod;
use crate::method::OneStepMethod;
use crate::options::Options;
use crate::problem::{Mode, OdeProblem};
use crate::radau5::Radau5Method;
use crate::rk4::Rk4Method;
use crate::rodas::RodasMethod;
use crate::solution::{Failure, Solution};

/// A solver of friction-lab: a [`OneStepMethod`], built in or a user's own.
#[derive(Clone, Copy)]
pub struct Solver {
    method: &'static dyn OneStepMethod,
    /// Whether it is a user's own ([`Solver::own`]).
    own: bool,
}

/// A built-in solver shows as its name, an own one as `own NAME`.
impl std::fmt::Debug for Solver {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.own {
            f.write_str("own ")?;
        }
        f.write_str(self.name())
    }
}

/// Built-in solvers are equal when they have the same name, and so are own methods (the name
/// is a method's identity in a study's tables); an own method is never equal to a built-in
/// one, so that a study refuses one under a built-in's name.
impl PartialEq for Solver {
    fn eq(&self, other: &Solver) -> bool {
        self.own == other.own && self.name() == other.name()
    }
}

impl Eq for Solver {}

impl Solver {
    /// Classical Runge–Kutta, fixed step.
    pub const RK4: Solver = Solver::built_in(&Rk4Method);
    /// Dormand–Prince 5(4), adaptive (or fixed with `--dt` only).
    pub const DOPRI5: Solver = Solver::built_in(&Dopri5Method);
    /// Implicit Euler with modified Newton, fixed or adaptive.
    pub const IMPLICIT_EULER: Solver = Solver::built_in(&ImplicitEulerMethod);
    /// diffsol's variable-order BDF.
    pub const BDF: Solver = Solver::built_in(&DiffsolMethod::Bdf);
    /// diffsol's TR-BDF2.
    pub const TR_BDF2: Solver = Solver::built_in(&DiffsolMethod::TrBdf2);
    /// diffsol's ESDIRK3(4).
    pub const ESDIRK34: Solver = Solver::built_in(&DiffsolMethod::Esdirk34);
    /// diffsol's Tsitouras 5(4).
    pub const TSIT45: Solver = Solver::built_in(&DiffsolMethod::Tsit45);
    /// Radau IIA of order 5, Hairer's RADAU5.
    pub const RADAU5: Solver = Solver::built_in(&Radau5Method);
    /// The Rosenbrock method RODAS, Hairer's RODAS.
    pub const RODAS: Solver = Solver::built_in(&RodasMethod);
    /// Dormand–Prince and Radau IIA(5), switched by stiffness within a run.
    pub const AUTO: Solver = Solver::built_in(&AutoMethod);

    /// Every built-in solver, in listing order: the ones the command line names.
    pub const ALL: [Solver; 10] = [
        Solver::RK4,
        Solver::DOPRI5,
        Solver::IMPLICIT_EULER,
        Solver::BDF,
        Solver::TR_BDF2,
        Solver::ESDIRK34,
        Solver::TSIT45,
        Solver::RADAU5,
        Solver::RODAS,
        Solver::AUTO,
    ];

    const fn built_in(method: &'static dyn OneStepMethod) -> Solver {
        Solver { method, own: false }
    }

    /// A method of the user's own, run wherever a built-in one runs.
    pub const fn own(method: &'static dyn OneStepMethod) -> Solver {
        Solver { method, own: true }
    }

    /// The method.
    pub fn method(self) -> &'static dyn OneStepMethod {
        self.method
    }

    /// The name the command line takes.
    pub fn name(self) -> &'static str {
        self.method.name()
    }

    /// The built-in solver called `name`.
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
    /// implicit methods, for Tsit45 (adaptive only) and for an own method that gives none.
    pub fn stability_polynomial(self) -> Option<&'static [f64]> {
        self.method.stability_polynomial()
    }

    /// Whether the method is implicit (solves a nonlinear system per step).
    pub fn is_implicit(self) -> bool {
        self.method.is_implicit()
    }

    /// The order p of the method: its global error ∝ h^p (BDF: its highest order, 5).
    pub fn order(self) -> usize {
        self.method.order()
    }

    /// Whether the method needs a fixed step (`--dt`) rather than tolerances.
    pub fn is_fixed_step(self) -> bool {
        self.method.is_fixed_step()
    }

    /// Whether the method takes fixed steps when a study asks for observed orders (every
    /// hand-written method; diffsol's take tolerances only).
    pub fn takes_fixed_steps(self) -> bool {
        self.method.takes_fixed_steps()
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

    /// As [`Solver::solve`], telling `observe` the time reached after every step
    /// ([`OneStepMethod::solve_observed`]).
    pub fn solve_observed(
        self,
        problem: &dyn OdeProblem,
        y0: &[f64],
        modes: &[Mode],
        options: Options,
        observe: &mut dyn FnMut(f64),
    ) -> Result<Solution, Failure> {
        self.method
            .solve_observed(problem, y0, modes, options, observe)
    }
}

impl std::str::FromStr for Solver {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Solver::from_name(s)
    }
}
