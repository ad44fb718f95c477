//! One friction curve as a front end asks for it ([`CurveRequest`]): the force against
//! velocity (or against displacement under a prescribed motion), its CSV, figure and a JSON
//! summary of its key values.

use crate::artifacts::Artifacts;
use crate::error::{field, AppError};
use crate::figure::{Drawn, KeyValues};
use crate::laws::used_parameters;
use crate::made::Made;
use crate::ranges;
use crate::settings::ModelSettings;
use friction_models::{CurveAxis, ModelId, Variant};
use scenarios::curves;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;

/// The samples on each side of zero of a curve unless told otherwise.
pub const CURVE_POINTS: i64 = 2000;

/// One friction curve of a model of the catalog (`friction-lab curve`).
#[derive(clap::Args, Clone, Debug)]
pub struct CurveRequest {
    /// The model, as `friction-lab models` lists it (AV, CS, CVS, DV, SD, SV, coulomb, ...).
    #[arg(value_name = "MODEL")]
    pub model: ModelId,
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
    pub model_settings: ModelSettings,
}

/// What `curve-MODEL.json` holds.
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

impl CurveRequest {
    /// The curve of `model` with every other setting at its default.
    pub fn new(model: ModelId) -> CurveRequest {
        CurveRequest {
            model,
            v_max: None,
            t_end: None,
            points: CURVE_POINTS,
            model_settings: ModelSettings::default(),
        }
    }

    /// The extent of the curve: the setting that belongs to the model's axis, or its
    /// default; the other setting is an error.
    fn extent(&self) -> Result<f64, AppError> {
        let axis = self.model.curve_axis();
        let (own, other, other_flag) = match axis {
            CurveAxis::Velocity => (self.v_max, self.t_end, field("t_end")),
            CurveAxis::Displacement => (self.t_end, self.v_max, field("v_max")),
        };
        if other.is_some() {
            let (drawn, use_flag) = match axis {
                CurveAxis::Velocity => ("velocity", field("v_max")),
                CurveAxis::Displacement => {
                    ("displacement under the prescribed motion", field("t_end"))
                }
            };
            return Err(AppError::Usage(format!(
                "{other_flag} does not apply to {}: it is drawn against {drawn}; use {use_flag}",
                self.model
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

    /// Checks and draws the curve: `curve-MODEL.csv`, its figure and `curve-MODEL.json` in
    /// `out` (in memory).
    pub fn run(&self, out: &Path) -> Result<Made, AppError> {
        let params = self.model_settings.params.resolve()?;
        let variant = self.model_settings.variant;
        let extent = self.extent()?;
        let points = ranges::POINTS.count(self.points)?;
        let model = self.model.build(variant, &params)?;
        let curve = curves::curve(model.as_ref(), extent, points)?;

        let suffix = match variant {
            Variant::Odd => String::new(),
            Variant::Printed => "-printed".into(),
        };
        let stem = format!("curve-{}{suffix}", self.model);
        let title = format!(
            "{}: {} ({})",
            self.model,
            self.model.title(),
            self.model.source()
        );
        let mut files = Artifacts::default();
        files.add_figure(
            out,
            &stem,
            title,
            self.model,
            &[Drawn {
                variant,
                curve: &curve,
            }],
        )?;
        files.add_json(
            out.join(format!("{stem}.json")),
            &Summary {
                model: self.model.name(),
                variant,
                equation: self.model.equation(variant),
                axis: curve.axis,
                extent,
                points,
                parameters: used_parameters(self.model, &params),
                key_values: KeyValues::of(&curve),
            },
        )?;
        Ok(Made {
            files,
            ..Made::default()
        })
    }
}
