//! The servo rig with a task and a compensator of the caller's: the same body, contact,
//! gains and integration as [`Scenario::SERVO`](crate::Scenario::SERVO), the controller
//! tracking another reference and compensating friction with a model of its own (the uses the
//! paper's conclusions name for a friction model: path tracking at low and high speed,
//! compensating resistive forces).

use crate::error::ScenarioError;
use crate::rig::Apparatus;
use crate::run::{run_system, Outcome, RunSpec};
use friction_systems::{Compensation, Reference};

/// Runs `spec` (a rig whose body a controller positions, such as the servo) with every
/// controller tracking `reference` and compensating friction with `compensation` (none:
/// none); `observe` is told of every step.
pub fn run_tracking(
    spec: &RunSpec,
    reference: &Reference,
    compensation: Option<&Compensation>,
    observe: &mut dyn FnMut(f64),
) -> Result<Outcome, ScenarioError> {
    let model = spec.law.build(&spec.friction)?;
    let rig = spec.scenario.rig();
    let Apparatus::Body(mut system) = rig.apparatus(&spec.params, &spec.friction, model) else {
        return Err(ScenarioError::Invalid(format!(
            "rig `{}` has no body to control",
            rig.name()
        )));
    };
    if system.controllers.is_empty() {
        return Err(ScenarioError::Invalid(format!(
            "rig `{}` has no controller to give a reference",
            rig.name()
        )));
    }
    for c in &mut system.controllers {
        c.reference = reference.clone();
        c.compensation = compensation.cloned();
    }
    run_system(spec, &system, observe)
}
