//! What a rig is: the [`Rig`] trait that the built-in rigs implement ([`crate::rigs`]) and a
//! user's own rig implements too, run through [`crate::Scenario::own`].

use crate::error::ScenarioError;
use crate::motion::Motion;
use crate::params::ScenarioParams;
use friction_models::{FrictionModel, FrictionParams, ModelId};
use friction_systems::System;
use std::sync::Arc;

/// The name of a rig's one body (and of its row in `final.csv` and `events.csv`).
pub const RIG_BODY: &str = "body";

/// What a rig puts the friction law into.
pub enum Apparatus {
    /// A system whose first body carries the rig's one contact, integrated with the law
    /// there: `m·ẍ = f(t, x, ẋ) − F(ẋ − v_surface)`.
    Body(System),
    /// A motion imposed on the contact: only the law's internal state is integrated, with the
    /// work `∫F·v dt` and the loop area `∮F dv` ([`crate::motion`]).
    Motion(Motion),
    /// Steady friction at each of these velocities, m/s, each point a constant-velocity run
    /// from zero internal state until it settles.
    SteadySweep(Vec<f64>),
}

/// A rig's end time when none is asked for.
#[derive(Clone, Debug, PartialEq)]
pub enum EndTime {
    /// A fixed time, s.
    Fixed(f64),
    /// A time derived from the parameters, with the rule and its values in words
    /// (`2·max(F_s, F_c)/rate with F_s = 7.5, F_c = 5, rate = 1`).
    Derived {
        /// The end time, s.
        t_end: f64,
        /// How it follows from the parameters.
        rule: String,
    },
}

impl EndTime {
    /// The end time, s.
    pub fn value(&self) -> f64 {
        match self {
            EndTime::Fixed(t) | EndTime::Derived { t_end: t, .. } => *t,
        }
    }

    /// The rule of a derived end time; `None` for a fixed one.
    pub fn rule(&self) -> Option<&str> {
        match self {
            EndTime::Fixed(_) => None,
            EndTime::Derived { rule, .. } => Some(rule),
        }
    }
}

/// A test rig: a friction law at one contact, and what drives it. The built-in rigs
/// implement it in [`crate::rigs`]; a user's own is run wherever a built-in one is through
/// [`crate::Scenario::own`] (see `examples/own_rig.rs`).
pub trait Rig: Send + Sync {
    /// The name the command line takes (`belt`).
    fn name(&self) -> &'static str;

    /// The rig's equation, in words (`m*x'' + c*x' + k*x = -F(x' - v_belt), from x0, v0`).
    fn equation(&self) -> &'static str;

    /// The scenario parameters the rig reads ([`ScenarioParams`] names).
    fn parameters(&self) -> &'static [&'static str];

    /// Whether a body is integrated ([`Apparatus::Body`]) rather than a motion imposed:
    /// only a body can be time-stepped, or held by a law's stick band.
    fn has_body(&self) -> bool;

    /// The rig's default parameters: the common ones unless it overrides some.
    fn defaults(&self) -> ScenarioParams {
        ScenarioParams::default()
    }

    /// The end time of a run that asks for none.
    fn end_time(&self, p: &ScenarioParams, f: &FrictionParams) -> EndTime;

    /// The law the rig runs when a run names none: a model of the catalog with the
    /// parameter set it is read at (`None`: a run must name its model).
    fn default_law(&self) -> Option<(ModelId, &'static str)> {
        None
    }

    /// Checks what the parameters' ranges alone do not (a spring the rig needs); the
    /// parameters are already within their ranges.
    fn check(&self, _p: &ScenarioParams) -> Result<(), ScenarioError> {
        Ok(())
    }

    /// The rig built from its parameters, the run's friction parameters (the rig's scales) and
    /// the law at its contact.
    fn apparatus(
        &self,
        p: &ScenarioParams,
        f: &FrictionParams,
        law: Arc<dyn FrictionModel>,
    ) -> Apparatus;
}
