//! The closed-loop rig: a PID-positioned unit mass hunts under stiction and converges without
//! it, and the hunting cycle's measures agree with the switching log and between solvers.

use friction_models::{FrictionParams, ModelId};
use friction_systems::Scheme;
use integrators::{Solver, StepControl};
use scenarios::analysis::closed_loop::ClosedLoop;
use scenarios::stick_slip::Regime;
use scenarios::{run, Limits, Outcome, RunSpec, Scenario};

fn servo_at(model: ModelId, friction: FrictionParams, solver: Solver, points: usize) -> Outcome {
    servo_with(model, friction, solver, points, Scenario::SERVO.defaults())
}

/// The servo with `model` at `friction` under `solver` at rtol 1e-9, to its own end time.
fn servo_spec(
    model: ModelId,
    friction: FrictionParams,
    solver: Solver,
    points: usize,
    params: scenarios::ScenarioParams,
) -> RunSpec {
    RunSpec {
        scenario: Scenario::SERVO,
        law: model.into(),
        friction,
        params,
        scheme: Scheme::events(solver),
        step: StepControl::Adaptive {
            rtol: 1e-9,
            atol: 1e-11,
            h0: None,
        },
        t_end: None,
        output_points: points,
        limits: Limits::default(),
    }
}

fn servo_with(
    model: ModelId,
    friction: FrictionParams,
    solver: Solver,
    points: usize,
    params: scenarios::ScenarioParams,
) -> Outcome {
    let spec = servo_spec(model, friction, solver, points, params);
    let o = run(&spec, &mut |_| {}).unwrap();
    assert!(o.error.is_none(), "{model}: {:?}", o.error);
    o
}

fn servo(model: ModelId, friction: FrictionParams, solver: Solver) -> Outcome {
    servo_at(model, friction, solver, 16001)
}

fn measures(o: &Outcome) -> ClosedLoop {
    ClosedLoop::of_outcome(o).expect("the servo's body is controlled")
}

#[test]
fn under_stiction_the_loop_hunts_on_a_cycle_the_switching_log_confirms() {
    // Coulomb friction with stiction at the paper's levels, F_s = 7.5 N over F_c = 6 N: the
    // integral winds up while the body sticks, it breaks away, overshoots and sticks on the
    // other side of the set point, cycle after cycle.
    let o = servo(ModelId::Static, FrictionParams::paper(), Solver::DOPRI5);
    let c = measures(&o);
    assert_eq!((c.settled, c.hunting), (true, Some(true)), "{c:?}");
    // The period from the velocity's crossings against the spacing of the last two
    // break-aways in the same direction, from the located events.
    let forward: Vec<f64> = (o.events.iter())
        .filter(|e| e.from == friction_systems::STICK && e.to == friction_systems::SLIP_POSITIVE)
        .map(|e| e.t)
        .collect();
    let logged = forward[forward.len() - 1] - forward[forward.len() - 2];
    assert!(
        (c.period - logged).abs() < 1e-2 * logged,
        "{} against {logged}",
        c.period
    );
    // The body sticks on alternate sides, symmetrically: the last stick's error is the
    // amplitude (half the range of x less its drift over the window, v̄·t).
    assert!(
        (c.final_error.abs() - c.amplitude).abs() < 1e-4 * c.amplitude,
        "{c:?}"
    );
    // It is stuck most of the cycle, and the stick time is at most the cycle.
    assert!(c.stick_time_per_cycle > 0.5 * c.period && c.stick_time_per_cycle < c.period);
}

#[test]
fn a_linear_damper_lets_the_loop_converge() {
    // Viscous friction alone is linear: the loop is a stable linear system and settles on the
    // set point.
    let c = measures(&servo(
        ModelId::Viscous,
        FrictionParams::paper(),
        Solver::DOPRI5,
    ));
    assert_eq!((c.settled, c.hunting), (true, Some(false)), "{c:?}");
    assert!(c.final_error.abs() < 1e-6 && c.period.is_nan(), "{c:?}");
    assert_eq!(c.max_error, 1.0);
}

#[test]
fn lugre_hunts_on_the_same_cycle_with_an_explicit_and_an_implicit_solver() {
    // The 1995 paper's example: LuGre at its parameters (F_c = 1 N, F_s = 1.5 N), kp = 3,
    // ki = 4, kd = 6, set point 1 m.
    let lugre = FrictionParams::lugre_1995();
    let a = measures(&servo(ModelId::LuGre, lugre, Solver::DOPRI5));
    let b = measures(&servo(ModelId::LuGre, lugre, Solver::BDF));
    for c in [a, b] {
        assert_eq!((c.settled, c.hunting), (true, Some(true)), "{c:?}");
    }
    assert!((a.period - b.period).abs() < 1e-3 * a.period, "{a:?} {b:?}");
    assert!(
        (a.amplitude - b.amplitude).abs() < 1e-3 * a.amplitude,
        "{a:?} {b:?}"
    );
    // LuGre has no stick mode: its body creeps while "stuck", which counts below 1e-3 of the
    // cycle's speed.
    assert!(a.stick_time_per_cycle > 0.5 * a.period, "{a:?}");
}

