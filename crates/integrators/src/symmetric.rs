//! Repeated solves `A·x = b` with a sparse symmetric matrix whose pattern is fixed and whose
//! values change: faer's sparse LDLᵀ (no pivoting), with the fill-reducing ordering (AMD) and
//! the symbolic factorisation computed once, then each factorisation numeric only, in buffers
//! kept between factorisations. Once built, factorising and solving allocate nothing.
//!
//! LDLᵀ without pivoting is stable for a symmetric positive definite matrix (Golub & Van Loan,
//! *Matrix Computations*, §4.2); a zero or non-finite pivot is reported as a failed
//! factorisation.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LdltRef, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, Par, Side};

/// The LDLᵀ factorisation of a symmetric `n × n` matrix of fixed pattern.
pub struct SparseLdlt {
    symbolic: SymbolicCholesky<usize>,
    /// The lower triangle in compressed columns.
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// The values of the lower triangle, in the order of `col_ptr`/`row_idx`.
    values: Vec<f64>,
    /// Where the k-th entry of the pattern given to [`SparseLdlt::new`] is stored in `values`.
    place: Vec<usize>,
    /// The values of L and D.
    factor: Vec<f64>,
    stack: MemBuffer,
    factored: bool,
}

/// Why a pattern was refused by [`SparseLdlt::new`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum PatternError {
    /// An entry above the diagonal or outside the matrix.
    #[error("entry ({row}, {col}) is not in the lower triangle of a {n} x {n} matrix")]
    NotLower {
        /// Its row.
        row: usize,
        /// Its column.
        col: usize,
        /// The size of the matrix.
        n: usize,
    },
    /// An entry given twice.
    #[error("entry ({row}, {col}) is given twice")]
    Duplicate {
        /// Its row.
        row: usize,
        /// Its column.
        col: usize,
    },
    /// faer's symbolic factorisation failed (out of memory).
    #[error("symbolic factorisation failed: {0}")]
    Symbolic(String),
}

