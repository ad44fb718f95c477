//! The belt's stick–slip as two studies ([`scenarios::stick_slip`]): the map of the settled
//! regime over belt speed × stiffness from rest, with the linear stability boundary of steady
//! sliding, and the bifurcation diagram of the settled amplitude against belt speed, from rest
//! and from steady sliding.

use super::{Study, StudyFiles};
use crate::error::AppError;
use crate::output::{Cell, Table};
use crate::plot::{Corner, Marker, Plot, Series, BLUE, PALETTE};
use plotters::style::RGBColor;
use scenarios::analysis::settled::Settled;
use scenarios::stick_slip::{
    bifurcation, log_space, map, stability_boundary, Branches, MapPoint, Regime,
};
use scenarios::{RunSpec, ScenarioError};

/// The span of belt speeds over which the linear stability boundary is sought, m/s, and the
/// points it is sampled at: wider than the map's (the boundary's lower end lies near v_s/60).
const BOUNDARY_SPAN: (f64, f64, usize) = (1e-5, 10.0, 800);

/// The belt speeds in [`BOUNDARY_SPAN`] where `c + dF/dv` changes sign for the base's law.
fn boundary(base: &RunSpec) -> Result<Vec<f64>, ScenarioError> {
    let model = base.law.build(&base.friction)?;
    let (lo, hi, n) = BOUNDARY_SPAN;
    Ok(stability_boundary(model.as_ref(), base.params.c, lo, hi, n))
}

/// What the figures call each regime, in legend order (one list for the map, the bifurcation
/// diagram and a sweep's figure).
pub const REGIMES: [(Regime, &str); 8] = [
    (Regime::Hunting, "hunting (a limit cycle)"),
    (Regime::Converged, "converged"),
    (Regime::DeadZone, "at rest in the dead zone"),
    (Regime::StickSlip, "stick-slip"),
    (Regime::Oscillation, "oscillation without stick"),
    (Regime::SteadySliding, "steady sliding"),
    (Regime::Stuck, "stuck all along"),
    (Regime::Unsettled, "not settled (a transient)"),
];

/// The colour and marker of a regime in the figures: a dot for a sustained oscillation, a
/// cross for the others.
fn regime_style(regime: Regime) -> (RGBColor, Marker) {
    match regime {
        Regime::StickSlip => (PALETTE[0], Marker::Dot),
        Regime::Oscillation => (PALETTE[2], Marker::Dot),
        Regime::SteadySliding => (BLUE, Marker::Cross),
        Regime::Stuck => (PALETTE[3], Marker::Cross),
        Regime::Unsettled => (PALETTE[4], Marker::Cross),
        Regime::Hunting => (PALETTE[0], Marker::Dot),
        Regime::Converged => (BLUE, Marker::Cross),
        Regime::DeadZone => (PALETTE[2], Marker::Cross),
    }
}

/// The points of one regime as the figures draw them, in its colour and marker
/// (`regime_style`), named `label`.
pub fn regime_series(regime: Regime, label: &str, points: Vec<(f64, f64)>) -> Series {
    let (color, marker) = regime_style(regime);
    Series {
        label: Some(label.into()),
        points,
        color,
        width: 0,
        marker,
        dash: crate::plot::Dash::Solid,
    }
}

/// The settled regime of the belt `base` from rest at every belt speed × stiffness.
pub struct StickSlipMapStudy<'a> {
    /// The belt run (its law, parameters, solver and duration).
    pub base: &'a RunSpec,
    /// Belt speeds: `v_belt_count` log-spaced over `v_belt_range`, m/s.
    pub v_belt_range: (f64, f64),
    /// How many belt speeds.
    pub v_belt_count: usize,
    /// Spring stiffnesses, N/m, ascending.
    pub ks: &'a [f64],
    /// The measured, settled fraction of each run (its end).
    pub settle: f64,
}

/// The map's points, in grid order (belt speed slowest), and the stability boundary.
pub struct StickSlipMap {
    /// Every (v_belt, k) with its settled state and regime.
    pub points: Vec<MapPoint>,
    /// The belt speeds where steady sliding changes stability (c + dF/dv = 0).
    pub boundary: Vec<f64>,
}

