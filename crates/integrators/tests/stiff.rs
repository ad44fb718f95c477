//! What Radau IIA(5) and RODAS must both do beyond their parity runs: locate events on their
//! dense output, integrate an index-1 DAE through a singular mass matrix, keep a stiff
//! component's accuracy and follow the tolerance on a smooth one (quadratures included), go
//! through the sparse LU on a large sparse system, and refuse a fixed step.

mod common;

use approx::assert_relative_eq;
use common::{Heat, Oscillator, ProtheroRobinson, RobertsonDae};
use integrators::radau5::Radau5Method;
use integrators::rodas::RodasMethod;
use integrators::testset::Robertson;
use integrators::{Control, Crossing, Entry, Mode, OdeProblem, OneStepMethod, Options, Solution};

/// The two methods, each with the accuracy its stiff component keeps on Prothero–Robinson.
const METHODS: [(&dyn OneStepMethod, f64); 2] = [(&Radau5Method, 1e-9), (&RodasMethod, 1e-8)];

fn solve(method: &dyn OneStepMethod, problem: &dyn OdeProblem, y0: &[f64], o: Options) -> Solution {
    method
        .solve_observed(problem, y0, &[Mode(0)], o, &mut |_| {})
        .unwrap()
}

#[test]
fn events_are_located_on_the_dense_output() {
    // x = cos t crosses zero falling at π/2: located to 1e-10 at tolerance 1e-12, and Stop
    // ends the run there.
    let p = Oscillator::watching(Crossing::Falling, Control::Stop);
    for (method, _) in METHODS {
        let s = solve(
            method,
            &p,
            &[1.0, 0.0],
            Options::adaptive(0.0, 3.0, 1e-12, 1e-12),
        );
        assert_eq!(s.events.len(), 1, "{}", method.name());
        let t = s.events[0].t;
        assert!(
            (t - std::f64::consts::FRAC_PI_2).abs() < 1e-10,
            "{}: {t}",
            method.name()
        );
        assert_eq!(s.last().unwrap().0, t, "{}", method.name());
    }
}

#[test]
fn an_index_one_dae_is_integrated_through_its_singular_mass_matrix() {
    // Robertson with its conservation law as the third equation: the algebraic equation
    // holds at every step, the DAE follows the ODE, and y1(40) = 0.7158270687 (Hairer &
    // Wanner, sec. IV.10).
    let o = || Options::adaptive(0.0, 40.0, 1e-8, 1e-12);
    for (method, _) in METHODS {
        let dae = solve(method, &RobertsonDae, &[1.0, 0.0, 0.0], o());
        let ode = solve(method, &Robertson, &[1.0, 0.0, 0.0], o());
        for i in 0..dae.len() {
            let sum: f64 = dae.y_at(i).iter().sum();
            assert!(
                (sum - 1.0).abs() < 1e-13,
                "{} step {i}: {sum}",
                method.name()
            );
        }
        let (y, z) = (dae.last().unwrap().1, ode.last().unwrap().1);
        for (a, b) in y.iter().zip(z) {
            assert_relative_eq!(*a, *b, max_relative = 1e-6);
        }
        assert_relative_eq!(y[0], 0.7158270687, max_relative = 1e-7);
    }
}

#[test]
fn the_error_follows_the_tolerance_on_a_stiff_problem() {
    // Prothero–Robinson depends on t. Its stiff component is slaved to sin t: both methods are
    // stiffly accurate, so its end value keeps its accuracy at every tolerance (no order
    // reduction at the step's end: Hairer & Wanner, sec. IV.15). The quadrature is the
    // smooth part the error control must follow: its error at t = 10 stays within the
    // tolerance and falls with it. References: sin 10 and 1 − cos 10.
    for (method, stiff_accuracy) in METHODS {
        let mut previous = f64::INFINITY;
        for tol in [1e-4, 1e-6, 1e-8, 1e-10] {
            let o = Options::adaptive(0.0, 10.0, tol, tol);
            let y = solve(method, &ProtheroRobinson, &[0.0, 0.0], o)
                .last()
                .unwrap()
                .1
                .to_vec();
            let stiff = (y[0] - 10f64.sin()).abs();
            assert!(
                stiff < stiff_accuracy,
                "{} tol {tol}: stiff {stiff:e}",
                method.name()
            );
            let smooth = (y[1] - (1.0 - 10f64.cos())).abs();
            assert!(
                smooth < tol,
                "{} tol {tol}: quadrature {smooth:e}",
                method.name()
            );
            assert!(
                smooth < previous / 10.0,
                "{} tol {tol}: {smooth:e}",
                method.name()
            );
            previous = smooth;
        }
    }
}

#[test]
fn a_sparse_stiff_system_goes_through_the_sparse_lu() {
    // 400 unknowns, 1198 Jacobian entries: faer's sparse LU (Radau's complex system as a real
    // one of order 800). The first sine mode decays as exp(λ₁t), λ₁ = −4k·sin²(π/(2(n+1)));
    // the stiffest mode's h·λ reaches −4k·h ≈ −1e4.
    let (n, k) = (400, 1e4);
    let u0: Vec<f64> = (1..=n)
        .map(|i| (std::f64::consts::PI * i as f64 / (n + 1) as f64).sin())
        .collect();
    let lambda = -4.0 * k * (std::f64::consts::PI / (2 * (n + 1)) as f64).sin().powi(2);
    for (method, _) in METHODS {
        let s = solve(
            method,
            &Heat { n, k },
            &u0,
            Options::adaptive(0.0, 1.0, 1e-8, 1e-10),
        );
        for (got, start) in s.last().unwrap().1.iter().zip(&u0) {
            let want = start * lambda.exp();
            assert!(
                (got - want).abs() < 1e-8,
                "{}: {got} vs {want}",
                method.name()
            );
        }
        assert_eq!(s.stats.matrix_order, n);
    }
}