impl SparseLdlt {
    /// The factorisation of matrices of size `n` whose lower triangle (diagonal included) has
    /// the entries `lower`, each `(row, col)` with `row ≥ col` once; the values passed to
    /// [`SparseLdlt::factor`] follow the same order. A diagonal entry left out is zero.
    pub fn new(n: usize, lower: &[(usize, usize)]) -> Result<SparseLdlt, PatternError> {
        let mut order: Vec<usize> = (0..lower.len()).collect();
        for &(row, col) in lower {
            if row < col || row >= n {
                return Err(PatternError::NotLower { row, col, n });
            }
        }
        order.sort_by_key(|&k| (lower[k].1, lower[k].0));
        let mut col_ptr = vec![0; n + 1];
        let mut row_idx = Vec::with_capacity(lower.len());
        let mut place = vec![0; lower.len()];
        if let Some(pair) = order.windows(2).find(|p| lower[p[0]] == lower[p[1]]) {
            let (row, col) = lower[pair[0]];
            return Err(PatternError::Duplicate { row, col });
        }
        for (at, &k) in order.iter().enumerate() {
            let (row, col) = lower[k];
            col_ptr[col + 1] += 1;
            row_idx.push(row);
            place[k] = at;
        }
        for c in 0..n {
            col_ptr[c + 1] += col_ptr[c];
        }
        let pattern = SymbolicSparseColMatRef::new_checked(n, n, &col_ptr, None, &row_idx);
        let symbolic = factorize_symbolic_cholesky(
            pattern,
            Side::Lower,
            SymmetricOrdering::Amd,
            Default::default(),
        )
        .map_err(|e| PatternError::Symbolic(format!("{e:?}")))?;
        let scratch = symbolic
            .factorize_numeric_ldlt_scratch::<f64>(Par::Seq, Default::default())
            .or(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq));
        Ok(SparseLdlt {
            factor: vec![0.0; symbolic.len_val()],
            values: vec![0.0; row_idx.len()],
            symbolic,
            col_ptr,
            row_idx,
            place,
            stack: MemBuffer::new(scratch),
            factored: false,
        })
    }

    /// The size n.
    pub fn n(&self) -> usize {
        self.col_ptr.len() - 1
    }

    /// Factorises the matrix with `values` of the pattern's entries, in its order; `false`
    /// when a pivot is zero or not finite.
    pub fn factor(&mut self, values: &[f64]) -> bool {
        assert_eq!(values.len(), self.place.len(), "one value per entry");
        for (&at, &v) in self.place.iter().zip(values) {
            self.values[at] = v;
        }
        let n = self.n();
        let pattern =
            SymbolicSparseColMatRef::new_checked(n, n, &self.col_ptr, None, &self.row_idx);
        let a = SparseColMatRef::new(pattern, &self.values);
        let factored = self.symbolic.factorize_numeric_ldlt(
            &mut self.factor,
            a,
            Side::Lower,
            LdltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut self.stack),
            Default::default(),
        );
        self.factored = factored.is_ok();
        self.factored
    }

    /// Overwrites `b` with `A⁻¹·b` for the last matrix factorised; `false` when there is
    /// none or the result is not finite.
    pub fn solve(&mut self, b: &mut [f64]) -> bool {
        if !self.factored || b.len() != self.n() {
            return false;
        }
        let n = b.len();
        LdltRef::new(&self.symbolic, &self.factor).solve_in_place_with_conj(
            Conj::No,
            faer::MatMut::from_column_major_slice_mut(b, n, 1),
            Par::Seq,
            MemStack::new(&mut self.stack),
        );
        b.iter().all(|v| v.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A path of n nodes (a chain) as the lower triangle, diagonal first.
    fn path(n: usize) -> Vec<(usize, usize)> {
        let mut e: Vec<(usize, usize)> = (0..n).map(|i| (i, i)).collect();
        e.extend((1..n).map(|i| (i, i - 1)));
        e
    }

    #[test]
    fn solves_a_chain_refactorised_with_new_values() {
        let n = 200;
        let pattern = path(n);
        let mut ldlt = SparseLdlt::new(n, &pattern).expect("a valid pattern");
        for scale in [1.0, 3.0] {
            // (−1, 2 + scale, −1): diagonally dominant, exact solution x_i = 1 + i/n.
            let values: Vec<f64> = pattern
                .iter()
                .map(|&(r, c)| if r == c { 2.0 + scale } else { -1.0 })
                .collect();
            let x: Vec<f64> = (0..n).map(|i| 1.0 + i as f64 / n as f64).collect();
            let mut b: Vec<f64> = (0..n).map(|i| (2.0 + scale) * x[i]).collect();
            for i in 1..n {
                b[i] -= x[i - 1];
                b[i - 1] -= x[i];
            }
            assert!(ldlt.factor(&values));
            assert!(ldlt.solve(&mut b));
            for (got, want) in b.iter().zip(&x) {
                assert!((got - want).abs() < 1e-14, "{got} vs {want}");
            }
        }
    }

    #[test]
    fn a_singular_matrix_and_a_bad_pattern_are_reported() {
        let mut ldlt = SparseLdlt::new(2, &[(0, 0), (1, 0), (1, 1)]).expect("valid");
        // [[1, 2], [2, 4]]: the second pivot is zero.
        assert!(!ldlt.factor(&[1.0, 2.0, 4.0]));
        assert!(!ldlt.solve(&mut [1.0, 1.0]));
        assert_eq!(
            SparseLdlt::new(2, &[(0, 1)]).err(),
            Some(PatternError::NotLower {
                row: 0,
                col: 1,
                n: 2
            })
        );
        assert_eq!(
            SparseLdlt::new(2, &[(1, 0), (1, 0)]).err(),
            Some(PatternError::Duplicate { row: 1, col: 0 })
        );
    }
}
