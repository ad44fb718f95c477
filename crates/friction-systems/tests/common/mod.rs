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
