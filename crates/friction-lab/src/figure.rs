//! A friction curve as the files that show it: a CSV table of its data and a plot.

use crate::output::{Cell, Table};
use crate::plot::{Corner, Marker, Plot, Series, BLUE, GREEN, RED};
use friction_models::{CurveAxis, ModelId, StickInterval, Variant};
use scenarios::curves::{Curve, Sample};
use serde::Serialize;

/// One curve of a figure, with the reading of the equations it was computed from.
#[derive(Clone, Debug, PartialEq)]
pub struct Drawn<'a> {
    /// The reading (`odd` or `printed`).
    pub variant: Variant,
    /// The computed curve.
    pub curve: &'a Curve,
}

/// The abscissa of a sample: velocity or displacement.
fn abscissa(axis: CurveAxis, s: &Sample) -> f64 {
    match axis {
        CurveAxis::Velocity => s.v,
        CurveAxis::Displacement => s.x,
    }
}

/// At most this many vertices per branch are drawn (wide lines with many short segments
/// render ragged); the CSV keeps every sample.
const DRAWN_PER_BRANCH: usize = 400;

/// Every k-th sample of a branch and its last one, so that at most [`DRAWN_PER_BRANCH`]
/// remain.
fn thinned(branch: &[Sample]) -> impl DoubleEndedIterator<Item = &Sample> {
    let stride = branch.len().div_ceil(DRAWN_PER_BRANCH).max(1);
    let last = branch.len() - 1;
    branch
        .iter()
        .enumerate()
        .filter(move |(i, _)| i % stride == 0 || *i == last)
        .map(|(_, s)| s)
}

/// The curve as one polyline from the negative end through the jump at zero to the positive
/// end.
fn polyline(curve: &Curve) -> Vec<(f64, f64)> {
    let point = |s: &Sample| (abscissa(curve.axis, s), s.force);
    let mut points: Vec<_> = thinned(&curve.negative).rev().map(point).collect();
    points.push((0.0, curve.left_of_zero));
    points.push((0.0, curve.right_of_zero));
    points.extend(thinned(&curve.positive).map(point));
    points
}

/// The data of all curves of a figure: one row per sample, in plotting order.
pub fn table(curves: &[Drawn]) -> Table {
    let axis = curves[0].curve.axis;
    let mut table = match axis {
        CurveAxis::Velocity => Table::new(&["variant", "branch", "v", "force"]),
        CurveAxis::Displacement => Table::new(&["variant", "branch", "t", "x", "v", "z", "force"]),
    };
    for d in curves {
        let c = d.curve;
        let row = |branch: &str, s: &Sample| {
            let mut row = vec![Cell::Text(d.variant.to_string()), Cell::Text(branch.into())];
            row.extend(match axis {
                CurveAxis::Velocity => vec![Cell::Num(s.v), Cell::Num(s.force)],
                CurveAxis::Displacement => [s.t, s.x, s.v, s.z, s.force].map(Cell::Num).to_vec(),
            });
            row
        };
        let at_rest = |force| Sample {
            t: 0.0,
            x: 0.0,
            v: 0.0,
            z: 0.0,
            force,
        };
        table
            .rows
            .extend(c.negative.iter().rev().map(|s| row("negative", s)));
        table
            .rows
            .push(row("rest_lower", &at_rest(c.at_rest.lower)));
        table
            .rows
            .push(row("rest_upper", &at_rest(c.at_rest.upper)));
        table
            .rows
            .extend(c.positive.iter().map(|s| row("positive", s)));
    }
    table
}

/// The plot of a figure: each curve as a polyline (the sign-consistent one red, the printed
/// one wider and blue, drawn first so that where they coincide the red shows on blue), and
/// the forces admissible at rest as a green segment at zero.
pub fn plot(title: String, model: ModelId, curves: &[Drawn]) -> Plot {
    let axis = curves[0].curve.axis;
    let mut series = Vec::new();
    for d in curves.iter().rev() {
        let (color, width, reading) = match d.variant {
            Variant::Odd => (RED, 2, "sign-consistent (odd)"),
            Variant::Printed => (BLUE, 4, "as printed"),
        };
        series.push(Series {
            label: Some(format!("{model}, {reading}")),
            points: polyline(d.curve),
            color,
            width,
            marker: Marker::None,
            dash: crate::plot::Dash::Solid,
        });
    }
    let main = curves[0].curve.at_rest;
    if main.upper > main.lower {
        series.push(Series {
            label: Some(format!(
                "forces admissible at rest: [{:.3}, {:.3}] N",
                main.lower, main.upper
            )),
            points: vec![(0.0, main.lower), (0.0, main.upper)],
            color: GREEN,
            width: 4,
            marker: Marker::None,
            dash: crate::plot::Dash::Solid,
        });
    }
    let x_label = match axis {
        CurveAxis::Velocity => "velocity v (m/s)",
        CurveAxis::Displacement => "displacement X (m)",
    };
    Plot {
        title,
        x_label: x_label.into(),
        y_label: "friction force F (N)".into(),
        series,
        legend: Corner::default(),
        log: false,
    }
}

/// Key values of a curve, as written to its JSON summary.
#[derive(Serialize)]
pub struct KeyValues {
    /// Force just left of zero (limit v → 0−), N.
    pub left_of_zero: f64,
    /// Force just right of zero (limit v → 0+), N.
    pub right_of_zero: f64,
    /// Forces admissible at rest, N.
    pub at_rest: StickInterval,
    /// Abscissa (v in m/s or X in m) at the positive end.
    pub end_abscissa: f64,
    /// Force at the positive end, N.
    pub end_force: f64,
    /// Force at the negative end, N.
    pub end_force_negative: f64,
}

impl KeyValues {
    /// The key values of `curve`.
    pub fn of(curve: &Curve) -> Self {
        let end = curve.positive[curve.positive.len() - 1];
        KeyValues {
            left_of_zero: curve.left_of_zero,
            right_of_zero: curve.right_of_zero,
            at_rest: curve.at_rest,
            end_abscissa: match curve.axis {
                CurveAxis::Velocity => end.v,
                CurveAxis::Displacement => end.x,
            },
            end_force: end.force,
            end_force_negative: curve.negative[curve.negative.len() - 1].force,
        }
    }
}
