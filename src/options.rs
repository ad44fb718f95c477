//! The options shared by every command that runs a model: `--param-set`, `--params`,
//! `--set` and `--variant`, resolved into validated parameters.

use clap::Args;
use friction_lab::error::AppError;
use friction_lab::params::ParamSource;
use friction_lab::scheme::SchemeName;
use friction_lab::settings::{ModelSettings, RunLimits, SchemeChoice, DEFAULT_MAX_STEPS};
use friction_models::Variant;
use scenarios::{Limits, SwitchingKind};
use std::path::PathBuf;

/// Where the parameters come from.
#[derive(Args, Clone, Debug, Default)]
pub struct ParamOptions {
    /// Start from a named parameter set: `paper` (Table 1) or `lugre-1995` [default: paper;
    /// for a rig run without --model, the set of its default law (servo: LuGre at
    /// lugre-1995)].
    #[arg(long = "param-set", value_name = "NAME")]
    pub param_set: Option<String>,
    /// A TOML file of `NAME = VALUE` lines, applied over the parameter set.
    #[arg(long = "params", value_name = "FILE.toml")]
    pub params: Option<PathBuf>,
    /// Override one parameter (repeatable; wins over --params). Names as `models` lists them.
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,
}

/// The help of a solver option: `what`, the names in [`integrators::SOLVERS`] (the list the
/// option takes, from the one registry of solvers), then `then` (its default and when it is
/// refused).
pub fn solver_help(what: &str, then: &str) -> String {
    let names = integrators::SOLVERS.names();
    format!("{what}: {} {then}", names.join(", "))
}

/// The help of a target argument: the names in [`scenarios::SCENARIOS`] (the rigs the
/// argument takes, from the one registry of rigs), then `then` (the other targets).
pub fn scenario_help(what: &str, then: &str) -> String {
    format!(
        "{what}: {} (one contact each), {then}",
        scenarios::SCENARIOS.names().join(", ")
    )
}

/// The bounds of a run: a step cap and a wall-clock limit.
#[derive(Args, Clone, Debug)]
pub struct LimitArgs {
    /// Most steps (accepted and rejected) of a run before it ends with an error, keeping what
    /// it computed.
    #[arg(
        long,
        value_name = "N",
        allow_hyphen_values = true,
        default_value_t = DEFAULT_MAX_STEPS
    )]
    pub max_steps: i64,
    /// Wall-clock limit of the command, s, counted from its start: a run in progress when it
    /// passes ends with an error, keeping what it computed, and a run not started yet ends at
    /// its first step (a study or a sweep of many runs is bounded as a whole).
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    pub time_limit: Option<f64>,
    /// When `--time-limit` started counting: set by a command that checks these bounds once
    /// for each of its runs (`sweep`), so that they bound the whole command; `None` for the
    /// moment they are checked.
    #[arg(skip)]
    pub since: Option<std::time::Instant>,
}

impl LimitArgs {
    /// The bounds as the library takes them.
    pub fn settings(&self) -> RunLimits {
        RunLimits {
            max_steps: self.max_steps,
            time_limit: self.time_limit,
            since: self.since,
        }
    }

    /// The bounds, checked against their ranges.
    pub fn limits(&self) -> Result<Limits, AppError> {
        self.settings().limits()
    }
}

/// The parameters and the reading of the equations of one model.
#[derive(Args, Clone, Debug, Default)]
pub struct ModelOptions {
    /// Where the parameters come from.
    #[command(flatten)]
    pub params: ParamOptions,
    /// `odd`: the static term carries sign(v) (default); `printed`: the equations as printed.
    #[arg(long, value_name = "odd|printed", default_value = "odd")]
    pub variant: Variant,
}

impl ModelOptions {
    /// The parameters' source and the variant as the library takes them.
    pub fn settings(&self) -> ModelSettings {
        ModelSettings {
            params: self.params.source(),
            variant: self.variant,
        }
    }
}

impl ParamOptions {
    /// Where these options say the parameters come from.
    pub fn source(&self) -> ParamSource {
        ParamSource {
            param_set: self.param_set.clone(),
            params: self.params.clone(),
            set: self.set.clone(),
        }
    }
}

/// `--scheme` and `--switching`: how a run or a study is integrated, and how v = 0 is treated
/// under the event-driven scheme.
#[derive(Args, Clone, Debug)]
pub struct SchemeArgs {
    /// event-driven (a solver steps between located events; v = 0 treated by --switching) or
    /// time-stepping (Moreau–Jean: fixed steps, no event located, no solver; a study's one
    /// method, over its step sizes, against an event-driven reference).
    #[arg(
        long,
        value_name = "event-driven|time-stepping",
        default_value = "event-driven"
    )]
    pub scheme: SchemeName,
    /// The treatment of v = 0 under event-driven integration: event (stick/slip switching),
    /// regularized (tanh, width epsilon) or naive [default: event]. (`timestepping`, the
    /// former spelling of --scheme time-stepping, is still taken, with a note.)
    #[arg(long, value_name = "event|regularized|naive")]
    pub switching: Option<SwitchingKind>,
}

impl SchemeArgs {
    /// The scheme and the switching as the library takes them.
    pub fn choice(&self) -> SchemeChoice {
        SchemeChoice {
            scheme: self.scheme,
            switching: self.switching,
        }
    }
}
