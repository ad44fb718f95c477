//! Work–precision: error against work and wall time for every solver and peer
//! ([`scenarios::studies::work_precision`]).

use super::draw::{per_solver_series, WORK_LABEL};
use super::tables::{resolution_cells, runs_table, timing_table};
use super::{check_lists, study_file, Study, StudyFiles};
use crate::error::AppError;
use crate::output::Cell;
use crate::plot::{Corner, Plot};
use scenarios::studies::{self, ErrorMeasure, Method, StudyCase, WorkPrecision};

/// Every method of `methods` on `case` (the studied ones and their peers, under another
/// treatment of v = 0), at the step sizes `steps` (fixed-step methods) or the tolerances `tols`, each run
/// `repeats` times for its median wall time.
pub struct WorkPrecisionStudy<'a> {
    /// The problem.
    pub case: &'a dyn StudyCase,
    /// The methods, each solver once among the studied ones.
    pub methods: &'a [Method],
    /// Step sizes, coarse to fine.
    pub steps: &'a [f64],
    /// Tolerances, loose to tight.
    pub tols: &'a [f64],
    /// Runs of each (method, resolution) for the median wall time.
    pub repeats: usize,
}

impl Study for WorkPrecisionStudy<'_> {
    type Result = WorkPrecision;

    fn name(&self) -> &'static str {
        "work-precision"
    }

    fn check(&self) -> Result<(), AppError> {
        check_lists(self.methods, self.steps, self.tols)
    }

    fn runs(&self) -> usize {
        Method::jobs(self.methods, self.steps, self.tols, false).len() * self.repeats
    }

    fn run(&self, progress: &(dyn Fn() + Sync)) -> Result<WorkPrecision, AppError> {
        studies::work_precision(
            self.case,
            self.methods,
            self.steps,
            self.tols,
            self.repeats,
            progress,
        )
        .map_err(AppError::from)
    }

    /// Every run failed: nothing to show ([`super::nothing_measured`]).
    fn failure(&self, w: &WorkPrecision) -> Option<AppError> {
        super::nothing_measured("work-precision", &w.runs)
    }

    /// `{stem}.csv` (a row per run), `{stem}-timing.csv` (their wall times over the repeats:
    /// median, extremes and quartiles, which vary between runs), `{stem}.json`,
    /// `{stem}.png`/`.svg` (error against counted work) and `{stem}-timing.png`/`.svg` (error
    /// against the median wall time).
    fn write(&self, w: &WorkPrecision, out: &mut StudyFiles) -> Result<(), AppError> {
        let case = self.case;
        let csv = out.path(".csv");
        out.files.add_table(csv.clone(), runs_table(&w.runs))?;
        let timing = timing_table(
            &["solver", "h", "tol"],
            w.runs.iter().map(|r| {
                let [h, tol] = resolution_cells(Some(r.step), Some(r.resolution));
                (vec![Cell::Text(r.solver.clone()), h, tol], r.wall_time)
            }),
        );
        let timing_csv = out.path("-timing.csv");
        out.files.add_table(timing_csv.clone(), timing)?;
        out.add_json(&study_file(case, self.methods, w))?;
        let error = ErrorMeasure::GridRelative.label();
        let plot = Plot {
            title: format!("Work-precision: {}", studies::describe(case, self.methods)),
            x_label: WORK_LABEL.into(),
            y_label: error.into(),
            series: per_solver_series(
                &w.runs,
                |_| true,
                |r| r.work as f64,
                |r| r.errors.grid_relative,
            ),
            legend: Corner::UpperRight,
            log: true,
        };
        out.files.add_plot(&out.path(""), &plot)?;
        // Error against wall time, the median of the repeats: a figure of its own, as the
        // timing table (it differs from run to run).
        let timed = Plot {
            title: format!(
                "Work-precision against wall time (median of {} repeats): {}",
                self.repeats,
                studies::describe(case, self.methods)
            ),
            x_label: "wall time, median (s)".into(),
            y_label: error.into(),
            series: per_solver_series(
                &w.runs,
                |_| true,
                |r| r.wall_time.median,
                |r| r.errors.grid_relative,
            ),
            legend: Corner::UpperRight,
            log: true,
        };
        out.files.add_plot(&out.path("-timing"), &timed)
    }
}
