//! The tables the studies share: one row per run, and the columns of a resolution.

use crate::output::{Cell, Table};
use scenarios::studies::{ErrorMeasure, StepKind, StudyRun, WallTimes};

/// The columns `h` and `tol` of a run with `resolution` of kind `step` (a step size or a
/// tolerance): the one that applies, the other empty, so that each column holds one quantity.
pub fn resolution_cells(step: Option<StepKind>, resolution: Option<f64>) -> [Cell; 2] {
    match (step, resolution) {
        (Some(StepKind::Fixed), Some(h)) => [Cell::Num(h), Cell::empty()],
        (Some(_), Some(tol)) => [Cell::empty(), Cell::Num(tol)],
        _ => [Cell::empty(), Cell::empty()],
    }
}

/// One CSV row per run: solver, step size or tolerance, the errors, the work.
pub fn runs_table(runs: &[StudyRun]) -> Table {
    let errors = ErrorMeasure::ALL.map(|m| format!("error_{}", m.name()));
    let header: Vec<&str> = ["solver", "step", "h", "tol", "work"]
        .into_iter()
        .chain(errors.iter().map(String::as_str))
        .chain([
            "steps",
            "rejected",
            "rhs_evals",
            "jacobian_evals",
            "lu_factorizations",
            "linear_solves",
            "newton_iterations",
            "events",
            "status",
            "reason",
        ])
        .collect();
    let mut t = Table::new(&header);
    for r in runs {
        // A missing measure (no events to compare) is written as an empty cell, never NaN.
        let num = Cell::num;
        let s = r.stats;
        let [h, tol] = resolution_cells(Some(r.step), Some(r.resolution));
        let mut row = vec![
            Cell::Text(r.solver.clone()),
            Cell::Text(r.step.name().into()),
            h,
            tol,
            Cell::Num(r.work as f64),
        ];
        row.extend(ErrorMeasure::ALL.map(|m| num(m.of(&r.errors))));
        row.extend([
            Cell::Num(s.steps as f64),
            Cell::Num(s.rejected() as f64),
            Cell::Num(s.rhs_evals as f64),
            Cell::Num(s.jacobian_evals as f64),
            Cell::Num(s.lu_factorizations as f64),
            Cell::Num(s.linear_solves as f64),
            Cell::Num(s.newton_iterations as f64),
            Cell::Num(s.events as f64),
            Cell::Text(r.verdict.status.name().into()),
            Cell::Text(r.verdict.reason.clone().unwrap_or_default()),
        ]);
        t.rows.push(row);
    }
    t
}

/// The wall times of a study's runs over their repeats, one row per run: its cells under
/// `keys` (the method and its resolution), then how many timings were taken and their
/// median, extremes and quartiles, s (they vary between runs: kept apart from the study's
/// other files).
pub fn timing_table(
    keys: &[&str],
    rows: impl IntoIterator<Item = (Vec<Cell>, WallTimes)>,
) -> Table {
    let header: Vec<&str> = keys
        .iter()
        .copied()
        .chain([
            "repeats",
            "wall_time_median_s",
            "wall_time_min_s",
            "wall_time_q1_s",
            "wall_time_q3_s",
            "wall_time_max_s",
        ])
        .collect();
    let mut table = Table::new(&header);
    for (mut row, t) in rows {
        row.extend([t.repeats as f64, t.median, t.min, t.q1, t.q3, t.max].map(Cell::Num));
        table.rows.push(row);
    }
    table
}
