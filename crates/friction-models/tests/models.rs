//! The models against values computed by hand from `models.md`, and every analytic partial
//! derivative against a central finite difference.

use approx::assert_relative_eq;
use friction_models::{
    Direction, FrictionModel, FrictionParams, ModelId, ParamError, Parameters, SignLaw,
    StatePartials, Variant,
};

fn build(id: ModelId, variant: Variant) -> Box<dyn FrictionModel> {
    id.build(variant, &FrictionParams::paper()).unwrap()
}

fn slip(id: ModelId, variant: Variant, v: f64, z: f64) -> f64 {
    let m = build(id, variant);
    m.force(0.0, v, &states(&*m, z), SignLaw::Discontinuous)
}

/// Every internal state of `m` set to `z`.
fn states(m: &dyn FrictionModel, z: f64) -> Vec<f64> {
    vec![z; m.n_states()]
}

/// F and ż at (x, v, z).
fn response(m: &dyn FrictionModel, x: f64, v: f64, z: &[f64], law: SignLaw) -> (f64, Vec<f64>) {
    let mut rate = vec![0.0; m.n_states()];
    (m.response(x, v, z, law, &mut rate), rate)
}

#[test]
fn slip_forces_match_hand_computation_with_table_1() {
    // Table 1: F_s = 7.5, F_c = 6, mu_v = 0.5, v_s = 0.1, C1 = C2 = 1.5.
    let e = (-(0.2f64 / 0.1).powi(2)).exp(); // Stribeck factor at |v| = 0.2
    let odd = Variant::Odd;
    assert_relative_eq!(slip(ModelId::Av, odd, 0.2, 0.0), 7.5 + 0.1 + 1.5 * e);
    assert_relative_eq!(slip(ModelId::Av, odd, -0.2, 0.0), -7.5 - 0.1 - 1.5 * e);
    assert_relative_eq!(slip(ModelId::Cs, odd, 0.2, 0.0), 6.0 + 1.5 * e);
    assert_relative_eq!(slip(ModelId::Cvs, odd, -0.2, 0.0), -6.0 - 0.1 - 1.5 * e);
    assert_relative_eq!(slip(ModelId::Dv, odd, 0.2, 2.0), 0.1 + 2.0);
    assert_relative_eq!(slip(ModelId::Sd, odd, -0.2, -2.0), -7.5 - 2.0);
    assert_relative_eq!(slip(ModelId::Sv, odd, 0.2, 2.0), 7.5 + 0.1 + 2.0);
    // As printed, the static term is +F_s in both directions.
    let printed = Variant::Printed;
    assert_relative_eq!(slip(ModelId::Av, printed, -0.2, 0.0), 7.5 - 0.1 - 1.5 * e);
    assert_relative_eq!(slip(ModelId::Sd, printed, -0.2, -2.0), 7.5 - 2.0);
    assert_relative_eq!(slip(ModelId::Sv, printed, -0.2, -2.0), 7.5 - 0.1 - 2.0);
    // Models without a static term are the same in both readings.
    assert_eq!(
        slip(ModelId::Cvs, printed, -0.2, 0.0),
        slip(ModelId::Cvs, odd, -0.2, 0.0)
    );
}

#[test]
fn stick_intervals_are_those_of_models_md() {
    let z = 0.8;
    let interval = |id, variant| {
        let m = build(id, variant);
        m.stick_interval(0.0, &states(&*m, z))
    };
    let odd = Variant::Odd;
    let check = |id, variant, lower: f64, upper: f64| {
        let s = interval(id, variant);
        assert_relative_eq!(s.lower, lower, max_relative = 1e-15);
        assert_relative_eq!(s.upper, upper, max_relative = 1e-15);
    };
    check(ModelId::Av, odd, -(7.5 + 1.5), 7.5 + 1.5);
    check(ModelId::Cs, odd, -7.5, 7.5);
    check(ModelId::Cvs, odd, -7.5, 7.5);
    check(ModelId::Dv, odd, z, z);
    check(ModelId::Sd, odd, z - 7.5, z + 7.5);
    check(ModelId::Sv, odd, z - 7.5, z + 7.5);
    check(ModelId::Av, Variant::Printed, 7.5 - 1.5, 7.5 + 1.5);
    check(ModelId::Sd, Variant::Printed, 7.5 + z, 7.5 + z);
    check(ModelId::Coulomb, odd, -6.0, 6.0);
    check(ModelId::Static, odd, -7.5, 7.5);
    check(ModelId::Stribeck, odd, -7.5, 7.5);
    check(ModelId::Karnopp, odd, -7.5, 7.5);
}

