//! Step-size independence: one solver at a ladder of resolutions, with a Richardson estimate
//! of the error left and a verdict ([`scenarios::studies::independence`]).

use super::tables::resolution_cells;
use super::{study_file, Study, StudyFiles};
use crate::error::AppError;
use crate::output::{Cell, Table};
use crate::plot::{Corner, Marker, Plot, Series, PALETTE};
use crate::ranges;
use scenarios::studies::{self, Independence, Method, StudyCase};

/// The levels of an independence study; by default four levels from 1e-3, halved each time,
/// judged at a relative tolerance of 1e-6 (the declared defaults).
#[derive(clap::Args, Clone, Copy, Debug)]
pub struct Refinement {
    /// The coarsest step size (rk4) or tolerance (adaptive solvers).
    #[arg(
        long,
        value_name = "H",
        default_value_t = 1e-3,
        allow_hyphen_values = true
    )]
    pub start: f64,
    /// Refinement ratio between levels.
    #[arg(
        long,
        value_name = "R",
        default_value_t = 2.0,
        allow_hyphen_values = true
    )]
    pub ratio: f64,
    /// Number of levels.
    #[arg(
        long,
        value_name = "N",
        default_value_t = 4,
        allow_hyphen_values = true
    )]
    pub levels: i64,
    /// Relative tolerance of the verdict.
    #[arg(
        long,
        value_name = "TOL",
        default_value = "1e-6",
        allow_hyphen_values = true
    )]
    pub tol: f64,
}

crate::settings::default_as_declared!(Refinement);

/// `method` on `case` at the levels of `refinement`: `start`, `start/ratio`, … (step sizes
/// for a fixed-step solver or time-stepping, else tolerances).
pub struct IndependenceStudy<'a> {
    /// The problem.
    pub case: &'a dyn StudyCase,
    /// The method.
    pub method: Method,
    /// The levels and the verdict's tolerance.
    pub refinement: Refinement,
}

impl Study for IndependenceStudy<'_> {
    type Result = Independence;

    fn name(&self) -> &'static str {
        "independence"
    }

    /// Each of `tol`, `ratio` and `levels` in its range, and every level in the range of a
    /// step size or a tolerance.
    fn check(&self) -> Result<(), AppError> {
        let method = self.method;
        let Refinement {
            start,
            ratio,
            levels,
            tol,
        } = self.refinement;
        ranges::VERDICT_TOL.check(tol)?;
        ranges::RATIO.check(ratio)?;
        ranges::LEVELS.count(levels)?;
        // Every level is a step size (fixed-step solvers) or a tolerance, in that option's range.
        let resolution = if method.is_fixed_step() {
            ranges::DT
        } else {
            ranges::RTOL
        };
        let finest = start / ratio.powi(levels as i32 - 1);
        resolution
            .check(start)
            .and(resolution.check(finest))
            .map_err(|_| {
                AppError::Usage(format!(
                    "option `{}` = {} (finest level {finest:e}) is out of range for {}: every \
                     level must lie in {} (the range of {})",
                    crate::error::field("start"),
                    ranges::show(start),
                    method.label(),
                    resolution.range,
                    crate::error::field(resolution.name)
                ))
            })?;
        Ok(())
    }

    fn runs(&self) -> usize {
        self.refinement.levels as usize
    }

    fn run(&self, progress: &(dyn Fn() + Sync)) -> Result<Independence, AppError> {
        let r = self.refinement;
        studies::independence(
            self.case,
            self.method,
            r.start,
            r.ratio,
            r.levels as usize,
            r.tol,
            progress,
        )
        .map_err(AppError::from)
    }

    /// The levels that failed, named: the files keep the levels that ran.
    fn failure(&self, s: &Independence) -> Option<AppError> {
        let levels = self.refinement.levels;
        let f = s.failed.first()?;
        Some(AppError::StudyRun(format!(
            "{} of {levels} levels of the independence study failed, the first at level {} \
             ({:e}): {}; levels {} to {} are judged",
            s.failed.len(),
            f.level,
            f.resolution,
            f.failure,
            s.first_level,
            s.first_level + s.resolutions.len() - 1
        )))
    }

    /// `{stem}.csv` (a row per output and level), `{stem}.json` and `{stem}.png`/`.svg` (the
    /// trajectories at every level).
    fn write(&self, s: &Independence, out: &mut StudyFiles) -> Result<(), AppError> {
        let case = self.case;
        let mut table = Table::new(&[
            "output",
            "level",
            "h",
            "tol",
            "value",
            "difference_to_previous",
            "remaining_error",
            "independent",
        ]);
        for o in &s.outputs {
            for (i, v) in o.values.iter().enumerate() {
                let [h, tol] = resolution_cells(Some(s.step), Some(s.resolutions[i]));
                table.rows.push(vec![
                    Cell::Text(o.name.clone()),
                    Cell::Num((s.first_level + i) as f64),
                    h,
                    tol,
                    Cell::Num(*v),
                    if i == 0 {
                        Cell::empty()
                    } else {
                        Cell::Num(o.differences[i - 1])
                    },
                    if i + 1 == o.values.len() && o.remaining_error.is_finite() {
                        Cell::Num(o.remaining_error)
                    } else {
                        Cell::empty()
                    },
                    Cell::Text(o.independent.to_string()),
                ]);
            }
        }
        let csv = out.path(".csv");
        out.files.add_table(csv.clone(), table)?;
        out.add_json(&study_file(case, &[self.method], s))?;
        let series = s
            .trajectories
            .iter()
            .zip(&s.resolutions)
            .zip(PALETTE.iter().cycle())
            .zip(crate::plot::Dash::ALL.iter().cycle())
            .map(|(((xs, h), &color), &dash)| Series {
                label: Some(format!("{} at {h:e}", s.solver)),
                points: xs
                    .iter()
                    .enumerate()
                    .map(|(i, &x)| (case.t_end() * i as f64 / (xs.len().max(2) - 1) as f64, x))
                    .collect(),
                color,
                width: 2,
                marker: Marker::None,
                dash,
            })
            .collect();
        let plot = Plot {
            title: format!(
                "Independence: {}: {}",
                studies::describe(case, &[self.method]),
                if s.independent {
                    "independent".to_string()
                } else if s.failed.is_empty() {
                    "NOT independent".to_string()
                } else {
                    format!("NOT independent ({} levels failed)", s.failed.len())
                }
            ),
            x_label: "time t (s)".into(),
            y_label: "displacement x (m)".into(),
            series,
            legend: Corner::default(),
            log: false,
        };
        out.files.add_plot(&out.path(""), &plot)
    }
}
