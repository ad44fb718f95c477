//! A sweep: one run per point of a grid of parameters (the product of its axes), in parallel,
//! each reduced to its settled state (`scenarios::analysis::settled`) and regime, written as `sweep.csv`
//! (a row per point), `sweep.json` and a figure. A [`SweepStudy`] is a [`Study`]; what is run
//! at a point comes from a [`Grid`] (a [`SweepRequest`]: a simulation with the point's values
//! assigned, or one's own). The rows do not depend on the thread count.

mod axis;
mod figure;
mod point;
mod simulation;

pub use axis::{points, Axis, MAX_AXIS, MAX_POINTS};
pub use point::{grid_options, PointResult, PointRun, SystemPoint, RECORD_LIMIT};
pub use simulation::{check_point_range, point_range, SweepRequest, DEFAULT_SETTLE};

use crate::error::AppError;
use crate::output::{Cell, Table};
use crate::study::{Study, StudyFiles};
use rayon::prelude::*;
use scenarios::analysis::closed_loop::ClosedLoop;
use serde::Serialize;
use std::ops::Range;

/// Where a sweep's runs start.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Start {
    /// From the rig's own initial state.
    Rest,
    /// From the equilibrium of steady sliding on the belt
    /// ([`scenarios::stick_slip::sliding_start`]).
    Sliding,
}

impl std::str::FromStr for Start {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "rest" => Ok(Start::Rest),
            "sliding" => Ok(Start::Sliding),
            _ => Err(format!("unknown start `{s}`; known: rest, sliding")),
        }
    }
}

/// What a sweep runs at each point of its grid.
pub trait Grid: Sync {
    /// The run at `point` (the value of every axis, by name, in axis order), set up and
    /// checked: bad input is [`AppError::Usage`].
    fn run_at(&self, point: &[(String, f64)]) -> Result<PointRun, AppError>;
}

/// A sweep of `grid` over the product of `axes`, each run measured over its last fraction
/// `settle`.
pub struct SweepStudy<'a> {
    /// What is run at each point.
    pub grid: &'a dyn Grid,
    /// The axes, the first varying slowest.
    pub axes: &'a [Axis],
    /// The measured, settled part of each run: its last fraction (0, 1] of the time span.
    pub settle: f64,
    /// The points run, in grid order (a part of the sweep, for spreading it over machines);
    /// every point of the grid is checked all the same.
    pub range: Range<usize>,
    /// What is swept, as the files name it: a rig, `chain` or a system file's path.
    pub target: String,
    /// The model, where one is named.
    pub model: Option<String>,
    /// Where the runs start.
    pub start: Start,
}

impl SweepStudy<'_> {
    fn grid_points(&self) -> Vec<Vec<(String, f64)>> {
        points(self.axes)
    }
}

/// What `sweep.json` holds.
#[derive(Serialize)]
struct SweepFile<'a> {
    target: String,
    model: Option<String>,
    start: Start,
    settle: f64,
    axes: &'a [Axis],
    /// The number of points in the whole grid.
    grid_points: usize,
    /// The points run, `[start, end)` in grid order.
    point_range: [usize; 2],
    points: &'a [PointResult],
}

