//! The iteration matrices of Hairer's stiff codes, factorised: the real `E = fac·M − J` of
//! RODAS and of Radau IIA(5), and Radau IIA(5)'s complex `E2 = (α + iβ)·M − J` (radau5.f's
//! DECOMR/DECOMC, rodas.f's DECOMR, and the solves of SLVRAD, ESTRAD and SLVROD), M diagonal.
//! Dense matrices are factorised by `decsol.f`'s DEC and DECC ([`crate::decsol`]), so that
//! runs match the Fortran's; sparse ones (at most 10 % non-zeros above 16 unknowns,
//! [`crate::linear::choice`]) by faer's sparse LU, the complex one as the real system of order
//! 2n `[[Re E2, −Im E2], [Im E2, Re E2]]·[x_re; x_im] = [b_re; b_im]`, its unknowns
//! interleaved so that a chain's band stays a band.

use crate::decsol::{DenseComplexLu, DenseLu};
use crate::linear::{self, FaerSparseLu, LinearSolver};
use crate::problem::Entry;

/// Whether a Jacobian of order `n` with `nnz` stored entries is factorised as sparse.
fn is_sparse(n: usize, nnz: usize) -> bool {
    linear::choice(n, nnz + n) == "faer sparse LU"
}

/// The diagonal of the mass matrix at `j` (1 for the identity).
fn mass_at(mass: Option<&[f64]>, j: usize) -> f64 {
    mass.map_or(1.0, |m| m[j])
}

/// `E = fac·M − J` factorised.
#[derive(Clone)]
pub enum RealSystem {
    /// `decsol.f`'s DEC.
    Dense(DenseLu),
    /// faer's sparse LU, with the entries being factorised as scratch.
    Sparse(Box<(FaerSparseLu, Vec<Entry>)>),
}

impl RealSystem {
    /// The factorisation for order `n` and a Jacobian of `nnz` stored entries.
    pub fn for_size(n: usize, nnz: usize) -> Self {
        if is_sparse(n, nnz) {
            RealSystem::Sparse(Box::default())
        } else {
            RealSystem::Dense(DenseLu::default())
        }
    }

    /// Whether this is the factorisation [`RealSystem::for_size`] chooses for `n`, `nnz`.
    pub fn suits(&self, n: usize, nnz: usize) -> bool {
        is_sparse(n, nnz) == matches!(self, RealSystem::Sparse(_))
    }

    /// Factorises `fac·M − J` for the Jacobian `jac` of order `n` (entries summed); `false`
    /// when it is singular. Dense: DECOMR's `E1(I,J) = −FJAC(I,J)`, then `E1(J,J) += FAC1`
    /// (`FMAS(J,J)·FAC1` with a mass matrix).
    pub fn factor(&mut self, n: usize, jac: &[Entry], mass: Option<&[f64]>, fac: f64) -> bool {
        match self {
            RealSystem::Dense(lu) => {
                let e = lu.matrix(n);
                for &(i, j, v) in jac {
                    e[i + j * n] -= v;
                }
                for j in 0..n {
                    e[j + j * n] += mass_at(mass, j) * fac;
                }
                lu.factor()
            }
            RealSystem::Sparse(sparse) => {
                let (lu, entries) = &mut **sparse;
                entries.clear();
                entries.extend(jac.iter().map(|&(i, j, v)| (i, j, -v)));
                entries.extend((0..n).map(|j| (j, j, mass_at(mass, j) * fac)));
                lu.factor(n, entries)
            }
        }
    }

    /// Overwrites `b` with `E⁻¹·b`. A singular matrix that pivoting did not reveal leaves
    /// non-finite values, which the method's error norm then reports.
    pub fn solve(&mut self, b: &mut [f64]) {
        match self {
            RealSystem::Dense(lu) => lu.solve(b),
            RealSystem::Sparse(sparse) => {
                sparse.0.solve(b);
            }
        }
    }
}

/// `E2 = (alphn + i·betan)·M − J` factorised.
#[derive(Clone)]
pub enum ComplexSystem {
    /// `decsol.f`'s DECC.
    Dense(DenseComplexLu),
    /// faer's sparse LU of the real form, unknowns (re₀, im₀, re₁, im₁, …), with the
    /// entries being factorised and an interleaved right-hand side as scratch.
    Sparse(Box<(FaerSparseLu, Vec<Entry>, Vec<f64>)>),
}

impl ComplexSystem {
    /// The factorisation for order `n` and a Jacobian of `nnz` stored entries.
    pub fn for_size(n: usize, nnz: usize) -> Self {
        if is_sparse(n, nnz) {
            ComplexSystem::Sparse(Box::default())
        } else {
            ComplexSystem::Dense(DenseComplexLu::default())
        }
    }

