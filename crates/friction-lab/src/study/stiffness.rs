//! The stiffness sweep: the cost to reach a target error across a stiffness parameter, and
//! where the implicit solvers overtake the explicit ones ([`scenarios::studies::stiffness`]).

use super::draw::row_at_top;
use super::tables::resolution_cells;
use super::{check_lists, positive_list, study_file, target_list, Study, StudyFiles};
use crate::error::AppError;
use crate::output::{Cell, Table};
use crate::plot::{Corner, Marker, Plot, Series, PALETTE};
use scenarios::studies::{self, Method, Reached, Stiffness, StudyCase, Sweep};

/// The most values a sweep takes.
const MAX_VALUES: usize = 50;

/// Every method of `methods` on `case` (the studied ones and their peers), at each value of the swept
/// parameter: the least work that reaches the sweep's target error, over the step sizes
/// `steps` (fixed-step methods) or the tolerances `tols`.
pub struct StiffnessStudy<'a> {
    /// The problem.
    pub case: &'a dyn StudyCase,
    /// The parameter, its values and the target error.
    pub sweep: Sweep<'a>,
    /// The methods, each solver once among the studied ones.
    pub methods: &'a [Method],
    /// Step sizes, coarse to fine.
    pub steps: &'a [f64],
    /// Tolerances, loose to tight.
    pub tols: &'a [f64],
}

