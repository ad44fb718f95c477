//! The options shared by every command that runs a model: `--param-set`, `--params`,
//! `--set` and `--variant`, resolved into validated parameters.

use clap::Args;
use friction_lab::error::AppError;
use friction_lab::ranges::{self, first_repeat};
use friction_lab::scheme::SchemeName;
use friction_models::{FrictionParams, ParamError, Parameters, Variant};
use scenarios::{Limits, Scenario, ScenarioParams, SwitchingKind};
use std::io::Read;
use std::path::{Path, PathBuf};

/// Where the parameters come from.
#[derive(Args, Clone, Debug, Default)]
pub struct ParamOptions {
    /// Start from a named parameter set: `paper` (Table 1) or `lugre-1995`.
    #[arg(long = "param-set", value_name = "NAME", default_value = "paper")]
    pub param_set: String,
    /// A TOML file of `NAME = VALUE` lines, applied over the parameter set.
    #[arg(long = "params", value_name = "FILE.toml")]
    pub params: Option<PathBuf>,
    /// Override one parameter (repeatable; wins over --params). Names as `models` lists them.
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,
}

/// The help of a solver option: `what`, the names of [`integrators::Solver::ALL`] (the list
/// the option takes, from the one registry of built-in solvers), then `then` (its default and
/// when it is refused).
pub fn solver_help(what: &str, then: &str) -> String {
    let names: Vec<&str> = integrators::Solver::ALL.iter().map(|s| s.name()).collect();
    format!("{what}: {} {then}", names.join(", "))
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
        default_value_t = 10_000_000
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
    /// The bounds, checked against their ranges.
    pub fn limits(&self) -> Result<Limits, AppError> {
        Ok(Limits {
            max_steps: ranges::MAX_STEPS.count(self.max_steps)?,
            time_limit: self
                .time_limit
                .map(|t| ranges::TIME_LIMIT.check(t))
                .transpose()?,
            time_limit_since: Some(self.since.unwrap_or_else(std::time::Instant::now)),
        })
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

impl ParamOptions {
    /// The friction parameters: the named set, then the file, then each `--set`, every value
    /// checked. Only friction parameters are accepted.
    pub fn resolve(&self) -> Result<FrictionParams, AppError> {
        Ok(self.resolve_for(None)?.0)
    }

    /// Friction and scenario parameters for `scenario`: names are looked up among the
    /// friction parameters first, then among the scenario's own.
    pub fn resolve_for(
        &self,
        scenario: Option<Scenario>,
    ) -> Result<(FrictionParams, ScenarioParams), AppError> {
        let mut rig = scenario.map_or_else(ScenarioParams::default, |s| s.defaults());
        let names = scenario.map_or(&[][..], |s| s.parameters());
        let friction = self.resolve_with(names, |name, value| match scenario {
            Some(s) if ScenarioParams::spec(name).is_some() => {
                if !s.parameters().contains(&name) {
                    return Err(AppError::Usage(format!(
                        "parameter `{name}` is not used by scenario {s} (it reads: {})",
                        if s.parameters().is_empty() {
                            "none".to_string()
                        } else {
                            s.parameters().join(", ")
                        }
                    )));
                }
                rig.set(name, value)?;
                Ok(true)
            }
            _ => Ok(false),
        })?;
        rig.validate()?;
        Ok((friction, rig))
    }

    /// Refuses what a system file does not read: a parameter set other than `paper`, and any
    /// parameter of `--params` or `--set` but `epsilon` (the regularisation width of the
    /// run): each `[[contact]]` of the file names its own model and parameters (exit 2 where
    /// they were ignored before).
    pub fn check_for_system_file(&self) -> Result<(), AppError> {
        const READ: &str = "each [[contact]] of the file names its own parameters (the file's \
                            `param_set` and a contact's `params`); of the friction parameters a \
                            system file run reads only `epsilon`, the regularisation width";
        if self.param_set != "paper" {
            return Err(AppError::Usage(format!(
                "option `--param-set` does not apply to --system: {READ}"
            )));
        }
        if let Some(path) = &self.params {
            if let Some((name, _)) = read_file(path)?.into_iter().find(|(n, _)| n != "epsilon") {
                return Err(AppError::ParamFile {
                    path: path.clone(),
                    message: format!("parameter `{name}` does not apply to --system: {READ}"),
                });
            }
        }
        for assignment in &self.set {
            let (name, _) = parse_assignment(assignment)?;
            if name != "epsilon" {
                return Err(AppError::Usage(format!(
                    "option `--set`: parameter `{name}` does not apply to --system: {READ}"
                )));
            }
        }
        Ok(())
    }

    /// The friction parameters, with the names that are not friction parameters given to
    /// `other` (a rig's or a system's own parameters), which says whether it took each; a
    /// name nobody takes is unknown, and the message lists the friction parameters and
    /// `other_names`. The named set, then the file, then each `--set`, every value checked.
    pub fn resolve_with(
        &self,
        other_names: &[&str],
        mut other: impl FnMut(&str, f64) -> Result<bool, AppError>,
    ) -> Result<FrictionParams, AppError> {
        let mut friction = FrictionParams::named(&self.param_set)?;
        let mut apply = |name: &str, value: f64| -> Result<(), AppError> {
            if FrictionParams::spec(name).is_some() {
                return Ok(friction.set(name, value)?);
            }
            if other(name, value)? {
                return Ok(());
            }
            let mut known: Vec<&str> = FrictionParams::specs().iter().map(|p| p.name).collect();
            known.extend(other_names);
            Err(ParamError::Unknown {
                name: name.to_string(),
                known: known.join(", "),
            }
            .into())
        };
        if let Some(path) = &self.params {
            for (name, value) in read_file(path)? {
                // A value from the file is blamed on the file (exit 2 all the same).
                apply(&name, value).map_err(|e| AppError::ParamFile {
                    path: path.clone(),
                    message: e.to_string(),
                })?;
            }
        }
        let assignments = self
            .set
            .iter()
            .map(|a| parse_assignment(a))
            .collect::<Result<Vec<_>, _>>()?;
        let names: Vec<&str> = assignments.iter().map(|a| a.0).collect();
        if let Some((j, k)) = first_repeat(&names) {
            return Err(AppError::Usage(format!(
                "option `--set`: parameter `{}` is set twice, {} and {}: set each parameter \
                 once (only the last would be used)",
                names[k], self.set[j], self.set[k]
            )));
        }
        for (name, value) in assignments {
            apply(name, value)?;
        }
        friction.validate()?;
        Ok(friction)
    }
}

/// Splits `NAME=VALUE` and parses the value as a number.
pub fn parse_assignment(text: &str) -> Result<(&str, f64), AppError> {
    let (name, value) = text.split_once('=').ok_or_else(|| {
        AppError::Usage(format!(
            "--set `{text}`: expected NAME=VALUE, e.g. --set F_s=7.5"
        ))
    })?;
    let (name, value) = (name.trim(), value.trim());
    let number = value.parse::<f64>().map_err(|_| {
        // The two misreadings seen: several parameters in one --set, and a list of values.
        let hint = if value.contains('=') {
            format!(" (one parameter per --set: --set {name}=… --set …)")
        } else if value.contains(',') {
            " (one value per --set: a list of values is a sweep, `sweep --grid NAME=a,b`)"
                .to_string()
        } else {
            String::new()
        };
        AppError::Usage(format!(
            "--set {name}={value}: `{value}` is not a number{hint}"
        ))
    })?;
    Ok((name, number))
}

/// The largest parameter file read, bytes.
pub const MAX_PARAMS_BYTES: u64 = 1 << 20;

/// Reads a TOML file of `NAME = number` lines (at most [`MAX_PARAMS_BYTES`]).
fn read_file(path: &Path) -> Result<Vec<(String, f64)>, AppError> {
    let file_error = |message: String| AppError::ParamFile {
        path: path.to_path_buf(),
        message,
    };
    let mut text = String::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(MAX_PARAMS_BYTES + 1).read_to_string(&mut text))
        .map_err(|e| file_error(format!("cannot be read: {e}")))?;
    if text.len() as u64 > MAX_PARAMS_BYTES {
        return Err(file_error(format!(
            "larger than {MAX_PARAMS_BYTES} bytes, the most a parameter file may hold"
        )));
    }
    parse_params(&text).map_err(file_error)
}

/// Parses the text of a parameter file: `NAME = number` lines (TOML), in file order.
pub fn parse_params(text: &str) -> Result<Vec<(String, f64)>, String> {
    let table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
        // Where: the line of the span's start, as the file numbers it.
        match e.span() {
            Some(span) => {
                let start = span.start.min(text.len());
                let line = text.as_bytes()[..start]
                    .iter()
                    .filter(|&&b| b == b'\n')
                    .count();
                let shown = text.lines().nth(line).unwrap_or("").trim();
                format!("line {}: {} (`{shown}`)", line + 1, e.message())
            }
            None => e.message().to_string(),
        }
    })?;
    table
        .into_iter()
        .map(|(name, value)| match value {
            toml::Value::Float(x) => Ok((name, x)),
            toml::Value::Integer(i) => Ok((name, i as f64)),
            other => Err(format!(
                "`{name}` must be a number, found {} `{other}`",
                other.type_str()
            )),
        })
        .collect()
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

