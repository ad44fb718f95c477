//! Linear stability of a fixed step: whether `h·λ` lies in an explicit method's region of
//! absolute stability `|R(z)| ≤ 1` for every eigenvalue λ of the problem's Jacobian at a state
//! (Hairer & Wanner, *Solving ODEs II*, §IV.2). An explicit Runge–Kutta method applied to
//! `y' = λy` multiplies the solution by its stability polynomial `R(hλ)` each step: where
//! `|R(hλ)| > 1` for a decaying mode, the numerical mode grows instead.

use crate::problem::{Entry, Mode, OdeProblem};
use nalgebra::DMatrix;
use serde::Serialize;

/// The stability polynomial of the classical fourth-order Runge–Kutta method,
/// `R(z) = 1 + z + z²/2 + z³/6 + z⁴/24` (Hairer & Wanner II, §IV.2, eq. (2.4)): its interval
/// on the negative real axis reaches −2.785, on the imaginary axis ±2.828.
pub const RK4_POLYNOMIAL: [f64; 5] = [1.0, 1.0, 0.5, 1.0 / 6.0, 1.0 / 24.0];

/// The stability polynomial of Dormand–Prince 5(4)'s fifth-order solution (seven stages),
/// `R(z) = Σ_{k≤5} z^k/k! + z⁶/600` (Hairer & Wanner II, §IV.2, the one of DOPRI5): its
/// interval on the negative real axis reaches −3.307.
pub const DOPRI5_POLYNOMIAL: [f64; 7] = [
    1.0,
    1.0,
    0.5,
    1.0 / 6.0,
    1.0 / 24.0,
    1.0 / 120.0,
    1.0 / 600.0,
];

/// The largest system whose eigenvalues are computed (a dense Schur decomposition, O(n³)):
/// above it the check is not made.
pub const MAX_CHECKED_DIM: usize = 400;

/// The most iterations of the Schur decomposition before a state's check is given up.
const SCHUR_ITERATIONS: usize = 10_000;

/// The most operations (n³ per state) a run's check spends: a run of n unknowns is checked at
/// `max(1, CHECK_BUDGET / n³)` of its recorded states, evenly spread (every state of a rig; 11
/// of a 100-block chain).
pub const CHECK_BUDGET: usize = 100_000_000;

/// A fixed step that makes a mode grow which the exact flow does not: an explicit method's
/// step beyond its stability limit ([`unstable_mode`]), or a time-stepping scheme's sampled
/// loop ([`sampled_loop_mode`]). Either makes a run at least `inaccurate`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Instability {
    /// A decaying mode of the Jacobian that an explicit method's step amplifies.
    Explicit(AmplifiedMode),
    /// A growing mode of a time-stepping scheme's one-step map where the continuous system
    /// has none.
    SampledLoop(SampledLoop),
}

impl Instability {
    /// The factor the mode grows by each step: |R(hλ)| or |μ|.
    pub fn amplification(&self) -> f64 {
        match self {
            Instability::Explicit(m) => m.amplification,
            Instability::SampledLoop(m) => m.amplification,
        }
    }
}

impl std::fmt::Display for Instability {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Instability::Explicit(m) => m.fmt(f),
            Instability::SampledLoop(m) => m.fmt(f),
        }
    }
}

/// A decaying mode that a fixed step amplifies.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct AmplifiedMode {
    /// The eigenvalue λ of the Jacobian, 1/s: real part.
    pub lambda_re: f64,
    /// Its imaginary part, 1/s.
    pub lambda_im: f64,
    /// The step, s.
    pub h: f64,
    /// The time of the state whose Jacobian has the mode, s.
    pub t: f64,
    /// |R(h·λ)| > 1: the factor the mode grows by each step.
    pub amplification: f64,
}

impl std::fmt::Display for AmplifiedMode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the fixed step h = {} s is beyond the method's stability limit: |R(hλ)| = {:.3} > 1 \
             for the decaying mode λ = {} 1/s of the Jacobian at t = {} s (|hλ| = {:.3})",
            self.h,
            self.amplification,
            complex(self.lambda_re, self.lambda_im),
            self.t,
            self.h * self.lambda_re.hypot(self.lambda_im)
        )
    }
}

