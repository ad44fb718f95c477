//! The work–precision study: every method at every resolution, with the work it took.

use super::{batch, Method, Reference, StudyCase, StudyRun};
use crate::error::ScenarioError;
use serde::Serialize;

/// A work–precision study: every solver at every resolution, with the work it took.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WorkPrecision {
    /// The reference.
    pub reference: Reference,
    /// Every run, its wall time over the repetitions.
    pub runs: Vec<StudyRun>,
    /// Where the reference limits the finest runs, the sentence that says so
    /// ([`Reference::limits`]).
    pub reference_limit: Option<String>,
}

/// Runs every method over its step sizes or tolerances, `repeats` times each for the
/// median wall time, the repetitions in the same list as the runs (each run alone on its
/// core: see docs/performance.md for what a neighbour costs a small problem). The reference
/// is the one of the studied methods ([`batch::reference`]).
pub fn work_precision(
    case: &dyn StudyCase,
    methods: &[Method],
    step_sizes: &[f64],
    tolerances: &[f64],
    repeats: usize,
    progress: &(dyn Fn() + Sync),
) -> Result<WorkPrecision, ScenarioError> {
    let jobs = Method::jobs(methods, step_sizes, tolerances, false);
    let posed = batch::Posed {
        case,
        reference_for: Some(methods),
        jobs: &jobs,
    };
    let c = batch::run_cases(&[posed], repeats.max(1) - 1, progress)?.remove(0);
    let (reference, _) = c.reference.expect("a reference was asked for");
    Ok(WorkPrecision {
        reference_limit: reference.limits(&c.runs),
        reference,
        runs: c.runs,
    })
}
