//! Implicit solvers on a fast belt, where the power into the contact changes by orders of
//! magnitude within one step: the energy accumulators are quadratures
//! (`OdeProblem::quadratures`), which implicit Euler leaves out of Newton's convergence test
//! and sets from the converged state, and diffsol's initial-step estimate leaves out.

mod common;

use common::belt;
use friction_models::ModelId;
use friction_systems::{simulate, Scheme, Switching};
use integrators::{Options, Solver};

const T_END: f64 = 0.2;

/// A 1 kg body on a 100 N/m spring to a wall, on a belt at `v_belt` under LuGre (the paper's
/// parameters), from rest, integrated by `solver` with `options`: `(x, v)` at T_END and the
/// energy balance's relative residual.
fn fast_belt(v_belt: f64, solver: &str, options: Options) -> ((f64, f64), f64) {
    let s = belt(ModelId::LuGre, 1.0, 100.0, v_belt);
    let run = simulate(
        &s,
        Scheme::EventDriven {
            solver: Solver::from_name(solver).expect("a solver"),
            switching: Switching::Event,
        },
        options,
        &mut |_| {},
    )
    .expect("a valid system");
    assert!(run.error.is_none(), "{solver}: {:?}", run.error);
    let end = run.final_states()[0];
    let energy = run.energy().expect("a recorded end");
    ((end.x, end.v), energy.relative_residual)
}

#[test]
fn implicit_euler_takes_the_bristles_settling_on_a_fast_belt_at_first_order() {
    // At t = 0 the bristles are undeflected and the friction force is σ1·v_rel, about 3e4 N;
    // they settle to F_c within about 1e-6 s, and the power into the contact drops from 3e6 W
    // to 6e2 W. While Newton's iteration counted the accumulators, its corrections of them
    // were the whole change of that power between iterates, larger at the second iterate
    // than at the first: every fixed step below was refused at t = 0 as diverging
    // (contraction factors 330, 92 and 11 at h = 1e-3, 1e-4 and 1e-5).
    let (reference, _) = fast_belt(
        100.0,
        "tr-bdf2",
        Options::adaptive(0.0, T_END, 1e-10, 1e-10),
    );
    let runs: Vec<(f64, f64)> = [1e-3, 5e-4, 2.5e-4]
        .into_iter()
        .map(|h| {
            let ((x, _), residual) =
                fast_belt(100.0, "implicit-euler", Options::fixed(0.0, T_END, h));
            ((x - reference.0).abs(), residual)
        })
        .collect();
    // Measured: errors in x of 1.95e-3, 9.7e-4 and 4.8e-4 m (x = 0.637 m), each half of the
    // one before; energy residuals 2.3e-4, 1.3e-4 and 7.4e-5 of the largest term.
    for pair in runs.windows(2) {
        let ratio = pair[0].0 / pair[1].0;
        assert!((1.8..2.2).contains(&ratio), "error ratio {ratio}: {runs:?}");
        assert!(pair[1].1 < pair[0].1, "energy residuals {runs:?}");
    }
    assert!(runs[2].0 < 1e-3 && runs[2].1 < 2e-4, "{runs:?}");
}

#[test]
fn bdf_starts_on_a_fast_belt() {
    // At 1000 m/s the power into the contact starts at 3e8 W and changes by 5e9 W within the
    // trial step of Hairer's initial-step estimate; weighted by atol alone (the accumulators
    // start at zero) it drove diffsol's estimate to 1.4e-14 s, below diffsol's smallest step,
    // and BDF failed at t = 2e-14 s. Measured: BDF at rtol 1e-8, atol 1e-10 within 2.2e-8 of
    // x = 5.61 m and 1.8e-7 of v = 35.5 m/s (relative) of TR-BDF2 at 1e-10; energy residual
    // 2.8e-9.
    let options = Options::adaptive(0.0, T_END, 1e-8, 1e-10);
    let ((x, v), residual) = fast_belt(1000.0, "bdf", options);
    let reference = Options::adaptive(0.0, T_END, 1e-10, 1e-10);
    let ((x_ref, v_ref), _) = fast_belt(1000.0, "tr-bdf2", reference);
    let (dx, dv) = ((x / x_ref - 1.0).abs(), (v / v_ref - 1.0).abs());
    assert!(
        dx < 2e-7 && dv < 2e-6,
        "x {x}, v {v}; TR-BDF2 {x_ref}, {v_ref}"
    );
    assert!(residual < 3e-8, "energy residual {residual:e}");
}
