//! Linear solves `A·x = b` for Newton's method, behind one small trait: nalgebra's LU for
//! small systems and faer's for large dense ones, both factorised in place in buffers kept
//! between factorisations, and faer's sparse LU for large sparse ones (a chain of many
//! blocks), chosen by size and fill.

use crate::problem::Entry;
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::Par;

/// Up to this many unknowns nalgebra's dense LU is used whatever the fill.
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
    /// matrix that pivoting did not reveal). Takes the solver mutably for its scratch space.
    fn solve(&mut self, b: &mut [f64]) -> bool;
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

/// nalgebra's LU with partial pivoting for small systems, run in place on a buffer kept between
/// factorisations: the loop of `nalgebra::LU::new` (pivot by largest magnitude, then
/// `gauss_step` or `gauss_step_swap`), without its allocations. Once sized, factorising and
/// solving allocate nothing.
pub struct NalgebraLu {
    lu: nalgebra::DMatrix<f64>,
    /// Row swaps (i, pivot) in the order they were made.
    swaps: Vec<(usize, usize)>,
    regular: bool,
}

impl Default for NalgebraLu {
    fn default() -> Self {
        NalgebraLu {
            lu: nalgebra::DMatrix::zeros(0, 0),
            swaps: Vec::new(),
            regular: false,
        }
    }
}

impl LinearSolver for NalgebraLu {
    fn name(&self) -> &'static str {
        "nalgebra dense LU"
    }

    fn factor(&mut self, n: usize, entries: &[Entry]) -> bool {
        use nalgebra::linalg::{gauss_step, gauss_step_swap};
        if self.lu.nrows() != n {
            self.lu = nalgebra::DMatrix::zeros(n, n);
            self.swaps = Vec::with_capacity(n);
        }
        self.lu.fill(0.0);
        self.swaps.clear();
        for &(i, j, v) in entries {
            self.lu[(i, j)] += v;
        }
        self.regular = true;
        for i in 0..n {
            let piv = self.lu.view_range(i.., i).icamax() + i;
            let diag = self.lu[(piv, i)];
            if diag == 0.0 {
                self.regular = false;
                continue;
            }
            if piv != i {
                self.swaps.push((i, piv));
                self.lu.columns_range_mut(..i).swap_rows(i, piv);
                gauss_step_swap(&mut self.lu, diag, i, piv);
            } else {
                gauss_step(&mut self.lu, diag, i);
            }
        }
        self.regular
    }

    fn solve(&mut self, b: &mut [f64]) -> bool {
        if !self.regular || b.len() != self.lu.nrows() {
            return false;
        }
        for &(i, piv) in &self.swaps {
            b.swap(i, piv);
        }
        let mut x = nalgebra::DVectorViewMut::from_slice(b, b.len());
        let _ = self.lu.solve_lower_triangular_with_diag_mut(&mut x, 1.0);
        self.lu.solve_upper_triangular_mut(&mut x) && b.iter().all(|v| v.is_finite())
    }
}

/// faer's dense LU with partial pivoting, factorised in place in buffers kept between
/// factorisations (faer's `lu_in_place` with a preallocated stack): once sized, factorising
/// and solving allocate nothing.
pub struct FaerDenseLu {
    n: usize,
    lu: faer::Mat<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    stack: Option<faer::dyn_stack::MemBuffer>,
}

impl Default for FaerDenseLu {
    fn default() -> Self {
        FaerDenseLu {
            n: 0,
            lu: faer::Mat::zeros(0, 0),
            perm: Vec::new(),
            perm_inv: Vec::new(),
            stack: None,
        }
    }
}

impl LinearSolver for FaerDenseLu {
    fn name(&self) -> &'static str {
        "faer dense LU"
    }

    fn factor(&mut self, n: usize, entries: &[Entry]) -> bool {
        use faer::linalg::lu::partial_pivoting::{factor, solve};
        if self.n != n || self.stack.is_none() {
            self.n = n;
            self.lu = faer::Mat::zeros(n, n);
            self.perm = vec![0; n];
            self.perm_inv = vec![0; n];
            let req = factor::lu_in_place_scratch::<usize, f64>(n, n, Par::Seq, Default::default())
                .or(solve::solve_in_place_scratch::<usize, f64>(n, 1, Par::Seq));
            self.stack = Some(faer::dyn_stack::MemBuffer::new(req));
        }
        self.lu.fill(0.0);
        for &(i, j, v) in entries {
            self.lu[(i, j)] += v;
        }
        let stack = self.stack.as_mut().expect("sized above");
        factor::lu_in_place(
            self.lu.as_mut(),
            &mut self.perm,
            &mut self.perm_inv,
            Par::Seq,
            faer::dyn_stack::MemStack::new(stack),
            Default::default(),
        );
        (0..n).all(|i| self.lu[(i, i)] != 0.0 && self.lu[(i, i)].is_finite())
    }

    fn solve(&mut self, b: &mut [f64]) -> bool {
        use faer::linalg::lu::partial_pivoting::solve;
        let Some(stack) = self.stack.as_mut() else {
            return false;
        };
        let n = self.n;
        let perm = faer::perm::PermRef::new_checked(&self.perm, &self.perm_inv, n);
        solve::solve_in_place_with_conj(
            self.lu.as_ref(),
            self.lu.as_ref(),
            perm,
            faer::Conj::No,
            faer::MatMut::from_column_major_slice_mut(b, n, 1),
            Par::Seq,
            faer::dyn_stack::MemStack::new(stack),
        );
        b.iter().all(|v| v.is_finite())
    }
}

/// faer's sparse LU.
#[derive(Clone, Default)]
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

    fn solve(&mut self, b: &mut [f64]) -> bool {
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
        // Dense solvers resized: their buffers follow the size.
        let (mut small, mut dense) = (NalgebraLu::default(), FaerDenseLu::default());
        check(&mut small, 7);
        check(&mut small, 12);
        check(&mut small, 7);
        check(&mut dense, 40);
        check(&mut dense, 7);
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
        assert!(!FaerDenseLu::default().factor(2, &singular));
    }
}
