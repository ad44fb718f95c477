//! A solver study written outside friction-lab, conducted like a built-in one; registered
//! (`NamedStudy::register`), it is a command of its own, found by its name as the built-in
//! studies are.
//!
//! The step-count study: an adaptive method whose error estimate is of order q (local error
//! O(h^(q+1))) keeps that error near the tolerance with steps h ∝ tol^(1/(q+1)), so it takes
//! N ∝ tol^(−1/(q+1)) steps. The slope s of log N against log(1/tol) gives the order of the
//! estimate, q̂ = 1/s − 1: 4 for Dormand–Prince (its embedded fourth-order solution), 1 for
//! implicit Euler (its step-doubling estimate of a first-order method). Each run's error
//! against the closed form tells whether the tolerance is met.
//!
//! It implements the public `Study` trait: its runs, its typed result, its table, JSON and
//! figure. It joins a report as `reproduce`'s studies do: one [`Entry`] (the study, the stem of
//! its files, the line its result reads as) in a [`Section`] of a [`Report`], which checks it,
//! runs it on a pool of threads with a progress bar, and adds its files and `report.md`;
//! `Artifacts::write` puts them in a folder, all or nothing.
//!
//! Run: `cargo run --release --example own_study -- OUT_DIR`.

use friction_lab::error::AppError;
use friction_lab::friction_models::{FrictionParams, ModelId};
use friction_lab::friction_systems::Scheme;
use friction_lab::integrators::{Solver, StepControl};
use friction_lab::made::Made;
use friction_lab::output::{Cell, Table};
use friction_lab::plot::{Corner, Marker, Plot, Series, PALETTE};
use friction_lab::reproduce::{Report, Section};
use friction_lab::scenarios::studies::{slope, Case, StudyCase};
use friction_lab::scenarios::{Limits, Scenario, ScenarioError};
use friction_lab::study::solver_studies::{Declared, NamedStudy, Runs};
use friction_lab::study::{Entry, Study, StudyFiles};
use serde::Serialize;
use std::path::Path;

/// Every adaptive solver of `solvers` on `case` at each of its tolerances (rtol = atol, loose
/// to tight, in the range where its step count follows its asymptotic law).
pub struct StepCountStudy<'a> {
    /// The problem, with a closed form.
    pub case: &'a dyn StudyCase,
    /// Adaptive solvers, each with its tolerances.
    pub solvers: &'a [(Solver, &'a [f64])],
}

/// One run: its tolerance, its accepted steps and its error at the end.
#[derive(Clone, Debug, Serialize)]
pub struct StepCount {
    /// The solver.
    pub solver: &'static str,
    /// rtol = atol.
    pub tol: f64,
    /// Accepted steps.
    pub steps: usize,
    /// max |Δx|, |Δv| at the end against the closed form.
    pub error: f64,
}

/// The study's result: every run, and per solver the fitted slope of log N against
/// log(1/tol) with the order of the error estimate it implies.
#[derive(Clone, Debug, Serialize)]
pub struct StepCounts {
    /// Every run, solver by solver.
    pub runs: Vec<StepCount>,
    /// Per solver: (name, slope s, estimated order q̂ = 1/s − 1).
    pub orders: Vec<(&'static str, f64, f64)>,
}

impl Study for StepCountStudy<'_> {
    type Result = StepCounts;