impl Study for StiffnessStudy<'_> {
    type Result = Stiffness;

    fn name(&self) -> &'static str {
        "stiffness"
    }

    fn check(&self) -> Result<(), AppError> {
        let values = self.sweep.values;
        positive_list("values", values)?;
        target_list("target", &[self.sweep.target])?;
        check_lists(self.methods, self.steps, self.tols)?;
        if values.len() > MAX_VALUES {
            return Err(AppError::Invalid(crate::error::Invalid {
                field: "values",
                value: format!("{} values", values.len()),
                allowed: format!("1 to {MAX_VALUES}"),
                list: true,
            }));
        }
        Ok(())
    }

    fn runs(&self) -> usize {
        Method::jobs(self.methods, self.steps, self.tols, false).len() * self.sweep.values.len()
    }

    /// No method met the target at any value: no cost was measured, no kind wins anywhere.
    fn failure(&self, s: &Stiffness) -> Option<AppError> {
        if s.points.iter().any(|p| p.decided()) {
            return None;
        }
        Some(AppError::StudyRun(format!(
            "stiffness: no method reached the target {} at any of the {} values of `{}`, \
             nothing was measured (the study's files give each method's closest error, or why \
             its runs failed)",
            friction_models::params::show(s.target),
            s.points.len(),
            s.parameter
        )))
    }

    fn run(&self, progress: &(dyn Fn() + Sync)) -> Result<Stiffness, AppError> {
        studies::stiffness(
            self.case,
            Sweep { ..self.sweep },
            self.methods,
            self.steps,
            self.tols,
            progress,
        )
        .map_err(AppError::from)
    }

    /// `{stem}.csv` (a row per value and method), `{stem}.json` and `{stem}.png`/`.svg`.
    fn write(&self, s: &Stiffness, out: &mut StudyFiles) -> Result<(), AppError> {
        let (case, methods) = (self.case, self.methods);
        let Sweep {
            parameter, target, ..
        } = self.sweep;
        let mut table = Table::new(&[
            "value",
            "solver",
            "implicit",
            "reached",
            "h",
            "tol",
            "error",
            "rhs_evals",
            "jacobian_evals",
            "lu_factorizations",
            "linear_solves",
            "work_estimate",
            "work_low",
            "work_high",
            "winner",
        ]);
        for p in &s.points {
            for c in &p.costs {
                // Numeric columns hold numbers or nothing: `reached` says why they are empty.
                let r = c.reached.as_ref();
                let [h, tol] = resolution_cells(r.map(|r| r.step), r.map(|r| r.resolution));
                let count =
                    |n: fn(&Reached) -> usize| r.map_or(Cell::empty(), |r| Cell::Num(n(r) as f64));
                table.rows.push(vec![
                    Cell::Num(p.value),
                    Cell::Text(c.solver.clone()),
                    Cell::Text(c.implicit.to_string()),
                    Cell::Text(r.is_some().to_string()),
                    h,
                    tol,
                    r.map_or(Cell::empty(), |r| Cell::num(r.error)),
                    count(|r| r.stats.rhs_evals),
                    count(|r| r.stats.jacobian_evals),
                    count(|r| r.stats.lu_factorizations),
                    count(|r| r.stats.linear_solves),
                    r.map_or(Cell::empty(), |r| Cell::Num(r.work_estimate)),
                    r.and_then(|r| r.work_bracket[0])
                        .map_or(Cell::empty(), Cell::Num),
                    r.and_then(|r| r.work_bracket[1])
                        .map_or(Cell::empty(), Cell::Num),
                    Cell::Text(p.winner.map_or("", |w| w.name()).into()),
                ]);
            }
        }
        let csv = out.path(".csv");
        out.files.add_table(csv.clone(), table)?;
        out.add_json(&study_file(case, methods, s))?;
        // A solver that met the target at a value: a dot at its interpolated cost and a bar
        // over the bracket its resolutions leave; one that did not: a cross at the top of the
        // plot, named, each such solver in a row of its own.
        let largest = (s.points.iter())
            .flat_map(|p| p.costs.iter().filter_map(|c| c.reached.as_ref()))
            .map(|r| r.work_bracket[1].unwrap_or(r.work_estimate))
            .fold(1.0, f64::max);
        let mut series = Vec::new();
        let mut rows = 0;
        for (method, &color) in methods.iter().zip(PALETTE.iter().cycle()) {
            let label = method.label();
            let costs = || {
                s.points
                    .iter()
                    .filter_map(|p| Some((p.value, p.costs.iter().find(|c| c.solver == label)?)))
            };
            let met: Vec<(f64, f64)> = costs()
                .filter_map(|(v, c)| Some((v, c.reached.as_ref()?.work_estimate)))
                .collect();
            for (v, r) in costs().filter_map(|(v, c)| Some((v, c.reached.as_ref()?))) {
                let [lo, hi] = r.work_bracket;
                series.push(Series {
                    label: None,
                    points: vec![
                        (v, lo.unwrap_or(r.work_estimate)),
                        (v, hi.unwrap_or(r.work_estimate)),
                    ],
                    color,
                    width: 1,
                    marker: Marker::None,
                    dash: crate::plot::Dash::Solid,
                });
            }
            let top = row_at_top(largest, rows);
            let missed: Vec<(f64, f64)> = costs()
                .filter(|(_, c)| c.reached.is_none())
                .map(|(v, _)| (v, top))
                .collect();
            if !met.is_empty() {
                series.push(Series {
                    label: Some(label.clone()),
                    points: met,
                    color,
                    width: 2,
                    marker: Marker::Dot,
                    dash: crate::plot::Dash::Solid,
                });
            }
            if !missed.is_empty() {
                rows += 1;
                series.push(Series {
                    label: Some(format!(
                        "{label}: target not reached at {} value(s) (at the top)",
                        missed.len()
                    )),
                    points: missed,
                    color,
                    width: 0,
                    marker: Marker::Cross,
                    dash: crate::plot::Dash::Solid,
                });
            }
        }
        let plot = Plot {
            title: format!(
                "Cost to reach error {target:e} against {parameter}: {}",
                studies::describe(case, methods)
            ),
            x_label: parameter.to_string(),
            y_label: "work at the target (f evaluations, weighted)".into(),
            series,
            legend: Corner::UpperRight,
            log: true,
        };
        out.files.add_plot(&out.path(""), &plot)
    }
}
