//! The rigs that impose a motion on the contact: only the law's internal state is
//! integrated along it ([`crate::motion`]).

use crate::motion::Motion;
use crate::params::ScenarioParams;
use crate::rig::{Apparatus, EndTime, Rig};
use friction_models::params::show;
use friction_models::{FrictionModel, FrictionParams};
use std::f64::consts::PI;
use std::sync::Arc;

/// Three periods of a motion of angular frequency `omega`: `6π/omega`.
fn three_periods(omega: f64) -> EndTime {
    EndTime::Derived {
        t_end: 3.0 * 2.0 * PI / omega,
        rule: format!("three periods, 6π/omega with omega = {}", show(omega)),
    }
}

/// The paper's `X(t) = t³/3 + t²/2` and its mirror image (Figures 5–7).
pub struct PrescribedMotion;

impl Rig for PrescribedMotion {
    fn name(&self) -> &'static str {
        "prescribed-motion"
    }
    fn equation(&self) -> &'static str {
        "X(t) = t^3/3 + t^2/2 and X -> -X; the model's state follows its law"
    }
    fn parameters(&self) -> &'static [&'static str] {
        &[]
    }
    fn has_body(&self) -> bool {
        false
    }
    fn end_time(&self, _: &ScenarioParams, _: &FrictionParams) -> EndTime {
        EndTime::Fixed(2.0)
    }
    fn apparatus(
        &self,
        _: &ScenarioParams,
        _: &FrictionParams,
        _: Arc<dyn FrictionModel>,
    ) -> Apparatus {
        Apparatus::Motion(Motion::Paper { mirrored: false })
    }
}

/// Steady friction at ±v_max·k/20, k = 1..20 (Figures 2–4).
pub struct VelocitySweep;

impl Rig for VelocitySweep {
    fn name(&self) -> &'static str {
        "velocity-sweep"
    }
    fn equation(&self) -> &'static str {
        "steady friction at constant v on +-v_max*k/20, k = 1..20"
    }
    fn parameters(&self) -> &'static [&'static str] {
        &["v_max"]
    }
    fn has_body(&self) -> bool {
        false
    }
    fn end_time(&self, _: &ScenarioParams, _: &FrictionParams) -> EndTime {
        EndTime::Fixed(0.0)
    }
    /// −v_max … −v_max/20, then v_max/20 … v_max.
    fn apparatus(
        &self,
        p: &ScenarioParams,
        _: &FrictionParams,
        _: Arc<dyn FrictionModel>,
    ) -> Apparatus {
        let v_max = p.v_max;
        let velocities = (1..=20)
            .rev()
            .map(|k| -v_max * k as f64 / 20.0)
            .chain((1..=20).map(|k| v_max * k as f64 / 20.0));
        Apparatus::SteadySweep(velocities.collect())
    }
}

/// Prescribed `x = amplitude·sin(omega·t)`.
pub struct Oscillation;

impl Rig for Oscillation {
    fn name(&self) -> &'static str {
        "oscillation"
    }
    fn equation(&self) -> &'static str {
        "x = amplitude*sin(omega*t) prescribed"
    }
    fn parameters(&self) -> &'static [&'static str] {
        &["amplitude", "omega"]
    }
    fn has_body(&self) -> bool {
        false
    }
    fn end_time(&self, p: &ScenarioParams, _: &FrictionParams) -> EndTime {
        three_periods(p.omega)
    }
    fn apparatus(
        &self,
        p: &ScenarioParams,
        _: &FrictionParams,
        _: Arc<dyn FrictionModel>,
    ) -> Apparatus {
        Apparatus::Motion(Motion::Sine {
            amplitude: p.amplitude,
            omega: p.omega,
        })
    }
}

/// Prescribed `v = v_mean + v_amplitude·cos(omega·t)`, x(0) = 0, internal states from zero.
pub struct VelocityOscillation;

impl Rig for VelocityOscillation {
    fn name(&self) -> &'static str {
        "velocity-oscillation"
    }
    fn equation(&self) -> &'static str {
        "v = v_mean + v_amplitude*cos(omega*t) prescribed, x(0) = 0, internal states from zero"
    }
    fn parameters(&self) -> &'static [&'static str] {
        &["v_mean", "v_amplitude", "omega"]
    }
    fn has_body(&self) -> bool {
        false
    }
    fn end_time(&self, p: &ScenarioParams, _: &FrictionParams) -> EndTime {
        three_periods(p.omega)
    }
    fn apparatus(
        &self,
        p: &ScenarioParams,
        _: &FrictionParams,
        _: Arc<dyn FrictionModel>,
    ) -> Apparatus {
        Apparatus::Motion(Motion::VelocityOscillation {
            mean: p.v_mean,
            amplitude: p.v_amplitude,
            omega: p.omega,
        })
    }
}
