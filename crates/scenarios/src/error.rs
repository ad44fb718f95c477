//! What goes wrong in setting up or running a rig, a study or a protocol.

use friction_models::ParamError;
use friction_systems::SystemError;
use integrators::SolverError;
use thiserror::Error;

/// A scenario that cannot be set up as asked.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ScenarioError {
    /// A parameter was rejected.
    #[error(transparent)]
    Param(#[from] ParamError),
    /// The rig's system was rejected.
    #[error(transparent)]
    System(#[from] SystemError),
    /// A combination that makes no sense.
    #[error("{0}")]
    Invalid(String),
    /// A run that a study depends on failed in the solver (not bad input).
    #[error("{what} failed: {error}")]
    Solver {
        /// Which run.
        what: String,
        /// The solver's error.
        error: SolverError,
    },
    /// A periodic orbit was not found ([`crate::orbit`]).
    #[error("the periodic orbit: {0}")]
    Orbit(#[from] periodic::OrbitError),
    /// A run of a study or of a Table 2 protocol did not give what it is for (it failed, or
    /// ended in a transient that decides nothing); the message names which and why.
    #[error("{0}")]
    RunFailed(String),
}
