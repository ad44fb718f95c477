//! Run statistics: a plain struct that tests compare and `summary.json` reports.

use serde::Serialize;
use std::ops::AddAssign;

/// Counts of the work a solver did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, serde::Deserialize)]
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
    /// Right-hand side evaluations, not counting those of finite-difference Jacobians (as
    /// radau5.f's NFCN): a Jacobian, analytic or not, is charged `n` in [`Stats::work`].
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
    /// LU factorisations of a complex matrix of the same order, Radau IIA's second system
    /// `(α + iβ)/h·M − J` (radau5.f's NDEC counts one with each real one); weighed as four
    /// real ones in [`Stats::work`], a complex multiply–add being four real ones.
    pub complex_lu_factorizations: usize,
    /// Back-solves with that complex matrix, one a Newton iteration (radau5.f's NSOL).
    pub complex_linear_solves: usize,
    /// Events handled.
    pub events: usize,
    /// The order of the matrix the method factorises: the problem's dimension for the
    /// implicit ODE methods, the number of bodies for Moreau–Jean's correction; 0 where it
    /// factorises none. With `matrix_entries` it sets the weights of [`Stats::work`].
    pub matrix_order: usize,
    /// The stored entries of that matrix's pattern (the Jacobian ∂f/∂y's for the implicit ODE
    /// methods, Ŵ's for Moreau–Jean's correction), the largest over the run.
    pub matrix_entries: usize,
}

/// The weights of the counted work ([`Stats::work`]), in right-hand-side evaluations, from
/// operation counts. One evaluation of f is taken to cost one multiply–add per stored entry
/// of its Jacobian (each entry is a dependence f evaluates): `c_f = max(nnz, n)` flops. Then
///
/// - a Jacobian costs `dim` evaluations (what forward differences pay; an analytic one is
///   counted at the same price so that methods compare on one scale);
/// - an LU factorisation of a dense `n × n` matrix costs `2n³/3` flops and a back-solve with
///   it `2n²` (forward and back substitution; Golub & Van Loan, *Matrix Computations*, 4th
///   ed., §3.2); a sparse one whose elimination creates no fill (a chain's tridiagonal or
///   block-tridiagonal pattern) about one flop per stored entry to factorise and two to solve
///   (`nnz` and `2·nnz`), as [`crate::linear::choice`] chooses between them;
///
/// so that `factorization = flops(LU)/c_f` and `solve = flops(solve)/c_f`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorkWeights {
    /// Evaluations per Jacobian.
    pub jacobian: f64,
    /// Evaluations per LU factorisation.
    pub factorization: f64,
    /// Evaluations per back-solve.
    pub solve: f64,
}

impl WorkWeights {
    /// The weights for a problem of `dim` unknowns whose method factorises a matrix of order
    /// `order` with `entries` stored entries (see the type).
    pub fn of(dim: usize, order: usize, entries: usize) -> WorkWeights {
        let (n, nnz) = (order as f64, entries as f64);
        let cost_f = nnz.max(n).max(1.0);
        let (lu, solve) = match crate::linear::choice(order, entries) {
            "faer sparse LU" => (nnz, 2.0 * nnz),
            _ => (2.0 / 3.0 * n.powi(3), 2.0 * n * n),
        };
        WorkWeights {
            jacobian: dim as f64,
            factorization: lu / cost_f,
            solve: solve / cost_f,
        }
    }
}

/// Real operations a complex one of linear algebra costs: a complex multiply–add is four real
/// multiplications and four additions.
const COMPLEX_COST: usize = 4;

impl Stats {
    /// The work of a run in right-hand-side evaluations, for a problem of `dim` unknowns:
    /// `rhs_evals + w_J·jacobian_evals + w_LU·F + w_s·S`, with F = `lu_factorizations +
    /// 4·complex_lu_factorizations` and S = `linear_solves + 4·complex_linear_solves`, the
    /// weights of
    /// [`WorkWeights::of`] for the matrix the run factorised, rounded to the nearest
    /// evaluation. The one definition of work that the studies use.
    pub fn work(&self, dim: usize) -> usize {
        let w = self.weights(dim);
        let factorizations = self.lu_factorizations + COMPLEX_COST * self.complex_lu_factorizations;
        let solves = self.linear_solves + COMPLEX_COST * self.complex_linear_solves;
        let linear_algebra = w.factorization * factorizations as f64 + w.solve * solves as f64;
        self.rhs_evals + dim * self.jacobian_evals + linear_algebra.round() as usize
    }

    /// The weights [`Stats::work`] uses for this run.
    pub fn weights(&self, dim: usize) -> WorkWeights {
        WorkWeights::of(dim, self.matrix_order, self.matrix_entries)
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
        self.complex_lu_factorizations += o.complex_lu_factorizations;
        self.complex_linear_solves += o.complex_linear_solves;
        self.events += o.events;
        self.matrix_order = self.matrix_order.max(o.matrix_order);
        self.matrix_entries = self.matrix_entries.max(o.matrix_entries);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_weights_follow_the_operation_counts_of_the_factorisation() {
        // A system of 5 unknowns and 10 Jacobian entries, dense: an LU is 2·125/3 flops and
        // a solve 50, against 10 for f.
        let w = WorkWeights::of(5, 5, 10);
        assert_eq!(w.jacobian, 5.0);
        assert!((w.factorization - 250.0 / 30.0).abs() < 1e-12, "{w:?}");
        assert!((w.solve - 5.0).abs() < 1e-12, "{w:?}");
        // A chain of 150 blocks (300 unknowns, 898 entries): sparse, no fill, one flop per
        // entry to factorise and two to solve.
        let w = WorkWeights::of(303, 300, 898);
        assert_eq!((w.jacobian, w.factorization, w.solve), (303.0, 1.0, 2.0));
        // An explicit method factorises nothing: its work is its evaluations.
        let explicit = Stats {
            rhs_evals: 60,
            ..Stats::default()
        };
        assert_eq!(explicit.work(5), 60);
        let implicit = Stats {
            rhs_evals: 60,
            jacobian_evals: 2,
            lu_factorizations: 3,
            linear_solves: 30,
            matrix_order: 5,
            matrix_entries: 10,
            ..Stats::default()
        };
        // 60 + 5·2 + 25 + 150.
        assert_eq!(implicit.work(5), 245);
        // Radau IIA: one real and one complex factorisation and solve, the complex ones
        // weighed four times: 60 + 5·2 + (1 + 4)·25/3 + (1 + 4)·5 ≈ 136.67.
        let radau = Stats {
            rhs_evals: 60,
            jacobian_evals: 2,
            lu_factorizations: 1,
            complex_lu_factorizations: 1,
            linear_solves: 1,
            complex_linear_solves: 1,
            matrix_order: 5,
            matrix_entries: 10,
            ..Stats::default()
        };
        assert_eq!(radau.work(5), 137);
    }
}
