//! Systems shared by the tests.
#![allow(dead_code)]

use friction_models::{FrictionParams, ModelId, Variant};
use friction_systems::{End, System};
use std::sync::Arc;

/// A body of mass m held by a spring k to a wall, on a belt at `v_belt`, with `model` at the
/// paper's parameters.
pub fn belt(model: ModelId, m: f64, k: f64, v_belt: f64) -> System {
    let mut s = System::default();
    let body = s.add_body("body", m, 0.0, 0.0);
    let wall = s.add_anchor("wall", 0.0, 0.0);
    s.add_spring(End::Body(body), End::Anchor(wall), k, 0.0);
    let law = model.build(Variant::Odd, &FrictionParams::paper()).unwrap();
    s.add_contact(body, v_belt, Arc::from(law));
    s
}

/// One block of mass m, pulled from rest by a spring k from a driver moving at v_d, Coulomb
/// friction F_c with stiction F_s on the floor. With e = x − v_d·t, every slip phase from a
/// break-away (spring force F_s, v = 0) at t_b is
/// `e(τ) = −F_c/k − a·cos ωτ − (v_d/ω)·sin ωτ`, a = (F_s − F_c)/k, ω = √(k/m),
/// and lasts `(π + 2·atan(v_d/(a·ω)))/ω` (until v = 0); the block then sticks until the
/// spring force k·(v_d·t − x) reaches F_s again. Returns (x, v) at t.
pub fn one_block_exact(t: f64, m: f64, k: f64, v_d: f64, f_s: f64, f_c: f64) -> (f64, f64) {
    let omega = (k / m).sqrt();
    let a = (f_s - f_c) / k;
    let slip = (std::f64::consts::PI + 2.0 * (v_d / (a * omega)).atan()) / omega;
    let mut x_stuck = 0.0;
    loop {
        let t_b = (f_s / k + x_stuck) / v_d;
        if t <= t_b {
            return (x_stuck, 0.0);
        }
        let slide = |tau: f64| {
            let (s, c) = (omega * tau).sin_cos();
            let e = -f_c / k - a * c - v_d / omega * s;
            let de = a * omega * s - v_d * c;
            (v_d * (t_b + tau) + e, v_d + de)
        };
        if t <= t_b + slip {
            return slide(t - t_b);
        }
        x_stuck = slide(slip).0;
    }
}
