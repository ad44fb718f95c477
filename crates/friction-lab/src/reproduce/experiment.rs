//! The paper's experiment (its section 3): a 1 kg block pushed by 15 N from rest, for each of
//! the six models, against the closed forms of its asymptote (`paper-experiment.md`, and the
//! velocities in `figures/paper-experiment-velocity.*`).

use super::Part;
use crate::error::AppError;
use crate::output::{Cell, Table};
use crate::plot::{Corner, Marker, Plot, Series, PALETTE};
use crate::study::{conduct, Output, Study, StudyFiles};
use friction_models::FrictionParams;
use scenarios::paper::{experiment, Asymptote, ExperimentFailure, ExperimentRow};
use scenarios::Scenario;

/// The experiment at `friction`, on the `paper-block` rig's defaults.
pub struct ExperimentStudy {
    /// The friction parameters.
    pub friction: FrictionParams,
}

/// Each model's run: measured against its closed form, or the failure with the velocity it
/// reached.
pub type ExperimentRows = Vec<Result<ExperimentRow, ExperimentFailure>>;

impl Study for ExperimentStudy {
    type Result = ExperimentRows;

    fn name(&self) -> &'static str {
        "the paper's experiment"
    }

    fn runs(&self) -> usize {
        friction_models::ModelId::PAPER.len()
    }

    fn run(&self, progress: &(dyn Fn() + Sync)) -> Result<ExperimentRows, AppError> {
        let rows = experiment(&self.friction, &Scenario::PAPER_BLOCK.defaults())?;
        rows.iter().for_each(|_| progress());
        Ok(rows)
    }

    /// A model whose run failed in the solver: the others are measured, and the files say
    /// which failed and why (exit 1).
    fn failure(&self, rows: &ExperimentRows) -> Option<AppError> {
        let failed: Vec<&ExperimentFailure> =
            rows.iter().filter_map(|r| r.as_ref().err()).collect();
        let first = failed.first()?;
        let models: Vec<String> = failed.iter().map(|f| f.model.to_string()).collect();
        Some(AppError::StudyRun(format!(
            "the paper's experiment failed for {} (paper-experiment.md keeps the other models, \
             and the velocity each failed run reached); {}: {}",
            models.join(", "),
            first.model,
            first.why
        )))
    }

    /// `figures/paper-experiment-velocity.{csv,png,svg}` and `paper-experiment.md`.
    fn write(&self, rows: &ExperimentRows, out: &mut StudyFiles) -> Result<(), AppError> {
        let stem = out.dir.join("figures/paper-experiment-velocity");
        let mut table = Table::new(&["model", "t", "v"]);
        let mut series = Vec::new();
        for (row, color) in rows.iter().zip(PALETTE) {
            let (model, velocity, label) = match row {
                Ok(r) => (r.model, &r.velocity, r.model.name().to_string()),
                Err(f) => (f.model, &f.velocity, format!("{} (failed)", f.model)),
            };
            table.rows.extend(
                velocity.iter().map(|&(t, v)| {
                    vec![Cell::Text(model.name().into()), Cell::Num(t), Cell::Num(v)]
                }),
            );
            series.push(Series {
                label: Some(label),
                points: velocity.clone(),
                color,
                width: 2,
                marker: Marker::None,
                dash: crate::plot::Dash::Solid,
            });
        }
        let csv = stem.with_extension("csv");
        out.files.add_table(csv.clone(), table)?;
        let p = Plot {
            title: "The paper's experiment: 1 kg pushed by 15 N from rest".into(),
            x_label: "time t (s)".into(),
            y_label: "velocity v (m/s)".into(),
            series,
            legend: Corner::default(),
            log: false,
        };
        out.files.add_plot(&stem, &p)?;
        out.files.add(
            out.path(".md"),
            format!("# The paper's experiment\n\n## {HEADING}\n\n{}", text(rows)).into_bytes(),
        );
        Ok(())
    }
}

/// The heading of the experiment's section.
const HEADING: &str = "The paper's experiment (section 3)";

/// What the experiment did, its figure, and each model's asymptote against the closed form.
fn text(rows: &ExperimentRows) -> String {
    let mut md = String::from(
        "A 1 kg block pushed by F_ex = 15 N from rest \
         (`paper-block`), Table 1 parameters, Dormand-Prince with rtol = atol = 1e-12 and event \
         switching. Once the Stribeck term has died out and the Dahl state has saturated, the \
         friction force is a constant level plus mu_v*v: a model with a viscous term tends to \
         v_t = (F_ex - level)/mu_v, one without accelerates at a = (F_ex - level)/m (and a \
         push that does not exceed the level, or the break-away at rest, leaves the block at \
         rest).\n\n\
         ![velocity](figures/paper-experiment-velocity.png)\n\n\
         | model | closed form | simulated | relative error | v(5 s) (m/s) | x(5 s) (m) |\n|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let r = match r {
            Ok(r) => r,
            Err(f) => {
                md += &format!("| {} | failed: {} | | | | |\n", f.model, f.why);
                continue;
            }
        };
        let closed = match r.predicted {
            Asymptote::TerminalVelocity(v) => format!("v_t = {v} m/s"),
            Asymptote::Acceleration(a) => format!("a = {a} m/s^2"),
            Asymptote::Rest => "at rest (v = 0)".to_string(),
        };
        md += &format!(
            "| {} | {closed} | {:.9} | {:.1e} | {:.4} | {:.4} |\n",
            r.model, r.measured, r.relative_error, r.v_at_5s, r.x_at_5s
        );
    }
    md
}

/// The report's section on the experiment.
pub struct Experiment {
    /// The friction parameters.
    pub friction: FrictionParams,
}

impl Part for Experiment {
    fn heading(&self) -> String {
        HEADING.into()
    }

    fn conduct(&self, target: &mut Output) -> Result<String, AppError> {
        let study = ExperimentStudy {
            friction: self.friction,
        };
        let rows = conduct(&study, target, "paper-experiment")?;
        match target.failure.take() {
            Some(failure) => Err(failure),
            None => Ok(text(&rows)),
        }
    }
}
