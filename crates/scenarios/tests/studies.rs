//! The study code recovers known orders, sees the jump at v = 0 cost an order, and judges
//! step-size independence correctly where the answer is known.

use friction_models::{FrictionParams, ModelId};
use integrators::Solver;
use scenarios::studies::{convergence, independence, Case, Reference};
use scenarios::{Limits, Scenario, SwitchingKind};

/// The block pushed by 15 N against viscous friction: smooth, with a closed form.
fn viscous_block() -> Case {
    Case {
        scenario: Scenario::PaperBlock,
        model: ModelId::Viscous,
        friction: FrictionParams::paper(),
        params: Scenario::PaperBlock.defaults(),
        switching: SwitchingKind::Event,
        t_end: 5.0,
        limits: Limits::default(),
    }
}

fn slope(case: &Case, solver: Solver, steps: &[f64], measure: &str) -> f64 {
    let c = convergence(case, &[solver], steps, &[], &|| {}).unwrap();
    let t = c.orders.iter().find(|t| t.measure == measure).unwrap();
    t.fitted_slope.unwrap()
}

#[test]
fn the_study_recovers_the_orders_of_the_methods_on_a_smooth_problem() {
    let case = viscous_block();
    let c = convergence(&case, &[Solver::Rk4], &[0.4, 0.2], &[], &|| {}).unwrap();
    assert!(
        matches!(c.reference, Reference::ClosedForm(_)),
        "{:?}",
        c.reference
    );
    let rk4 = slope(&case, Solver::Rk4, &[0.4, 0.2, 0.1, 0.05], "grid_max");
    assert!((rk4 - 4.0).abs() < 0.2, "rk4 {rk4}");
    let dopri5 = slope(&case, Solver::Dopri5, &[1.0, 0.5, 0.25, 0.125], "grid_max");
    assert!((dopri5 - 5.0).abs() < 0.3, "dopri5 {dopri5}");
    let euler = slope(
        &case,
        Solver::ImplicitEuler,
        &[0.04, 0.02, 0.01, 0.005],
        "grid_max",
    );
    assert!((euler - 1.0).abs() < 0.1, "implicit Euler {euler}");
}

/// Free vibration against Coulomb friction with stiction (m = 1, k = 100, x0 = 0.5): every
/// half period π/10 s the velocity crosses zero and the friction jumps; after four half
/// periods the body sticks at x = 0.02 m.
fn coulomb_vibration(switching: SwitchingKind) -> Case {
    Case {
        scenario: Scenario::FreeVibration,
        model: ModelId::Static,
        friction: FrictionParams::paper(),
        params: Scenario::FreeVibration.defaults(),
        switching,
        t_end: 2.0,
        limits: Limits::default(),
    }
}

#[test]
fn stepping_through_v_0_costs_rk4_its_order_and_event_location_restores_it() {
    let steps = [2e-2, 1e-2, 5e-3, 2.5e-3];
    let naive = slope(
        &coulomb_vibration(SwitchingKind::Naive),
        Solver::Rk4,
        &steps,
        "grid_max",
    );
    assert!((naive - 1.0).abs() < 0.25, "naive {naive}");
    let switched = slope(
        &coulomb_vibration(SwitchingKind::Event),
        Solver::Rk4,
        &steps,
        "grid_max",
    );
    assert!((switched - 4.0).abs() < 0.25, "switched {switched}");
    // The switched events are the closed form's: reversals every π/ω.
    let c = convergence(
        &coulomb_vibration(SwitchingKind::Event),
        &[Solver::Rk4],
        &[1e-3],
        &[],
        &|| {},
    )
    .unwrap();
    let m = &c.runs[0].measures;
    for (k, t) in m.event_times.iter().take(4).enumerate() {
        assert!(
            (t - (k + 1) as f64 * std::f64::consts::PI / 10.0).abs() < 1e-9,
            "event {k} at {t}"
        );
    }
    assert!(
        (m.final_state[0] - 0.02).abs() < 1e-9,
        "rest at {}",
        m.final_state[0]
    );
}

#[test]
fn the_independence_verdict_is_negative_for_a_coarse_step_and_positive_for_a_fine_one() {
    let case = viscous_block();
    let coarse = independence(&case, Solver::Rk4, 2.0, 2.0, 3, 1e-6, &|| {}).unwrap();
    assert!(!coarse.independent, "{:?}", coarse.outputs);
    let fine = independence(&case, Solver::Rk4, 1e-2, 2.0, 3, 1e-6, &|| {}).unwrap();
    assert!(fine.independent, "{:?}", fine.outputs);
    // The Richardson estimate of the remaining error in v(5) bounds the true error.
    let v = fine
        .outputs
        .iter()
        .find(|o| o.name.starts_with("final v"))
        .unwrap();
    let exact = 30.0 * (1.0 - (-2.5f64).exp());
    assert!(
        (v.values[2] - exact).abs() <= 2.0 * v.remaining_error + 1e-12,
        "{v:?}"
    );
}

#[test]
fn the_stiffness_verdict_names_a_crossover_only_inside_the_sweep() {
    use scenarios::studies::{Stiffness, StiffnessPoint};
    let sweep = |wins: &[bool]| Stiffness {
        parameter: "epsilon".into(),
        target: 1e-3,
        points: wins
            .iter()
            .enumerate()
            .map(|(i, &w)| StiffnessPoint {
                value: 10f64.powi(-(i as i32)),
                costs: vec![],
                implicit_wins: w,
            })
            .collect(),
        crossover: wins
            .iter()
            .position(|&w| w)
            .map(|i| 10f64.powi(-(i as i32))),
    };
    assert_eq!(
        sweep(&[true, true, true]).verdict(),
        "the implicit solvers win at every epsilon of the sweep: no crossover in this range"
    );
    assert_eq!(
        sweep(&[false, false]).verdict(),
        "the explicit solvers win at every epsilon of the sweep: no crossover in this range"
    );
    assert_eq!(
        sweep(&[false, true, true]).verdict(),
        "the implicit solvers overtake the explicit ones from epsilon = 0.1"
    );
    assert!(sweep(&[false, true, false])
        .verdict()
        .starts_with("the winner changes more than once"));
}