/// The growth per step of a sampled loop beyond which [`sampled_loop_mode`] calls it unstable:
/// a multiplier |μ| > 1 + this. Finite differences of a map with a double multiplier 1 (a free
/// body's position and velocity, a Jordan block) split it by about the square root of their
/// relative error, 1e-4 at most here.
pub const SAMPLED_GROWTH_MARGIN: f64 = 1e-3;

/// A mode of a time-stepping scheme's one-step map `y_{k+1} = Φ(y_k)` that grows, |μ| > 1,
/// where every mode of the continuous system's Jacobian decays or is neutral (Re λ ≤ 0): the
/// controllers' forces, held over each step (a zero-order hold), close a sampled loop that the
/// step destabilises.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SampledLoop {
    /// The multiplier μ of the one-step map's Jacobian: real part.
    pub multiplier_re: f64,
    /// Its imaginary part.
    pub multiplier_im: f64,
    /// The largest real part of the continuous Jacobian's eigenvalues, 1/s (≤ 0).
    pub abscissa: f64,
    /// The step, s.
    pub h: f64,
    /// The time of the state the map is taken at, s.
    pub t: f64,
    /// |μ| > 1: the factor the mode grows by each step.
    pub amplification: f64,
}

impl std::fmt::Display for SampledLoop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the fixed step h = {} s is beyond the sampled loop's stability limit: with each \
             force held over the step (zero-order hold), the step map at t = {} s has the \
             multiplier μ = {} (|μ| = {:.3} > 1) where every mode of the continuous system \
             decays or is neutral (largest Re λ = {:.4} 1/s)",
            self.h,
            self.t,
            complex(self.multiplier_re, self.multiplier_im),
            self.amplification,
            self.abscissa
        )
    }
}

/// `re ± im·i` at four decimals, `re` alone where `im` is 0.
fn complex(re: f64, im: f64) -> String {
    match im.abs() {
        0.0 => format!("{re:.4}"),
        im => format!("{re:.4} ± {im:.4}i"),
    }
}

/// |R(z)| for the polynomial `coefficients` (ascending powers) at z = re + i·im.
pub fn amplification(coefficients: &[f64], re: f64, im: f64) -> f64 {
    // Horner's scheme in complex arithmetic.
    let (mut a, mut b) = (0.0, 0.0);
    for &c in coefficients.iter().rev() {
        (a, b) = (a * re - b * im + c, a * im + b * re);
    }
    a.hypot(b)
}

/// The Jacobian of `problem` at (t, y) in `modes` over its unknowns other than the quadratures,
/// with the mass matrix divided out: analytic where the problem gives one, else forward
/// differences. `None` for a differential–algebraic problem (a zero on the mass diagonal).
pub fn jacobian(
    problem: &dyn OdeProblem,
    t: f64,
    y: &[f64],
    modes: &[Mode],
) -> Option<DMatrix<f64>> {
    let n = problem.dim() - problem.quadratures();
    let mut j = DMatrix::zeros(n, n);
    let mut entries: Vec<Entry> = Vec::new();
    if problem.jacobian(t, y, modes, &mut entries) {
        for (r, c, v) in entries {
            if r < n && c < n {
                j[(r, c)] += v;
            }
        }
    } else {
        let mut f0 = vec![0.0; y.len()];
        let mut f1 = vec![0.0; y.len()];
        problem.rhs(t, y, modes, &mut f0);
        let mut yd = y.to_vec();
        for c in 0..n {
            let delta = (1e-16 * y[c].abs().max(1e-5)).sqrt();
            yd[c] = y[c] + delta;
            problem.rhs(t, &yd, modes, &mut f1);
            yd[c] = y[c];
            for r in 0..n {
                j[(r, c)] = (f1[r] - f0[r]) / delta;
            }
        }
    }
    if let Some(m) = problem.mass() {
        for (r, &mass) in m.iter().take(n).enumerate() {
            if mass == 0.0 {
                return None;
            }
            j.row_mut(r).scale_mut(1.0 / mass);
        }
    }
    Some(j)
}

/// The largest system whose spectral radius [`spectral_radius`] takes from all its
/// eigenvalues (a dense Schur decomposition, about 10·n³ operations); above it, by
/// [`crate::power`] iteration.
pub const EXACT_RADIUS_DIM: usize = 100;