    fn name(&self) -> &'static str {
        "step counts"
    }

    fn check(&self) -> Result<(), AppError> {
        if let Some((s, _)) = self.solvers.iter().find(|(s, _)| s.is_fixed_step()) {
            return Err(AppError::Usage(format!(
                "solver `{}` takes fixed steps: a step-count study needs adaptive solvers",
                s.name()
            )));
        }
        if self.case.closed_form().is_none() {
            return Err(AppError::Usage(format!(
                "{} has no closed form to measure the error against",
                self.case.describe()
            )));
        }
        Ok(())
    }

    fn runs(&self) -> usize {
        self.solvers.iter().map(|(_, tols)| tols.len()).sum()
    }

    fn run(&self, progress: &(dyn Fn() + Sync)) -> Result<StepCounts, AppError> {
        let (_, exact) = self.case.closed_form().expect("checked");
        let mut runs = Vec::new();
        for &(solver, tols) in self.solvers {
            for &tol in tols {
                let step = StepControl::Adaptive {
                    rtol: tol,
                    atol: tol,
                    h0: None,
                };
                let m = self.case.measure(Scheme::events(solver), step)?;
                if let Some(error) = m.error {
                    return Err(ScenarioError::Solver {
                        what: format!("{} at tol {tol:e}", solver.name()),
                        error,
                    }
                    .into());
                }
                let error = m
                    .measures
                    .final_state
                    .iter()
                    .zip(&exact.final_state)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max);
                runs.push(StepCount {
                    solver: solver.name(),
                    tol,
                    steps: m.stats.steps,
                    error,
                });
                progress();
            }
        }
        let orders = self
            .solvers
            .iter()
            .map(|(s, _)| {
                let points: Vec<(f64, f64)> = runs
                    .iter()
                    .filter(|r| r.solver == s.name())
                    .map(|r| ((1.0 / r.tol).ln(), (r.steps as f64).ln()))
                    .collect();
                let s_fit = slope(&points);
                (s.name(), s_fit, 1.0 / s_fit - 1.0)
            })
            .collect();
        Ok(StepCounts { runs, orders })
    }

    /// `{stem}.csv` (a row per run), `{stem}.json`, and `{stem}.png`/`.svg`: steps against
    /// 1/tol on log–log axes, each solver labelled with its fitted slope and order.
    fn write(&self, r: &StepCounts, out: &mut StudyFiles) -> Result<(), AppError> {
        let mut table = Table::new(&["solver", "tol", "steps", "error_final_state"]);
        for run in &r.runs {
            table.rows.push(vec![
                Cell::Text(run.solver.into()),
                Cell::Num(run.tol),
                Cell::Num(run.steps as f64),
                Cell::num(run.error),
            ]);
        }
        let csv = out.path(".csv");
        out.files.add(csv.clone(), table.to_csv(&csv)?);
        out.files.add_json(out.path(".json"), r)?;
        let series = r
            .orders
            .iter()
            .zip(PALETTE.iter().cycle())
            .map(|(&(name, s, q), &color)| Series {
                label: Some(format!(
                    "{name}: slope {s:.3}, order of the estimate {q:.2}"
                )),
                points: r
                    .runs
                    .iter()
                    .filter(|run| run.solver == name)
                    .map(|run| (1.0 / run.tol, run.steps as f64))
                    .collect(),
                color,
                width: 2,
                marker: Marker::Dot,
                dash: friction_lab::plot::Dash::Solid,
            })
            .collect();
        let plot = Plot {
            title: format!(
                "Steps against tolerance: {} (event switching)",
                self.case.describe()
            ),
            x_label: "1/tol (rtol = atol)".into(),
            y_label: "accepted steps".into(),
            series,
            legend: Corner::UpperLeft,
            log: true,
        };
        out.files.add_plot(&out.path(""), &plot)
    }
}

/// What the example wrote, for the test that runs it.
pub struct Outcome {
    /// The files written, relative to the folder.
    pub files: Vec<String>,
    /// The report.
    pub report: String,
}

/// The study's line in the report: each solver's fitted order.
fn reads(counts: &StepCounts) -> String {
    let orders: Vec<String> = (counts.orders.iter())
        .map(|(name, _, q)| format!("{name} {q:.2}"))
        .collect();
    format!(
        "- [Steps against the tolerance](step-counts.png): the order of each error estimate, \
         from the slope of its step counts: {}.\n",
        orders.join(", ")
    )
}

