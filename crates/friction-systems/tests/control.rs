//! Controllers in systems: a PID on a body's position against closed forms (a frictionless
//! PD loop, a stuck body whose integral winds up to break-away), its Jacobian, its energy
//! (the actuator's work), the same loop under every scheme, friction compensation, and the
//! refusals of a bad `[[controller]]` table.

use friction_models::{FrictionParams, ModelId, Variant};
use friction_systems::file::parse;
use friction_systems::{
    simulate, CompensatedAt, Compensation, Controller, FrictionSystem, Reference, Scheme,
    Switching, System, SLIP_POSITIVE, STICK,
};
use integrators::{Mode, OdeProblem, Options, Output, Solver, StepControl};
use std::sync::Arc;

/// The gains of the hunting example of Canudas de Wit, Olsson, Åström & Lischinsky (1995).
const KP: f64 = 3.0;
const KI: f64 = 4.0;
const KD: f64 = 6.0;

fn pid(body: usize, reference: Reference) -> Controller {
    Controller {
        body,
        kp: KP,
        ki: KI,
        kd: KD,
        reference,
        saturation: None,
        compensation: None,
    }
}

fn law(model: ModelId) -> Arc<dyn friction_models::FrictionModel> {
    Arc::from(model.build(Variant::Odd, &FrictionParams::paper()).unwrap())
}

/// A unit mass on the floor with `model`, under `controller`.
fn servo(model: Option<ModelId>, controller: Controller) -> System {
    let mut s = System::default();
    let body = s.add_body("mass", 1.0, 0.0, 0.0);
    if let Some(model) = model {
        s.add_contact(body, 0.0, law(model));
    }
    s.add_controller(controller);
    s
}

fn tight(t_end: f64, points: usize) -> Options {
    Options {
        output: Output::Grid(integrators::even_grid(0.0, t_end, points)),
        ..Options::adaptive(0.0, t_end, 1e-11, 1e-12)
    }
}

fn event_driven(switching: Switching) -> Scheme {
    Scheme::EventDriven {
        solver: Solver::DOPRI5,
        switching,
    }
}

#[test]
fn a_frictionless_pd_loop_follows_its_closed_form() {
    // m·ẍ = kp·(1 − x) − kd·ẋ from rest: ẍ + 6ẋ + 3x = 3, roots −3 ± √6, overdamped.
    let c = Controller {
        ki: 0.0,
        ..pid(0, Reference::Constant { x: 1.0 })
    };
    let system = servo(None, c);
    let run = simulate(
        &system,
        event_driven(Switching::Event),
        tight(5.0, 51),
        &mut |_| {},
    )
    .unwrap();
    assert!(run.error.is_none(), "{:?}", run.error);
    let (l1, l2) = (-3.0 + 6f64.sqrt(), -3.0 - 6f64.sqrt());
    let exact = |t: f64| 1.0 - (l2 * (l1 * t).exp() - l1 * (l2 * t).exp()) / (l2 - l1);
    for b in run.body(0) {
        assert!(
            (b.x - exact(b.t)).abs() < 1e-9,
            "t {}: {} vs {}",
            b.t,
            b.x,
            exact(b.t)
        );
    }
    // The actuator's work is the kinetic energy it left, the loop having no spring.
    let e = run.energy().unwrap();
    assert!(e.relative_residual < 1e-9, "{e:?}");
    assert!(e.external_work > 0.0);
}

#[test]
fn a_stuck_body_breaks_away_when_the_integral_has_wound_up_to_the_static_level() {
    // The `static` law holds the body up to F_s = 7.5 N. At rest at x = 0 with r = 1 m the
    // control force is kp·1 + ki·t: it reaches F_s at t = (7.5 − 3)/4 = 1.125 s.
    let system = servo(
        Some(ModelId::Static),
        pid(0, Reference::Constant { x: 1.0 }),
    );
    let exact = (7.5 - KP) / KI;
    let run = simulate(
        &system,
        event_driven(Switching::Event),
        tight(2.0, 201),
        &mut |_| {},
    )
    .unwrap();
    assert!(run.error.is_none(), "{:?}", run.error);
    let first = run.contact_events()[0];
    assert_eq!((first.from, first.to), (STICK, SLIP_POSITIVE));
    assert!(
        (first.t - exact).abs() < 1e-9,
        "break-away at {} s",
        first.t
    );
    // While stuck the contact holds the whole control force.
    let at_one = run.body(0).into_iter().find(|b| b.t == 1.0).unwrap();
    assert!(
        (at_one.friction - (KP + KI * 1.0)).abs() < 1e-9,
        "{at_one:?}"
    );
    let e = run.energy().unwrap();
    assert!(e.relative_residual < 1e-8, "{e:?}");
}

