//! A sweep's figure: the settled amplitude over one axis, or the regimes over the plane of
//! two, each regime drawn as in the stick–slip map.

use super::{Axis, PointResult};
use crate::plot::{Corner, Marker, Plot, Series, PALETTE};
use crate::study::{regime_series, REGIMES};

/// Whether `values` are drawn on a log axis: all positive and spanning a decade or more.
fn log_axis(values: &[f64]) -> bool {
    let (lo, hi) = values.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &v| {
        (lo.min(v), hi.max(v))
    });
    values.iter().all(|&v| v > 0.0) && hi >= 10.0 * lo
}

/// The figure of a sweep of one or two axes (none for more): over one axis the settled
/// amplitude of x − v̄·t at every point, over two the plane of the axes, each point in the
/// colour and marker of its regime; a failed or diverged point is a cross of its own (on the axis, for
/// one axis).
pub fn figure(axes: &[Axis], results: &[PointResult], title: &str) -> Option<Plot> {
    let failed = |at: &dyn Fn(&PointResult) -> (f64, f64)| Series {
        label: Some("failed or diverged (sweep.csv says why)".into()),
        points: results
            .iter()
            .filter(|r| r.regime.is_none())
            .map(at)
            .collect(),
        color: PALETTE[5],
        width: 0,
        marker: Marker::Cross,
        dash: crate::plot::Dash::Solid,
    };
    let by_regime = |at: &dyn Fn(&PointResult) -> (f64, f64)| {
        let mut series: Vec<Series> = (REGIMES.iter())
            .map(|&(regime, label)| {
                let mine = results.iter().filter(|r| r.regime == Some(regime));
                regime_series(regime, label, mine.map(at).collect())
            })
            .chain([failed(at)])
            .collect();
        series.retain(|s| !s.points.is_empty());
        series
    };
    let label = |a: &Axis| {
        use friction_models::{FrictionParams, Parameters};
        let unit = (FrictionParams::spec(&a.name).map(|s| s.unit))
            .or_else(|| scenarios::ScenarioParams::spec(&a.name).map(|s| s.unit))
            .or_else(|| {
                let chain = friction_systems::chain::CHAIN_PARAMETERS;
                chain.iter().find(|p| p.0 == a.name).map(|p| p.2)
            });
        match unit {
            Some(u) if !u.is_empty() && u != "1" => format!("{} ({u})", a.name),
            _ => a.name.clone(),
        }
    };
    match axes {
        [x] => Some(Plot {
            title: format!("{title}: settled amplitude"),
            x_label: label(x),
            y_label: "amplitude of x − v̄·t (m)".into(),
            series: by_regime(&|r| (r.values[0], r.settled.x_amplitude.max(0.0))),
            legend: Corner::UpperRight,
            log: false,
        }),
        [x, y] => Some(Plot {
            title: format!("{title}: settled regime"),
            x_label: label(x),
            y_label: label(y),
            series: by_regime(&|r| (r.values[0], r.values[1])),
            legend: Corner::UpperRight,
            log: log_axis(&x.values) && log_axis(&y.values),
        }),
        _ => None,
    }
}
