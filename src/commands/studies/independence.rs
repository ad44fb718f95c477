//! `independence`: one solver at a ladder of resolutions, with a Richardson estimate of the
//! error left and a verdict.

use super::{resolution_cells, study_error, study_file, CaseArgs, Refinement, Target};
use crate::artifacts::Made;
use crate::error::AppError;
use crate::output::{Cell, Table};
use crate::plot::{Corner, Marker, Plot, Series, PALETTE};
use crate::progress::Progress;
use crate::ranges;
use crate::threads::with_threads;
use crate::warnings::diverged_line;
use clap::Args;
use integrators::Solver;
use scenarios::studies::{self, Independence, StudyCase};

/// Options of `independence`.
#[derive(Args, Debug)]
pub struct IndependenceArgs {
    /// The problem.
    #[command(flatten)]
    pub case: CaseArgs,
    /// The solver.
    #[arg(long, value_name = "SOLVER", default_value = "rk4")]
    pub solver: Solver,
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

/// Computes an independence study and adds its files under `dir` with stem `stem`.
pub fn add_independence(
    t: &mut Target,
    stem: &str,
    case: &dyn StudyCase,
    solver: Solver,
    r: Refinement,
) -> Result<Independence, AppError> {
    let (dir, threads) = (t.dir, t.threads);
    let Refinement {
        start,
        ratio,
        levels,
        tol,
    } = r;
    if !(0.0..=1.0).contains(&tol) || tol == 0.0 {
        return Err(AppError::Usage(format!(
            "option `tol` = {tol} is out of range: allowed (0, 1]"
        )));
    }
    if !(ratio.is_finite() && ratio > 1.0 && ratio <= 1e3) {
        return Err(AppError::Usage(format!(
            "option `ratio` = {ratio} is out of range: allowed (1, 1000]"
        )));
    }
    if !(2..=12).contains(&levels) {
        return Err(AppError::Usage(format!(
            "option `levels` = {levels} is out of range: allowed [2, 12]"
        )));
    }
    let levels = levels as usize;
    // Every level is a step size (fixed-step solvers) or a tolerance, in that option's range.
    let resolution = if solver.is_fixed_step() || case.switching().is_time_stepping() {
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
                "option `start` = {} (finest level {finest:e}) is out of range for {}: every \
             level must lie in {} (the range of --{})",
                ranges::show(start),
                solver.name(),
                resolution.range,
                resolution.name
            ))
        })?;
    let b = Progress::runs(levels, "independence");
    let s = with_threads(threads, || {
        studies::independence(case, solver, start, ratio, levels, tol, &|| b.inc())
    })?
    .map_err(study_error)?;
    b.finish();
    if let Some(f) = s.failed.first() {
        t.failure.get_or_insert(AppError::StudyRun(format!(
            "{} of {levels} levels of the independence study failed, the first at level {} \
             ({:e}): {}; levels {} to {} are judged",
            s.failed.len(),
            f.level,
            f.resolution,
            f.failure,
            s.first_level,
            s.first_level + s.resolutions.len() - 1
        )));
    }
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
                    Cell::Text(String::new())
                } else {
                    Cell::Num(o.differences[i - 1])
                },
                if i + 1 == o.values.len() && o.remaining_error.is_finite() {
                    Cell::Num(o.remaining_error)
                } else {
                    Cell::Text(String::new())
                },
                Cell::Text(o.independent.to_string()),
            ]);
        }
    }
    let csv = dir.join(format!("{stem}.csv"));
    t.files.add(csv.clone(), table.to_csv(&csv)?);
    t.files
        .add_json(dir.join(format!("{stem}.json")), &study_file(case, &s))?;
    let series = s
        .trajectories
        .iter()
        .zip(&s.resolutions)
        .zip(PALETTE.iter().cycle())
        .map(|((xs, h), &color)| Series {
            label: Some(format!("{} at {h:e}", s.solver)),
            points: xs
                .iter()
                .enumerate()
                .map(|(i, &x)| (case.t_end() * i as f64 / (xs.len().max(2) - 1) as f64, x))
                .collect(),
            color,
            width: 2,
            marker: Marker::None,
        })
        .collect();
    let plot = Plot {
        title: format!(
            "Independence: {}: {}",
            case.describe(),
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
    t.files.add_plot(&dir.join(stem), &plot)?;
    Ok(s)
}

/// Runs `independence`; its files in memory.
pub fn independence(a: &IndependenceArgs) -> Result<Made, AppError> {
    a.case.make(|t, case| {
        let r = Refinement {
            start: a.start,
            ratio: a.ratio,
            levels: a.levels,
            tol: a.tol,
        };
        let s = add_independence(t, "independence", case, a.solver, r)?;
        let mut notes: Vec<String> = s
            .outputs
            .iter()
            .map(|o| {
                let verdict = if o.independent {
                    "independent"
                } else {
                    "NOT independent"
                };
                format!(
                    "{:24} remaining error {:.3e} {verdict}",
                    o.name, o.remaining_error
                )
            })
            .collect();
        let verdict = if s.independent {
            "independent of"
        } else {
            "not independent of"
        };
        notes.extend(s.failed.iter().map(|f| {
            format!(
                "level {} ({:e}) failed, not judged: {}",
                f.level, f.resolution, f.failure
            )
        }));
        if s.failed.iter().any(|f| f.diverged) {
            notes.push(diverged_line("--start"));
        }
        notes.push(format!("verdict: {verdict} the step size"));
        Ok(notes)
    })
}