    /// Factorises E2 for the Jacobian `jac` of order `n`; `false` when it is singular.
    /// Dense: DECOMC's `E2R(I,J) = −FJAC(I,J)`, then `E2R(J,J) += ALPHN`, `E2I(J,J) = BETAN`.
    pub fn factor(
        &mut self,
        n: usize,
        jac: &[Entry],
        mass: Option<&[f64]>,
        (alphn, betan): (f64, f64),
    ) -> bool {
        match self {
            ComplexSystem::Dense(lu) => {
                let (e2r, e2i) = lu.matrix(n);
                for &(i, j, v) in jac {
                    e2r[i + j * n] -= v;
                }
                for j in 0..n {
                    e2r[j + j * n] += mass_at(mass, j) * alphn;
                    e2i[j + j * n] = mass_at(mass, j) * betan;
                }
                lu.factor()
            }
            ComplexSystem::Sparse(sparse) => {
                let (lu, entries, _) = &mut **sparse;
                entries.clear();
                for &(i, j, v) in jac {
                    entries.push((2 * i, 2 * j, -v));
                    entries.push((2 * i + 1, 2 * j + 1, -v));
                }
                for j in 0..n {
                    let (re, im) = (mass_at(mass, j) * alphn, mass_at(mass, j) * betan);
                    entries.extend([
                        (2 * j, 2 * j, re),
                        (2 * j + 1, 2 * j + 1, re),
                        (2 * j, 2 * j + 1, -im),
                        (2 * j + 1, 2 * j, im),
                    ]);
                }
                lu.factor(2 * n, entries)
            }
        }
    }

    /// Overwrites `(br, bi)` with `E2⁻¹·(br + i·bi)`.
    pub fn solve(&mut self, br: &mut [f64], bi: &mut [f64]) {
        match self {
            ComplexSystem::Dense(lu) => lu.solve(br, bi),
            ComplexSystem::Sparse(sparse) => {
                let (lu, _, rhs) = &mut **sparse;
                rhs.clear();
                rhs.extend(br.iter().zip(bi.iter()).flat_map(|(r, i)| [*r, *i]));
                lu.solve(rhs);
                for (k, pair) in rhs.chunks_exact(2).enumerate() {
                    br[k] = pair[0];
                    bi[k] = pair[1];
                }
            }
        }
    }
}

/// The factorised pair E1, E2 of a Radau IIA(5) step.
#[derive(Clone)]
pub struct RadauSystems {
    /// E1 = (γ/h)·M − J.
    pub real: RealSystem,
    /// E2 = ((α + iβ)/h)·M − J.
    pub complex: ComplexSystem,
}

impl RadauSystems {
    /// The factorisations for order `n` and a Jacobian of `nnz` stored entries.
    pub fn for_size(n: usize, nnz: usize) -> Self {
        RadauSystems {
            real: RealSystem::for_size(n, nnz),
            complex: ComplexSystem::for_size(n, nnz),
        }
    }

    /// Factorises E1 = fac1·M − J and E2 = (alphn + i·betan)·M − J; `false` when either is
    /// singular. The factorisations are chosen anew when the Jacobian's fill changes between
    /// dense and sparse.
    pub fn factor(
        &mut self,
        n: usize,
        jac: &[Entry],
        mass: Option<&[f64]>,
        (fac1, alphn, betan): (f64, f64, f64),
    ) -> bool {
        if !self.real.suits(n, jac.len()) {
            *self = RadauSystems::for_size(n, jac.len());
        }
        self.real.factor(n, jac, mass, fac1) && self.complex.factor(n, jac, mass, (alphn, betan))
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
        let mut sparse = RadauSystems::for_size(n, jac.len());
        assert!(matches!(sparse.real, RealSystem::Sparse(_)));
        assert!(matches!(sparse.complex, ComplexSystem::Sparse(_)));
        let mut dense = RadauSystems {
            real: RealSystem::Dense(DenseLu::default()),
            complex: ComplexSystem::Dense(DenseComplexLu::default()),
        };
        assert!(!dense.real.suits(n, jac.len()));
        for s in [&mut sparse, &mut dense] {
            // Factorised directly, so that the dense pair is kept for the comparison.
            assert!(s.real.factor(n, &jac, Some(&mass), 3.6));
            assert!(s.complex.factor(n, &jac, Some(&mass), (2.7, 1.5)));
        }
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
        let c: Vec<f64> = (0..n).map(|i| (i as f64 * 0.11).cos()).collect();
        let (mut x1, mut x2) = (b.clone(), b.clone());
        sparse.real.solve(&mut x1);
        dense.real.solve(&mut x2);
        let (mut r1, mut i1, mut r2, mut i2) = (b.clone(), c.clone(), b.clone(), c.clone());
        sparse.complex.solve(&mut r1, &mut i1);
        dense.complex.solve(&mut r2, &mut i2);
        for (a, b) in [(&x1, &x2), (&r1, &r2), (&i1, &i2)] {
            for (u, v) in a.iter().zip(b.iter()) {
                assert!((u - v).abs() < 1e-12 * (1.0 + v.abs()), "{u} vs {v}");
            }
        }
    }
}
