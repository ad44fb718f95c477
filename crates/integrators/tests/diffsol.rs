//! diffsol's methods behind the same interface: a stiff problem with a published reference.
//! (The switched stick–slip cycle and the index-1 friction DAE are in friction-systems.)

use integrators::diffsol_backend::{self, DiffsolMethod};
use integrators::testset::Robertson;
use integrators::{Dopri5, ImplicitEuler, Integrator, Mode, NewtonKind, Options};

/// y(40) of Robertson's problem, as tabulated in the IVP test set of Mazzia et al.
/// (Bari), problem "HIRES/ROBER" reference at t = 40: 0.7158270687, 9.185534764e-6,
/// 0.2841637457.
const ROBERTSON_40: [f64; 3] = [0.7158270687, 9.185534764e-6, 0.2841637457];

fn relative_errors(y: &[f64]) -> Vec<f64> {
    y.iter()
        .zip(ROBERTSON_40)
        .map(|(a, b)| ((a - b) / b).abs())
        .collect()
}

#[test]
fn diffsol_and_native_solvers_agree_on_robertson() {
    let y0 = [1.0, 0.0, 0.0];
    for method in [
        DiffsolMethod::Bdf,
        DiffsolMethod::TrBdf2,
        DiffsolMethod::Esdirk34,
    ] {
        let o = Options::adaptive(0.0, 40.0, 1e-8, 1e-12);
        let s = diffsol_backend::solve(&Robertson, method, &y0, &[Mode(0)], o).unwrap();
        let e = relative_errors(s.last().unwrap().1);
        assert!(
            e.iter().all(|&e| e < 1e-6),
            "{}: relative errors {e:?}",
            method.name()
        );
        assert!(
            s.stats.lu_factorizations > 0
                && s.stats.newton_iterations > 0
                && s.stats.linear_solves == s.stats.newton_iterations,
            "{:?}",
            s.stats
        );
    }
    let o = Options::adaptive(0.0, 40.0, 1e-7, 1e-12);
    let ie = ImplicitEuler::new(o.step, NewtonKind::Modified, o.h_max(), o.max_steps, 3);
    let s = Integrator::new(&Robertson, Box::new(ie), &y0, &[Mode(0)], o)
        .unwrap()
        .solve()
        .unwrap();
    let e = relative_errors(s.last().unwrap().1);
    assert!(
        e.iter().all(|&e| e < 1e-3),
        "implicit Euler: relative errors {e:?}"
    );
}

#[test]
fn dopri5_flags_robertson_as_stiff() {
    // Hairer's test first runs at accepted step NSTIFF = 1000 and needs 15 stiff verdicts
    // in a row; by t = 1 dopri5 has taken fewer than 1000 steps, so run to t = 10.
    let o = Options::adaptive(0.0, 10.0, 1e-6, 1e-10);
    let stepper = Dopri5::new(o.step, o.h_max(), o.max_steps, 3);
    let s = Integrator::new(
        &Robertson,
        Box::new(stepper),
        &[1.0, 0.0, 0.0],
        &[Mode(0)],
        o,
    )
    .unwrap()
    .solve()
    .unwrap();
    let at = s
        .stiffness_detected_at
        .expect("Hairer's test finds the stiffness");
    assert!(at > 0.0 && at < 10.0);
    assert!(
        s.stats.steps > 1000,
        "the test runs after NSTIFF = 1000 accepted steps"
    );
}
