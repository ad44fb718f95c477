//! The rigs on which friction models and solvers are run (`docs/scenarios.md`), and
//! the paper's own experiments.
//!
//! The curve rigs of Figures 2–7 ([`curves`]) and the catalogue of those figures
//! ([`figures`]); the rigs (the [`Rig`] trait, the built-in ones in [`rigs`], their registry [`scenario`], [`mod@run`]); the paper's experiment ([`paper`]);
//! Table 2 by simulation ([`phenomena`]); the solver studies ([`studies`], [`cases`], the chain
//! they build again for each swept value: [`chain`]; their
//! runs as one list: [`batch`]); what a run's result says, computed after it ([`analysis`]: the settled state a sweep measures, the closed loop, the describing function);
//! what a run's result is worth ([`verdict`]).

pub mod analysis;
pub mod batch;
pub mod cases;
pub mod chain;
pub mod curves;
pub mod error;
pub mod errors;
pub mod figures;
pub mod grid;
pub mod method;
pub mod motion;
pub mod orbit;
pub mod paper;
pub mod params;
pub mod phenomena;
pub mod quantity;
pub mod rig;
pub mod rigs;
pub mod run;
pub mod scenario;
pub mod schedule;
pub mod spans;
pub mod stick_slip;
pub mod studies;
pub mod study_run;
pub mod tracking;
pub mod verdict;

pub use error::ScenarioError;
pub use params::ScenarioParams;
pub use rig::{Apparatus, EndTime, Rig};
pub use run::{run, run_measuring_stiffness, Law, Limits, Outcome, Row, RunSpec};
pub use scenario::{Scenario, SCENARIOS};
pub use spans::{run_until, simulate_until};
