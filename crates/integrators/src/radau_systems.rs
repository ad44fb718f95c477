//! The two linear systems of a Radau IIA(5) step (radau5.f's DECOMR/DECOMC and the solves of
//! SLVRAD and ESTRAD): the real matrix `E1 = (γ/h)·M − J` and the complex matrix
//! `E2 = ((α + iβ)/h)·M − J`, M diagonal. Dense matrices are factorised by `decsol.f`'s DEC
//! and DECC ([`crate::decsol`]), so that runs match radau5.f's; sparse ones (at most 10 %
//! non-zeros above 16 unknowns, [`crate::linear::choice`]) by faer's sparse LU, the complex
//! one as the real system of order 2n
//! `[[Re E2, −Im E2], [Im E2, Re E2]]·[x_re; x_im] = [b_re; b_im]`, its unknowns interleaved
//! so that a chain's band stays a band.

use crate::decsol::{DenseComplexLu, DenseLu};
use crate::linear::{self, FaerSparseLu, LinearSolver};
use crate::problem::Entry;

/// The factorised pair E1, E2.
pub enum RadauSystems {
    /// `decsol.f`'s dense LU, real and complex.
    Dense {
        /// E1.
        real: DenseLu,
        /// E2.
        complex: DenseComplexLu,
    },
    /// faer's sparse LU of E1 and of E2 written as a real system of order 2n.
    Sparse(Box<SparseSystems>),
}

/// E1 and E2 by faer's sparse LU.
#[derive(Default)]
pub struct SparseSystems {
    /// E1.
    real: FaerSparseLu,
    /// E2 as a real system, unknowns (re₀, im₀, re₁, im₁, …).
    complex: FaerSparseLu,
    /// Scratch: the entries being factorised.
    entries: Vec<Entry>,
    /// Scratch: a complex right-hand side, interleaved.
    rhs: Vec<f64>,
}

impl RadauSystems {
    /// The solver for `n` unknowns and a Jacobian of `nnz` stored entries.
    pub fn for_size(n: usize, nnz: usize) -> Self {
        match linear::choice(n, nnz + n) {
            "faer sparse LU" => RadauSystems::Sparse(Box::default()),
            _ => RadauSystems::Dense {
                real: DenseLu::default(),
                complex: DenseComplexLu::default(),
            },
        }
    }

    /// Whether this is the solver [`RadauSystems::for_size`] chooses for `n` and `nnz`.
    pub fn suits(&self, n: usize, nnz: usize) -> bool {
        let sparse = linear::choice(n, nnz + n) == "faer sparse LU";
        sparse == matches!(self, RadauSystems::Sparse(_))
    }

    /// Factorises `E1 = fac1·M − J` and `E2 = (alphn + i·betan)·M − J` for the Jacobian
    /// `jac` of order `n` (entries summed) and the diagonal `mass` (identity when absent);
    /// `false` when either is singular.
    pub fn factor(
        &mut self,
        n: usize,
        jac: &[Entry],
        mass: Option<&[f64]>,
        (fac1, alphn, betan): (f64, f64, f64),
    ) -> bool {
        let m = |j: usize| mass.map_or(1.0, |m| m[j]);
        match self {
            RadauSystems::Dense { real, complex } => {
                // DECOMR and DECOMC, IJOB = 1 (or 5 with the mass matrix): −J, then the
                // diagonal.
                let e1 = real.matrix(n);
                for &(i, j, v) in jac {
                    e1[i + j * n] -= v;
                }
                for j in 0..n {
                    e1[j + j * n] += m(j) * fac1;
                }
                if !real.factor() {
                    return false;
                }
                let (e2r, e2i) = complex.matrix(n);
                for &(i, j, v) in jac {
                    e2r[i + j * n] -= v;
                }
                for j in 0..n {
                    e2r[j + j * n] += m(j) * alphn;
                    e2i[j + j * n] = m(j) * betan;
                }
                complex.factor()
            }
            RadauSystems::Sparse(sparse) => {
                let SparseSystems {
                    real,
                    complex,
                    entries,
                    ..
                } = &mut **sparse;
                entries.clear();
                entries.extend(jac.iter().map(|&(i, j, v)| (i, j, -v)));
                entries.extend((0..n).map(|j| (j, j, m(j) * fac1)));
                if !real.factor(n, entries) {
                    return false;
                }
                entries.clear();
                for &(i, j, v) in jac {
                    entries.push((2 * i, 2 * j, -v));
                    entries.push((2 * i + 1, 2 * j + 1, -v));
                }
                for j in 0..n {
                    let (re, im) = (m(j) * alphn, m(j) * betan);
                    entries.extend([
                        (2 * j, 2 * j, re),
                        (2 * j + 1, 2 * j + 1, re),
                        (2 * j, 2 * j + 1, -im),
                        (2 * j + 1, 2 * j, im),
                    ]);
                }
                complex.factor(2 * n, entries)
            }
        }
    }

