//! RODAS: parity with Hairer's rodas.f on its driver (Van der Pol), count for count and value
//! for value; events, an index-1 DAE, a stiff problem with a closed form, a sparse system.
//!
//! The reference is the output of Hairer's dr_rodas.f with rodas.f, decsol.f and dc_decsol.f
//! (gfortran 12, `-O0`, its format widened to 17 digits): the analytic Jacobian, IFCN = 0,
//! every WORK and IWORK entry left at 0. rodas.f's NFCN counts neither the evaluations of a
//! finite-difference Jacobian nor that of ∂f/∂t, as `rhs_evals` does not; its NSTEP counts
//! every attempt; its NREJCT leaves out rejections before the first accepted step.

// The reference as rodas.f printed it.
#![allow(clippy::excessive_precision)]

mod common;

use approx::assert_relative_eq;
use common::{Heat, Oscillator, ProtheroRobinson, Robertson, RobertsonDae, VanDerPol};
use integrators::rodas::RodasMethod;
use integrators::{
    Control, Crossing, Mode, OdeProblem, OneStepMethod, Options, Output, Solution, StepControl,
};

fn solve(problem: &dyn OdeProblem, y0: &[f64], o: Options) -> Solution {
    RodasMethod
        .solve_observed(problem, y0, &[Mode(0)], o, &mut |_| {})
        .unwrap()
}

#[test]
fn rodas_matches_hairers_van_der_pol_driver() {
    // dr_rodas.f: ε = 1e-6, y0 = (2, −0.66) on [0, 2], RTOL = 1e-4, ATOL = 1e-10, H = 1e-6;
    // its SOLOUT prints CONTRO at x = 0.2, 0.4, …, 2.0 (once a step).
    let printed = [
        (0.2, 1.8582069203335245, -7.5755367673130680e-01),
        (0.4, 1.6932067028784297, -9.0693316047594341e-01),
        (0.6, 1.4845739098450543, -1.2331251456669576),
        (0.8, 1.0838914167225790, -6.1976811899743787),
        (1.0, -1.8636412912407445, 7.5355882363338111e-01),
        (1.2, -1.6997091545046239, 8.9982452132130597e-01),
        (1.4, -1.4933758804240369, 1.2139665831406119),
        (1.6, -1.1207707998840699, 4.3754987963922769),
        (1.8, 1.8690494751110656, -7.4961401987252940e-01),
        (2.0, 1.7061572228085222, -8.9282094763826902e-01),
    ];
    let mut o = Options::adaptive(0.0, 2.0, 1e-4, 1e-10);
    o.step = StepControl::Adaptive {
        rtol: 1e-4,
        atol: 1e-10,
        h0: Some(1e-6),
    };
    o.output = Output::GridOnly(printed.iter().map(|p| p.0).collect());
    let s = solve(&VanDerPol { eps: 1e-6 }, &[2.0, -0.66], o);
    for (i, (t, y1, y2)) in printed.into_iter().enumerate() {
        assert_eq!(s.t[i], t);
        assert_relative_eq!(s.y_at(i)[0], y1, max_relative = 1e-14);
        assert_relative_eq!(s.y_at(i)[1], y2, max_relative = 1e-14);
    }
    // fcn = 2016, jac = 321, step = 339, accpt = 321, rejct = 16, dec = 339, sol = 2034.
    let st = s.stats;
    assert_eq!(st.rhs_evals, 2016);
    assert_eq!(st.jacobian_evals, 321);
    assert_eq!(st.steps, 321);
    assert_eq!(st.steps + st.rejected_error, 339);
    assert_eq!(st.lu_factorizations, 339);
    assert_eq!(st.linear_solves, 2034);
    assert_eq!(st.newton_iterations, 0);
}

#[test]
fn events_are_located_on_the_dense_output() {
    let p = Oscillator::watching(Crossing::Falling, Control::Stop);
    let s = solve(&p, &[1.0, 0.0], Options::adaptive(0.0, 3.0, 1e-12, 1e-12));
    assert_eq!(s.events.len(), 1);
    let t = s.events[0].t;
    assert!((t - std::f64::consts::FRAC_PI_2).abs() < 1e-10, "{t}");
}

#[test]
fn an_index_one_dae_is_integrated_through_its_singular_mass_matrix() {
    let o = || Options::adaptive(0.0, 40.0, 1e-8, 1e-12);
    let (dae, ode) = (
        solve(&RobertsonDae, &[1.0, 0.0, 0.0], o()),
        solve(&Robertson, &[1.0, 0.0, 0.0], o()),
    );
    for i in 0..dae.len() {
        let sum: f64 = dae.y_at(i).iter().sum();
        assert!((sum - 1.0).abs() < 1e-13, "step {i}: {sum}");
    }
    let (y, z) = (dae.last().unwrap().1, ode.last().unwrap().1);
    for (a, b) in y.iter().zip(z) {
        assert_relative_eq!(*a, *b, max_relative = 1e-6);
    }
    assert_relative_eq!(y[0], 0.7158270687, max_relative = 1e-7);
}

#[test]
fn the_error_follows_the_tolerance_on_a_stiff_non_autonomous_problem() {
    // Prothero–Robinson depends on t: ∂f/∂t enters every stage. The stiff component keeps
    // its accuracy at every tolerance; the quadrature's error stays within the tolerance and
    // falls with it.
    let mut previous = f64::INFINITY;
    for tol in [1e-4, 1e-6, 1e-8, 1e-10] {
        let s = solve(
            &ProtheroRobinson,
            &[0.0, 0.0],
            Options::adaptive(0.0, 10.0, tol, tol),
        );
        let y = s.last().unwrap().1;
        let stiff = (y[0] - 10f64.sin()).abs();
        assert!(
            stiff < 1e-8,
            "tol {tol}: error of the stiff component {stiff:e}"
        );
        let smooth = (y[1] - (1.0 - 10f64.cos())).abs();
        assert!(
            smooth < tol,
            "tol {tol}: error of the quadrature {smooth:e}"
        );
        assert!(
            smooth < previous / 10.0,
            "tol {tol}: {smooth:e} against {previous:e}"
        );
        previous = smooth;
    }
}

#[test]
fn a_sparse_stiff_system_goes_through_the_sparse_lu() {
    let (n, k) = (400, 1e4);
    let u0: Vec<f64> = (1..=n)
        .map(|i| (std::f64::consts::PI * i as f64 / (n + 1) as f64).sin())
        .collect();
    let s = solve(
        &Heat { n, k },
        &u0,
        Options::adaptive(0.0, 1.0, 1e-8, 1e-10),
    );
    let lambda = -4.0 * k * (std::f64::consts::PI / (2 * (n + 1)) as f64).sin().powi(2);
    let u = s.last().unwrap().1;
    for (got, start) in u.iter().zip(&u0) {
        assert!((got - start * lambda.exp()).abs() < 1e-8, "{got}");
    }
    assert_eq!(s.stats.matrix_order, n);
}