#[test]
fn time_stepping_and_regularisation_break_away_where_event_location_does() {
    let system = servo(
        Some(ModelId::Static),
        pid(0, Reference::Constant { x: 1.0 }),
    );
    let exact = (7.5 - KP) / KI;
    let h = 1e-3;
    let stepped = Options {
        step: StepControl::Fixed { h },
        ..tight(2.0, 201)
    };
    let run = simulate(
        &system,
        Scheme::TimeStepping { theta: 0.5 },
        stepped,
        &mut |_| {},
    )
    .unwrap();
    assert!(run.error.is_none(), "{:?}", run.error);
    let first = run.contact_events()[0];
    // The controller is sampled at each step's start and held over the step: the force
    // first exceeds F_s at a step's start after the exact time, and the switch is recorded
    // at that step's end.
    assert!(
        first.t > exact && first.t <= exact + 2.0 * h + 1e-12,
        "time-stepped break-away at {} s",
        first.t
    );
    // Regularised, a law has no static level above its kinetic one: Coulomb's body creeps
    // under any force and moves off when the control force reaches F_c = 6 N, at
    // (6 − 3)/4 = 0.75 s, where event location breaks away.
    let system = servo(
        Some(ModelId::Coulomb),
        pid(0, Reference::Constant { x: 1.0 }),
    );
    let kinetic = (6.0 - KP) / KI;
    let moving = |switching| {
        let run = simulate(
            &system,
            event_driven(switching),
            tight(2.0, 2001),
            &mut |_| {},
        )
        .unwrap();
        assert!(run.error.is_none(), "{:?}", run.error);
        let first = run.contact_events().first().map(|e| e.t);
        (
            first,
            run.body(0).into_iter().find(|b| b.v > 1e-2).unwrap().t,
        )
    };
    let (break_away, event) = moving(Switching::Event);
    let break_away = break_away.unwrap();
    assert!(
        (break_away - kinetic).abs() < 1e-9,
        "break-away at {break_away} s"
    );
    let (_, regularised) = moving(Switching::Regularized { epsilon: 1e-4 });
    assert!(
        (regularised - event).abs() < 2e-3,
        "v > 1e-2 at {regularised} s, not {event} s"
    );
}

#[test]
fn a_sampled_pd_loop_is_unstable_where_its_step_map_has_a_multiplier_beyond_one() {
    // m·ẍ = kp·(1 − x) − kd·ẋ (m = 1, kp = 3, kd = 6: roots −3 ± √6, both decaying), time-
    // stepped with the control force held over each step. One step of the θ-method on (x, v):
    //   v' = v + h·(kp·(1 − x) − kd·v),  x' = x + h·(θ·v' + (1 − θ)·v),
    // a linear map whose matrix [[1 − θh²kp, h(1 − θh·kd)], [−h·kp, 1 − h·kd]] has the
    // multipliers of the sampled loop (the error's integral adds a multiplier 1).
    let c = Controller {
        ki: 0.0,
        ..pid(0, Reference::Constant { x: 1.0 })
    };
    let system = servo(None, c);
    let theta = 0.5;
    let multiplier = |h: f64| {
        let (a, b) = (1.0 - theta * h * h * KP, h * (1.0 - theta * h * KD));
        let (c, d) = (-h * KP, 1.0 - h * KD);
        let (trace, det) = (a + d, a * d - b * c);
        let root = (trace * trace - 4.0 * det).sqrt();
        ((trace + root) / 2.0)
            .abs()
            .max(((trace - root) / 2.0).abs())
    };
    let instability = |h: f64| {
        let scheme = Scheme::TimeStepping { theta };
        let run = simulate(&system, scheme, Options::fixed(0.0, 3.0, h), &mut |_| {}).unwrap();
        run.instability(&scheme, StepControl::Fixed { h })
    };
    // h = 0.5: |μ| = 2.136, the loop grows though the continuous one decays.
    let found = instability(0.5).expect("the sampled loop at h = 0.5 s is unstable");
    assert!(
        (found.amplification() - multiplier(0.5)).abs() < 1e-6 && multiplier(0.5) > 2.0,
        "{found:?}, {}",
        multiplier(0.5)
    );
    assert!(found.to_string().contains("zero-order hold"), "{found}");
    // h = 0.25: |μ| = 0.55, stable.
    assert!(multiplier(0.25) < 1.0);
    assert_eq!(instability(0.25), None);
}

