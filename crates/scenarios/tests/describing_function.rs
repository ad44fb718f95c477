//! The describing function of a mass with Coulomb friction, stiction and viscous friction
//! against closed forms, and the harmonic balance of the servo's PID loop.

use num_complex::Complex64;
use scenarios::analysis::describing_function::{
    break_away_gain, predict_hunting, Pid, StictionMass,
};
use std::f64::consts::PI;

const SERVO: Pid = Pid {
    kp: 3.0,
    ki: 4.0,
    kd: 6.0,
};

/// `static` at the paper's levels on the servo's unit mass.
const STATIC: StictionMass = StictionMass {
    m: 1.0,
    f_c: 6.0,
    f_s: 7.5,
    f_v: 0.0,
};

#[test]
fn a_mass_with_viscous_friction_alone_has_its_linear_frequency_response() {
    let mass = StictionMass {
        m: 2.0,
        f_c: 0.0,
        f_s: 0.0,
        f_v: 0.7,
    };
    for omega in [0.3, 1.0, 3.0] {
        let n = mass.response(1.3, omega).unwrap().n;
        // x = u/(m·s² + F_v·s) at s = jω.
        let exact = 1.0 / Complex64::new(-mass.m * omega * omega, mass.f_v * omega);
        assert!(
            (n - exact).norm() <= 1e-9 * exact.norm(),
            "ω = {omega}: {n} against {exact}"
        );
    }
}

#[test]
fn a_force_far_above_the_friction_levels_sees_the_bare_mass() {
    let mass = StictionMass {
        m: 1.5,
        f_c: 1.0,
        f_s: 1.3,
        f_v: 0.0,
    };
    let n = mass.response(1e5, 2.0).unwrap().n;
    let bare = -1.0 / (1.5 * 4.0);
    assert!(
        (n.re - bare).abs() <= 1e-4 * bare.abs() && n.im.abs() <= 1e-4 * bare.abs(),
        "{n}"
    );
}

#[test]
fn a_force_below_the_static_level_moves_nothing() {
    assert!(STATIC.response(7.5, 0.5).is_none());
}

#[test]
fn the_stick_slip_response_is_its_closed_form() {
    // U = 9 N at ω = 0.5 rad/s: the mass breaks away forwards at U·sin ωt = F_s, slides with
    // v = (U/ω·(cos ωt_b − cos ωt) − F_c·(t − t_b))/m until it stops, sticks, and does the
    // same backwards half a period after the break-away.
    let (u, omega, m, f_c) = (9.0, 0.5, STATIC.m, STATIC.f_c);
    let r = STATIC.response(u, omega).unwrap();
    let period = 2.0 * PI / omega;
    let t_b = (STATIC.f_s / u).asin() / omega;
    let slide = (period - r.stick_time) / 2.0;
    let t1 = t_b + slide;
    let v = |t: f64| (u / omega * ((omega * t_b).cos() - (omega * t).cos()) - f_c * (t - t_b)) / m;
    let x = |t: f64| {
        let d = t - t_b;
        (u / omega * (omega * t_b).cos() * d
            - u / (omega * omega) * ((omega * t).sin() - (omega * t_b).sin())
            - f_c * d * d / 2.0)
            / m
    };
    assert!(
        v(t1).abs() <= 1e-9 * u / (m * omega),
        "v at the stop: {}",
        v(t1)
    );
    assert!(
        (u * (omega * t1).sin()).abs() <= STATIC.f_s,
        "it sticks at the stop"
    );
    let travel = x(t1);
    assert!(
        (r.half_range - travel / 2.0).abs() <= 1e-9 * travel,
        "{} against {}",
        r.half_range,
        travel / 2.0
    );
    // The first harmonic of the whole waveform over the period from t_b: the slide to
    // `travel` (it ends after T/2, where the force has turned), at rest there until T/2 + t_b,
    // the same slide back, at rest at 0 until T + t_b; by the composite Simpson rule.
    assert!(t1 > period / 2.0 && t1 < t_b + period / 2.0);
    let position = |t: f64| {
        let back = t >= t_b + period / 2.0;
        let h = if back { t - period / 2.0 } else { t };
        let forward = if h >= t1 { travel } else { x(h) };
        if back {
            travel - forward
        } else {
            forward
        }
    };
    let n = 200_000;
    let h = period / n as f64;
    let mut x1 = Complex64::new(0.0, 0.0);
    for i in 0..=n {
        let t = t_b + i as f64 * h;
        let w = match i {
            0 => 1.0,
            i if i == n => 1.0,
            i if i % 2 == 1 => 4.0,
            _ => 2.0,
        };
        x1 += w * position(t) * Complex64::from_polar(1.0, -omega * t);
    }
    x1 *= h / 3.0 * 2.0 / period;
    let expected = x1 / Complex64::new(0.0, -u);
    assert!(
        (r.n - expected).norm() <= 1e-6 * expected.norm(),
        "{} against {expected}",
        r.n
    );
}

#[test]
fn the_servo_loop_with_stiction_balances_once_and_scales_with_the_friction_levels() {
    let cycles = predict_hunting(&STATIC, &SERVO);
    assert_eq!(cycles.len(), 1, "{cycles:?}");
    let c = cycles[0];
    assert!(c.residual <= 1e-9, "|1 + C·N| = {}", c.residual);
    assert!(c.force_amplitude > STATIC.f_s);
    // The loop is homogeneous: friction levels ×2 double the force and the position, not the
    // period; the mass, the gains and the levels ×3 change nothing but the force.
    let doubled = StictionMass {
        f_c: 12.0,
        f_s: 15.0,
        ..STATIC
    };
    let d = predict_hunting(&doubled, &SERVO)[0];
    assert!((d.period / c.period - 1.0).abs() <= 1e-9);
    assert!((d.amplitude / c.amplitude - 2.0).abs() <= 1e-8);
    assert!((d.force_amplitude / c.force_amplitude - 2.0).abs() <= 1e-8);
    let heavy = StictionMass {
        m: 3.0,
        f_c: 18.0,
        f_s: 22.5,
        f_v: 0.0,
    };
    let pid = Pid {
        kp: 9.0,
        ki: 12.0,
        kd: 18.0,
    };
    let h = predict_hunting(&heavy, &pid)[0];
    assert!((h.period / c.period - 1.0).abs() <= 1e-9);
    assert!((h.amplitude / c.amplitude - 1.0).abs() <= 1e-8);
    // At break-away the loop gain is below 1: the cycle balances above it.
    assert!(break_away_gain(&STATIC, &SERVO).unwrap() < 1.0);
}

#[test]
fn lugre_levels_with_their_viscous_term_jump_over_the_balance_at_break_away() {
    // F_c = 1 N, F_s = 1.5 N, σ2 = 0.4 N·s/m (lugre-1995): the loop gain at the phase
    // crossover is already above 1 when the mass starts to move, so no U balances.
    let lugre = StictionMass {
        m: 1.0,
        f_c: 1.0,
        f_s: 1.5,
        f_v: 0.4,
    };
    assert!(break_away_gain(&lugre, &SERVO).unwrap() > 1.0);
    assert!(predict_hunting(&lugre, &SERVO).is_empty());
}