#[test]
fn a_fixed_step_is_refused_with_the_reason() {
    for (method, _) in METHODS {
        let f = method
            .solve_observed(
                &Robertson,
                &[1.0, 0.0, 0.0],
                &[Mode(0)],
                Options::fixed(0.0, 1.0, 1e-3),
                &mut |_| {},
            )
            .unwrap_err();
        assert_eq!(
            f.error.to_string(),
            format!(
                "{} cannot integrate this problem: it takes adaptive steps only: give \
                 tolerances, not a fixed step",
                method.name()
            )
        );
    }
}

#[test]
fn the_spectral_radius_is_the_largest_eigenvalue_modulus() {
    // The heat equation on 3 points, k = 1: eigenvalues −4·sin²(jπ/8), j = 1..3; the largest
    // modulus is 4·sin²(3π/8) = 2 + √2.
    let rho = integrators::stability::spectral_radius(&Heat { n: 3, k: 1.0 }, 0.0, &[0.0; 3], &[])
        .unwrap();
    assert!((rho - (2.0 + 2f64.sqrt())).abs() < 1e-12, "{rho}");
    // An index-1 DAE has no ODE Jacobian to measure.
    let dae = integrators::stability::spectral_radius(&RobertsonDae, 0.0, &[1.0, 0.0, 0.0], &[]);
    assert_eq!(dae, None);
}

/// A chain of `n` unit masses between unit springs, fixed at both ends, with dampers `c`
/// to the ground: x' = v, v' = −K·x − c·v, K the tridiagonal (−1, 2, −1). Each eigenvalue μ
/// of K gives λ = (−c ± √(c² − 4μ))/2, so |λ| = √μ for c² < 4μ: ρ = √(4·sin²(nπ/(2(n + 1)))),
/// the top of a clustered spectrum of complex pairs, where plain power iteration never
/// settles. With `analytic` false it gives no Jacobian (the products are differences).
struct SpringChain {
    n: usize,
    c: f64,
    analytic: bool,
}

impl OdeProblem for SpringChain {
    fn dim(&self) -> usize {
        2 * self.n
    }
    fn rhs(&self, _t: f64, y: &[f64], _m: &[Mode], f: &mut [f64]) {
        let (x, v) = y.split_at(self.n);
        for i in 0..self.n {
            let left = if i > 0 { x[i - 1] } else { 0.0 };
            let right = if i + 1 < self.n { x[i + 1] } else { 0.0 };
            f[i] = v[i];
            f[self.n + i] = left - 2.0 * x[i] + right - self.c * v[i];
        }
    }
    fn jacobian(&self, _t: f64, _y: &[f64], _m: &[Mode], jac: &mut Vec<Entry>) -> bool {
        if !self.analytic {
            return false;
        }
        let n = self.n;
        for i in 0..n {
            jac.push((i, n + i, 1.0));
            jac.push((n + i, i, -2.0));
            jac.push((n + i, n + i, -self.c));
            if i > 0 {
                jac.push((n + i, i - 1, 1.0));
            }
            if i + 1 < n {
                jac.push((n + i, i + 1, 1.0));
            }
        }
        true
    }
}

#[test]
fn the_power_estimate_of_a_large_spectral_radius() {
    use integrators::power::spectral_radius_estimate;
    use integrators::stability::{spectral_radius, EXACT_RADIUS_DIM};
    // sin² of the top mode's angle, nπ/(2(n + 1)).
    let top = |n: usize| {
        (n as f64 * std::f64::consts::PI / (2.0 * (n + 1) as f64))
            .sin()
            .powi(2)
    };
    for n in [150, 1000, 10_000] {
        let y = vec![0.0; 2 * n];
        let chain = SpringChain {
            n,
            c: 0.1,
            analytic: true,
        };
        let rho = (4.0 * top(n)).sqrt();
        let estimate = spectral_radius_estimate(&chain, 0.0, &y, &[]).unwrap();
        // On the clustered top of the spectrum (printed, for docs/solvers.md).
        println!(
            "spring chain of {n}: estimate/rho - 1 = {:.1e}",
            estimate / rho - 1.0
        );
        assert!(
            (estimate / rho - 1.0).abs() < 5e-3,
            "n = {n}: {estimate} against {rho}"
        );
        // Above EXACT_RADIUS_DIM unknowns the spectral radius is the estimate.
        assert!(2 * n > EXACT_RADIUS_DIM);
        assert_eq!(spectral_radius(&chain, 0.0, &y, &[]), Some(estimate));
        // Without a Jacobian, the products by differences give the same estimate.
        let differences = SpringChain {
            analytic: false,
            ..chain
        };
        let by_differences = spectral_radius_estimate(&differences, 0.0, &y, &[]).unwrap();
        assert_relative_eq!(by_differences, estimate, max_relative = 1e-6);
        // A symmetric spectrum (the heat equation's, ρ = 4·sin²(…)): the same.
        let heat = spectral_radius_estimate(&Heat { n, k: 1.0 }, 0.0, &vec![0.0; n], &[]).unwrap();
        assert!(
            (heat / (4.0 * top(n)) - 1.0).abs() < 5e-3,
            "heat n = {n}: {heat}"
        );
    }
}
