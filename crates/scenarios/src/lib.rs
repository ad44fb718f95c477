//! The rigs on which friction models and solvers are run (`shared/spec/scenarios.md`), and
//! the paper's own experiments.
//!
//! So far: the two curve rigs of Figures 2–7 ([`curves`]) and the catalogue of those
//! figures with what the paper says of each ([`figures`]).

pub mod cases;
pub mod curves;
pub mod figures;
pub mod motion;
pub mod paper;
pub mod params;
pub mod phenomena;
pub mod run;
pub mod scenario;
pub mod studies;

pub use params::ScenarioParams;
pub use run::{run, Limits, Outcome, Row, RunSpec, ScenarioError, SwitchingKind};
pub use scenario::Scenario;