    /// Overwrites `b` with `E1⁻¹·b`. A singular matrix that pivoting did not reveal leaves
    /// non-finite values, which the Newton norm or the error estimate then reports.
    pub fn solve_real(&mut self, b: &mut [f64]) {
        match self {
            RadauSystems::Dense { real, .. } => real.solve(b),
            RadauSystems::Sparse(sparse) => {
                sparse.real.solve(b);
            }
        }
    }

    /// Overwrites `(br, bi)` with `E2⁻¹·(br + i·bi)`.
    pub fn solve_complex(&mut self, br: &mut [f64], bi: &mut [f64]) {
        match self {
            RadauSystems::Dense { complex, .. } => complex.solve(br, bi),
            RadauSystems::Sparse(sparse) => {
                let SparseSystems { complex, rhs, .. } = &mut **sparse;
                rhs.clear();
                rhs.extend(br.iter().zip(bi.iter()).flat_map(|(r, i)| [*r, *i]));
                complex.solve(rhs);
                for (k, pair) in rhs.chunks_exact(2).enumerate() {
                    br[k] = pair[0];
                    bi[k] = pair[1];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chain's Jacobian of order n: tridiagonal (1, −2, 1)·k with k = 50.
    fn chain(n: usize) -> Vec<Entry> {
        let mut jac = Vec::new();
        for i in 0..n {
            jac.push((i, i, -100.0));
            if i > 0 {
                jac.push((i, i - 1, 50.0));
            }
            if i + 1 < n {
                jac.push((i, i + 1, 50.0));
            }
        }
        jac
    }

    #[test]
    fn the_sparse_solves_agree_with_the_dense_ones() {
        let n = 200;
        let jac = chain(n);
        let mass: Vec<f64> = (0..n).map(|i| if i % 7 == 3 { 0.0 } else { 1.0 }).collect();
        let coefficients = (3.6, 2.7, 1.5);
        let mut sparse = RadauSystems::for_size(n, jac.len());
        assert!(sparse.suits(n, jac.len()) && matches!(sparse, RadauSystems::Sparse(_)));
        let mut dense = RadauSystems::Dense {
            real: DenseLu::default(),
            complex: DenseComplexLu::default(),
        };
        assert!(!dense.suits(n, jac.len()));
        for s in [&mut sparse, &mut dense] {
            assert!(s.factor(n, &jac, Some(&mass), coefficients));
        }
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
        let c: Vec<f64> = (0..n).map(|i| (i as f64 * 0.11).cos()).collect();
        let (mut x1, mut x2) = (b.clone(), b.clone());
        sparse.solve_real(&mut x1);
        dense.solve_real(&mut x2);
        let (mut r1, mut i1, mut r2, mut i2) = (b.clone(), c.clone(), b.clone(), c.clone());
        sparse.solve_complex(&mut r1, &mut i1);
        dense.solve_complex(&mut r2, &mut i2);
        for (a, b) in [(&x1, &x2), (&r1, &r2), (&i1, &i2)] {
            for (u, v) in a.iter().zip(b.iter()) {
                assert!((u - v).abs() < 1e-12 * (1.0 + v.abs()), "{u} vs {v}");
            }
        }
    }
}