#[test]
fn the_cycle_is_measured_alike_on_a_coarse_output_grid() {
    // 2001 points over 800 s, 0.4 s apart, against 16001: the error holds still while the
    // body sticks, so a slip between two samples still changes its sign once.
    let lugre = FrictionParams::lugre_1995();
    let coarse = measures(&servo_at(ModelId::LuGre, lugre, Solver::DOPRI5, 2001));
    let fine = measures(&servo(ModelId::LuGre, lugre, Solver::DOPRI5));
    assert!(
        (coarse.period - fine.period).abs() < 1e-3 * fine.period,
        "{coarse:?} {fine:?}"
    );
    assert!((coarse.amplitude - fine.amplitude).abs() < 1e-3 * fine.amplitude);
}

#[test]
fn a_body_at_rest_off_the_set_point_is_stuck_or_in_the_dead_zone_only_without_integral_action() {
    // Coulomb friction, F_c = 6 N. Under PID the body sticks ever closer to the set point
    // while the integral winds up, for ever longer: after 800 s it is stuck 1.7 mm short and
    // will move again, a transient, not a rest state.
    let pid = measures(&servo(
        ModelId::Coulomb,
        FrictionParams::paper(),
        Solver::DOPRI5,
    ));
    assert_eq!((pid.settled, pid.hunting), (false, None), "{pid:?}");
    assert!(pid.final_error.abs() > 1e-4, "{pid:?}");
    assert!(!pid.stuck, "{pid:?}");
    assert_eq!(Regime::of_closed_loop(&pid), Regime::Unsettled);
    // Under PD (ki = 0) the set point is 1 m away and kp·1 m = 3 N < F_c: the body never
    // moves, and that is the loop's rest state: stuck, not converged.
    let pd = |x_ref: f64| scenarios::ScenarioParams {
        ki: 0.0,
        x_ref,
        ..Scenario::SERVO.defaults()
    };
    let coulomb_pd = |x_ref: f64| {
        measures(&servo_with(
            ModelId::Coulomb,
            FrictionParams::paper(),
            Solver::DOPRI5,
            2001,
            pd(x_ref),
        ))
    };
    let c = coulomb_pd(1.0);
    assert_eq!(
        (c.settled, c.stuck, c.hunting, c.final_error),
        (true, true, Some(false), 1.0),
        "{c:?}"
    );
    assert_eq!(Regime::of_closed_loop(&c), Regime::Stuck);
    assert!(c.to_string().contains("stuck, the body never moved"), "{c}");
    // With the set point 6 m away (kp·6 m = 18 N > F_c) it moves, and stops inside the dead
    // zone |e| <= F_c/kp = 2 m, off the set point.
    let c = coulomb_pd(6.0);
    assert!(!c.stuck && c.settled, "{c:?}");
    assert!(
        c.final_error.abs() > 1e-3 && c.final_error.abs() <= 2.0 + 1e-9,
        "{c:?}"
    );
    assert_eq!(Regime::of_closed_loop(&c), Regime::DeadZone);
    assert!(c.to_string().contains("dead zone"), "{c}");
}

#[test]
fn a_body_that_never_follows_a_sinusoid_is_stuck_not_hunting() {
    use friction_systems::Reference;
    use scenarios::tracking::run_tracking;
    // x_r = sin(t) m under P control against Coulomb friction: kp·1 m = 3 N < F_c = 6 N, so
    // the body never moves, while its error r − x = sin(t) crosses zero like a cycle.
    let spec = RunSpec {
        t_end: Some(100.0),
        ..servo_spec(
            ModelId::Coulomb,
            FrictionParams::paper(),
            Solver::DOPRI5,
            5001,
            scenarios::ScenarioParams {
                ki: 0.0,
                kd: 0.0,
                ..Scenario::SERVO.defaults()
            },
        )
    };
    let sine = Reference::Sinusoid {
        x0: 0.0,
        amplitude: 1.0,
        omega: 1.0,
    };
    let o = run_tracking(&spec, &sine, None, &mut |_| {}).unwrap();
    let c = ClosedLoop::of(&o, &sine);
    assert!(c.stuck, "{c:?}");
    assert_ne!(c.hunting, Some(true), "{c:?}");
    assert_ne!(Regime::of_closed_loop(&c), Regime::Hunting);
    // Its RMS error is the reference's own, 1/√2 m.
    assert!((c.rms_error - 0.5f64.sqrt()).abs() < 1e-2, "{c:?}");
}

#[test]
fn a_tracking_task_replaces_the_set_point_and_needs_a_controlled_rig() {
    use friction_systems::Reference;
    use scenarios::tracking::run_tracking;
    let spec = |scenario: Scenario| RunSpec {
        scenario,
        t_end: Some(50.0),
        ..servo_spec(
            ModelId::Viscous,
            FrictionParams::paper(),
            Solver::DOPRI5,
            5001,
            Scenario::SERVO.defaults(),
        )
    };
    // A ramp x_r = 0.1·t under viscous friction mu_v (a linear plant): the PID's integral
    // action removes the steady tracking error, which a set point of 1 m would not measure.
    let ramp = Reference::Ramp { x0: 0.0, v: 0.1 };
    let o = run_tracking(&spec(Scenario::SERVO), &ramp, None, &mut |_| {}).unwrap();
    assert!(o.error.is_none(), "{:?}", o.error);
    assert_eq!(o.reference, Some(ramp.clone()));
    let last = o.last().unwrap();
    assert!((0.1 * last.t - last.x).abs() < 1e-6, "{last:?}");
    // A rig without a controller has no reference to replace.
    let e = run_tracking(&spec(Scenario::BELT), &ramp, None, &mut |_| {}).unwrap_err();
    assert!(e.to_string().contains("`belt` has no controller"), "{e}");
}
