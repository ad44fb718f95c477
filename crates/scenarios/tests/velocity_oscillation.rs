//! The velocity-oscillation rig, v = v_mean + v_amplitude·cos(omega·t), against closed forms.

use friction_models::{FrictionParams, ModelId};
use friction_systems::Scheme;
use integrators::{Solver, StepControl};
use scenarios::{run, Limits, Outcome, RunSpec, Scenario};
use std::f64::consts::PI;

fn oscillate(model: ModelId) -> Outcome {
    let spec = RunSpec {
        scenario: Scenario::VELOCITY_OSCILLATION,
        law: model.into(),
        friction: FrictionParams::paper(),
        params: Scenario::VELOCITY_OSCILLATION.defaults(),
        scheme: Scheme::events(Solver::DOPRI5),
        step: StepControl::Adaptive {
            rtol: 1e-10,
            atol: 1e-12,
            h0: None,
        },
        t_end: None,
        output_points: 301,
        limits: Limits::default(),
    };
    let o = run(&spec, &mut |_| {}).unwrap();
    assert!(o.error.is_none(), "{:?}", o.error);
    o
}

#[test]
fn viscous_friction_does_the_closed_form_work_and_draws_no_loop() {
    // F = mu_v·v: over three periods T = 3·2π/ω, W = ∫F·v dt = mu_v·T·(v̄² + a²/2), and a
    // single-valued F(v) encloses no area, ∮F dv = 0; x(T) = v̄·T.
    let p = Scenario::VELOCITY_OSCILLATION.defaults();
    let mu_v = FrictionParams::paper().mu_v;
    let t = 3.0 * 2.0 * PI / p.omega;
    let o = oscillate(ModelId::Viscous);
    let w = mu_v * t * (p.v_mean.powi(2) + p.v_amplitude.powi(2) / 2.0);
    let work = o.friction_work.unwrap();
    assert!((work - w).abs() < 1e-9 * w, "{work} vs {w}");
    assert!(o.loop_area.unwrap().abs() < 1e-12, "{:?}", o.loop_area);
    let last = o.last().unwrap();
    assert!((last.t - t).abs() < 1e-12 && (last.x - p.v_mean * t).abs() < 1e-12);
    assert!((last.v - (p.v_mean + p.v_amplitude)).abs() < 1e-12);
}

#[test]
fn lugre_lags_behind_the_velocity_and_draws_a_loop() {
    // LuGre's bristles make friction lag the velocity (Canudas de Wit et al. 1995): under a
    // velocity that never reverses the friction–velocity curve is a loop of non-zero area.
    let lugre = oscillate(ModelId::LuGre).loop_area.unwrap();
    let viscous = oscillate(ModelId::Viscous).loop_area.unwrap();
    assert!(lugre.abs() > 1e-3, "LuGre ∮F dv = {lugre}");
    assert!(lugre.abs() > 1e6 * viscous.abs(), "{lugre} vs {viscous}");
}
