//! Radau IIA(5): parity with Hairer's radau5.f on the drivers of the stiff test set (Van der
//! Pol, Robertson), count for count and value for value.
//!
//! The references are the outputs of Hairer's radau5.f with decsol.f and dc_decsol.f
//! (compiled with gfortran 12, `-O0`), driven as his drivers drive them: the analytic
//! Jacobian, IOUT = 1, every WORK and IWORK entry left at 0. radau5.f's NFCN counts the first
//! evaluation of f and none of a finite-difference Jacobian, as `rhs_evals` does; its NSTEP
//! counts every attempt (accepted, rejected by the error test, rejected by Newton's
//! iteration); its NREJCT leaves out rejections before the first accepted step. The values
//! agree to 1e-14 relative, the sixteen digits printed. What Radau IIA shares with RODAS
//! beyond parity is tested in `stiff.rs`.

// The references as radau5.f printed them, trailing zeros included.
#![allow(clippy::excessive_precision)]

use approx::assert_relative_eq;
use integrators::radau5::Radau5Method;
use integrators::testset::{Robertson, VanDerPol};
use integrators::{Mode, OneStepMethod, Options, Output, StepControl};

fn options(t_end: f64, rtol: f64, atol: f64, output: Output) -> Options {
    let mut o = Options::adaptive(0.0, t_end, rtol, atol);
    o.step = StepControl::Adaptive {
        rtol,
        atol,
        h0: Some(1e-6),
    };
    o.output = output;
    o
}

#[test]
fn radau5_matches_hairers_van_der_pol_driver() {
    // dr1_radau5.f: ε = 1e-6, y0 = (2, −0.66) on [0, 2], RTOL = ATOL = 1e-4, H = 1e-6; its
    // SOLOUT prints CONTR5 at x = 0.2, 0.4, …, 2.0.
    let printed = [
        (0.2, 1.858198963529426, -0.7574791034458630),
        (0.4, 1.693205231356672, -0.9069021616882742),
        (0.6, 1.484565763233076, -1.233096964774197),
        (0.8, 1.083912894828025, -6.196077501343200),
        (1.0, -1.863645642467308, 0.7535323766548747),
        (1.2, -1.699724325407358, 0.8997692747329687),
        (1.4, -1.493375073281624, 1.213880891197609),
        (1.6, -1.120780440545238, 4.374794948980488),
        (1.8, 1.869050586423352, -0.7495753072331208),
        (2.0, 1.706161100558755, -0.8928074776815651),
    ];
    let grid = printed.iter().map(|p| p.0).collect();
    let o = options(2.0, 1e-4, 1e-4, Output::GridOnly(grid));
    let s = Radau5Method
        .solve_observed(&VanDerPol, &[2.0, -0.66], &[Mode(0)], o, &mut |_| {})
        .unwrap();
    for (i, (t, y1, y2)) in printed.into_iter().enumerate() {
        assert_eq!(s.t[i], t);
        assert_relative_eq!(s.y_at(i)[0], y1, max_relative = 1e-14);
        assert_relative_eq!(s.y_at(i)[1], y2, max_relative = 1e-14);
    }
    // NFCN 2218, NJAC 161, NDEC 248, NSOL 660, NSTEP 275, NACCPT 238, NREJCT 8.
    let st = s.stats;
    assert_eq!(st.rhs_evals, 2218);
    assert_eq!(st.jacobian_evals, 161);
    assert_eq!(st.lu_factorizations, 248);
    assert_eq!(st.complex_lu_factorizations, 248);
    assert_eq!(st.complex_linear_solves, 660);
    assert_eq!(st.steps, 238);
    assert_eq!(st.rejected_error, 8);
    assert_eq!(st.steps + st.rejected_error + st.rejected_newton, 275);
}

