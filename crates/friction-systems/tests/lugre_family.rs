//! The two LuGre variants the literature uses, each against a property from its paper.

use friction_models::{
    steady, FrictionModel, FrictionParams, ModelId, SignLaw, StatePartials, Variant,
};
use friction_systems::{simulate, Profile, Scheme, Switching, System};
use integrators::{Options, Solver};
use std::sync::Arc;

/// A 1 kg body on a fixed surface under F(t) = bias + amplitude·sin(2πt), from rest: its
/// position at the ends of periods `from` and `to`.
fn positions(model: ModelId, bias: f64, amplitude: f64, from: f64, to: f64) -> (f64, f64) {
    let law = model
        .build(Variant::Odd, &FrictionParams::lugre_1995())
        .expect("valid parameters");
    let mut s = System::default();
    let body = s.add_body("body", 1.0, 0.0, 0.0);
    s.add_contact(body, 0.0, Arc::from(law));
    s.add_force(
        body,
        bias,
        Profile::Sine {
            amplitude,
            omega: 2.0 * std::f64::consts::PI,
        },
    );
    let at = |t_end: f64| {
        let run = simulate(
            &s,
            Scheme::EventDriven {
                solver: Solver::from_name("bdf").expect("a solver"),
                switching: Switching::Event,
            },
            Options::adaptive(0.0, t_end, 1e-10, 1e-14),
            &mut |_| {},
        )
        .expect("a valid system");
        assert!(run.error.is_none(), "{:?}", run.error);
        run.final_states()[0].x
    };
    (at(from), at(to))
}

#[test]
fn elasto_plastic_sticks_without_drift_where_lugre_creeps() {
    // Dupont, Hayward, Armstrong & Altpeter (2002), Sec. III: under a periodic force below
    // break-away LuGre's bristle deflection always has a plastic part, so the body creeps cycle
    // after cycle; the elasto-plastic bristle is purely elastic while |z| <= z_ba (here
    // z_ba = 0.5·F_c/σ0 = 5 µm, a force of 0.5 N), so the body returns to the same place.
    // Load 0.2 + 0.2·sin(2πt) N: at most 0.4 N, under z_ba·σ0 = 0.5 N and F_c = 1 N.
    let (a, b) = positions(ModelId::LuGre, 0.2, 0.2, 10.0, 20.0);
    let lugre_drift = b - a;
    let (a, b) = positions(ModelId::ElastoPlastic, 0.2, 0.2, 10.0, 20.0);
    let plastic_drift = b - a;
    assert!(
        lugre_drift > 1e-9,
        "LuGre creeps: {lugre_drift:e} m over 10 periods"
    );
    assert!(
        plastic_drift.abs() < 1e-6 * lugre_drift,
        "elasto-plastic: {plastic_drift:e} m against LuGre's {lugre_drift:e} m"
    );
}

#[test]
fn velocity_dependent_damping_acts_at_rest_and_fades_in_sliding() {
    // Canudas de Wit et al. (1995), eq. (10): σ1(v) = σ1·exp(−(v/v_d)²) keeps the bristle
    // damping where it is needed, at small velocities, and removes it from gross sliding, where
    // the friction's velocity slope is the viscous σ2 alone. LuGre keeps σ1 at every speed.
    let p = FrictionParams::lugre_1995();
    let vd = ModelId::LuGreVd.build(Variant::Odd, &p).unwrap();
    let lugre = ModelId::LuGre.build(Variant::Odd, &p).unwrap();
    let law = SignLaw::Discontinuous;
    // At rest with a relaxed bristle: dF/dv = σ1·dż/dv + σ2 = σ1 + σ2 for both.
    let slope = |m: &dyn FrictionModel, v: f64, z: f64| {
        m.partials(0.0, v, &[z], law, &mut [StatePartials::default()])
            .force_dv
    };
    assert!((slope(vd.as_ref(), 0.0, 0.0) - (p.sigma1 + p.sigma2)).abs() < 1e-9);
    assert!((slope(lugre.as_ref(), 0.0, 0.0) - (p.sigma1 + p.sigma2)).abs() < 1e-9);
    // At v = 10·v_d, off the steady state (z = 0): LuGre's slope still carries σ1, LuGre-vd's
    // is σ2 to within σ1·exp(−100).
    let v = 10.0 * p.v_d;
    assert!((slope(vd.as_ref(), v, 0.0) - p.sigma2).abs() < 1e-30 * p.sigma1);
    assert!((slope(lugre.as_ref(), v, 0.0) - (p.sigma1 + p.sigma2)).abs() < 1e-9);
    // Both share LuGre's steady state (the damping multiplies ż = 0 there).
    for v in [1e-4, 1e-3, 1e-2] {
        let (a, b) = (steady::states(&*vd, v), steady::states(&*lugre, v));
        assert_eq!(a, b);
        let mut rate = [0.0];
        vd.response(0.0, v, &a, law, &mut rate);
        assert!(rate[0].abs() < 1e-12);
    }
}
