//! The closed-loop rig: a PID-controlled mass on the floor, the hunting example of Canudas de
//! Wit, Olsson, Åström & Lischinsky (1995).

use crate::params::ScenarioParams;
use crate::rig::{Apparatus, EndTime, Rig, RIG_BODY};
use friction_models::{FrictionModel, FrictionParams, ModelId};
use friction_systems::{Controller, Reference, System};
use std::sync::Arc;

/// A mass m on the floor, no spring, positioned by a PID:
/// `m·ẍ = u − F(ẋ)`, `u = kp·(r − x) + ki·∫(r − x) dt + kd·(ṙ − ẋ)`, `r = x_ref + v_ref·t`,
/// from rest at x = 0. The defaults are the 1995 paper's: m = 1 kg, kp = 3 N/m, ki = 4
/// N/(m·s), kd = 6 N·s/m, set point 1 m, and LuGre at that paper's parameters
/// (`lugre-1995`) as the plant.
pub struct Servo;

impl Rig for Servo {
    fn name(&self) -> &'static str {
        "servo"
    }
    fn equation(&self) -> &'static str {
        "m*x'' = u - F(x'), u = kp*(r - x) + ki*I + kd*(r' - x'), I' = r - x, r = x_ref + v_ref*t, from rest"
    }
    fn parameters(&self) -> &'static [&'static str] {
        &["m", "kp", "ki", "kd", "x_ref", "v_ref"]
    }
    fn has_body(&self) -> bool {
        true
    }
    fn end_time(&self, _: &ScenarioParams, _: &FrictionParams) -> EndTime {
        EndTime::Fixed(800.0)
    }
    fn default_law(&self) -> Option<(ModelId, &'static str)> {
        Some((ModelId::LuGre, "lugre-1995"))
    }
    fn apparatus(
        &self,
        p: &ScenarioParams,
        _: &FrictionParams,
        law: Arc<dyn FrictionModel>,
    ) -> Apparatus {
        let mut s = System::default();
        let body = s.add_body(RIG_BODY, p.m, 0.0, 0.0);
        s.add_contact(body, 0.0, law);
        let reference = if p.v_ref == 0.0 {
            Reference::Constant { x: p.x_ref }
        } else {
            Reference::Ramp {
                x0: p.x_ref,
                v: p.v_ref,
            }
        };
        s.add_controller(Controller {
            body,
            kp: p.kp,
            ki: p.ki,
            kd: p.kd,
            reference,
            saturation: None,
            compensation: None,
        });
        Apparatus::Body(s)
    }
}
