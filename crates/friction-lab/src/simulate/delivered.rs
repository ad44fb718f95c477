//! What a run made, once its record is complete: its files (from the record) and the advice
//! on it, the same for a rig and a system.

use crate::artifacts::Artifacts;
use crate::error::AppError;
use crate::made::Made;
use crate::run_record::RunRecord;
use crate::trajectory::RecordAs;
use crate::warnings::{coarse_step_warning, failure_warnings, stiffness_warning};
use friction_systems::Scheme;
use scenarios::analysis::closed_loop::ClosedLoop;
use std::path::Path;

/// What the advice on a run reads beside its record.
pub struct Advice {
    /// The scheme it ran under.
    pub scheme: Scheme,
    /// Its shortest natural period 2π√(m/(k + kp)), s, where it has one.
    pub period: Option<f64>,
    /// Advice of its own kind (a chain's spread its law does not read).
    pub own: Option<String>,
}

/// A closed loop that has not settled (neither hunting nor at rest: a transient whose
/// measures describe no regime): its line, which every front end gives as a warning.
fn unsettled_loop(closed_loop: Option<&ClosedLoop>) -> Option<String> {
    closed_loop
        .filter(|c| c.hunting.is_none())
        .map(|c| c.to_string())
}

/// What one run made: `record`'s files added to `files` in `out`, or its values, as
/// `record_as` asks ([`RunRecord::deliver`]), the `notes`, and the advice on it: where Hairer's test found it stiff, a fixed
/// step too coarse for its shortest natural period, why it failed under its scheme, its own
/// advice, and the summary's caution. The failure its summary names is kept for the front end
/// to report once the files are written.
pub fn made_of_record(
    record: RunRecord,
    mut files: Artifacts,
    out: &Path,
    record_as: RecordAs,
    advice: Advice,
    notes: Vec<String>,
) -> Result<Made, AppError> {
    let Advice {
        scheme,
        period,
        own,
    } = advice;
    let (failure, caution) = (record.summary.failure(), record.summary.caution());
    let setup = &record.summary.setup;
    let integrated = &record.summary.integrated;
    let unsettled = unsettled_loop(integrated.closed_loop.as_ref());
    // `auto` answered the stiffness it found by switching to Radau IIA: no advice then.
    let warnings = (integrated.stiffness_detected_at)
        .filter(|_| setup.solver != integrators::Solver::AUTO.name())
        .map(|t| stiffness_warning(setup.solver, t))
        .into_iter()
        .chain(coarse_step_warning(setup.step, period))
        .chain(failure_warnings(
            scheme,
            setup.step,
            setup.t_end,
            period,
            integrated.error.as_ref(),
        ))
        .chain(own)
        .chain(caution)
        .chain(unsettled.clone())
        .collect();
    let notes = (notes.into_iter())
        .filter(|n| Some(n) != unsettled.as_ref())
        .collect();
    let run = record.deliver(&mut files, out, record_as)?;
    Ok(Made {
        files,
        run,
        notes,
        warnings,
        failure,
    })
}