/// The fewest points at which a run's stiffness is measured, whatever its size (all of them
/// where it has fewer): [`radius_cost`] against [`CHECK_BUDGET`] may allow more.
pub const MIN_STIFFNESS_POINTS: usize = 21;

/// The operations [`spectral_radius`] spends on a system of `n` unknowns: about 10·n³ for the
/// Schur decomposition, `14·POWER_ITERATIONS·n` for power iteration (a sparse Jacobian of a
/// few entries a row).
pub fn radius_cost(n: usize) -> usize {
    if n <= EXACT_RADIUS_DIM {
        10 * n.pow(3)
    } else {
        14 * crate::power::POWER_ITERATIONS * n
    }
}

/// The spectral radius `ρ = max |λ|` of the Jacobian of `problem` at (t, y) in `modes` (over
/// its unknowns other than the quadratures, the mass matrix divided out): `h·ρ` against a
/// method's stability boundary says how stiff a step of size h is (Hairer & Wanner, *Solving
/// ODEs II*, sec. IV.2). Up to [`EXACT_RADIUS_DIM`] unknowns from its eigenvalues (Schur);
/// above, [`crate::power::spectral_radius_estimate`], by power iteration. `None` for a
/// differential–algebraic problem, a non-finite Jacobian and an iteration that does not
/// converge.
pub fn spectral_radius(problem: &dyn OdeProblem, t: f64, y: &[f64], modes: &[Mode]) -> Option<f64> {
    if problem.dim() - problem.quadratures() > EXACT_RADIUS_DIM {
        return crate::power::spectral_radius_estimate(problem, t, y, modes);
    }
    exact_spectral_radius(problem, t, y, modes)
}

/// [`spectral_radius`] from all the eigenvalues of the dense Jacobian (Schur), whatever the
/// size: about 10·n³ operations.
pub fn exact_spectral_radius(
    problem: &dyn OdeProblem,
    t: f64,
    y: &[f64],
    modes: &[Mode],
) -> Option<f64> {
    let lambdas = eigenvalues(jacobian(problem, t, y, modes)?)?;
    Some(lambdas.iter().map(|l| l.norm()).fold(0.0, f64::max))
}

/// The decaying mode of `problem` at (t, y) in `modes` that the fixed step `h` of the explicit
/// method with stability polynomial `coefficients` amplifies most, if any: over the
/// eigenvalues λ of the Jacobian with Re λ ≤ 0, the largest `|R(hλ)|` above 1 — a mode the
/// exact flow damps (a spring, a steep regularised slope) that the step makes grow. A growing
/// mode (a Stribeck slope's negative damping) grows in the exact solution too: it is not
/// judged here but by the run's energy balance and its error. `None` where no decaying mode is
/// amplified, for a differential–algebraic problem, and above [`MAX_CHECKED_DIM`] unknowns.
pub fn unstable_mode(
    problem: &dyn OdeProblem,
    t: f64,
    y: &[f64],
    modes: &[Mode],
    h: f64,
    coefficients: &[f64],
) -> Option<Instability> {
    if problem.dim() > MAX_CHECKED_DIM {
        return None;
    }
    // A mode is decaying (or neutral) when its real part is not positive beyond round-off of
    // its size. The Schur iteration is bounded: a state that has left every scale (a diverged
    // run) may give a matrix on which it would not converge.
    let decaying = |re: f64, im: f64| re <= 1e-12 * re.hypot(im);
    (eigenvalues(jacobian(problem, t, y, modes)?)?.iter())
        .filter(|l| decaying(l.re, l.im))
        .map(|l| AmplifiedMode {
            lambda_re: l.re,
            lambda_im: l.im,
            h,
            t,
            amplification: amplification(coefficients, h * l.re, h * l.im),
        })
        .filter(|i| i.amplification > 1.0 + 1e-9)
        .max_by(|a, b| a.amplification.total_cmp(&b.amplification))
        .map(Instability::Explicit)
}