impl Study for SweepStudy<'_> {
    type Result = Vec<PointResult>;

    fn name(&self) -> &'static str {
        "sweep"
    }

    /// `settle` in (0, 1], at most [`MAX_POINTS`] points, and every point's run set up and
    /// checked ([`Grid::run_at`]) before any runs.
    fn check(&self) -> Result<(), AppError> {
        crate::ranges::SETTLE.check(self.settle)?;
        let grid = self.grid_points();
        if grid.len() > MAX_POINTS {
            return Err(AppError::Usage(format!(
                "option `{}` makes {} points: allowed at most {MAX_POINTS}",
                crate::error::field("grid"),
                grid.len()
            )));
        }
        for point in &grid {
            self.grid.run_at(point)?;
        }
        Ok(())
    }

    fn runs(&self) -> usize {
        self.range.len()
    }

    fn run(&self, progress: &(dyn Fn() + Sync)) -> Result<Vec<PointResult>, AppError> {
        self.grid_points()[self.range.clone()]
            .par_iter()
            .map(|point| {
                let r = self.grid.run_at(point)?.run(self.settle);
                progress();
                r.map(|r| PointResult {
                    values: point.iter().map(|(_, v)| *v).collect(),
                    ..r
                })
            })
            .collect()
    }

    /// Points whose run failed or diverged: the others are measured, `sweep.csv` says which
    /// and why.
    fn failure(&self, results: &Vec<PointResult>) -> Option<AppError> {
        let failed = results.iter().filter(|r| r.verdict.is_broken()).count();
        (failed > 0).then(|| {
            AppError::StudyRun(format!(
                "{failed} of {} runs failed or diverged; sweep.csv says which and why",
                results.len()
            ))
        })
    }

    /// `{stem}.csv` (a row per point: the axes' values, the settled measures, the regime, the
    /// solver's counts and the status), `{stem}.json` (the grid, the options, the rows) and,
    /// over one or two axes, `{stem}.png`/`.svg`.
    fn write(&self, results: &Vec<PointResult>, out: &mut StudyFiles) -> Result<(), AppError> {
        let mut header: Vec<&str> = self.axes.iter().map(|a| a.name.as_str()).collect();
        header.extend([
            "stick_phases",
            "stick_per_cycle",
            "period",
            "x_amplitude",
            "v_amplitude",
            "v_amplitude_ratio",
            "v_mean",
            "friction_mean",
            "friction_peak",
            "settled",
            "regime",
            "drift",
            "t_end",
            "steps",
            "rhs_evals",
            "events",
            "status",
            "reason",
        ]);
        // A closed loop's own measures (docs/closed-loop.md), after the others.
        let closed = results.iter().any(|r| r.closed_loop.is_some());
        if closed {
            header.extend([
                "stick_time_per_cycle",
                "final_error",
                "rms_error",
                "max_error",
            ]);
        }
        let mut table = Table::new(&header);
        // An undefined measure (no oscillation) is an empty cell, never NaN.
        let num = Cell::num;
        for r in results {
            let s = &r.settled;
            let mut row: Vec<Cell> = r.values.iter().map(|&v| Cell::Num(v)).collect();
            // A failed or diverged point measured nothing: its stick phases are no count.
            let stick_phases = match r.verdict.is_broken() {
                true => Cell::empty(),
                false => Cell::Num(s.stick_phases as f64),
            };
            row.extend([
                stick_phases,
                num(s.stick_per_cycle),
                num(s.period),
                num(s.x_amplitude),
                num(s.v_amplitude),
                num(s.v_amplitude_ratio),
                num(s.v_mean),
                num(s.friction_mean),
                num(s.friction_peak),
                Cell::Text(s.settled.to_string()),
                Cell::Text(r.regime.map(|g| format!("{g:?}")).unwrap_or_default()),
                num(s.drift),
                Cell::Num(s.to),
                Cell::Num(r.stats.steps as f64),
                Cell::Num(r.stats.rhs_evals as f64),
                Cell::Num(r.stats.events as f64),
                Cell::Text(r.verdict.status.name().into()),
                Cell::Text(r.verdict.reason.clone().unwrap_or_default()),
            ]);
            if closed {
                let c = r.closed_loop.as_ref();
                let of = |f: fn(&ClosedLoop) -> f64| num(c.map_or(f64::NAN, f));
                row.extend([
                    of(|c| c.stick_time_per_cycle),
                    of(|c| c.final_error),
                    of(|c| c.rms_error),
                    of(|c| c.max_error),
                ]);
            }
            table.rows.push(row);
        }
        let csv = out.path(".csv");
        out.files.add_table(csv.clone(), table)?;
        let title = match &self.model {
            Some(m) => format!("{} with {m}", self.target),
            None => self.target.clone(),
        };
        if let Some(plot) = figure::figure(self.axes, results, &title) {
            out.files.add_plot(&out.path(""), &plot)?;
        }
        out.files.add_json(
            out.path(".json"),
            &SweepFile {
                target: self.target.clone(),
                model: self.model.clone(),
                start: self.start,
                settle: self.settle,
                axes: self.axes,
                grid_points: self.grid_points().len(),
                point_range: [self.range.start, self.range.end],
                points: results,
            },
        )
    }
}
