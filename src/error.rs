//! Every way a command can fail, each with a message that names what was wrong.

use friction_models::ParamError;
use friction_systems::file::SystemFileError;
use friction_systems::SystemError;
use integrators::SolverError;
use scenarios::curves::CurveError;
use scenarios::ScenarioError;
use std::path::PathBuf;
use thiserror::Error;

/// A failed command.
#[derive(Debug, Error)]
pub enum AppError {
    /// A parameter was rejected.
    #[error(transparent)]
    Param(#[from] ParamError),
    /// A system (file, chain or rig) was rejected.
    #[error(transparent)]
    System(#[from] SystemError),
    /// A system file could not be read or declares no valid system.
    #[error(transparent)]
    SystemFile(#[from] SystemFileError),
    /// A curve option was rejected.
    #[error(transparent)]
    Curve(#[from] CurveError),
    /// A command-line value that does not parse or does not apply.
    #[error("{0}")]
    Usage(String),
    /// A parameter file that is not valid TOML or holds something other than numbers.
    #[error("parameter file {path}: {message}")]
    ParamFile {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },
    /// An output that would contain NaN or an infinity.
    #[error("refusing to write {path}: {what} is not finite ({value})")]
    NonFinite {
        /// The file that was to be written.
        path: PathBuf,
        /// Which value.
        what: String,
        /// The value.
        value: f64,
    },
    /// The output folder cannot be written as asked (bad input: exit 2).
    #[error("output folder {path}: {why}")]
    OutputFolder {
        /// The folder.
        path: PathBuf,
        /// Why.
        why: String,
    },
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The solver failed; the files written say how far it got.
    #[error("{}", solver_failure(.0))]
    Solver(SolverError),
    /// A run that a study needs failed in the solver.
    #[error("{0}")]
    StudyRun(String),
    /// A run ended without a solver error, but its result diverged (the verdict's reason).
    #[error("the run diverged: {0} (summary.json and trajectory.csv keep what was computed)")]
    Diverged(String),
    /// A signal stopped the command before anything was computed (while loading its input):
    /// nothing was written.
    #[error("stopped while {0}: nothing was run or written")]
    Stopped(String),
    /// A plot could not be drawn.
    #[error("drawing {path}: {message}")]
    Plot {
        /// The figure being drawn.
        path: PathBuf,
        /// The drawing back-end's error.
        message: String,
    },
}

impl AppError {
    /// The process exit code: 2 for bad input, 1 for a failure while running, 130 for a
    /// command stopped by a signal before it computed anything.
    pub fn exit_code(&self) -> i32 {
        match self {
            AppError::Param(_)
            | AppError::System(_)
            | AppError::SystemFile(_)
            | AppError::Curve(_)
            | AppError::OutputFolder { .. }
            | AppError::Usage(_)
            | AppError::ParamFile { .. } => 2,
            AppError::NonFinite { .. }
            | AppError::Io { .. }
            | AppError::Plot { .. }
            | AppError::Solver(_)
            | AppError::StudyRun(_)
            | AppError::Diverged(_) => 1,
            AppError::Stopped(_) => 130,
        }
    }
}

impl From<ScenarioError> for AppError {
    /// Bad input stays bad input (exit 2); a failed run is a failure (exit 1).
    fn from(e: ScenarioError) -> AppError {
        match e {
            ScenarioError::Param(p) => AppError::Param(p),
            ScenarioError::System(s) => AppError::System(s),
            ScenarioError::Invalid(m) => AppError::Usage(m),
            e @ (ScenarioError::Solver { .. } | ScenarioError::RunFailed(_)) => {
                AppError::StudyRun(e.to_string())
            }
        }
    }
}

/// The message of a run that ended in the solver: stopped by a signal
/// ([`SolverError::Interrupted`]), or failed.
fn solver_failure(e: &SolverError) -> String {
    match e {
        SolverError::Interrupted { .. } => {
            format!("stopped: {e} (summary.json and trajectory.csv keep the run up to there)")
        }
        _ => format!(
            "the solver failed: {e} (summary.json and trajectory.csv keep the run up to the \
             failure)"
        ),
    }
}