#[test]
fn the_jacobian_of_a_controlled_body_matches_central_differences() {
    let reference = Reference::Sinusoid {
        x0: 0.2,
        amplitude: 0.5,
        omega: 2.0,
    };
    let mut c = pid(0, reference);
    c.compensation = Some(Compensation {
        model: law(ModelId::Cvs),
        at: CompensatedAt::Measured,
    });
    let system = servo(Some(ModelId::Cvs), c);
    for switching in [Switching::Event, Switching::Regularized { epsilon: 0.05 }] {
        let p = FrictionSystem::new(&system, switching);
        let mut y = p.initial_state();
        y[p.layout.x[0]] = 0.1;
        y[p.layout.v(0)] = 0.3;
        y[p.layout.integral[0]] = -0.2;
        let modes: [Mode; 1] = [SLIP_POSITIVE];
        let n = p.layout.accumulators;
        let mut analytic = vec![0.0; n * n];
        let mut entries = Vec::new();
        assert!(p.jacobian(0.7, &y, &modes, &mut entries));
        for (i, j, a) in entries {
            analytic[i * n + j] += a;
        }
        let (mut fp, mut fm) = (vec![0.0; p.dim()], vec![0.0; p.dim()]);
        for j in 0..n {
            let h = 1e-6;
            let (mut yp, mut ym) = (y.clone(), y.clone());
            yp[j] += h;
            ym[j] -= h;
            p.rhs(0.7, &yp, &modes, &mut fp);
            p.rhs(0.7, &ym, &modes, &mut fm);
            for i in 0..n {
                let fd = (fp[i] - fm[i]) / (2.0 * h);
                let a = analytic[i * n + j];
                assert!(
                    (a - fd).abs() < 1e-6 * a.abs().max(1.0),
                    "{switching:?} ({i}, {j}): {a} vs {fd}"
                );
            }
        }
    }
}

#[test]
fn a_saturated_actuator_pushes_with_its_limit_and_no_more() {
    // Frictionless, r = 10 m: kp·10 = 30 N would be asked; the actuator gives 2 N, so the
    // body accelerates at 2 m/s² from rest until the error shrinks.
    let mut c = pid(0, Reference::Constant { x: 10.0 });
    c.saturation = Some(2.0);
    let system = servo(None, c);
    let run = simulate(
        &system,
        event_driven(Switching::Event),
        tight(1.0, 11),
        &mut |_| {},
    )
    .unwrap();
    let end = run.body(0).pop().unwrap();
    assert!(
        (end.x - 1.0).abs() < 1e-9 && (end.v - 2.0).abs() < 1e-9,
        "{end:?}"
    );
}

/// RMS of the tracking error of a unit mass, with Coulomb friction (`friction`) or none,
/// following r = sin(t) over its second 10 s, compensated with `compensation`.
fn tracking_error(friction: bool, compensation: Option<CompensatedAt>) -> f64 {
    let reference = Reference::Sinusoid {
        x0: 0.0,
        amplitude: 1.0,
        omega: 1.0,
    };
    let mut c = pid(0, reference.clone());
    c.compensation = compensation.map(|at| Compensation {
        model: law(ModelId::Coulomb),
        at,
    });
    let system = servo(friction.then_some(ModelId::Coulomb), c);
    let run = simulate(
        &system,
        event_driven(Switching::Event),
        tight(20.0, 2001),
        &mut |_| {},
    )
    .unwrap();
    assert!(run.error.is_none(), "{:?}", run.error);
    let settled: Vec<f64> = (run.body(0).into_iter())
        .filter(|b| b.t >= 10.0)
        .map(|b| b.x - reference.at(b.t).0)
        .collect();
    (settled.iter().map(|e| e * e).sum::<f64>() / settled.len() as f64).sqrt()
}

#[test]
fn friction_compensation_brings_tracking_back_to_the_frictionless_loop() {
    // The linear loop's own error at ω = 1: |e/r| = |s³/(s³ + 6s² + 3s + 4)| at s = i, that
    // is 1/|−2 + 2i| = 0.354, an RMS of 0.25 m.
    let linear = tracking_error(false, None);
    assert!(
        (linear - 0.25).abs() < 0.01,
        "frictionless RMS error {linear}"
    );
    let none = tracking_error(true, None);
    let reference = tracking_error(true, Some(CompensatedAt::Reference));
    let measured = tracking_error(true, Some(CompensatedAt::Measured));
    // Uncompensated, the integral must swing from +F_c to −F_c at each reversal while the
    // body sticks. Compensated at the reference velocity by the plant's own law, the loop is
    // the linear one. At the measured velocity the compensation is zero while the body is at
    // rest, so it still sticks at each reversal until the loop alone overcomes F_c: better
    // than none, not linear.
    assert!(none > 2.0 * linear, "uncompensated {none} against {linear}");
    assert!(
        (reference - linear).abs() < 0.02 * linear,
        "at the reference: {reference}"
    );
    assert!(
        measured < 0.8 * none && measured > 1.5 * linear,
        "at the measured: {measured}"
    );
}

const MASS: &str = "[[body]]\nname = \"mass\"\nm = 1\n[[anchor]]\nname = \"wall\"\n";

