//! Linear solves `A·x = b` for Newton's method, behind one small trait: nalgebra's LU for
//! small dense systems, faer's LU for large dense ones and faer's sparse LU for large sparse
//! ones (a chain of many blocks), chosen by size and fill.

use crate::problem::Entry;
use faer::linalg::solvers::{PartialPivLu, Solve};
use faer::sparse::{SparseColMat, Triplet};

/// Up to this many unknowns nalgebra's dense LU is used.
pub const SMALL_DENSE: usize = 16;
/// Above [`SMALL_DENSE`], a matrix with at most this fraction of non-zeros goes to the
/// sparse LU.
pub const SPARSE_FILL: f64 = 0.1;

/// A factorised square matrix.
pub trait LinearSolver: Send {
    /// Which factorisation this is.
    fn name(&self) -> &'static str;

    /// Factorises the `n × n` matrix given by `entries` (duplicates summed); `false` when
    /// it is singular.
    fn factor(&mut self, n: usize, entries: &[Entry]) -> bool;

    /// Overwrites `b` with `A⁻¹·b`; `false` when the result is not finite (a singular
    /// matrix that pivoting did not reveal).
    fn solve(&self, b: &mut [f64]) -> bool;
}

/// The name of the solver chosen for an `n × n` matrix with `nnz` stored entries.
pub fn choice(n: usize, nnz: usize) -> &'static str {
    if n <= SMALL_DENSE {
        "nalgebra dense LU"
    } else if (nnz as f64) <= SPARSE_FILL * (n * n) as f64 {
        "faer sparse LU"
    } else {
        "faer dense LU"
    }
}

/// The solver for an `n × n` matrix with `nnz` stored entries (see [`choice`]).
pub fn for_size(n: usize, nnz: usize) -> Box<dyn LinearSolver> {
    match choice(n, nnz) {
        "nalgebra dense LU" => Box::new(NalgebraLu::default()),
        "faer sparse LU" => Box::new(FaerSparseLu::default()),
        _ => Box::new(FaerDenseLu::default()),
    }
}

/// nalgebra's LU with partial pivoting.
#[derive(Default)]
pub struct NalgebraLu {
    lu: Option<nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>>,
}

impl LinearSolver for NalgebraLu {
    fn name(&self) -> &'static str {
        "nalgebra dense LU"
    }

    fn factor(&mut self, n: usize, entries: &[Entry]) -> bool {
        let mut a = nalgebra::DMatrix::<f64>::zeros(n, n);
        for &(i, j, v) in entries {
            a[(i, j)] += v;
        }
        let lu = a.lu();
        let regular = lu.is_invertible();
        self.lu = Some(lu);
        regular
    }

    fn solve(&self, b: &mut [f64]) -> bool {
        let Some(lu) = &self.lu else { return false };
        let mut x = nalgebra::DVectorViewMut::from_slice(b, b.len());
        lu.solve_mut(&mut x) && b.iter().all(|v| v.is_finite())
    }
}

/// faer's dense LU with partial pivoting.
#[derive(Default)]
pub struct FaerDenseLu {
    lu: Option<PartialPivLu<f64>>,
}

impl LinearSolver for FaerDenseLu {
    fn name(&self) -> &'static str {
        "faer dense LU"
    }

    fn factor(&mut self, n: usize, entries: &[Entry]) -> bool {
        let mut a = faer::Mat::<f64>::zeros(n, n);
        for &(i, j, v) in entries {
            a[(i, j)] += v;
        }
        self.lu = Some(a.partial_piv_lu());
        true
    }

    fn solve(&self, b: &mut [f64]) -> bool {
        let Some(lu) = &self.lu else { return false };
        let n = b.len();
        lu.solve_in_place(faer::MatMut::from_column_major_slice_mut(b, n, 1));
        b.iter().all(|v| v.is_finite())
    }
}

/// faer's sparse LU.
#[derive(Default)]
pub struct FaerSparseLu {
    lu: Option<faer::sparse::linalg::solvers::Lu<usize, f64>>,
}

impl LinearSolver for FaerSparseLu {
    fn name(&self) -> &'static str {
        "faer sparse LU"
    }

    fn factor(&mut self, n: usize, entries: &[Entry]) -> bool {
        let triplets: Vec<_> = entries
            .iter()
            .map(|&(i, j, v)| Triplet::new(i, j, v))
            .collect();
        let lu = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &triplets)
            .ok()
            .and_then(|a| a.sp_lu().ok());
        let factored = lu.is_some();
        self.lu = lu;
        factored
    }

    fn solve(&self, b: &mut [f64]) -> bool {
        let Some(lu) = &self.lu else { return false };
        let n = b.len();
        lu.solve_in_place(faer::MatMut::from_column_major_slice_mut(b, n, 1));
        b.iter().all(|v| v.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tridiagonal matrix (−1, 4, −1) of size n as entries, with a duplicate entry on the
    /// diagonal that must be summed.
    fn tridiagonal(n: usize) -> Vec<Entry> {
        let mut e = Vec::new();
        for i in 0..n {
            e.push((i, i, 3.0));
            e.push((i, i, 1.0));
            if i > 0 {
                e.push((i, i - 1, -1.0));
            }
            if i + 1 < n {
                e.push((i, i + 1, -1.0));
            }
        }
        e
    }

    fn check(solver: &mut dyn LinearSolver, n: usize) {
        let a = tridiagonal(n);
        let x: Vec<f64> = (0..n).map(|i| 1.0 + i as f64 / n as f64).collect();
        let mut b = vec![0.0; n];
        for &(i, j, v) in &a {
            b[i] += v * x[j];
        }
        assert!(solver.factor(n, &a));
        assert!(solver.solve(&mut b));
        for (got, want) in b.iter().zip(&x) {
            assert!(
                (got - want).abs() < 1e-13,
                "{}: {got} vs {want}",
                solver.name()
            );
        }
    }

    #[test]
    fn every_solver_solves_a_known_system() {
        check(&mut NalgebraLu::default(), 7);
        check(&mut FaerDenseLu::default(), 40);
        check(&mut FaerSparseLu::default(), 300);
    }

    #[test]
    fn the_choice_follows_size_and_fill() {
        assert_eq!(for_size(3, 9).name(), "nalgebra dense LU");
        assert_eq!(for_size(300, 898).name(), "faer sparse LU");
        assert_eq!(for_size(40, 1600).name(), "faer dense LU");
    }

    #[test]
    fn singular_matrices_are_reported() {
        let singular = [(0, 0, 1.0), (0, 1, 2.0), (1, 0, 2.0), (1, 1, 4.0)];
        assert!(!NalgebraLu::default().factor(2, &singular));
        let mut dense = FaerDenseLu::default();
        dense.factor(2, &singular);
        assert!(!dense.solve(&mut [1.0, 1.0]));
    }
}