/// The note given for `--switching timestepping`, the former spelling of `--scheme
/// time-stepping`, which is still taken.
pub const TIMESTEPPING_SPELLING: &str = "`--switching timestepping` is now spelt `--scheme \
     time-stepping` (time-stepping is a scheme, not a treatment of v = 0); the old spelling is \
     taken for now and will be refused in a later release";

impl SchemeArgs {
    /// The notes on their spelling: [`TIMESTEPPING_SPELLING`] for `--switching timestepping`.
    pub fn spelling_notes(&self) -> Vec<String> {
        let old = matches!(self.switching, Some(SwitchingKind::TimeStepping { .. }));
        old.then(|| TIMESTEPPING_SPELLING.to_string())
            .into_iter()
            .collect()
    }

    /// The treatment of v = 0 they ask for: time-stepping at `theta` (also from the former
    /// spelling `--switching timestepping`), or `--switching` under event-driven integration
    /// (event by default). `--switching regularized` or `naive` with `--scheme time-stepping` is
    /// refused: time-stepping treats v = 0 by the set-valued law.
    pub fn treatment(&self, theta: f64) -> Result<SwitchingKind, AppError> {
        match (self.scheme, self.switching) {
            (_, Some(SwitchingKind::TimeStepping { .. }))
            | (SchemeName::TimeStepping, None | Some(SwitchingKind::Event)) => {
                Ok(SwitchingKind::TimeStepping { theta })
            }
            (SchemeName::TimeStepping, Some(s)) => Err(AppError::Usage(format!(
                "option `--switching {}` applies to --scheme event-driven: time-stepping locates \
                 no event and treats v = 0 by the set-valued law at the end of each step",
                s.name()
            ))),
            (SchemeName::EventDriven, s) => Ok(s.unwrap_or(SwitchingKind::Event)),
        }
    }
}