#[test]
fn asymmetric_stribeck_amplitudes_set_the_av_limits() {
    let mut p = FrictionParams::paper();
    p.set("C1", 1.0).unwrap();
    p.set("C2", 2.0).unwrap();
    let av = ModelId::Av.build(Variant::Odd, &p).unwrap();
    let s = av.stick_interval(0.0, &[]);
    assert_eq!((s.lower, s.upper), (-9.5, 8.5));
    // The frozen law gives the one-sided limits of the slip force.
    let up = av.force(0.0, 0.0, &[], SignLaw::Frozen(Direction::Positive));
    assert_eq!(up, 8.5);
}

#[test]
fn stick_law_clamps_the_applied_force() {
    let cs = build(ModelId::Cs, Variant::Odd);
    let s = cs.stick_interval(0.0, &[]);
    assert_eq!(s.clamp(5.0), 5.0);
    assert_eq!(s.clamp(-15.0), -7.5);
    assert!(s.contains(7.5) && !s.contains(7.6));
}

#[test]
fn odd_models_are_odd() {
    for id in ModelId::ALL {
        let m = build(id, Variant::Odd);
        for &(v, z) in &[(0.03, 0.4), (0.7, 5.0), (2.0, -1.0)] {
            let plus = response(&*m, 0.0, v, &states(&*m, z), SignLaw::Discontinuous);
            let minus = response(&*m, 0.0, -v, &states(&*m, -z), SignLaw::Discontinuous);
            assert_relative_eq!(plus.0, -minus.0, max_relative = 1e-14);
            for (p, q) in plus.1.iter().zip(&minus.1) {
                assert_relative_eq!(*p, -q, max_relative = 1e-14);
            }
        }
    }
}

#[test]
fn regularised_force_tends_to_the_slip_force() {
    for id in ModelId::ALL {
        let m = build(id, Variant::Odd);
        let v = 0.05;
        let mut z = states(&*m, 0.0);
        m.steady_state(v, &mut z);
        z.iter_mut().for_each(|z| *z *= 0.5);
        let exact = m.force(0.0, v, &z, SignLaw::Discontinuous);
        let smooth = m.force(0.0, v, &z, SignLaw::Smooth { epsilon: 1e-4 });
        assert_relative_eq!(smooth, exact, max_relative = 1e-12);
        // and is smooth through zero: no jump between ±1e-12
        let eps = SignLaw::Smooth { epsilon: 1e-3 };
        let jump = m.force(0.0, 1e-12, &z, eps) - m.force(0.0, -1e-12, &z, eps);
        assert!(jump.abs() < 1e-6, "{id}: jump {jump}");
    }
}

fn assert_close(analytic: f64, numeric: f64, what: &str) {
    let scale = analytic.abs().max(numeric.abs()).max(1.0);
    assert!(
        (analytic - numeric).abs() <= 1e-6 * scale,
        "{what}: analytic {analytic} vs finite difference {numeric}"
    );
}

#[test]
fn analytic_partials_match_finite_differences() {
    let laws = [
        SignLaw::Discontinuous,
        SignLaw::Frozen(Direction::Positive),
        SignLaw::Frozen(Direction::Negative),
        SignLaw::Smooth { epsilon: 0.05 },
    ];
    let mut lugre_params = FrictionParams::lugre_1995();
    lugre_params.set("v_s", 0.1).unwrap(); // keep g(v) varying over the sampled velocities
    lugre_params.set("v_d", 0.1).unwrap(); // and the damping σ1·exp(−(v/v_d)²)
                                           // z_ba = 4e-6 m: no sampled z sits on the kink of α at |z| = z_ba (α is C¹ there, not C²).
    lugre_params.set("r_ba", 0.4).unwrap();
    for id in ModelId::ALL {
        for variant in [Variant::Odd, Variant::Printed] {
            let lugre_family = matches!(
                id,
                ModelId::LuGre | ModelId::LuGreVd | ModelId::ElastoPlastic | ModelId::Gms
            );
            let params = if lugre_family {
                lugre_params
            } else {
                FrictionParams::paper()
            };
            let m = id.build(variant, &params).unwrap();
            let n = m.n_states();
            for law in laws {
                // For the elasto-plastic model the third point lies in its elastic range
                // (|z| < z_ba) and the second and last in its transition to plastic sliding
                // (z_ba < |z| < z_max); GMS's blocks are on both sides of their switch at
                // the third and last.
                for &(x, v, z) in &[
                    (0.1, 0.07, 0.3),
                    (-0.4, -0.12, -0.5e-5),
                    (1.0, 0.02, 2e-6),
                    (0.2, 0.05, 0.9e-5),
                ] {
                    // Unequal states: z_i = z·(1 + i/10).
                    let z: Vec<f64> = (0..n).map(|i| z * (1.0 + 0.1 * i as f64)).collect();
                    let mut d = vec![StatePartials::default(); n];
                    let p = m.partials(x, v, &z, law, &mut d);
                    let at = |x: f64, v: f64, z: &[f64]| response(&*m, x, v, z, law);
                    let what = |name: &str| {
                        format!("{name} of {id} {variant} {law:?} at x = {x}, v = {v}, z = {z:?}")
                    };
                    // Derivatives in x and v of F and of every ż_i.
                    let dx = central_all(|u| at(u, v, &z), x);
                    let dv = central_all(|u| at(x, u, &z), v);
                    assert_close(p.force_dx, dx.0, &what("dF/dx"));
                    assert_close(p.force_dv, dv.0, &what("dF/dv"));
                    for i in 0..n {
                        assert_close(d[i].rate_dx, dx.1[i], &what(&format!("dz{i}dot/dx")));
                        assert_close(d[i].rate_dv, dv.1[i], &what(&format!("dz{i}dot/dv")));
                        let dz = central_all(
                            |u| {
                                let mut z = z.clone();
                                z[i] = u;
                                at(x, v, &z)
                            },
                            z[i],
                        );
                        assert_close(d[i].force_dz, dz.0, &what(&format!("dF/dz{i}")));
                        for (j, numeric) in dz.1.iter().enumerate() {
                            // The state block is diagonal.
                            let analytic = if i == j { d[i].rate_dz } else { 0.0 };
                            assert_close(analytic, *numeric, &what(&format!("dz{j}dot/dz{i}")));
                        }
                    }
                }
            }
        }
    }
}

