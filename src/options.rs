//! The options shared by every command that runs a model: `--param-set`, `--params`,
//! `--set` and `--variant`, resolved into validated parameters.

use crate::error::AppError;
use clap::Args;
use friction_models::{FrictionParams, Parameters, Variant};
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
    /// The parameters: the named set, then the file, then each `--set`, every value checked.
    pub fn resolve(&self) -> Result<FrictionParams, AppError> {
        let mut params = FrictionParams::named(&self.param_set)?;
        if let Some(path) = &self.params {
            apply_file(&mut params, path)?;
        }
        for assignment in &self.set {
            let (name, value) = parse_assignment(assignment)?;
            params.set(name, value)?;
        }
        params.validate()?;
        Ok(params)
    }
}

/// Splits `NAME=VALUE` and parses the value as a number.
fn parse_assignment(text: &str) -> Result<(&str, f64), AppError> {
    let (name, value) = text.split_once('=').ok_or_else(|| {
        AppError::Usage(format!(
            "--set `{text}`: expected NAME=VALUE, e.g. --set F_s=7.5"
        ))
    })?;
    let (name, value) = (name.trim(), value.trim());
    let number = value
        .parse::<f64>()
        .map_err(|_| AppError::Usage(format!("--set {name}={value}: `{value}` is not a number")))?;
    Ok((name, number))
}

/// Applies a TOML file of `NAME = number` lines.
fn apply_file(params: &mut FrictionParams, path: &Path) -> Result<(), AppError> {
    let file_error = |message: String| AppError::ParamFile {
        path: path.to_path_buf(),
        message,
    };
    let text =
        std::fs::read_to_string(path).map_err(|e| file_error(format!("cannot be read: {e}")))?;
    let table: toml::Table = text
        .parse()
        .map_err(|e: toml::de::Error| file_error(e.message().to_string()))?;
    for (name, value) in &table {
        let number = match value {
            toml::Value::Float(x) => *x,
            toml::Value::Integer(i) => *i as f64,
            other => {
                return Err(file_error(format!(
                    "`{name}` must be a number, found {} `{other}`",
                    other.type_str()
                )))
            }
        };
        params.set(name, number)?;
    }
    Ok(())
}
