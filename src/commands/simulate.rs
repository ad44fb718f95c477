//! `friction-lab simulate SCENARIO --model MODEL --solver SOLVER --out DIR`: one scenario,
//! written as `trajectory.csv`, `summary.json` and figures (time histories of x, v and
//! friction; phase portrait; friction against velocity and against displacement).

use clap::Args;
use friction_lab::laws::ModelChoice;
use friction_lab::settings::{ModelSettings, SolverSettings};
use friction_lab::simulate::{Simulation, Target as Run};
use scenarios::Scenario;
use std::path::PathBuf;

/// What `simulate` integrates: a single-body rig, or the built-in chain of blocks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// A rig of `docs/scenarios.md`.
    Rig(Scenario),
    /// The Burridge–Knopoff chain of `docs/systems.md`.
    Chain,
}

impl std::str::FromStr for Target {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Ok(match Run::named(s)? {
            Run::Rig(scenario) => Target::Rig(scenario),
            _ => Target::Chain,
        })
    }
}

/// Options of `simulate`.
#[derive(Args, Clone, Debug)]
pub struct SimulateArgs {
    /// The rig (docs/scenarios.md) or the chain.
    #[arg(
        help = crate::options::scenario_help(
            "The rig",
            "or chain (the Burridge–Knopoff chain of docs/systems.md, parameters n_bodies, m, \
             k_chain, k_driver, v_driver, spread by --set)",
        ),
        value_name = "SCENARIO",
        required_unless_present = "system",
        conflicts_with = "system"
    )]
    pub scenario: Option<Target>,
    /// A system file (TOML or JSON, docs/systems.md) to integrate instead of a scenario.
    #[arg(long, value_name = "FILE.toml")]
    pub system: Option<PathBuf>,
    /// The friction model, as `friction-lab models` lists it, or a law registered by name
    /// (from Python: docs/python.md) (rigs and chain).
    #[arg(long, value_name = "MODEL")]
    pub model: Option<ModelChoice>,
    /// Folder to write into (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// End time, s [default: the scenario's; 50 for the chain; 20 for a system file].
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub t_end: Option<f64>,
    /// Evenly spaced output points (events are recorded besides) [default: 2001; for a
    /// system, fewer when 2001 states would exceed 1e7 numbers].
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub points: Option<i64>,
    /// Systems: the bodies written to trajectory.csv, as names or 1-based indices,
    /// comma-separated; velocity.png, the phase portraits and the spectra draw at most four of
    /// them, spread evenly [default: all up to 20 bodies, else 20 evenly spaced].
    #[arg(long, value_name = "LIST", value_delimiter = ',')]
    pub bodies: Vec<String>,
    /// The span of time the figures draw, T0:T1 in seconds (time histories, phase portraits,
    /// friction plots, space-time pictures, stiffness), and the spectra measure [default: the
    /// whole run; the spectra its last half]. The data files keep every point.
    #[arg(long, value_name = "T0:T1")]
    pub window: Option<String>,
    /// The solver.
    #[command(flatten)]
    pub solver: SolverSettings,
    /// The model's parameters (friction and scenario parameters alike) and reading.
    #[command(flatten)]
    pub model_options: ModelSettings,
}

impl SimulateArgs {
    /// The run as the library takes it.
    pub fn simulation(&self) -> Simulation {
        let target = match (self.scenario, &self.system) {
            (Some(Target::Rig(scenario)), _) => Run::Rig(scenario),
            (_, Some(file)) => Run::System(file.clone()),
            _ => Run::Chain,
        };
        Simulation {
            target,
            model: self.model.clone(),
            model_settings: self.model_options.clone(),
            solver: self.solver,
            t_end: self.t_end,
            points: self.points,
            bodies: self.bodies.clone(),
            window: self.window.clone(),
        }
    }
}
