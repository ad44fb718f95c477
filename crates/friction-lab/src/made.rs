//! What a command made, before its files are written: the files staged in memory, the lines
//! it prints, the failure its files keep, and a run's record as values.

use crate::artifacts::Artifacts;
use crate::error::AppError;
use crate::run_record::RunValues;

/// What a command made: its files staged in memory (figures not drawn yet), the lines it
/// prints once they are written, and the failure of a run whose partial results the files
/// keep (a solver that stopped early, a sweep with failed points).
#[derive(Debug, Default)]
pub struct Made {
    /// The files.
    pub files: Artifacts,
    /// Lines for the terminal, printed after the files are written.
    pub notes: Vec<String>,
    /// Advice about the run (a solver that found the problem stiff), printed on stderr.
    pub warnings: Vec<String>,
    /// The failure the files record, returned once they are written.
    pub failure: Option<AppError>,
    /// A run's record as values, where they were asked for instead of its files
    /// ([`crate::trajectory::RecordAs::Values`]).
    pub run: Option<RunValues>,
}
