//! `friction-lab curve MODEL --out DIR`: one friction curve as CSV, PNG, SVG and a JSON
//! summary of its key values.

use crate::options::ModelOptions;
use clap::Args;
use friction_lab::artifacts::{Artifacts, Made};
use friction_lab::error::AppError;
use friction_lab::figure::{Drawn, KeyValues};
use friction_lab::laws::used_parameters;
use friction_lab::ranges;
use friction_models::{CurveAxis, ModelId, Variant};
use scenarios::curves;
use serde::Serialize;
use std::collections::BTreeMap;
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
        default_value_t = 2000,
        allow_hyphen_values = true
    )]
    pub points: i64,
    /// The model's parameters and reading.
    #[command(flatten)]
    pub model_options: ModelOptions,
}

#[derive(Serialize)]
struct Summary<'a> {
    model: &'a str,
    variant: Variant,
    equation: &'a str,
    axis: CurveAxis,
    extent: f64,
    points: usize,
    parameters: BTreeMap<&'a str, f64>,
    key_values: KeyValues,
}

/// The extent of the curve: the option that belongs to the model's axis, or its default;
/// the other option is an error.
fn extent(args: &CurveArgs) -> Result<f64, AppError> {
    let axis = args.model.curve_axis();
    let (own, other, other_flag) = match axis {
        CurveAxis::Velocity => (args.v_max, args.t_end, "--t-end"),
        CurveAxis::Displacement => (args.t_end, args.v_max, "--v-max"),
    };
    if other.is_some() {
        let (drawn, use_flag) = match axis {
            CurveAxis::Velocity => ("velocity", "--v-max"),
            CurveAxis::Displacement => ("displacement under the prescribed motion", "--t-end"),
        };
        return Err(AppError::Usage(format!(
            "{other_flag} does not apply to {}: it is drawn against {drawn}; use {use_flag}",
            args.model
        )));
    }
    let range = match axis {
        CurveAxis::Velocity => ranges::V_MAX,
        CurveAxis::Displacement => ranges::T_END,
    };
    own.map(|v| range.check(v))
        .transpose()
        .map(|v| v.unwrap_or_else(|| curves::default_extent(axis)))
}

/// Runs `curve`; its files in memory.
pub fn make(args: &CurveArgs) -> Result<Made, AppError> {
    let params = args.model_options.params.source().resolve()?;
    let variant = args.model_options.variant;
    let extent = extent(args)?;
    let points = ranges::POINTS.count(args.points)?;
    let model = args.model.build(variant, &params)?;
    let curve = curves::curve(model.as_ref(), extent, points)?;

    let suffix = match variant {
        Variant::Odd => String::new(),
        Variant::Printed => "-printed".into(),
    };
    let stem = format!("curve-{}{suffix}", args.model);
    let title = format!(
        "{}: {} ({})",
        args.model,
        args.model.title(),
        args.model.source()
    );
    let mut files = Artifacts::default();
    files.add_figure(
        &args.out,
        &stem,
        title,
        args.model,
        &[Drawn {
            variant,
            curve: &curve,
        }],
    )?;
    files.add_json(
        args.out.join(format!("{stem}.json")),
        &Summary {
            model: args.model.name(),
            variant,
            equation: args.model.equation(variant),
            axis: curve.axis,
            extent,
            points,
            parameters: used_parameters(args.model, &params),
            key_values: KeyValues::of(&curve),
        },
    )?;
    Ok(Made {
        files,
        ..Made::default()
    })
}
