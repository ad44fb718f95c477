//! Cost against size: every method at one resolution on cases of growing size (the chain
//! study of `reproduce`).

use super::tables::resolution_cells;
use super::{CaseRecord, Study, StudyFiles};
use crate::error::AppError;
use crate::output::{Cell, Table};
use crate::plot::{Corner, Marker, Plot, Series, PALETTE};
use integrators::StepControl;
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

/// Every method of `methods` at its one resolution on each case of `cases`, each case with its
/// number of bodies: steps, work, work per step and its fitted exponent in N, and wall times.
pub struct ScalingStudy<'a> {
    /// The cases, each with its number of bodies, smallest first.
    pub cases: &'a [(usize, Box<dyn StudyCase>)],
    /// The methods, each at one step size or tolerance.
    pub methods: &'a [(Method, StepControl)],
}

impl Study for ScalingStudy<'_> {
    type Result = studies::Scaling;

    fn name(&self) -> &'static str {
        "cost against size"
    }

    /// Each method on each case twice: once for its statistics, on the pool, and once more
    /// for its wall time, one run after another.
    fn runs(&self) -> usize {
        2 * self.cases.len() * self.methods.len()
    }

    fn run(&self, progress: &(dyn Fn() + Sync)) -> Result<studies::Scaling, AppError> {
        studies::scaling(self.cases, self.methods, progress).map_err(AppError::from)
    }

    /// Every run failed: no cost was measured.
    fn failure(&self, s: &studies::Scaling) -> Option<AppError> {
        let first = s.runs.first()?;
        let why = first.failure.as_ref()?;
        s.runs.iter().all(|r| r.failure.is_some()).then(|| {
            AppError::StudyRun(format!(
                "{}: every run failed ({n} of {n}), nothing was measured; the first, {} on {} \
                 bodies: {why}",
                self.name(),
                first.solver,
                first.size,
                n = s.runs.len()
            ))
        })
    }

    /// The runs (`{stem}.csv`, `{stem}.json`: steps, work, work per step and its fitted
    /// exponent in N), and their wall times (`{stem}-timing.csv`) with wall time per step
    /// against the number of bodies on log–log axes (`{stem}-timing.png`, `.svg`): the files
    /// that vary between runs.
    fn write(&self, s: &studies::Scaling, out: &mut StudyFiles) -> Result<(), AppError> {
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
                Cell::Text(r.failure.as_ref().map_or("ok".into(), |e| e.to_string())),
            ]);
            timing.rows.push(vec![
                Cell::Num(r.size as f64),
                Cell::Text(r.solver.clone()),
                h,
                tol,
                Cell::Num(r.wall_time_s),
            ]);
        }
        let csv = out.path(".csv");
        out.files.add_table(csv.clone(), table)?;
        let timing_csv = out.path("-timing.csv");
        out.files.add_table(timing_csv.clone(), timing)?;
        let methods: Vec<Method> = self.methods.iter().map(|&(m, _)| m).collect();
        let file = ScalingFile {
            cases: self
                .cases
                .iter()
                .map(|(bodies, case)| SizedCase {
                    bodies: *bodies,
                    case: CaseRecord::of(case.as_ref(), &methods),
                })
                .collect(),
            study: s,
        };
        out.add_json(&file)?;
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
                dash: crate::plot::Dash::Solid,
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
        out.files.add_plot(&out.path("-timing"), &plot)
    }
}

#[cfg(test)]
mod tests {
    use super::{ScalingStudy, Study};
    use integrators::{SolverError, Stats};
    use scenarios::studies::{Scaling, ScalingRun, StepKind};

    fn run(size: usize, failure: Option<SolverError>) -> ScalingRun {
        ScalingRun {
            size,
            solver: "dopri5".into(),
            resolution: 1e-6,
            step: StepKind::Adaptive,
            stats: Stats::default(),
            work: 0,
            work_per_step: f64::NAN,
            failure,
            wall_time_s: 0.0,
        }
    }

    #[test]
    fn a_study_whose_every_run_failed_has_measured_nothing() {
        let study = ScalingStudy {
            cases: &[],
            methods: &[],
        };
        let cap = |t| SolverError::TooManySteps {
            t,
            h: 1e-3,
            max: 10,
        };
        let all_failed = Scaling {
            runs: vec![run(10, Some(cap(0.5))), run(100, Some(cap(0.25)))],
            exponents: Vec::new(),
        };
        let e = study.failure(&all_failed).expect("nothing was measured");
        assert_eq!(e.kind(), crate::error::ErrorKind::Failed);
        assert_eq!(
            e.to_string(),
            format!(
                "cost against size: every run failed (2 of 2), nothing was measured; the \
                 first, dopri5 on 10 bodies: {}",
                cap(0.5)
            )
        );
        let one_ran = Scaling {
            runs: vec![run(10, Some(cap(0.5))), run(100, None)],
            exponents: Vec::new(),
        };
        assert!(study.failure(&one_ran).is_none());
    }
}
