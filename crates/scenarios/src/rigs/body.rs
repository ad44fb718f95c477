//! The rigs that integrate one body: `m·ẍ = f(t, x, ẋ) − F(ẋ − v_surface)`, the applied
//! force `f` a constant, a ramp, a load cycle or a spring to a wall.

use crate::error::ScenarioError;
use crate::params::ScenarioParams;
use crate::rig::RIG_BODY;
use crate::rig::{Apparatus, EndTime, Rig};
use friction_models::params::show;
use friction_models::{FrictionModel, FrictionParams};
use friction_systems::{End, Profile, System};
use std::sync::Arc;

/// One body named [`RIG_BODY`] of mass `m`, starting at `start` (x, v), driven as `drive`
/// adds its forces or springs, with the law at its contact on a surface moving at
/// `surface_velocity`.
fn one_body(
    p: &ScenarioParams,
    start: (f64, f64),
    surface_velocity: f64,
    law: Arc<dyn FrictionModel>,
    drive: impl FnOnce(&mut System, usize),
) -> Apparatus {
    let mut s = System::default();
    let body = s.add_body(RIG_BODY, p.m, start.0, start.1);
    drive(&mut s, body);
    s.add_contact(body, surface_velocity, law);
    Apparatus::Body(s)
}

/// The body held by a spring `k` (with damper `c`) to a wall at x = 0.
fn held(s: &mut System, body: usize, p: &ScenarioParams) {
    let wall = s.add_anchor("wall", 0.0, 0.0);
    s.add_spring(End::Body(body), End::Anchor(wall), p.k, p.c);
}

/// Refuses a spring that does not hold the body (`k` = 0).
fn spring_needed(rig: &str, p: &ScenarioParams) -> Result<(), ScenarioError> {
    if p.k <= 0.0 {
        return Err(ScenarioError::Invalid(format!(
            "parameter `k` = {} is out of range for {rig}: allowed (0, inf) N/m (the spring holds the body)",
            p.k
        )));
    }
    Ok(())
}

/// The paper's experiment: `m·v' = F_ex − F(v)` from (x0, v0).
pub struct PaperBlock;

impl Rig for PaperBlock {
    fn name(&self) -> &'static str {
        "paper-block"
    }
    fn equation(&self) -> &'static str {
        "m*v' = F_ex - F(v), from x0, v0 (rest)"
    }
    fn parameters(&self) -> &'static [&'static str] {
        &["m", "F_ex", "x0", "v0"]
    }
    fn has_body(&self) -> bool {
        true
    }
    fn end_time(&self, _: &ScenarioParams, _: &FrictionParams) -> EndTime {
        EndTime::Fixed(5.0)
    }
    fn apparatus(
        &self,
        p: &ScenarioParams,
        _: &FrictionParams,
        law: Arc<dyn FrictionModel>,
    ) -> Apparatus {
        one_body(p, (p.x0, p.v0), 0.0, law, |s, body| {
            s.add_force(body, p.f_ex, Profile::None)
        })
    }
}

/// A spring-held body on a moving belt: `m·ẍ + c·ẋ + k·x = −F(ẋ − v_belt)`.
pub struct Belt;

impl Rig for Belt {
    fn name(&self) -> &'static str {
        "belt"
    }
    fn equation(&self) -> &'static str {
        "m*x'' + c*x' + k*x = -F(x' - v_belt), from x0, v0"
    }
    fn parameters(&self) -> &'static [&'static str] {
        &["m", "k", "c", "v_belt", "x0", "v0"]
    }
    fn has_body(&self) -> bool {
        true
    }
    fn end_time(&self, _: &ScenarioParams, _: &FrictionParams) -> EndTime {
        EndTime::Fixed(20.0)
    }
    fn check(&self, p: &ScenarioParams) -> Result<(), ScenarioError> {
        spring_needed(self.name(), p)
    }
    fn apparatus(
        &self,
        p: &ScenarioParams,
        _: &FrictionParams,
        law: Arc<dyn FrictionModel>,
    ) -> Apparatus {
        one_body(p, (p.x0, p.v0), p.v_belt, law, |s, body| held(s, body, p))
    }
}

