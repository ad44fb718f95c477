//! Newton's correction of nonsmooth Gauss–Seidel for stiffly coupled bodies
//! ([`crate::moreau_jean`]).
//!
//! Gauss–Seidel solves body i's problem with its neighbours' velocities fixed: `v_i = φ_i(b_i)`,
//! `b_i = known_i + Σ_o w_io·v_o` (the couplings `w_io = h·θ·(c + h·θ·k)` of the iteration
//! matrix Ŵ). The coupled problem is the fixed point `v = φ(known + W·v)`. Where the couplings
//! are near the diagonal (h²θ²k ≫ m) its iteration contracts slowly; Newton's method on the same
//! fixed point, with the contacts' modes held (a semismooth Newton step: Qi & Sun 1993), takes
//! the whole coupling at once. With `φ_i' = 1/R_i'`, R_i' = `∂R_i/∂u` the slope of
//! body i's sliding residual at its solution (Ŵ_ii for a body without contact, 0 at rest), and
//! `d_i` the change of b_i since body i's last visit (so that its residual is `φ_i'·d_i` to
//! first order), the correction δ solves, for every body that slides or has no contact,
//!
//! ```text
//! R_i'·δ_i − Σ_o w_io·δ_o = d_i        (o over the neighbours that slide or have no contact)
//! ```
//!
//! and is 0 for a body at rest (its velocity is its surface's whatever b is). The matrix is
//! Ŵ's restricted to the moving bodies with the slopes of their laws on the diagonal:
//! symmetric, positive definite where the laws' slopes do not cancel Ŵ (a body whose slope is
//! not positive is held, as at rest, for the correction); it has Ŵ's pattern, tridiagonal on a
//! chain, and is factorised by a sparse LDLᵀ ([`integrators::symmetric::SparseLdlt`]) in
//! O(N) on a chain. The sweep that follows a correction solves every body's problem exactly
//! again: it corrects the linearisation, changes the modes where the correction crossed a
//! switch, and decides convergence as before.

use integrators::symmetric::{PatternError, SparseLdlt};
use std::collections::HashMap;

/// Marks a coupling above the diagonal in [`Correction::slot`]: its value is set through the
/// one below.
const UPPER: usize = usize::MAX;

/// The correction's matrix and its factorisation, for one coupling pattern.
pub(crate) struct Correction {
    ldlt: SparseLdlt,
    /// Per coupling of the rows given to [`Correction::new`] (concatenated), the index of its
    /// entry in `values`, or [`UPPER`].
    slot: Vec<usize>,
    /// The lower triangle's values: the n diagonal entries, then the couplings.
    values: Vec<f64>,
    /// The right-hand side, then δ.
    delta: Vec<f64>,
}

impl Correction {
    /// The correction for `n` bodies whose couplings are `rows(i)`: `(o, w_io)` for each
    /// neighbour o of body i (a neighbour may come more than once: two springs between the
    /// same bodies). The rows are read again, in the same order, by [`Correction::solve`].
    pub fn new<'r>(
        n: usize,
        rows: impl Fn(usize) -> &'r [(usize, f64)],
    ) -> Result<Correction, PatternError> {
        let mut pattern: Vec<(usize, usize)> = (0..n).map(|i| (i, i)).collect();
        let (mut slot, mut entries) = (Vec::new(), HashMap::new());
        for i in 0..n {
            for &(o, _) in rows(i) {
                if o > i {
                    slot.push(UPPER);
                    continue;
                }
                let entry = *entries.entry((i, o)).or_insert_with(|| {
                    pattern.push((i, o));
                    pattern.len() - 1
                });
                slot.push(entry);
            }
        }
        Ok(Correction {
            ldlt: SparseLdlt::new(n, &pattern)?,
            values: vec![0.0; pattern.len()],
            delta: vec![0.0; n],
            slot,
        })
    }

    /// δ from the slopes `slope(i)` (`Some(R_i')` for a body that moves, `None` for one held)
    /// and the changes `drift(i)` of b since each body's last visit, for the couplings
    /// `rows(i)` (the pattern of [`Correction::new`], with this step's values); `None` when
    /// the matrix is singular or δ is not finite.
    pub fn solve<'r>(
        &mut self,
        rows: impl Fn(usize) -> &'r [(usize, f64)],
        slope: impl Fn(usize) -> Option<f64>,
        drift: impl Fn(usize) -> f64,
    ) -> Option<&[f64]> {
        let n = self.delta.len();
        self.values[n..].fill(0.0);
        let mut slots = self.slot.iter();
        for i in 0..n {
            let row = rows(i);
            let moving = slope(i);
            // A held body keeps δ = 0: a unit row and column, nothing on its right-hand side.
            (self.values[i], self.delta[i]) = match moving {
                Some(s) => (s, drift(i)),
                None => (1.0, 0.0),
            };
            for (&(o, w), &entry) in row.iter().zip(slots.by_ref()) {
                if entry != UPPER && moving.is_some() && slope(o).is_some() {
                    self.values[entry] -= w;
                }
            }
        }
        (self.ldlt.factor(&self.values) && self.ldlt.solve(&mut self.delta))
            .then_some(&self.delta[..])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_correction_solves_the_linear_coupled_problem_with_held_bodies_left_out() {
        // Four bodies in a chain, w = 2 between neighbours, the pair (1, 2) joined by two
        // springs; body 3 is held.
        let rows: Vec<Vec<(usize, f64)>> = vec![
            vec![(1, 2.0)],
            vec![(0, 2.0), (2, 1.0), (2, 1.0)],
            vec![(1, 1.0), (1, 1.0), (3, 2.0)],
            vec![(2, 2.0)],
        ];
        let mut c = Correction::new(4, |i| &rows[i]).expect("a valid pattern");
        let slope = [Some(5.0), Some(6.0), Some(7.0), None];
        let drift = [1.0, -2.0, 3.0, 100.0];
        let delta = c
            .solve(|i| &rows[i], |i| slope[i], |i| drift[i])
            .expect("regular")
            .to_vec();
        // The moving bodies' equations: 5δ0 − 2δ1 = 1, −2δ0 + 6δ1 − 2δ2 = −2, −2δ1 + 7δ2 = 3.
        let residual = [
            5.0 * delta[0] - 2.0 * delta[1] - 1.0,
            -2.0 * delta[0] + 6.0 * delta[1] - 2.0 * delta[2] + 2.0,
            -2.0 * delta[1] + 7.0 * delta[2] - 3.0,
        ];
        assert!(residual.iter().all(|r| r.abs() < 1e-14), "{residual:?}");
        assert_eq!(delta[3], 0.0);
    }
}
