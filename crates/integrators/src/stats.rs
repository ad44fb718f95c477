//! Run statistics: a plain struct that tests compare and `summary.json` reports.

use serde::Serialize;
use std::ops::AddAssign;

/// Counts of the work a solver did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Stats {
    /// Accepted steps (a step cut short by an event counts once, as accepted).
    pub steps: usize,
    /// Steps rejected by the local error test.
    pub rejected_error: usize,
    /// Steps rejected because Newton's iteration did not converge.
    pub rejected_newton: usize,
    /// Accepted steps whose end was discarded because an event occurred inside them; the
    /// solution is kept up to the event and the solver restarts there.
    pub cut_at_event: usize,
    /// Right-hand side evaluations (including those of finite-difference Jacobians).
    pub rhs_evals: usize,
    /// Jacobian evaluations (analytic or by finite differences).
    pub jacobian_evals: usize,
    /// LU factorisations of the iteration matrix M − h·γ·J.
    pub lu_factorizations: usize,
    /// Newton iterations.
    pub newton_iterations: usize,
    /// Linear back-solves with a factorised iteration matrix: one a Newton iteration in
    /// implicit Euler and in diffsol's implicit methods (whose Newton solver makes one linear
    /// solve an iteration), one a correction in Moreau–Jean's scheme.
    pub linear_solves: usize,
    /// Events handled.
    pub events: usize,
}

impl Stats {
    /// The work of a run in right-hand-side evaluations: `rhs_evals + dim·jacobian_evals`
    /// for a problem of `dim` unknowns (a finite-difference Jacobian costs `dim` evaluations,
    /// and an analytic one is counted at the same price so that solvers compare on one scale).
    /// The one definition of work that the studies use.
    pub fn work(&self, dim: usize) -> usize {
        self.rhs_evals + dim * self.jacobian_evals
    }

    /// All rejected steps, whatever the cause.
    pub fn rejected(&self) -> usize {
        self.rejected_error + self.rejected_newton
    }
}

impl AddAssign for Stats {
    fn add_assign(&mut self, o: Stats) {
        self.steps += o.steps;
        self.rejected_error += o.rejected_error;
        self.rejected_newton += o.rejected_newton;
        self.cut_at_event += o.cut_at_event;
        self.rhs_evals += o.rhs_evals;
        self.jacobian_evals += o.jacobian_evals;
        self.lu_factorizations += o.lu_factorizations;
        self.newton_iterations += o.newton_iterations;
        self.linear_solves += o.linear_solves;
        self.events += o.events;
    }
}
