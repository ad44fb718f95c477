//! A run's parameters resolved: a named set, then a file of `NAME = VALUE` lines, then single
//! assignments `NAME=VALUE`, every value checked against its range; the friction parameters,
//! and a rig's or a system's own.

use crate::error::{field, AppError};
use crate::ranges::first_repeat;
use friction_models::{FrictionParams, ParamError, Parameters};
use scenarios::{Scenario, ScenarioParams};
use std::io::Read;
use std::path::{Path, PathBuf};

/// The parameter set a run starts from unless told otherwise: Table 1 of the paper.
pub const DEFAULT_PARAM_SET: &str = "paper";

/// Whether `name` is the path of a number of a system file (`contact.pad.F_c`): a name with a
/// dot, which no parameter has.
pub fn is_file_path(name: &str) -> bool {
    name.contains('.')
}

/// Where the parameters come from (`--param-set`, `--params` and `--set` on the command line);
/// the default: the run's default set, no file, no assignment.
#[derive(clap::Args, Clone, Debug, Default)]
pub struct ParamSource {
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

impl ParamSource {
    /// The name of the set started from: the one given, else [`DEFAULT_PARAM_SET`].
    pub fn set_name(&self) -> &str {
        self.param_set.as_deref().unwrap_or(DEFAULT_PARAM_SET)
    }

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
    /// run) and the paths of the file's own numbers ([`ParamSource::file_assignments`]): each
    /// `[[contact]]` of the file names its own model and parameters.
    pub fn check_for_system_file(&self) -> Result<(), AppError> {
        let [set, system, param_set] = ["set", "system", "param_set"].map(field);
        let read = format!(
            "each [[contact]] of the file names its own parameters (the file's `param_set` and \
             a contact's `params`); a system file run reads `epsilon`, the regularisation \
             width, and the file's own numbers by their paths, e.g. {set} contact.pad.F_c=2 \
             (docs/systems.md)"
        );
        if self.set_name() != DEFAULT_PARAM_SET {
            return Err(AppError::Usage(format!(
                "option `{param_set}` does not apply to {system}: {read}"
            )));
        }
        if let Some(path) = &self.params {
            if let Some((name, _)) = read_file(path)?.into_iter().find(|(n, _)| n != "epsilon") {
                return Err(AppError::ParamFile {
                    path: path.clone(),
                    message: format!("parameter `{name}` does not apply to {system}: {read}"),
                });
            }
        }
        for assignment in &self.set {
            let (name, _) = parse_assignment(assignment)?;
            if name != "epsilon" && !is_file_path(name) {
                return Err(AppError::Usage(format!(
                    "option `{set}`: parameter `{name}` does not apply to {system}: {read}"
                )));
            }
        }
        Ok(())
    }

    /// The assignments of `--set` to the numbers of a system file, by their paths
    /// `TABLE.WHICH.KEY`, in order.
    pub fn file_assignments(&self) -> Result<Vec<(String, f64)>, AppError> {
        let mut paths = Vec::new();
        for assignment in &self.set {
            let (name, value) = parse_assignment(assignment)?;
            if is_file_path(name) {
                paths.push((name.to_string(), value));
            }
        }
        Ok(paths)
    }

    /// This source without the assignments to a system file's numbers: the friction
    /// parameters alone.
    pub fn without_file_paths(&self) -> ParamSource {
        let set = (self.set.iter())
            .filter(|a| !parse_assignment(a).is_ok_and(|(name, _)| is_file_path(name)))
            .cloned()
            .collect();
        ParamSource {
            set,
            ..self.clone()
        }
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
        let mut friction = FrictionParams::named(self.set_name()).map_err(|_| {
            AppError::Usage(format!(
                "option `{}` = `{}` is no parameter set: known sets: {}",
                field("param_set"),
                self.set_name(),
                friction_models::params::PARAM_SETS.join(", ")
            ))
        })?;
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
                "option `{}`: parameter `{}` is set twice, {} and {}: set each parameter \
                 once (only the last would be used)",
                field("set"),
                names[k],
                self.set[j],
                self.set[k]
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
    let set = field("set");
    let (name, value) = text.split_once('=').ok_or_else(|| {
        AppError::Usage(format!(
            "{set} `{text}`: expected NAME=VALUE, e.g. {set} F_s=7.5"
        ))
    })?;
    let (name, value) = (name.trim(), value.trim());
    let number = value.parse::<f64>().map_err(|_| {
        // The two misreadings seen: several parameters in one --set, and a list of values.
        let hint = if value.contains('=') {
            format!(" (one parameter per {set}: {set} {name}=… {set} …)")
        } else if value.contains(',') {
            format!(
                " (one value per {set}: a list of values is a sweep, `sweep {} NAME=a,b`)",
                field("grid")
            )
        } else {
            String::new()
        };
        AppError::Usage(format!(
            "{set} {name}={value}: `{value}` is not a number{hint}"
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
