//! The spectral radius of a Jacobian too large for its eigenvalues, estimated by power
//! iteration through Gelfand's formula ρ = lim ‖J^k‖^(1/k): the sequence
//! `x_{k+1} = J·x_k/‖J·x_k‖` from a fixed start vector, and the geometric mean of its growth
//! factors ‖J·x_k‖ over its last [`MEASURED`] of [`POWER_ITERATIONS`] steps. Once the start
//! vector's other components have died out, ‖J^k·x‖ grows as ρ^k times a bounded factor, so the
//! mean converges to ρ whatever the dominant eigenvalues are: one real, a complex pair (a
//! spring's ±iω, on which the ratio ‖J·x‖/‖x‖ of one step oscillates for ever), or a cluster of
//! nearly equal moduli (a chain's top modes). Projections (Arnoldi's Ritz values, a
//! Rayleigh–Ritz block) strayed beyond the spectrum of friction systems' Jacobians, which stuck
//! bodies make far from normal; this mean stays within a few per cent of it (tests
//! `the_power_estimate_of_a_large_spectral_radius` in integrators,
//! `the_stiffness_of_a_large_chain_is_its_spectral_radius` in friction-systems).

use crate::problem::{Entry, Mode, OdeProblem};

/// The iterations of [`spectral_radius_estimate`], each one product J·v and one inner product
/// of length n: about `POWER_ITERATIONS·(2·nnz + 4·n)` operations in all.
pub const POWER_ITERATIONS: usize = 400;

/// The last iterations whose growth factors' geometric mean is the estimate: those before
/// bring the vector onto the dominant eigenvalues' space.
pub const MEASURED: usize = 200;

/// The products `v ↦ M⁻¹·J·v` over a problem's unknowns other than its quadratures.
enum Product<'a> {
    /// From the problem's sparse Jacobian.
    Sparse(Vec<Entry>),
    /// By forward differences of f from `f0 = f(t, y)`, a step δ·v of `delta` = √ε·(1 + ‖y‖)
    /// relative to ‖v‖.
    Differences {
        problem: &'a dyn OdeProblem,
        t: f64,
        y: &'a [f64],
        modes: &'a [Mode],
        f0: Vec<f64>,
        delta: f64,
    },
}

impl Product<'_> {
    /// `out = J·v` (before the mass matrix is divided out).
    fn apply(&self, v: &[f64], out: &mut [f64]) {
        let n = out.len();
        match self {
            Product::Sparse(entries) => {
                out.fill(0.0);
                for &(r, c, value) in entries {
                    if r < n && c < n {
                        out[r] += value * v[c];
                    }
                }
            }
            Product::Differences {
                problem,
                t,
                y,
                modes,
                f0,
                delta,
            } => {
                let delta = delta / dot(v, v).sqrt().max(f64::MIN_POSITIVE);
                let mut yd = y.to_vec();
                for (yi, vi) in yd.iter_mut().zip(v) {
                    *yi += delta * vi;
                }
                let mut f1 = vec![0.0; y.len()];
                problem.rhs(*t, &yd, modes, &mut f1);
                for r in 0..n {
                    out[r] = (f1[r] - f0[r]) / delta;
                }
            }
        }
    }
}

/// A start vector: deterministic, with every component non-zero and no structure a Jacobian
/// could be blind to (a linear congruential sequence in [−1, 1) from `seed`, normalised).
fn start_vector(n: usize, seed: u64) -> Vec<f64> {
    let mut state: u64 = 0x2545_f491_4f6c_dd1d ^ seed;
    let mut v: Vec<f64> = (0..n)
        .map(|_| {
            // Knuth's MMIX multiplier and increment.
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        })
        .collect();
    let norm = dot(&v, &v).sqrt();
    v.iter_mut().for_each(|x| *x /= norm);
    v
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// An estimate of the spectral radius ρ = max |λ| of the Jacobian of `problem` at (t, y) in
/// `modes` over its unknowns other than the quadratures, the mass matrix divided out, by power
/// iteration (see the module), on the problem's sparse Jacobian where it gives one, else on
/// forward differences of f. 0 for a nilpotent Jacobian (every body stuck). `None` for a
/// differential–algebraic problem (a zero on the mass diagonal) or a non-finite product.
pub fn spectral_radius_estimate(
    problem: &dyn OdeProblem,
    t: f64,
    y: &[f64],
    modes: &[Mode],
) -> Option<f64> {
    let n = problem.dim() - problem.quadratures();
    if n == 0 {
        return Some(0.0);
    }
    let mass = problem.mass().map(|m| m[..n].to_vec());
    if mass.as_ref().is_some_and(|m| m.contains(&0.0)) {
        return None;
    }
    let mut entries = Vec::new();
    let product = if problem.jacobian(t, y, modes, &mut entries) {
        Product::Sparse(entries)
    } else {
        let mut f0 = vec![0.0; y.len()];
        problem.rhs(t, y, modes, &mut f0);
        Product::Differences {
            problem,
            t,
            y,
            modes,
            f0,
            delta: f64::EPSILON.sqrt() * (1.0 + dot(y, y).sqrt()),
        }
    };
    // The product's argument: the vector, with the quadratures (which no f reads) held.
    let mut argument = vec![0.0; y.len()];
    let mut apply = |x: &[f64], out: &mut [f64]| -> Option<()> {
        argument[..n].copy_from_slice(x);
        product.apply(&argument, out);
        if let Some(mass) = &mass {
            out.iter_mut().zip(mass).for_each(|(o, m)| *o /= m);
        }
        out.iter().all(|o| o.is_finite()).then_some(())
    };
    // x_{k+1} = J·x_k/‖J·x_k‖: ‖J·x_k‖ is the growth of step k.
    let mut x = start_vector(n, 0);
    let mut jx = vec![0.0; n];
    let mut log_growth = 0.0;
    for k in 0..POWER_ITERATIONS {
        apply(&x, &mut jx)?;
        let growth = dot(&jx, &jx).sqrt();
        if growth == 0.0 {
            return Some(0.0);
        }
        if k >= POWER_ITERATIONS - MEASURED {
            log_growth += growth.ln();
        }
        x.iter_mut().zip(&jx).for_each(|(xi, ji)| *xi = ji / growth);
    }
    Some((log_growth / MEASURED as f64).exp())
}