/// The study as a command a front end names, once registered: `friction-lab step-counts
/// --out DIR [--t-end T]`.
#[derive(clap::Args, Debug)]
pub struct StepCountRequest {
    /// End time of the paper's block, s.
    #[arg(long, value_name = "T", default_value_t = 5.0)]
    pub t_end: f64,
}

impl Runs for StepCountRequest {
    fn run(&self, out: &Path) -> Result<Made, AppError> {
        made(out, self.t_end)
    }

    fn threads(&self) -> Option<i64> {
        None
    }
}

/// `step-counts`, registered with `NamedStudy::register(&STEP_COUNTS)`.
pub static STEP_COUNTS: Declared<StepCountRequest> = Declared::new(
    "step-counts",
    "Step counts of adaptive solvers against the tolerance",
);

/// Registers the study and runs `friction-lab step-counts --out DIR` through the command
/// line's own library calls, as a user's program built on it would: the study is found by its
/// name, as a built-in one is, and writes its files into `dir`.
pub fn by_name(dir: &Path) -> Result<(), AppError> {
    NamedStudy::register(&STEP_COUNTS).map_err(AppError::Usage)?;
    let words = [
        "friction-lab",
        "step-counts",
        "--out",
        &dir.display().to_string(),
    ]
    .map(String::from);
    let invocation =
        friction_lab_cli::parse_from(words).map_err(|e| AppError::Usage(e.to_string()))?;
    friction_lab_cli::invoke(invocation)
}

/// The paper's block pushed from rest against viscous friction (x, v in closed form) to
/// `t_end`, studied with Dormand–Prince from tol 1e-7 to 1e-12 (looser, it takes a dozen
/// steps, too few for the asymptotic law) and implicit Euler from 1e-3 to 1e-7: the study's
/// files and its report, in `dir`, in memory.
fn made(dir: &Path, t_end: f64) -> Result<Made, AppError> {
    let case = Case {
        scenario: Scenario::PAPER_BLOCK,
        law: ModelId::Viscous.into(),
        friction: FrictionParams::paper(),
        params: Scenario::PAPER_BLOCK.defaults(),
        t_end,
        limits: Limits::default(),
    };
    let study = StepCountStudy {
        case: &case,
        solvers: &[
            (Solver::DOPRI5, &[1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12]),
            (Solver::IMPLICIT_EULER, &[1e-3, 1e-4, 1e-5, 1e-6, 1e-7]),
        ],
    };
    let entry = Entry {
        stem: "step-counts",
        study,
        reads,
    };
    let section = Section {
        heading: "Step counts against the tolerance".into(),
        folder: "",
        intro: format!(
            "{} (event switching), adaptive solvers, rtol = atol.\n\n",
            case.describe()
        ),
        entries: vec![&entry],
    };
    let report = Report {
        title: "# Step counts of adaptive solvers".into(),
        preface: String::new(),
        parts: vec![&section],
    };
    report.conduct(dir, None)
}

/// The study of [`made`] to 5 s, written into `dir` with its report.
pub fn run(dir: &Path) -> Result<Outcome, AppError> {
    let made = made(dir, 5.0)?;
    if let Some(failure) = made.failure {
        return Err(failure);
    }
    let written = made.files.write(dir)?;
    let mut files: Vec<String> = written
        .files
        .iter()
        .map(|p| p.strip_prefix(dir).unwrap_or(p).display().to_string())
        .collect();
    files.sort();
    let report = std::fs::read_to_string(dir.join("report.md")).map_err(|source| AppError::Io {
        path: dir.join("report.md"),
        source,
    })?;
    Ok(Outcome { files, report })
}

fn main() {
    let dir = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "step-counts".into());
    match run(Path::new(&dir)) {
        Ok(o) => {
            print!("{}", o.report);
            println!("wrote {} into {dir}", o.files.join(", "));
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(friction_lab_cli::exit_code(&e));
        }
    }
}