#[test]
fn radau5_matches_hairers_robertson_driver() {
    // Robertson to x = 0.3, RTOL = 1e-2, ATOL = 1e-8, H = 1e-6; SOLOUT prints every
    // accepted step.
    let printed = [
        [
            9.999999600000008e-01,
            3.999998320000048e-08,
            1.599999952000000e-14,
        ],
        [
            9.999996400000648e-01,
            3.599882716565646e-07,
            1.166354336752796e-11,
        ],
        [
            9.999970800042659e-01,
            2.913787382334434e-06,
            6.208351820680937e-09,
        ],
        [
            9.999863148909263e-01,
            1.307919521098008e-05,
            6.059138628105538e-07,
        ],
        [
            9.999755499712033e-01,
            2.135889538415425e-05,
            3.091133412644609e-06,
        ],
        [
            9.999647854413735e-01,
            2.724901208916896e-05,
            7.965546537469531e-06,
        ],
        [
            9.999478453625211e-01,
            3.255484201352816e-05,
            1.959979546541985e-05,
        ],
        [
            9.999253573022412e-01,
            3.530902486682289e-05,
            3.933367289202561e-05,
        ],
        [
            9.999028742076045e-01,
            3.614958793293449e-05,
            6.097620446265629e-05,
        ],
        [
            9.998490892191750e-01,
            3.647645985151893e-05,
            1.144343209735185e-04,
        ],
        [
            9.997567898163745e-01,
            3.647881802650698e-05,
            2.067313655991122e-04,
        ],
        [
            9.995023134527544e-01,
            3.643227719665359e-05,
            4.612542700490673e-04,
        ],
        [
            9.982091577136206e-01,
            3.619191783743626e-05,
            1.754650368542118e-03,
        ],
        [
            9.930472117084378e-01,
            3.525604364520644e-05,
            6.917532247917142e-03,
        ],
        [
            9.886740138499884e-01,
            3.447720471782071e-05,
            1.129150894529390e-02,
        ],
    ];
    let o = options(0.3, 1e-2, 1e-8, Output::Steps);
    let s = Radau5Method
        .solve_observed(&Robertson, &[1.0, 0.0, 0.0], &[Mode(0)], o, &mut |_| {})
        .unwrap();
    assert_eq!(s.len(), 1 + printed.len());
    assert_eq!(s.t[printed.len()], 0.3);
    for (i, y) in printed.iter().enumerate() {
        for (a, b) in s.y_at(i + 1).iter().zip(y) {
            assert_relative_eq!(*a, *b, max_relative = 1e-14);
        }
    }
    // NFCN 87, NJAC 8, NDEC 15, NSOL 24, NSTEP 17, NACCPT 15, NREJCT 1.
    let st = s.stats;
    assert_eq!(st.rhs_evals, 87);
    assert_eq!(st.jacobian_evals, 8);
    assert_eq!(st.lu_factorizations, 15);
    assert_eq!(st.complex_lu_factorizations, 15);
    assert_eq!(st.complex_linear_solves, 24);
    assert_eq!(st.steps, 15);
    assert_eq!(st.rejected_error, 1);
    assert_eq!(st.steps + st.rejected_error + st.rejected_newton, 17);
}

#[test]
fn a_run_continued_past_its_first_end_stays_on_the_solution() {
    // Driven step by step to t = 1, then on to t = 2: the step after the end evaluates f
    // there and refactorises for its own step size. x'' = −x from (1, 0): x = cos t.
    use integrators::{Ode, Stepper};
    let p = oscillator();
    let ode = Ode {
        problem: &p,
        modes: &[Mode(0)],
    };
    let mut s = integrators::Radau5::new(1e-10, 1e-10, None, 2.0, 100_000, 2).unwrap();
    s.start(&ode, 0.0, &[1.0, 0.0]).unwrap();
    for end in [1.0, 2.0] {
        while s.state().t < end {
            s.step(&ode, end).unwrap();
        }
        assert_eq!(s.state().t, end);
        let x = s.state().y[0];
        assert!((x - f64::cos(end)).abs() < 1e-8, "t = {end}: {x}");
    }
}

/// x'' = −x as a first-order system.
fn oscillator() -> impl integrators::OdeProblem {
    struct Oscillator;
    impl integrators::OdeProblem for Oscillator {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&self, _t: f64, y: &[f64], _m: &[Mode], f: &mut [f64]) {
            f[0] = y[1];
            f[1] = -y[0];
        }
    }
    Oscillator
}
