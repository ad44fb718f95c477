//! The energy balance kept by the solver closes to the solver's tolerance.

use friction_models::{FrictionParams, ModelId};
use friction_systems::Scheme;
use integrators::{Solver, StepControl};
use scenarios::{run, Limits, RunSpec, Scenario};

fn belt(model: ModelId, rtol: f64) -> friction_systems::EnergyBalance {
    let spec = RunSpec {
        scenario: Scenario::BELT,
        law: model.into(),
        friction: FrictionParams::paper(),
        params: Scenario::BELT.defaults(),
        scheme: Scheme::events(Solver::DOPRI5),
        step: StepControl::Adaptive {
            rtol,
            atol: rtol * 1e-2,
            h0: None,
        },
        t_end: Some(20.0),
        output_points: 11,
        limits: Limits::default(),
    };
    run(&spec, &mut |_| {}).unwrap().energy.unwrap()
}

#[test]
fn switched_stick_slip_energy_residual_is_below_1e_6_of_the_energy_turned_over() {
    // 20 s of stick–slip (about 17 cycles, 34 events) at rtol = 1e-10: the residual is the
    // accumulated error of the integration; bound it by 1e-6 of the largest term.
    for model in [ModelId::Cs, ModelId::Static, ModelId::Sv] {
        let e = belt(model, 1e-10);
        assert!(e.relative_residual < 1e-6, "{model}: {e:?}");
        // The belt's work is what friction turns into heat, up to the stored energy.
        assert!(e.belt_work > 0.0 && e.friction_work > 0.0, "{model}: {e:?}");
    }
}

#[test]
fn the_residual_shrinks_with_the_tolerance() {
    let loose = belt(ModelId::Cs, 1e-5).relative_residual;
    let tight = belt(ModelId::Cs, 1e-10).relative_residual;
    assert!(tight < loose, "{tight} vs {loose}");
}
