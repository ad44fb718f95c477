//! Implicit Euler: order, stiffness, Newton variants and failures.

mod common;

use common::*;
use integrators::{
    ImplicitEuler, Integrator, Mode, NewtonKind, OdeProblem, Options, Rk4, Solution, SolverError,
    Stepper,
};

fn implicit_euler(o: &Options, newton: NewtonKind, dim: usize) -> Box<dyn Stepper> {
    Box::new(ImplicitEuler::new(
        o.step,
        newton,
        o.h_max(),
        o.max_steps,
        dim,
    ))
}

fn solve(
    p: &dyn OdeProblem,
    s: Box<dyn Stepper + '_>,
    y0: &[f64],
    o: Options,
) -> Result<Solution, integrators::Failure> {
    Integrator::new(p, s, y0, &[Mode(0)], o).unwrap().solve()
}

/// Prothero–Robinson: y' = λ(y − sin t) + cos t, y(0) = 0, exact y = sin t, λ = −1e6.
struct ProtheroRobinson;

impl OdeProblem for ProtheroRobinson {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&self, t: f64, y: &[f64], _m: &[Mode], f: &mut [f64]) {
        f[0] = -1e6 * (y[0] - t.sin()) + t.cos();
    }
    fn jacobian(
        &self,
        _t: f64,
        _y: &[f64],
        _m: &[Mode],
        jac: &mut Vec<(usize, usize, f64)>,
    ) -> bool {
        jac.push((0, 0, -1e6));
        true
    }
}

/// A problem's right-hand side without its analytic Jacobian: the solvers difference it.
struct WithoutJacobian<P>(P);

impl<P: OdeProblem> OdeProblem for WithoutJacobian<P> {
    fn dim(&self) -> usize {
        self.0.dim()
    }
    fn rhs(&self, t: f64, y: &[f64], m: &[Mode], f: &mut [f64]) {
        self.0.rhs(t, y, m, f)
    }
}

#[test]
fn implicit_euler_converges_with_order_one() {
    let steps = [0.02, 0.01, 0.005, 0.0025];
    let errors: Vec<f64> = steps
        .iter()
        .map(|&h| {
            let o = Options::fixed(0.0, 2.0, h);
            let s = solve(
                &Oscillator::plain(),
                implicit_euler(&o, NewtonKind::Modified, 2),
                &[1.0, 0.0],
                o,
            )
            .unwrap();
            (s.last().unwrap().1[0] - 2f64.cos()).abs()
        })
        .collect();
    for w in errors.windows(2) {
        let p = (w[0] / w[1]).log2();
        assert!(
            (p - 1.0).abs() < 0.05,
            "observed order {p}, errors {errors:?}"
        );
    }
}

#[test]
fn implicit_euler_is_stable_where_rk4_is_not() {
    let o = Options::fixed(0.0, 1.0, 0.05);
    let s = solve(
        &ProtheroRobinson,
        implicit_euler(&o, NewtonKind::Modified, 1),
        &[0.0],
        o.clone(),
    )
    .unwrap();
    // Local error of order h·|y''|/|λ|: tiny, despite h·|λ| = 5e4.
    assert!((s.last().unwrap().1[0] - 1f64.sin()).abs() < 1e-6);
    // A linear problem with its exact Jacobian: one Jacobian and one factorisation for the
    // whole run; each Newton solve is exact after one iteration, and the convergence test
    // sometimes takes a second to confirm it.
    assert_eq!(s.stats.jacobian_evals, 1);
    assert_eq!(s.stats.lu_factorizations, 1);
    assert_eq!(s.stats.steps, 20);
    assert!(
        (20..=40).contains(&s.stats.newton_iterations),
        "{:?}",
        s.stats
    );
    // One back-solve with the factorised matrix per Newton iteration, and no other: the
    // counted cost of the run, pinned (a change of the Newton iteration or of its convergence
    // test shows here): 48 evaluations, 1 Jacobian, 1 LU factorisation, 27 Newton iterations
    // and 27 back-solves.
    let s = s.stats;
    let counts = (
        s.rhs_evals,
        s.jacobian_evals,
        s.lu_factorizations,
        s.newton_iterations,
    );
    assert_eq!((counts, s.linear_solves), ((48, 1, 1, 27), 27), "{s:?}");
    // The counted work weighs them by their operation counts (`WorkWeights`): f of this
    // 1 × 1 problem costs one flop, an LU 2/3 and a back-solve 2, so 48 evaluations + 1 per
    // Jacobian + 2/3 + 2·27 = 103.67, rounded to 104.
    assert_eq!((s.matrix_order, s.matrix_entries), (1, 1), "{s:?}");
    assert_eq!(s.work(1), 104, "{s:?}");
    // The same problem without its analytic Jacobian: the Jacobian by forward differences
    // costs one Jacobian in the count, as the analytic one, and not also its evaluation of f.
    // (Its rounding changes Newton's convergence test: 30 iterations, each one evaluation,
    // against 27; the evaluations outside Newton's iteration are the same 21.)
    let d = solve(
        &WithoutJacobian(ProtheroRobinson),
        implicit_euler(&o, NewtonKind::Modified, 1),
        &[0.0],
        o.clone(),
    )
    .unwrap()
    .stats;
    assert_eq!(d.jacobian_evals, 1, "{d:?}");
    assert_eq!(d.rhs_evals - d.newton_iterations, 21, "{d:?}");
    assert_eq!(s.rhs_evals - s.newton_iterations, 21, "{s:?}");
    assert_eq!(
        d.work(1),
        d.rhs_evals + 1 + 2 * d.linear_solves + 1,
        "{d:?}"
    );
    let explicit = solve(&ProtheroRobinson, Box::new(Rk4::new(0.05, 1)), &[0.0], o);
    let error = explicit.unwrap_err().error;
    assert!(matches!(error, SolverError::NonFinite { .. }), "{error}");
}

