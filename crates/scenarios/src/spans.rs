//! A run extended span by span until it settles, without integrating a span twice: the
//! outcomes of [`until_settled`] over [`run`] ([`run_until`]) and over
//! [`friction_systems::simulate`] ([`simulate_until`]).

use crate::analysis::settled::{spanned, until_settled, MAX_EXTENSION};
use crate::error::ScenarioError;
use crate::rig::Apparatus;
use crate::run::{options, outcome_of, run, validate, Outcome, RunSpec};
use friction_systems::{simulate_spans, Run, Scheme, System, SystemError};
use integrators::Options;

/// `system` integrated by `scheme` over `factor` = 1, 2, 4, … times a span (`options` of
/// each factor), stopping at the first run that `done` accepts (told its factor) or at
/// [`MAX_EXTENSION`]; `done` sees every run. The runs are those of [`until_settled`] over
/// [`friction_systems::simulate`], but each longer one continues the one before from before its
/// last step where the method allows it ([`simulate_spans`]).
pub fn simulate_until<'a>(
    system: &'a System,
    scheme: Scheme,
    options: &dyn Fn(u32) -> Options,
    done: &mut dyn FnMut(u32, &Run<'a>) -> bool,
) -> Result<Run<'a>, SystemError> {
    let mut factor = 1;
    simulate_spans(system, scheme, options(1), &mut |run| {
        if done(factor, run) || factor >= MAX_EXTENSION {
            return None;
        }
        factor *= 2;
        Some(options(factor))
    })
}

/// The outcome of `spec` over `factor` = 1, 2, 4, … times its span ([`spanned`]), stopping at
/// the first that `done` accepts or at [`MAX_EXTENSION`]: [`until_settled`] over [`run`], with
/// the same outcomes, but a body scenario's longer run continues the shorter one
/// ([`simulate_until`]) rather than integrating its span again.
pub fn run_until(
    spec: &RunSpec,
    done: &mut dyn FnMut(&Outcome) -> bool,
) -> Result<Outcome, ScenarioError> {
    validate(spec)?;
    let model = spec.law.build(&spec.friction)?;
    let apparatus = (spec.scenario.rig()).apparatus(&spec.params, &spec.friction, model);
    let Apparatus::Body(system) = apparatus else {
        return until_settled(
            |factor| run(&spanned(spec, factor), &mut |_| {}),
            |o| done(o),
        );
    };
    let options = |factor: u32| {
        let spec = spanned(spec, factor);
        options(&spec, spec.end_time())
    };
    let mut outcome = None;
    simulate_until(&system, spec.scheme, &options, &mut |factor, run| {
        let o = outcome_of(&spanned(spec, factor), &system, run, Vec::new());
        let accepted = done(&o);
        outcome = Some(o);
        accepted
    })?;
    Ok(outcome.expect("every span's run is seen"))
}
