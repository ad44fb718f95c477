//! The phenomena protocols: textbook answers on models whose behaviour is beyond doubt, and
//! the same table from two different solvers.

use friction_models::{FrictionParams, ModelId};
use integrators::{Solver, StepControl};
use scenarios::phenomena::{decide, parameters_for, table, Phenomenon, Protocol};

fn measured(phenomenon: Phenomenon, model: ModelId) -> bool {
    decide(
        phenomenon,
        model,
        &parameters_for(model),
        Protocol::default(),
    )
    .unwrap()
    .measured
}

#[test]
fn coulomb_with_stiction_sticks_and_slips_but_has_no_stribeck_effect() {
    // The `static` model: Coulomb friction F_c = 6 N with stiction F_s = 7.5 N.
    assert!(measured(Phenomenon::Stiction, ModelId::Static));
    assert!(measured(Phenomenon::StickSlip, ModelId::Static));
    assert!(!measured(Phenomenon::Stribeck, ModelId::Static));
    assert!(!measured(Phenomenon::Viscous, ModelId::Static));
    assert!(!measured(Phenomenon::Hysteresis, ModelId::Static));
}

#[test]
fn viscous_friction_has_no_stiction() {
    let v = decide(
        Phenomenon::Stiction,
        ModelId::Viscous,
        &FrictionParams::paper(),
        Protocol::default(),
    )
    .unwrap();
    assert!(!v.measured);
    // Under 3.75 N against 0.5 N·s/m the body slides towards 7.5 m/s: metres in 5 s.
    assert!(v.evidence["drift_m"] > 10.0, "{:?}", v.evidence);
    assert!(measured(Phenomenon::Viscous, ModelId::Viscous));
}

#[test]
fn dahl_has_presliding_and_hysteresis() {
    assert!(measured(Phenomenon::Presliding, ModelId::Dahl));
    assert!(measured(Phenomenon::Hysteresis, ModelId::Dahl));
    assert!(!measured(Phenomenon::Stribeck, ModelId::Dahl));
}

#[test]
fn lugre_has_the_stribeck_effect_and_a_break_away_force_that_falls_with_the_rate() {
    assert!(measured(Phenomenon::Stribeck, ModelId::LuGre));
    let v = decide(
        Phenomenon::RisingStaticFriction,
        ModelId::LuGre,
        &FrictionParams::lugre_1995(),
        Protocol::default(),
    )
    .unwrap();
    assert!(v.measured);
    assert!(
        v.evidence["breakaway_fast_N"] < v.evidence["breakaway_slow_N"],
        "{:?}",
        v.evidence
    );
    // The slow ramp breaks away close to the static level F_s = 1.5 N.
    assert!(
        (v.evidence["breakaway_slow_N"] - 1.5).abs() < 0.1,
        "{:?}",
        v.evidence
    );
}

#[test]
fn static_maps_have_no_hysteresis_loop() {
    for model in [ModelId::Av, ModelId::Cs, ModelId::Cvs, ModelId::Coulomb] {
        let v = decide(
            Phenomenon::Hysteresis,
            model,
            &FrictionParams::paper(),
            Protocol::default(),
        )
        .unwrap();
        assert!(!v.measured, "{model}: {:?}", v.evidence);
        assert!(
            v.evidence["relative_area"] < 1e-6,
            "{model}: {:?}",
            v.evidence
        );
    }
}

#[test]
fn two_solvers_agree_on_every_cell() {
    let dopri5 = table(&ModelId::ALL, Protocol::default(), None).unwrap();
    let bdf = table(
        &ModelId::ALL,
        Protocol {
            solver: Solver::from_name("bdf").unwrap(),
            step: StepControl::Adaptive {
                rtol: 1e-9,
                atol: 1e-12,
                h0: None,
            },
        },
        None,
    )
    .unwrap();
    for ((model, a), (_, b)) in dopri5.iter().zip(&bdf) {
        for ((phenomenon, x), (_, y)) in a.iter().zip(b) {
            assert_eq!(
                x.measured,
                y.measured,
                "{model} {}: {:?} vs {:?}",
                phenomenon.name(),
                x.evidence,
                y.evidence
            );
        }
    }
}
