//! RODAS: parity with Hairer's rodas.f on its driver (Van der Pol), count for count and value
//! for value. What RODAS shares with Radau IIA beyond parity is tested in `stiff.rs`.
//!
//! The reference is the output of Hairer's dr_rodas.f with rodas.f, decsol.f and dc_decsol.f
//! (gfortran 12, `-O0`, its format widened to 17 digits): the analytic Jacobian, IFCN = 0,
//! every WORK and IWORK entry left at 0. rodas.f's NFCN counts neither the evaluations of a
//! finite-difference Jacobian nor that of ∂f/∂t, as `rhs_evals` does not; its NSTEP counts
//! every attempt; its NREJCT leaves out rejections before the first accepted step.

// The reference as rodas.f printed it.
#![allow(clippy::excessive_precision)]

use approx::assert_relative_eq;
use integrators::rodas::RodasMethod;
use integrators::testset::VanDerPol;
use integrators::{Mode, OdeProblem, OneStepMethod, Options, Output, Solution, StepControl};

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
    let s = solve(&VanDerPol, &[2.0, -0.66], o);
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