/// The growing mode of a fixed-step scheme's one-step map `step` (from (t, y) in `modes` to
/// the end of a step h) where the continuous system has none, if any: with Φ the forward
/// difference Jacobian of `step` over the unknowns other than the quadratures and α the
/// largest real part of the eigenvalues of the continuous Jacobian there, the multiplier μ of
/// Φ of largest modulus when α ≤ 0 and |μ| > 1 + [`SAMPLED_GROWTH_MARGIN`]. The exact flow
/// changes each mode by e^{hλ} over a step, at most 1 in modulus when α ≤ 0; a scheme that
/// holds a force over the step (a controller under zero-order hold) may not. Where the
/// continuous system has a growing mode (a Stribeck slope's negative damping) nothing is
/// judged here. `None` also where `step` fails, for a differential–algebraic problem and above
/// [`MAX_CHECKED_DIM`] unknowns.
pub fn sampled_loop_mode(
    problem: &dyn OdeProblem,
    (t, h): (f64, f64),
    y: &[f64],
    modes: &[Mode],
    step: &mut dyn FnMut(&[f64]) -> Option<Vec<f64>>,
) -> Option<Instability> {
    if problem.dim() > MAX_CHECKED_DIM {
        return None;
    }
    let lambdas = eigenvalues(jacobian(problem, t, y, modes)?)?;
    let radius = lambdas.iter().map(|l| l.norm()).fold(0.0, f64::max);
    let abscissa = lambdas
        .iter()
        .map(|l| l.re)
        .fold(f64::NEG_INFINITY, f64::max);
    // Growing beyond round-off of the largest eigenvalue's size.
    if abscissa > 1e-12 * radius {
        return None;
    }
    let n = problem.dim() - problem.quadratures();
    let end = step(y)?;
    let mut map = DMatrix::zeros(n, n);
    let mut yd = y.to_vec();
    for c in 0..n {
        // A relative perturbation, floored where the unknown is near zero: the map is
        // piecewise linear in a friction system (linear while no contact switches), so the
        // difference is exact but for the step's own solver tolerance.
        let delta = FD_STEP * y[c].abs().max(FD_FLOOR);
        yd[c] = y[c] + delta;
        let moved = step(&yd)?;
        yd[c] = y[c];
        for r in 0..n {
            map[(r, c)] = (moved[r] - end[r]) / delta;
        }
    }
    let mu = eigenvalues(map)?
        .into_iter()
        .max_by(|a, b| a.norm().total_cmp(&b.norm()))?;
    (mu.norm() > 1.0 + SAMPLED_GROWTH_MARGIN).then_some(Instability::SampledLoop(SampledLoop {
        multiplier_re: mu.re,
        multiplier_im: mu.im,
        abscissa,
        h,
        t,
        amplification: mu.norm(),
    }))
}

/// The relative perturbation of [`sampled_loop_mode`]'s forward differences.
const FD_STEP: f64 = 1e-7;

/// The smallest perturbation of [`sampled_loop_mode`]'s forward differences, in the unknown's
/// units, over [`FD_STEP`].
const FD_FLOOR: f64 = 1e-3;

/// The eigenvalues of `j` (Schur, at most [`SCHUR_ITERATIONS`]); `None` for a matrix with a
/// non-finite entry or on which the iteration does not converge.
fn eigenvalues(j: DMatrix<f64>) -> Option<Vec<nalgebra::Complex<f64>>> {
    if !j.iter().all(|v| v.is_finite()) {
        return None;
    }
    let schur = nalgebra::linalg::Schur::try_new(j, f64::EPSILON, SCHUR_ITERATIONS)?;
    Some(schur.complex_eigenvalues().iter().copied().collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Where |R| crosses 1 along a ray from 0, by bisection.
    fn limit(coefficients: &[f64], re: f64, im: f64) -> f64 {
        let (mut lo, mut hi) = (0.1, 10.0);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if amplification(coefficients, mid * re, mid * im) > 1.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        lo
    }

    #[test]
    fn the_stability_intervals_are_hairers() {
        // Hairer & Wanner II, Table IV.2.1 and Fig. IV.2.1: RK4 reaches −2.785 on the real
        // axis and ±2√2 on the imaginary one; DOPRI5 reaches −3.307.
        assert!((limit(&RK4_POLYNOMIAL, -1.0, 0.0) - 2.785).abs() < 1e-3);
        assert!((limit(&RK4_POLYNOMIAL, 0.0, 1.0) - 8f64.sqrt()).abs() < 1e-9);
        assert!((limit(&DOPRI5_POLYNOMIAL, -1.0, 0.0) - 3.307).abs() < 1e-3);
    }
}