/// Central differences of the force and of every state rate at `u`, step scaled to `u`.
fn central_all(f: impl Fn(f64) -> (f64, Vec<f64>), u: f64) -> (f64, Vec<f64>) {
    let h = 1e-6 * u.abs().max(1e-3);
    let (plus, minus) = (f(u + h), f(u - h));
    let rates = plus
        .1
        .iter()
        .zip(&minus.1)
        .map(|(p, m)| (p - m) / (2.0 * h));
    ((plus.0 - minus.0) / (2.0 * h), rates.collect())
}

#[test]
fn dahl_state_reproduces_the_closed_form_under_the_paper_motion() {
    // Along X(t) = t³/3 + t²/2 from rest, the state propagated by Dahl's law equals the
    // printed closed form F_c(1 − exp(−σ|X|/F_c)) to 1e-10 relative, for every Dahl model.
    let p = FrictionParams::paper();
    for id in [ModelId::Dv, ModelId::Sd, ModelId::Sv, ModelId::Dahl] {
        let m = build(id, Variant::Odd);
        let position = |t: f64| t.powi(3) / 3.0 + t * t / 2.0;
        let mut z = [0.0];
        let n = 2000;
        for i in 1..=n {
            let (t0, t1) = ((i - 1) as f64 * 2.0 / n as f64, i as f64 * 2.0 / n as f64);
            let z0 = z;
            assert!(m.state_after_displacement(&z0, position(t1) - position(t0), &mut z));
            let closed =
                friction_models::terms::dahl_closed_form(p.sigma, p.f_c, position(t1), 1.0);
            assert_relative_eq!(z[0], closed, max_relative = 1e-10);
        }
    }
}

#[test]
fn lugre_steady_state_is_the_stribeck_curve() {
    let p = FrictionParams::lugre_1995();
    for id in [ModelId::LuGre, ModelId::Gms] {
        let m = id.build(Variant::Odd, &p).unwrap();
        for &v in &[-0.01, -1e-3, 2e-4, 5e-3, 0.1] {
            let mut z = states(&*m, 0.0);
            m.steady_state(v, &mut z);
            let (force, rate) = response(&*m, 0.0, v, &z, SignLaw::Discontinuous);
            let g = p.f_c + (p.f_s - p.f_c) * (-(v / p.v_s).powi(2)).exp();
            for rate in rate {
                assert!(
                    rate.abs() < 1e-12 * v.abs().max(1e-12) * 1e3,
                    "{id}: {rate}"
                );
            }
            assert_relative_eq!(force, g * v.signum() + p.sigma2 * v, max_relative = 1e-12);
        }
        assert!(!m.state_after_displacement(&[0.0], 1.0, &mut [0.0]));
    }
}

#[test]
fn lugre_rejects_a_zero_static_level() {
    let mut p = FrictionParams::lugre_1995();
    p.set("F_s", 0.0).unwrap();
    let err = ModelId::LuGre.build(Variant::Odd, &p).unwrap_err();
    assert!(matches!(err, ParamError::Invalid { ref name, .. } if name == "F_s"));
    assert!(err.to_string().contains("F_s in (0, inf) N"), "{err}");
}