impl StickSlipMapStudy<'_> {
    fn v_belts(&self) -> Vec<f64> {
        let (lo, hi) = self.v_belt_range;
        log_space(lo, hi, self.v_belt_count)
    }
}

impl Study for StickSlipMapStudy<'_> {
    type Result = StickSlipMap;

    fn name(&self) -> &'static str {
        "stick-slip map"
    }

    fn runs(&self) -> usize {
        self.v_belt_count * self.ks.len()
    }

    fn run(&self, progress: &(dyn Fn() + Sync)) -> Result<StickSlipMap, AppError> {
        Ok(StickSlipMap {
            points: map(self.base, &self.v_belts(), self.ks, self.settle, progress)?,
            boundary: boundary(self.base)?,
        })
    }

    /// `{stem}.csv` (a row per point) and `{stem}.png`/`.svg`: the regimes over the plane,
    /// the stability boundary inside the map's speeds.
    fn write(&self, r: &StickSlipMap, out: &mut StudyFiles) -> Result<(), AppError> {
        let (points, boundary, ks) = (&r.points, &r.boundary, self.ks);
        let (v_lo, v_hi) = self.v_belt_range;
        let mut table = Table::new(&[
            "v_belt",
            "k",
            "regime",
            "linearly_unstable",
            "stick_per_cycle",
            "period",
            "x_amplitude",
            "t_end",
            "drift",
        ]);
        let num = Cell::num;
        for p in points {
            table.rows.push(vec![
                Cell::Num(p.v_belt),
                Cell::Num(p.k),
                Cell::Text(format!("{:?}", p.regime)),
                Cell::Text(p.linearly_unstable.to_string()),
                num(p.settled.stick_per_cycle),
                num(p.settled.period),
                num(p.settled.x_amplitude),
                Cell::Num(p.settled.to),
                num(p.settled.drift),
            ]);
        }
        let csv = out.path(".csv");
        out.files.add_table(csv.clone(), table)?;
        let at = |regime: Regime| {
            (points.iter())
                .filter(|p| p.regime == regime)
                .map(|p| (p.v_belt, p.k))
                .collect()
        };
        let mut series: Vec<Series> = (REGIMES.into_iter())
            .map(|(regime, label)| regime_series(regime, label, at(regime)))
            .filter(|s| !s.points.is_empty())
            .collect();
        let inside: Vec<f64> = boundary
            .iter()
            .copied()
            .filter(|v| (v_lo..=v_hi).contains(v))
            .collect();
        for (i, &v) in inside.iter().enumerate() {
            series.push(Series {
                label: (i == 0).then(|| "c + dF/dv = 0 (linear stability of sliding)".into()),
                points: vec![(v, ks[0]), (v, ks[ks.len() - 1])],
                color: plotters::style::RGBColor(90, 90, 90),
                width: 2,
                marker: Marker::None,
                dash: crate::plot::Dash::Solid,
            });
        }
        out.files.add_plot(
            &out.path(""),
            &Plot {
                title: "Belt with CVS from rest: settled regime (c = 0, m = 1)".into(),
                x_label: "belt speed v_belt (m/s)".into(),
                y_label: "spring stiffness k (N/m)".into(),
                series,
                legend: Corner::UpperRight,
                log: true,
            },
        )
    }
}

/// The settled amplitude of the belt `base` (at its stiffness) against belt speed, from rest
/// and from steady sliding.
pub struct BifurcationStudy<'a> {
    /// The belt run (its law, parameters, stiffness, solver and duration).
    pub base: &'a RunSpec,
    /// Belt speeds, m/s, ascending.
    pub v_belts: &'a [f64],
    /// The measured, settled fraction of each run (its end).
    pub settle: f64,
}

/// The two branches at each belt speed, and the stability boundary.
pub struct Bifurcation {
    /// Per belt speed, the settled state from rest and from steady sliding.
    pub branches: Vec<Branches>,
    /// The belt speeds where steady sliding changes stability (c + dF/dv = 0).
    pub boundary: Vec<f64>,
}

