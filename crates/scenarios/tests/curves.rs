//! The curves of Figures 2–7 against values computed by hand from the equations.

use approx::assert_relative_eq;
use friction_models::{FrictionModel, FrictionParams, ModelId, Variant};
use scenarios::curves::{self, CurveError};
use scenarios::figures::{assess, Claim, PAPER_FIGURES};

fn model(id: ModelId, variant: Variant) -> Box<dyn FrictionModel> {
    id.build(variant, &FrictionParams::paper()).unwrap()
}

fn paper_curve(id: ModelId, variant: Variant) -> curves::Curve {
    let m = model(id, variant);
    curves::curve(m.as_ref(), curves::default_extent(id.curve_axis()), 2000).unwrap()
}

#[test]
fn cs_curve_falls_from_static_to_coulomb_level() {
    let c = paper_curve(ModelId::Cs, Variant::Odd);
    assert_eq!((c.left_of_zero, c.right_of_zero), (-7.5, 7.5));
    assert_eq!((c.at_rest.lower, c.at_rest.upper), (-7.5, 7.5));
    let end = c.positive.last().unwrap();
    assert_eq!(end.v, 1.0);
    assert_relative_eq!(
        end.force,
        6.0 + 1.5 * (-100.0f64).exp(),
        max_relative = 1e-15
    );
    assert_relative_eq!(c.negative.last().unwrap().force, -end.force);
}

#[test]
fn sv_curve_reaches_the_closed_form_at_t_2() {
    // t = 2: v = 6, X = 8/3 + 2; F = F_s + mu_v v + F_c (1 - exp(-sigma X / F_c)).
    let c = paper_curve(ModelId::Sv, Variant::Odd);
    let x = 8.0 / 3.0 + 2.0;
    let expected = 7.5 + 0.5 * 6.0 + 6.0 * (1.0 - (-5.0 * x / 6.0f64).exp());
    let end = c.positive.last().unwrap();
    assert_relative_eq!(end.x, x, max_relative = 1e-14);
    assert_relative_eq!(end.force, expected, max_relative = 1e-12);
    assert_relative_eq!(
        c.negative.last().unwrap().force,
        -expected,
        max_relative = 1e-12
    );
    assert!(
        (expected - 16.38).abs() < 0.01,
        "the ~17 of Figure 7: {expected}"
    );
}

#[test]
fn printed_sd_has_no_jump_and_is_not_odd() {
    let c = paper_curve(ModelId::Sd, Variant::Printed);
    assert_eq!((c.left_of_zero, c.right_of_zero), (7.5, 7.5));
    let x = 8.0 / 3.0 + 2.0;
    let dahl = 6.0 * (1.0 - (-5.0 * x / 6.0f64).exp());
    assert_relative_eq!(
        c.negative.last().unwrap().force,
        7.5 - dahl,
        max_relative = 1e-12
    );
}

#[test]
fn karnopp_branches_start_outside_the_stick_band() {
    let m = model(ModelId::Karnopp, Variant::Odd);
    let c = curves::velocity_sweep(m.as_ref(), 1.0, 100).unwrap();
    assert!(c.positive.iter().all(|s| s.v > 1e-3));
    assert!(c.negative.iter().all(|s| s.v < -1e-3));
}

#[test]
fn figure_claims_are_decided_by_the_equations() {
    let verdicts = |number: u32| -> Vec<(Claim, bool)> {
        let fig = PAPER_FIGURES.iter().find(|f| f.number == number).unwrap();
        let c = paper_curve(fig.model, Variant::Odd);
        fig.claims
            .iter()
            .map(|&cl| (cl, assess(cl, &c).agrees))
            .collect()
    };
    // Figure 2 (AV): Stribeck drop then viscous growth, as the paper says.
    assert!(verdicts(2).iter().all(|&(_, ok)| ok));
    // Figure 3 (CS): drop to a constant Coulomb level.
    assert!(verdicts(3).iter().all(|&(_, ok)| ok));
    // Figure 5 (DV): no jump at zero and no saturation, against the paper.
    assert_eq!(
        verdicts(5),
        vec![
            (Claim::JumpAtZero(true), false),
            (Claim::LevelsOff(true), false)
        ]
    );
    // Figure 6 (SD): a jump from -7.5 to +7.5; "about -10" disagrees, "about +8" agrees
    // within 10 %; the force levels off towards F_s + F_c.
    assert_eq!(
        verdicts(6),
        vec![
            (Claim::JumpAtZero(true), true),
            (Claim::LeftOfZero(-10.0), false),
            (Claim::RightOfZero(8.0), true),
            (Claim::LevelsOff(true), true),
        ]
    );
    // Figure 7 (SV): ~17 agrees with 16.4, but the viscous term keeps the force growing.
    assert_eq!(
        verdicts(7),
        vec![
            (Claim::JumpAtZero(true), true),
            (Claim::EndLevel(17.0), true),
            (Claim::LevelsOff(true), false),
        ]
    );
}

#[test]
fn bad_curve_options_are_rejected() {
    let m = model(ModelId::Av, Variant::Odd);
    let err = curves::velocity_sweep(m.as_ref(), 0.0, 10).unwrap_err();
    assert_eq!(
        err.to_string(),
        "option `v_max` = 0 is out of range: allowed (0, inf)"
    );
    assert!(matches!(
        curves::velocity_sweep(m.as_ref(), 1.0, 1),
        Err(CurveError::OutOfRange { name: "points", .. })
    ));
    assert!(curves::prescribed_motion(m.as_ref(), f64::NAN, 10).is_err());
    let lugre = ModelId::LuGre
        .build(Variant::Odd, &FrictionParams::lugre_1995())
        .unwrap();
    assert_eq!(
        curves::prescribed_motion(lugre.as_ref(), 1.0, 10).unwrap_err(),
        CurveError::RateDependentState("lugre".into())
    );
}