#[test]
fn model_names_round_trip_and_unknown_names_are_listed() {
    for id in ModelId::ALL {
        assert_eq!(ModelId::from_name(&id.name().to_lowercase()), Ok(id));
    }
    let err = ModelId::from_name("bouc-wen").unwrap_err();
    assert!(
        err.starts_with("unknown model `bouc-wen`; known models: AV, CS"),
        "{err}"
    );
}

#[test]
fn the_catalog_lists_every_model_at_its_own_index() {
    // The catalog's entries are indexed by `ModelId as usize`: ALL must list the models in
    // their declaration order, and each entry must be its model's.
    for (i, id) in ModelId::ALL.into_iter().enumerate() {
        assert_eq!(id as usize, i, "{id}");
    }
    assert_eq!(ModelId::Gms.entry().name, "gms");
    assert_eq!(
        ModelId::Sd.curve_axis(),
        friction_models::CurveAxis::Displacement
    );
    assert!(ModelId::Sv.has_printed_form() && !ModelId::Cvs.has_printed_form());
    assert_ne!(
        ModelId::Av.equation(Variant::Printed),
        ModelId::Av.equation(Variant::Odd)
    );
    assert_eq!(
        ModelId::Cs.equation(Variant::Printed),
        ModelId::Cs.equation(Variant::Odd)
    );
}

#[test]
fn every_model_declares_parameters_that_exist() {
    for id in ModelId::ALL {
        for name in id.parameters() {
            assert!(FrictionParams::spec(name).is_some(), "{id}: {name}");
        }
    }
}

#[test]
fn a_law_that_says_it_ignores_x_gives_the_same_force_partials_and_stick_interval_at_any_x() {
    let mut checked = 0;
    for params in [FrictionParams::paper(), FrictionParams::lugre_1995()] {
        for id in ModelId::ALL {
            let Ok(m) = id.build(Variant::Odd, &params) else {
                continue;
            };
            if m.depends_on_position() {
                continue;
            }
            let n = m.n_states();
            let z = vec![0.3; n];
            for law in [
                SignLaw::Discontinuous,
                SignLaw::Frozen(Direction::Negative),
                SignLaw::Smooth { epsilon: 1e-3 },
            ] {
                for v in [-0.2, 0.0, 1e-4, 0.3] {
                    let at = |x: f64| {
                        let (mut rate, mut d) = (vec![0.0; n], vec![StatePartials::default(); n]);
                        let (f, p) = m.evaluate(x, v, &z, law, &mut rate, &mut d);
                        (f, p, rate, d)
                    };
                    let (a, b) = (at(0.0), at(-3.7));
                    assert_eq!(a, b, "{id:?} at v = {v} under {law:?}");
                    assert_eq!(a.1.force_dx, 0.0, "{id:?}");
                    checked += 1;
                }
            }
            assert_eq!(
                m.stick_interval(0.0, &z),
                m.stick_interval(2.5, &z),
                "{id:?}"
            );
        }
    }
    // The 16 models of the catalog all ignore x; some are built under both parameter sets.
    assert!(checked >= 16 * 12, "{checked} points checked");
}

/// A law that says it is affine in v gives, in each direction of sliding, the force on the
/// line through its value and slope at rest (to rounding), at speeds from 1e-6 to 30 m/s;
/// and the laws that say so are exactly those without a Stribeck term or a state.
#[test]
fn a_law_that_says_it_is_affine_in_v_lies_on_its_tangent_at_rest() {
    let mut affine = Vec::new();
    for id in ModelId::ALL {
        let m = build(id, Variant::Odd);
        if !m.affine_in_velocity() {
            continue;
        }
        affine.push(id);
        let z = states(&*m, 0.0);
        for d in [Direction::Positive, Direction::Negative] {
            let law = SignLaw::Frozen(d);
            let at = |v: f64| {
                let (mut rate, mut s) = (z.clone(), vec![StatePartials::default(); z.len()]);
                m.evaluate(0.0, v, &z, law, &mut rate, &mut s)
            };
            let (f0, p0) = at(0.0);
            for speed in [1e-6, 0.05, 1.0, 30.0] {
                let v = d.sign() * speed;
                let line = f0 + p0.force_dv * v;
                let (f, p) = at(v);
                assert!(
                    (f - line).abs() <= 8.0 * f64::EPSILON * f.abs().max(1.0),
                    "{id:?} at v = {v}: {f} off the line {line}"
                );
                assert_eq!(p.force_dv, p0.force_dv, "{id:?} at v = {v}");
            }
        }
    }
    assert_eq!(
        affine,
        [
            ModelId::Coulomb,
            ModelId::Viscous,
            ModelId::Static,
            ModelId::Karnopp
        ]
    );
}