impl Study for BifurcationStudy<'_> {
    type Result = Bifurcation;

    fn name(&self) -> &'static str {
        "bifurcation"
    }

    /// From rest and from steady sliding at each speed.
    fn runs(&self) -> usize {
        2 * self.v_belts.len()
    }

    fn run(&self, progress: &(dyn Fn() + Sync)) -> Result<Bifurcation, AppError> {
        Ok(Bifurcation {
            branches: bifurcation(self.base, self.v_belts, self.settle, progress)?,
            boundary: boundary(self.base)?,
        })
    }

    /// `{stem}.csv` (a row per speed) and `{stem}.png`/`.svg`: both branches' amplitudes and
    /// the stability boundary.
    fn write(&self, r: &Bifurcation, out: &mut StudyFiles) -> Result<(), AppError> {
        let (branches, boundary) = (&r.branches, &r.boundary);
        let num = Cell::num;
        let mut table = Table::new(&[
            "v_belt",
            "from_rest_regime",
            "from_rest_x_amplitude",
            "from_rest_t_end",
            "from_sliding_regime",
            "from_sliding_x_amplitude",
            "from_sliding_t_end",
        ]);
        for b in branches {
            table.rows.push(vec![
                Cell::Num(b.v_belt),
                Cell::Text(format!("{:?}", Regime::of(&b.from_rest, b.v_belt))),
                num(b.from_rest.x_amplitude),
                Cell::Num(b.from_rest.to),
                Cell::Text(format!("{:?}", Regime::of(&b.from_sliding, b.v_belt))),
                num(b.from_sliding.x_amplitude),
                Cell::Num(b.from_sliding.to),
            ]);
        }
        let csv = out.path(".csv");
        out.files.add_table(csv.clone(), table)?;
        // Each branch's points in the colour of their regime, filled from rest and open
        // from steady sliding; its settled amplitudes joined by a thin grey line (a run
        // that did not settle is no amplitude of the branch).
        type Pick = fn(&Branches) -> &Settled;
        let picks: [(&str, Pick, Marker); 2] = [
            ("from rest", |b| &b.from_rest, Marker::Dot),
            ("from steady sliding", |b| &b.from_sliding, Marker::Ring),
        ];
        let mut series = Vec::new();
        for (name, pick, marker) in picks {
            series.push(Series {
                label: None,
                points: (branches.iter())
                    .filter(|b| Regime::of(pick(b), b.v_belt) != Regime::Unsettled)
                    .map(|b| (b.v_belt, pick(b).x_amplitude))
                    .collect(),
                color: RGBColor(170, 170, 170),
                width: 1,
                marker: Marker::None,
                dash: crate::plot::Dash::Solid,
            });
            for (regime, label) in REGIMES {
                series.push(Series {
                    label: Some(format!("{label}, {name}")),
                    points: (branches.iter())
                        .filter(|b| Regime::of(pick(b), b.v_belt) == regime)
                        .map(|b| (b.v_belt, pick(b).x_amplitude))
                        .collect(),
                    color: regime_style(regime).0,
                    width: 0,
                    marker,
                    dash: crate::plot::Dash::Solid,
                });
            }
        }
        series.retain(|s| !s.points.is_empty());
        let top = branches
            .iter()
            .map(|b| b.from_rest.x_amplitude.max(b.from_sliding.x_amplitude))
            .fold(0.0, f64::max);
        for (i, &v) in boundary.iter().enumerate() {
            series.push(Series {
                label: (i == 0).then(|| "c + dF/dv = 0".into()),
                points: vec![(v, 0.0), (v, top)],
                color: plotters::style::RGBColor(90, 90, 90),
                width: 1,
                marker: Marker::None,
                dash: crate::plot::Dash::Solid,
            });
        }
        out.files.add_plot(
            &out.path(""),
            &Plot {
                title: "Belt with CVS, k = 100 N/m: settled amplitude against belt speed".into(),
                x_label: "belt speed v_belt (m/s)".into(),
                y_label: "amplitude of x − v̄·t (m)".into(),
                series,
                legend: Corner::UpperRight,
                log: false,
            },
        )
    }
}
