//! Every solver by the name the command line uses, behind one call: a [`Solver`] is a
//! [`OneStepMethod`], the built-in ones listed in [`Solver::ALL`] and a user's own through
//! [`Solver::own`] (registered with [`Solver::register`], found by its name too).

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

registry::handle!(
    /// A solver of friction-lab: a [`OneStepMethod`], built in or a user's own. Built-in
    /// solvers are equal when they have the same name, and so are own methods (the name is a
    /// method's identity in a study's tables); an own method is never equal to a built-in one,
    /// so that a study refuses one under a built-in's name.
    Solver => dyn OneStepMethod, SOLVERS
);

/// Every solver by name: the built-in ones ([`Solver::ALL`]) and those registered with
/// [`Solver::register`].
pub static SOLVERS: registry::Registry<Solver> =
    registry::Registry::new("solver", "solvers", &Solver::ALL);

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

    /// The method.
    pub fn method(self) -> &'static dyn OneStepMethod {
        self.0.item()
    }

    /// Integrates `problem` from `y0` in `modes` with `options`.
    pub fn solve(
        self,
        problem: &dyn OdeProblem,
        y0: &[f64],
        modes: &[Mode],
        options: Options,
    ) -> Result<Solution, Failure> {
        self.method()
            .solve_observed(problem, y0, modes, options, &mut |_| {})
    }
}
