//! The convergence study: observed orders of every solver against a reference
//! ([`scenarios::studies::convergence`]), one panel for fixed steps and one for tolerances,
//! each fit drawn through its asymptotic range.

use super::draw::{fitted_guides, per_solver_series};
use super::tables::runs_table;
use super::{check_lists, study_file, Study, StudyFiles};
use crate::error::AppError;
use crate::plot::{Corner, Plot};
use scenarios::studies::{
    self, Convergence, ErrorMeasure, Method, OrderTable, StepKind, StudyCase,
};

/// Every method of `methods` on `case` at the fixed step sizes `steps` (those that take fixed
/// steps) or at the tolerances `tols` (rtol = atol), against one reference.
pub struct ConvergenceStudy<'a> {
    /// The problem.
    pub case: &'a dyn StudyCase,
    /// The methods, each solver once.
    pub methods: &'a [Method],
    /// Step sizes, coarse to fine.
    pub steps: &'a [f64],
    /// Tolerances, loose to tight.
    pub tols: &'a [f64],
}

impl Study for ConvergenceStudy<'_> {
    type Result = Convergence;

    fn name(&self) -> &'static str {
        "converge"
    }

    fn check(&self) -> Result<(), AppError> {
        check_lists(self.methods, self.steps, self.tols)
    }

    fn runs(&self) -> usize {
        Method::jobs(self.methods, self.steps, self.tols, true).len()
    }

    fn run(&self, progress: &(dyn Fn() + Sync)) -> Result<Convergence, AppError> {
        studies::convergence(self.case, self.methods, self.steps, self.tols, progress)
            .map_err(AppError::from)
    }

    /// Every run failed: nothing to show ([`super::nothing_measured`]).
    fn failure(&self, c: &Convergence) -> Option<AppError> {
        super::nothing_measured("converge", &c.runs)
    }

    /// `{stem}.csv` (a row per run), `{stem}.json` and `{stem}.png`/`.svg`.
    fn write(&self, c: &Convergence, out: &mut StudyFiles) -> Result<(), AppError> {
        let case = self.case;
        let csv = out.path(".csv");
        out.files.add_table(csv.clone(), runs_table(&c.runs))?;
        out.add_json(&study_file(case, self.methods, c))?;
        // Step sizes and tolerances are different things: one panel each, each fitted slope
        // drawn through the asymptotic range it rests on.
        let panel = |step: StepKind, x_label: &str| {
            let mut series = per_solver_series(
                &c.runs,
                |r| r.step == step,
                |r| r.resolution,
                |r| r.errors.grid_relative,
            );
            let tables: Vec<&OrderTable> = (c.orders.iter())
                .filter(|t| t.step == step && t.measure == ErrorMeasure::GridRelative)
                .collect();
            series.extend(fitted_guides(&tables));
            Plot {
                title: format!(
                    "Convergence ({} steps): {}",
                    step.name(),
                    studies::describe(case, self.methods)
                ),
                x_label: x_label.into(),
                y_label: ErrorMeasure::GridRelative.label().into(),
                series,
                legend: Corner::default(),
                log: true,
            }
        };
        let panels: Vec<Plot> = [
            panel(StepKind::Fixed, "step size h (s)"),
            panel(StepKind::Adaptive, "tolerance (rtol = atol)"),
        ]
        .into_iter()
        .filter(|p| !p.series.is_empty())
        .collect();
        out.files.add_panels(&out.path(""), &panels)
    }
}