/// `m·ẍ + c·ẋ + k·x = −F(ẋ)`, released from x0 (0.5 m by default) at v0.
pub struct FreeVibration;

impl Rig for FreeVibration {
    fn name(&self) -> &'static str {
        "free-vibration"
    }
    fn equation(&self) -> &'static str {
        "m*x'' + c*x' + k*x = -F(x'), released from x0 at v0"
    }
    fn parameters(&self) -> &'static [&'static str] {
        &["m", "k", "c", "x0", "v0"]
    }
    fn has_body(&self) -> bool {
        true
    }
    fn defaults(&self) -> ScenarioParams {
        ScenarioParams {
            x0: 0.5,
            ..ScenarioParams::default()
        }
    }
    fn end_time(&self, _: &ScenarioParams, _: &FrictionParams) -> EndTime {
        EndTime::Fixed(10.0)
    }
    fn check(&self, p: &ScenarioParams) -> Result<(), ScenarioError> {
        spring_needed(self.name(), p)
    }
    fn apparatus(
        &self,
        p: &ScenarioParams,
        _: &FrictionParams,
        law: Arc<dyn FrictionModel>,
    ) -> Apparatus {
        one_body(p, (p.x0, p.v0), 0.0, law, |s, body| held(s, body, p))
    }
}

/// `m·v' = rate·t − F(v)` from rest, until the load reaches twice the larger friction level.
pub struct ForceRamp;

impl Rig for ForceRamp {
    fn name(&self) -> &'static str {
        "force-ramp"
    }
    fn equation(&self) -> &'static str {
        "m*v' = rate*t - F(v), from rest"
    }
    fn parameters(&self) -> &'static [&'static str] {
        &["m", "rate"]
    }
    fn has_body(&self) -> bool {
        true
    }
    /// `2·max(F_s, F_c)/rate`.
    fn end_time(&self, p: &ScenarioParams, f: &FrictionParams) -> EndTime {
        EndTime::Derived {
            t_end: 2.0 * f.f_s.max(f.f_c) / p.rate,
            rule: format!(
                "2·max(F_s, F_c)/rate with F_s = {}, F_c = {}, rate = {}",
                show(f.f_s),
                show(f.f_c),
                show(p.rate)
            ),
        }
    }
    fn apparatus(
        &self,
        p: &ScenarioParams,
        _: &FrictionParams,
        law: Arc<dyn FrictionModel>,
    ) -> Apparatus {
        one_body(p, (0.0, 0.0), 0.0, law, |s, body| {
            s.add_force(body, 0.0, Profile::Ramp { rate: p.rate })
        })
    }
}

/// The pre-sliding test: a load of `fraction`·F_s applied in 1 s, held 1 s, released in 1 s,
/// then 1 s at rest.
pub struct Presliding;

impl Rig for Presliding {
    fn name(&self) -> &'static str {
        "presliding"
    }
    fn equation(&self) -> &'static str {
        "m*v' = L(t) - F(v), L: 0 -> fraction*F_s in 1 s, held 1 s, back to 0 in 1 s, 1 s at 0"
    }
    fn parameters(&self) -> &'static [&'static str] {
        &["m", "fraction"]
    }
    fn has_body(&self) -> bool {
        true
    }
    fn end_time(&self, _: &ScenarioParams, _: &FrictionParams) -> EndTime {
        EndTime::Fixed(4.0)
    }
    fn apparatus(
        &self,
        p: &ScenarioParams,
        f: &FrictionParams,
        law: Arc<dyn FrictionModel>,
    ) -> Apparatus {
        let load = Profile::Trapezoid {
            peak: p.fraction * f.f_s,
            rise: 1.0,
            hold: 1.0,
            fall: 1.0,
        };
        one_body(p, (0.0, 0.0), 0.0, law, |s, body| {
            s.add_force(body, 0.0, load)
        })
    }
}