fn refused(controller: &str) -> String {
    parse(&format!("{MASS}[[controller]]\n{controller}")).unwrap_err()
}

#[test]
fn a_bad_controller_table_is_refused_naming_its_key() {
    let constant = "reference = { kind = \"constant\", x = 1.0 }\n";
    let gains = "kp = 3\nki = 0\nkd = 0\n";
    // A gain left out is refused, not run as 0.
    let e = refused(&format!("body = \"mass\"\nkp = 3\nkd = 0\n{constant}"));
    assert!(e.contains("missing field `ki`"), "{e}");
    let e = refused(&format!("body = \"wall\"\n{gains}{constant}"));
    assert!(
        e.contains("[[controller]] 1: `body` names the anchor \"wall\""),
        "{e}"
    );
    let e = refused(&format!("body = \"cart\"\n{gains}{constant}"));
    assert!(
        e.contains("`body` names \"cart\", which is no body or anchor"),
        "{e}"
    );
    let e = refused(&format!(
        "body = \"mass\"\nkp = 3\nki = -4\nkd = 0\n{constant}"
    ));
    assert!(
        e.contains("[[controller]] 1: `ki` = -4 is out of range: allowed [0, inf)"),
        "{e}"
    );
    let e = refused(&format!(
        "body = \"mass\"\n{gains}reference = {{ kind = \"table\", t = [0, 2, 1], x = [0, 1, 2] }}\n"
    ));
    assert!(
        e.contains("`reference.t` does not increase: t = 1 after t = 2"),
        "{e}"
    );
    let e = refused(&format!(
        "body = \"mass\"\n{gains}reference = {{ kind = \"step\", x = 1 }}\n"
    ));
    assert!(e.contains("unknown variant `step`"), "{e}");
    let e = refused(&format!(
        "body = \"mass\"\n{gains}{constant}compensation = {{ model = \"coulomb2\" }}\n"
    ));
    assert!(
        e.contains("[[controller]] 1: `compensation.model`: unknown model `coulomb2`"),
        "{e}"
    );
    let e = refused(&format!(
        "body = \"mass\"\n{gains}saturation = 0\n{constant}"
    ));
    assert!(
        e.contains("`saturation` = 0 is out of range: allowed (0, inf)"),
        "{e}"
    );
    let twice = format!(
        "body = \"mass\"\n{gains}{constant}[[controller]]\nbody = \"mass\"\n{gains}{constant}"
    );
    let e = refused(&twice);
    assert!(
        e.contains("[[controller]] 2: body \"mass\" has a controller already"),
        "{e}"
    );
}

#[test]
fn a_controller_table_declares_the_controller_of_code() {
    let s = parse(&format!(
        "{MASS}[[contact]]\nbody = \"mass\"\nmodel = \"static\"\n[[controller]]\n\
         body = \"mass\"\nkp = 3.0\nki = 4.0\nkd = 6.0\nsaturation = 10.0\n\
         reference = {{ kind = \"table\", t = [0.0, 1.0], x = [0.0, 2.0] }}\n\
         compensation = {{ model = \"coulomb\", params = {{ F_c = 1.0 }}, velocity = \"measured\" }}\n"
    ))
    .unwrap();
    let c = &s.controllers[0];
    assert_eq!(
        (c.body, c.kp, c.ki, c.kd, c.saturation),
        (0, 3.0, 4.0, 6.0, Some(10.0))
    );
    // Linear between the points, constant outside them.
    assert_eq!(c.reference.at(0.25), (0.5, 2.0));
    assert_eq!(c.reference.at(3.0), (2.0, 0.0));
    let k = c.compensation.as_ref().unwrap();
    assert_eq!(k.at, CompensatedAt::Measured);
    assert_eq!(k.force(0.3, friction_models::SignLaw::Discontinuous).0, 1.0);
}

#[test]
fn a_controller_gain_is_set_by_its_path() {
    let text = format!(
        "{MASS}[[controller]]\nbody = \"mass\"\nkp = 3\nki = 0\nkd = 0\nreference = {{ kind = \"constant\", x = 1 }}\n"
    );
    let set = |path: &str, value: f64| {
        friction_systems::file::parse_with(&text, &[(path.to_string(), value)])
    };
    let s = set("controller.mass.ki", 2.5).unwrap();
    assert_eq!((s.controllers[0].kp, s.controllers[0].ki), (3.0, 2.5));
    assert_eq!(
        set("controller.1.saturation", 4.0).unwrap().controllers[0].saturation,
        Some(4.0)
    );
    let e = set("controller.mass.gain", 1.0).unwrap_err();
    assert!(e.contains("[[controller]] has no number `gain`"), "{e}");
    let e = set("controller.mass.kd", -1.0).unwrap_err();
    assert!(e.contains("`kd` = -1 is out of range"), "{e}");
}
