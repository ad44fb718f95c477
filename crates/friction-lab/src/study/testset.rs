//! Work–precision on a problem of the stiff test set: significant correct digits against
//! counted work and wall time for every solver, the test set's own plot
//! ([`scenarios::studies::testset_work_precision`]).

use super::draw::{per_solver_series, WORK_LABEL};
use super::tables::timing_table;
use super::{distinct, Study, StudyFiles};
use crate::error::AppError;
use crate::output::{Cell, Table};
use crate::plot::{Corner, Plot};
use crate::ranges;
use integrators::testset::TestProblem;
use integrators::Solver;
use scenarios::run::Limits;
use scenarios::studies::{self, TestSetCounts, TestSetRun, TestSetWorkPrecision};

/// Every solver of `solvers` on a test problem at every tolerance of `tols` (rtol = tol, atol
/// by [`TestProblem::tolerances`]), each run `repeats` times for its median wall time.
pub struct TestSetStudy<'a> {
    /// The problem.
    pub problem: &'static TestProblem,
    /// The solvers, each once; adaptive ones only.
    pub solvers: &'a [Solver],
    /// Tolerances, loose to tight.
    pub tols: &'a [f64],
    /// Runs of each (solver, tolerance) for the median wall time.
    pub repeats: usize,
    /// The bounds of each run.
    pub limits: Limits,
}

/// The y axis of the figures: the error max_i |y_i − y_i,ref|/|y_i,ref| at t_end, whose
/// −log10 is the test set's scd.
const ERROR_LABEL: &str = "relative error at t_end = 10^−scd (1)";

impl Study for TestSetStudy<'_> {
    type Result = TestSetWorkPrecision;

    fn name(&self) -> &'static str {
        "work-precision"
    }

    /// Each solver once and adaptive (the test set is run at tolerances), every tolerance in
    /// its range.
    fn check(&self) -> Result<(), AppError> {
        distinct(self.solvers)?;
        if let Some(s) = self.solvers.iter().find(|s| s.is_fixed_step()) {
            let adaptive: Vec<&str> = (Solver::ALL.iter())
                .filter(|s| !s.is_fixed_step())
                .map(|s| s.name())
                .collect();
            return Err(AppError::Usage(format!(
                "option `{}` names `{}`, which takes a fixed step: the test set is run at \
                 tolerances; allowed: {}",
                crate::error::field("solvers"),
                s.name(),
                adaptive.join(", ")
            )));
        }
        ranges::RTOL.list("tol_list", self.tols)?;
        Ok(())
    }

    fn runs(&self) -> usize {
        self.solvers.len() * self.tols.len() * self.repeats
    }

    fn run(&self, progress: &(dyn Fn() + Sync)) -> Result<TestSetWorkPrecision, AppError> {
        studies::testset_work_precision(
            self.problem,
            self.solvers,
            self.tols,
            self.repeats,
            &self.limits,
            progress,
        )
        .map_err(AppError::from)
    }

    /// Every run failed: nothing was measured (exit 1, after the files that say why).
    fn failure(&self, w: &TestSetWorkPrecision) -> Option<AppError> {
        let first = w.runs.first()?.failure.as_ref()?;
        w.runs.iter().all(|r| r.failure.is_some()).then(|| {
            AppError::StudyRun(format!(
                "work-precision: every run failed ({n} of {n}), nothing was measured; the first, \
                 {} at tol = {}: {first}",
                w.runs[0].solver,
                w.runs[0].tol,
                n = w.runs.len()
            ))
        })
    }

    /// `{stem}.csv` (a row per run: its tolerances, scd, counts and work), `{stem}-timing.csv`
    /// (wall times over the repeats), `{stem}.json`, `{stem}.png`/`.svg` (error against counted
    /// work) and `{stem}-timing.png`/`.svg` (error against the median wall time).
    fn write(&self, w: &TestSetWorkPrecision, out: &mut StudyFiles) -> Result<(), AppError> {
        let csv = out.path(".csv");
        out.files.add_table(csv.clone(), runs_table(&w.runs))?;
        let timing = timing_table(
            &["solver", "tol"],
            (w.runs.iter()).map(|r| {
                (
                    vec![Cell::Text(r.solver.into()), Cell::Num(r.tol)],
                    r.wall_time,
                )
            }),
        );
        let timing_csv = out.path("-timing.csv");
        out.files.add_table(timing_csv.clone(), timing)?;
        out.add_json(w)?;
        let title = format!("Work-precision: {} to t = {}", w.problem, w.t_end);
        let error = |r: &TestSetRun| r.relative_error();
        let plot = Plot {
            title: title.clone(),
            x_label: WORK_LABEL.into(),
            y_label: ERROR_LABEL.into(),
            series: per_solver_series(&w.runs, |_| true, |r| r.work as f64, error),
            legend: Corner::UpperRight,
            log: true,
        };
        out.files.add_plot(&out.path(""), &plot)?;
        let timed = Plot {
            title: format!("{title}, median of {} repeats", self.repeats),
            x_label: "wall time, median (s)".into(),
            y_label: ERROR_LABEL.into(),
            series: per_solver_series(&w.runs, |_| true, |r| r.wall_time.median, error),
            legend: Corner::UpperRight,
            log: true,
        };
        out.files.add_plot(&out.path("-timing"), &timed)
    }
}

/// One row per run: solver, tolerances, status ([`TestSetRun::status`]), scd, the test set's counts and the work.
fn runs_table(runs: &[TestSetRun]) -> Table {
    let header: Vec<&str> = ["solver", "tol", "rtol", "atol", "status", "scd", "work"]
        .into_iter()
        .chain(TestSetCounts::NAMES)
        .chain(["reason"])
        .collect();
    let mut t = Table::new(&header);
    for r in runs {
        let mut row = vec![
            Cell::Text(r.solver.into()),
            Cell::Num(r.tol),
            Cell::Num(r.rtol),
            Cell::Num(r.atol),
            Cell::Text(r.status.name().into()),
            r.scd.map_or_else(Cell::empty, Cell::Num),
            Cell::Num(r.work as f64),
        ];
        let counts = TestSetCounts::of(&r.stats).values();
        row.extend(counts.map(|n| Cell::Num(n as f64)));
        row.push(Cell::Text(r.reason().unwrap_or_default()));
        t.rows.push(row);
    }
    t
}