#[test]
fn adaptive_implicit_euler_error_falls_like_the_square_root_of_the_tolerance() {
    // Error-per-step control of a first-order method: N ∝ tol^(−1/2) steps, each with a
    // local error ≈ tol, so the global error ≈ N·tol ∝ tol^(1/2): a factor √10 per decade.
    let tols = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7];
    let runs: Vec<(f64, usize)> = tols
        .iter()
        .map(|&tol| {
            let o = Options::adaptive(0.0, 2.0, tol, tol);
            let s = solve(
                &Oscillator::plain(),
                implicit_euler(&o, NewtonKind::Modified, 2),
                &[1.0, 0.0],
                o,
            )
            .unwrap();
            ((s.last().unwrap().1[0] - 2f64.cos()).abs(), s.stats.steps)
        })
        .collect();
    for w in runs.windows(2) {
        let slope = (w[0].0 / w[1].0).log10();
        assert!(
            (0.35..0.65).contains(&slope),
            "error slope per decade {slope}: {runs:?}"
        );
        assert!(w[1].1 > w[0].1, "{runs:?}");
    }
}

#[test]
fn modified_newton_reuses_the_jacobian_full_newton_does_not() {
    let o = Options::fixed(0.0, 1.0, 0.01);
    let modified = solve(
        &Oscillator::plain(),
        implicit_euler(&o, NewtonKind::Modified, 2),
        &[1.0, 0.0],
        o.clone(),
    )
    .unwrap();
    let full = solve(
        &Oscillator::plain(),
        implicit_euler(&o, NewtonKind::Full, 2),
        &[1.0, 0.0],
        o,
    )
    .unwrap();
    let (a, b) = (modified.last().unwrap().1, full.last().unwrap().1);
    assert!((a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9);
    assert_eq!(modified.stats.jacobian_evals, 1);
    assert_eq!(modified.stats.lu_factorizations, 1);
    assert!(full.stats.jacobian_evals >= 100, "{:?}", full.stats);
    assert!(full.stats.lu_factorizations >= 100);
}

#[test]
fn newton_failure_is_reported_with_time_and_step() {
    // y' = y², y(0) = 1, one implicit Euler step of h = 2: Y − 1 − 2Y² = 0 has no real root.
    let o = Options::fixed(0.0, 2.0, 2.0);
    let f = solve(&BlowUp, implicit_euler(&o, NewtonKind::Full, 1), &[1.0], o).unwrap_err();
    let SolverError::NewtonDivergence { t, h, .. } = f.error else {
        panic!("{}", f.error)
    };
    assert_eq!((t, h), (0.0, 2.0));
    assert!(
        f.error
            .to_string()
            .starts_with("Newton iteration diverged at t = 0 with h = 2e0"),
        "{}",
        f.error
    );
    assert_eq!(f.solution.len(), 1, "the initial point is kept");
}

/// A semi-explicit index-1 DAE: y0' = −y1, 0 = y1 − y0 (so y0 = exp(−t)).
struct LinearDae;

impl OdeProblem for LinearDae {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], _m: &[Mode], f: &mut [f64]) {
        f[0] = -y[1];
        f[1] = y[1] - y[0];
    }
    fn mass(&self) -> Option<&[f64]> {
        Some(&[1.0, 0.0])
    }
}

#[test]
fn explicit_methods_refuse_a_dae_and_implicit_euler_solves_it() {
    let o = Options::fixed(0.0, 1.0, 1e-3);
    let err = Integrator::new(
        &LinearDae,
        Box::new(Rk4::new(1e-3, 2)),
        &[1.0, 1.0],
        &[Mode(0)],
        o.clone(),
    )
    .err()
    .unwrap();
    assert!(
        err.to_string()
            .starts_with("rk4 cannot integrate this problem"),
        "{err}"
    );
    let s = solve(
        &LinearDae,
        implicit_euler(&o, NewtonKind::Modified, 2),
        &[1.0, 1.0],
        o,
    )
    .unwrap();
    let y = s.last().unwrap().1;
    // Implicit Euler on y' = −y: (1 + h)^(−n).
    assert!((y[0] - 1.001f64.powi(-1000)).abs() < 1e-11, "{}", y[0]);
    assert!((y[1] - y[0]).abs() < 1e-12, "the constraint holds");
}
