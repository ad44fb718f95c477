//! `converge`: observed orders of every solver against a reference.

use super::{
    distinct, failures, per_solver_series, runs_table, slope_lines, study_error, study_file,
    CaseArgs, Target,
};
use crate::artifacts::Made;
use crate::error::AppError;
use crate::plot::{Corner, Plot};
use crate::progress::Progress;
use crate::ranges;
use crate::threads::with_threads;
use clap::Args;
use integrators::Solver;
use scenarios::studies::{self, Convergence, StudyCase};

/// Options of `converge`.
#[derive(Args, Debug)]
pub struct ConvergeArgs {
    /// The problem.
    #[command(flatten)]
    pub case: CaseArgs,
    /// Solvers, comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "rk4,dopri5,implicit-euler"
    )]
    pub solvers: Vec<Solver>,
    /// Step sizes of rk4, dopri5 and implicit-euler (fixed steps), coarse to fine.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "0.02,0.01,0.005,0.0025"
    )]
    pub dt_list: Vec<f64>,
    /// Tolerances of diffsol's adaptive methods, loose to tight.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "1e-4,1e-6,1e-8"
    )]
    pub tol_list: Vec<f64>,
}

/// Computes a convergence study and adds its files (`converge.csv`, `converge.json`,
/// `converge.png`/`.svg`) under `dir` with file stem `stem`.
pub fn add_convergence(
    t: &mut Target,
    stem: &str,
    case: &dyn StudyCase,
    solvers: &[Solver],
    steps: &[f64],
    tols: &[f64],
) -> Result<Convergence, AppError> {
    let (dir, threads) = (t.dir, t.threads);
    distinct(solvers)?;
    ranges::DT.list("dt-list", steps)?;
    ranges::RTOL.list("tol-list", tols)?;
    let jobs = solvers
        .iter()
        .map(|&s| studies::steps_for(s, steps, tols, true).len())
        .sum();
    let b = Progress::runs(jobs, "converge");
    let c = with_threads(threads, || {
        studies::convergence(case, solvers, steps, tols, &|| b.inc())
    })?
    .map_err(study_error)?;
    b.finish();
    let csv = dir.join(format!("{stem}.csv"));
    t.files.add(csv.clone(), runs_table(&c.runs, &csv)?);
    t.files
        .add_json(dir.join(format!("{stem}.json")), &study_file(case, &c))?;
    // Step sizes and tolerances are different things: one panel each.
    let panel = |step: &str, x_label: &str, slopes: &[f64]| {
        let mut series = per_solver_series(
            &c.runs,
            |r| r.step == step,
            |r| r.resolution,
            |r| r.errors.grid_max,
        );
        series.extend(slope_lines(&series, slopes));
        Plot {
            title: format!("Convergence ({step} steps): {}", case.describe()),
            x_label: x_label.into(),
            y_label: "max error on the time grid".into(),
            series,
            legend: Corner::default(),
            log: true,
        }
    };
    let panels: Vec<Plot> = [
        panel("fixed", "step size h (s)", &[1.0, 4.0, 5.0]),
        panel("adaptive", "tolerance (rtol = atol)", &[1.0]),
    ]
    .into_iter()
    .filter(|p| !p.series.is_empty())
    .collect();
    t.files.add_panels(&dir.join(stem), &panels)?;
    Ok(c)
}

/// Runs `converge`; its files in memory.
pub fn converge(a: &ConvergeArgs) -> Result<Made, AppError> {
    a.case.make(|t, case| {
        let c = add_convergence(t, "converge", case, &a.solvers, &a.dt_list, &a.tol_list)?;
        let orders = c.orders.iter().map(|o| {
            // No slope: say why (docs/studies.md, "Observed orders").
            let slope = match o.fitted_slope {
                Some(s) => format!("{s:.3}"),
                None => format!("- ({})", o.unfitted().unwrap_or_default()),
            };
            format!("{:15} {:16} fitted slope {slope}", o.solver, o.measure)
        });
        Ok(orders.chain(failures(&c.runs, "converge.csv")).collect())
    })
}
