//! `friction-lab curve MODEL --out DIR`: one friction curve as CSV, PNG, SVG and a JSON
//! summary of its key values ([`FrictionCurve`]).

use clap::Args;
use friction_lab::curve::{FrictionCurve, CURVE_POINTS};
use friction_lab::settings::ModelSettings;
use friction_models::ModelId;
use std::path::PathBuf;

/// Options of `curve`.
#[derive(Args, Debug)]
pub struct CurveArgs {
    /// The model, as `friction-lab models` lists it (AV, CS, CVS, DV, SD, SV, coulomb, ...).
    #[arg(value_name = "MODEL")]
    pub model: ModelId,
    /// Folder to write into (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Largest |v| of a force-velocity curve, m/s [default: 1].
    #[arg(long, value_name = "V", allow_hyphen_values = true)]
    pub v_max: Option<f64>,
    /// End time of the prescribed motion X(t) = t^3/3 + t^2/2 of a force-displacement curve,
    /// s [default: 2].
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub t_end: Option<f64>,
    /// Samples on each side of zero.
    #[arg(
        long,
        value_name = "N",
        default_value_t = CURVE_POINTS,
        allow_hyphen_values = true
    )]
    pub points: i64,
    /// The model's parameters and reading.
    #[command(flatten)]
    pub model_options: ModelSettings,
}

impl CurveArgs {
    /// The curve as the library takes it.
    pub fn curve(&self) -> FrictionCurve {
        FrictionCurve {
            model: self.model,
            v_max: self.v_max,
            t_end: self.t_end,
            points: self.points,
            model_settings: self.model_options.clone(),
        }
    }
}
