//! Cost against size: every method at one resolution on cases of growing size (the chain
//! study of `reproduce`).

use super::{resolution_cells, study_error, CaseRecord, Target};
use crate::error::AppError;
use crate::output::{Cell, Table};
use crate::plot::{Corner, Marker, Plot, Series, PALETTE};
use crate::progress::Progress;
use crate::threads::with_threads;
use scenarios::studies::{self, Method, StudyCase};
use serde::Serialize;

/// A cost-against-size study's JSON: the case at each size, beside the study's own fields.
#[derive(Serialize)]
struct ScalingFile<'a> {
    cases: Vec<SizedCase>,
    #[serde(flatten)]
    study: &'a studies::Scaling,
}

/// One size of a cost-against-size study and its case.
#[derive(Serialize)]
struct SizedCase {
    bodies: usize,
    #[serde(flatten)]
    case: CaseRecord,
}

/// Computes a cost-against-size study (every method at one resolution on each case) and adds
/// its files under `dir` with stem `stem`: the runs (CSV, JSON: steps, work, work per step
/// and its fitted exponent in N), and their wall times (`-timing.csv`) with wall time per step
/// against the number of bodies on log–log axes (`-timing.png`, `.svg`): the files that vary
/// between runs.
pub fn add_scaling(
    t: &mut Target,
    stem: &str,
    cases: &[(usize, Box<dyn StudyCase>)],
    methods: &[(Method, integrators::StepControl)],
) -> Result<studies::Scaling, AppError> {
    let (dir, threads) = (t.dir, t.threads);
    let b = Progress::runs(2 * cases.len() * methods.len(), "cost against size");
    let s = with_threads(threads, || studies::scaling(cases, methods, &|| b.inc()))?
        .map_err(study_error)?;
    b.finish();
    let mut table = Table::new(&[
        "bodies",
        "solver",
        "h",
        "tol",
        "steps",
        "work",
        "work_per_step",
        "rhs_evals",
        "jacobian_evals",
        "lu_factorizations",
        "events",
        "status",
    ]);
    let mut timing = Table::new(&["bodies", "solver", "h", "tol", "wall_time_s"]);
    for r in &s.runs {
        let [h, tol] = resolution_cells(Some(r.step), Some(r.resolution));
        table.rows.push(vec![
            Cell::Num(r.size as f64),
            Cell::Text(r.solver.clone()),
            h.clone(),
            tol.clone(),
            Cell::Num(r.stats.steps as f64),
            Cell::Num(r.work as f64),
            Cell::Num(r.work_per_step),
            Cell::Num(r.stats.rhs_evals as f64),
            Cell::Num(r.stats.jacobian_evals as f64),
            Cell::Num(r.stats.lu_factorizations as f64),
            Cell::Num(r.stats.events as f64),
            Cell::Text(r.failure.clone().unwrap_or_else(|| "ok".into())),
        ]);
        timing.rows.push(vec![
            Cell::Num(r.size as f64),
            Cell::Text(r.solver.clone()),
            h,
            tol,
            Cell::Num(r.wall_time_s),
        ]);
    }
    let csv = dir.join(format!("{stem}.csv"));
    t.files.add(csv.clone(), table.to_csv(&csv)?);
    let timing_csv = dir.join(format!("{stem}-timing.csv"));
    t.files.add(timing_csv.clone(), timing.to_csv(&timing_csv)?);
    let file = ScalingFile {
        cases: cases
            .iter()
            .map(|(bodies, case)| SizedCase {
                bodies: *bodies,
                case: CaseRecord::of(case.as_ref()),
            })
            .collect(),
        study: &s,
    };
    t.files.add_json(dir.join(format!("{stem}.json")), &file)?;
    // Wall time per step against N, with each method's fitted slope: the one figure of the
    // study that varies between runs (hence `-timing`).
    let mut series = Vec::new();
    for ((label, _), &color) in s.exponents.iter().zip(PALETTE.iter().cycle()) {
        let points: Vec<(f64, f64)> = s
            .runs
            .iter()
            .filter(|r| &r.solver == label && r.failure.is_none() && r.stats.steps > 0)
            .map(|r| (r.size as f64, r.wall_time_s / r.stats.steps as f64))
            .collect();
        let logs: Vec<(f64, f64)> = points.iter().map(|p| (p.0.ln(), p.1.ln())).collect();
        series.push(Series {
            label: Some(format!("{label} (slope {:.2})", studies::slope(&logs))),
            points,
            color,
            width: 2,
            marker: Marker::Dot,
        });
    }
    let plot = Plot {
        title: "Wall time per step against the number of bodies".into(),
        x_label: "bodies".into(),
        y_label: "wall time per step (s)".into(),
        series,
        legend: Corner::UpperLeft,
        log: true,
    };
    t.files
        .add_plot(&dir.join(format!("{stem}-timing")), &plot)?;
    Ok(s)
}
