//! `work-precision`: error against work and wall time for every solver and peer.

use super::{
    distinct, failures, per_solver_series, resolution_cells, runs_table, study_error, study_file,
    CaseArgs, Target,
};
use crate::artifacts::Made;
use crate::error::AppError;
use crate::output::{Cell, Table};
use crate::plot::{Corner, Plot};
use crate::progress::Progress;
use crate::ranges;
use crate::threads::with_threads;
use clap::Args;
use integrators::Solver;
use scenarios::studies::{self, Method, StudyCase, WorkPrecision};

/// Options of `work-precision`.
#[derive(Args, Debug)]
pub struct WorkPrecisionArgs {
    /// The problem.
    #[command(flatten)]
    pub case: CaseArgs,
    /// Solvers, comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "rk4,dopri5,implicit-euler,bdf,tr-bdf2,esdirk34,tsit45"
    )]
    pub solvers: Vec<Solver>,
    /// Step sizes of rk4, coarse to fine.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "0.01,0.003,0.001,0.0003"
    )]
    pub dt_list: Vec<f64>,
    /// Tolerances of the adaptive solvers, loose to tight.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "1e-3,1e-4,1e-5,1e-6,1e-7,1e-8"
    )]
    pub tol_list: Vec<f64>,
    /// Repetitions of each run for the median wall time.
    #[arg(
        long,
        value_name = "N",
        default_value_t = 3,
        allow_hyphen_values = true
    )]
    pub repeats: i64,
}

/// Computes a work–precision study and adds its files under `dir` with stem `stem`.
pub fn add_work_precision(
    t: &mut Target,
    stem: &str,
    case: &dyn StudyCase,
    solvers: &[Solver],
    steps: &[f64],
    tols: &[f64],
    repeats: usize,
) -> Result<WorkPrecision, AppError> {
    let (dir, threads) = (t.dir, t.threads);
    distinct(solvers)?;
    ranges::DT.list("dt-list", steps)?;
    ranges::RTOL.list("tol-list", tols)?;
    let methods: Vec<Method> = Method::studied(case.switching(), solvers)
        .into_iter()
        .chain(case.peers())
        .collect();
    let jobs = Method::jobs(&methods, steps, tols, false).len();
    let b = Progress::runs(jobs * repeats, "work-precision");
    let w = with_threads(threads, || {
        studies::work_precision(case, &methods, steps, tols, repeats, &|| b.inc())
    })?
    .map_err(study_error)?;
    b.finish();
    let csv = dir.join(format!("{stem}.csv"));
    t.files.add(csv.clone(), runs_table(&w.runs, &csv)?);
    let mut timing = Table::new(&["solver", "h", "tol", "wall_time_median_s"]);
    for r in &w.runs {
        let [h, tol] = resolution_cells(Some(r.step), Some(r.resolution));
        timing.rows.push(vec![
            Cell::Text(r.solver.clone()),
            h,
            tol,
            Cell::Num(r.wall_time_s),
        ]);
    }
    let timing_csv = dir.join(format!("{stem}-timing.csv"));
    t.files.add(timing_csv.clone(), timing.to_csv(&timing_csv)?);
    t.files
        .add_json(dir.join(format!("{stem}.json")), &study_file(case, &w))?;
    let plot = Plot {
        title: format!("Work-precision: {}", case.describe()),
        x_label: "work (f evaluations + dim per Jacobian)".into(),
        y_label: "max error on the time grid".into(),
        series: per_solver_series(&w.runs, |_| true, |r| r.work as f64, |r| r.errors.grid_max),
        legend: Corner::UpperRight,
        log: true,
    };
    t.files.add_plot(&dir.join(stem), &plot)?;
    Ok(w)
}

/// Runs `work-precision`; its files in memory.
pub fn work_precision(a: &WorkPrecisionArgs) -> Result<Made, AppError> {
    a.case.make(|t, case| {
        add_work_precision(
            t,
            "work-precision",
            case,
            &a.solvers,
            &a.dt_list,
            &a.tol_list,
            ranges::REPEATS.count(a.repeats)?,
        )
        .map(|w| failures(&w.runs, "work-precision.csv"))
    })
}
