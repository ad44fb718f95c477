//! One problem of the standard stiff test set (`integrators::testset`) solved by one solver,
//! as `testset` writes it: `final.csv` (the state at the end time) and `summary.json` (the
//! counts and the significant correct digits against the published reference).

use crate::artifacts::Artifacts;
use crate::error::AppError;
use crate::made::Made;
use crate::ranges;
use crate::settings::RunLimits;
use integrators::testset::{self, TestProblem};
use integrators::{MethodSwitch, Solution, Solver};
use scenarios::studies::{self, TestRun, TestSetCounts, TestSetRun};
use scenarios::verdict::Status;
use scenarios::Limits;
use serde::Serialize;
use std::path::Path;

/// A run of a test problem (`friction-lab testset`): the problem, the solver (adaptive), its
/// tolerances, its initial step (the solver's choice when `None`), the end time and the
/// bounds.
#[derive(clap::Args, Clone, Debug)]
pub struct TestSetRequest {
    /// The problem: van-der-pol, robertson, hires, orego or pollution.
    #[arg(value_name = "PROBLEM")]
    pub problem: String,
    /// The solver; `None`: radau5.
    #[arg(
        long,
        value_name = "SOLVER",
        help = crate::settings::solver_help("The solver", "[default: radau5]")
    )]
    pub solver: Option<Solver>,
    /// Relative tolerance.
    #[arg(
        long,
        value_name = "R",
        allow_hyphen_values = true,
        default_value = "1e-6"
    )]
    pub rtol: f64,
    /// Absolute tolerance [default: rtol, but 1e-14·rtol for robertson, whose y2 is of order
    /// 1e-13].
    #[arg(long, value_name = "A", allow_hyphen_values = true)]
    pub atol: Option<f64>,
    /// Initial step, s [default: the solver's choice].
    #[arg(long, value_name = "H", allow_hyphen_values = true)]
    pub h0: Option<f64>,
    /// End time [default: the problem's, where its reference is given]; `scd` is null at a
    /// time without published values (Robertson has them at 40 too).
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub t_end: Option<f64>,
    /// The run's step cap and wall-clock limit.
    #[command(flatten)]
    pub limits: RunLimits,
}

impl TestSetRequest {
    /// Checks the run, solves it and makes its files in `out`: `final.csv`, `summary.json`.
    pub fn run(&self, out: &Path) -> Result<Made, AppError> {
        let problem = testset::named(&self.problem).map_err(AppError::Usage)?;
        let solver = self.solver.unwrap_or(Solver::RADAU5);
        if solver.is_fixed_step() {
            return Err(AppError::Usage(format!(
                "option `{}` takes a fixed step: the test set is run with tolerances; choose \
                 an adaptive solver",
                crate::error::setting("solver", solver.name())
            )));
        }
        let rtol = ranges::RTOL.check(self.rtol)?;
        let checked = Checked {
            problem,
            solver,
            rtol,
            atol: match self.atol {
                Some(atol) => ranges::ATOL.check(atol)?,
                None => problem.tolerances(rtol).1,
            },
            h0: self.h0.map(|h| ranges::H0.check(h)).transpose()?,
            t_end: match self.t_end {
                Some(t) => ranges::TESTSET_T_END.check(t)?,
                None => problem.t_end,
            },
            limits: self.limits.limits()?,
        };
        solve_test_problem(&checked, out)
    }
}

/// A [`TestSetRequest`] run checked: the problem found, the default solver and end time taken.
struct Checked<'a> {
    problem: &'a TestProblem,
    solver: Solver,
    rtol: f64,
    atol: f64,
    h0: Option<f64>,
    t_end: f64,
    limits: Limits,
}

/// The counts of `summary.json`, in the test set's terms.
#[derive(Serialize)]
struct Counts {
    /// The test set's counts.
    #[serde(flatten)]
    counts: TestSetCounts,
    /// Significant correct digits where the run ended, against the published values there;
    /// null at a time without them, or on failure.
    scd: Option<f64>,
}

#[derive(Serialize)]
struct Summary<'a> {
    problem: &'a str,
    title: &'a str,
    reference: &'a str,
    solver: &'a str,
    rtol: f64,
    atol: f64,
    h0: Option<f64>,
    t_end: f64,
    status: &'a str,
    /// Why the run is not `ok`: the solver's error, or too few correct digits.
    reason: Option<String>,
    error: Option<String>,
    /// The end time when reached; null for a run that recorded nothing.
    t_reached: Option<f64>,
    stats: Counts,
    /// `auto`'s switches of method (empty for the other solvers).
    method_switches: &'a [MethodSwitch],
    wall_time_s: f64,
}

/// Solves `run` and its files into `out`, in memory: `final.csv` and `summary.json`, a note
/// of the significant correct digits where the reference gives them, and the solver's failure.
fn solve_test_problem(run: &Checked, out: &Path) -> Result<Made, AppError> {
    let (problem, solver) = (run.problem, run.solver);
    let solved = studies::solve_test_problem(
        problem,
        solver,
        (run.rtol, run.atol, run.h0),
        run.t_end,
        &run.limits,
    );
    let scd = solved.scd(problem);
    let TestRun {
        solution,
        failure,
        wall_time_s,
    } = solved;
    // Judged by its digits where the published values give them, as the study's runs are.
    let status = match (&failure, scd) {
        (Some(_), _) => Status::Failed,
        (None, Some(d)) => TestSetRun::status(Some(d)),
        (None, None) => Status::Ok,
    };
    let reason = match (&failure, scd) {
        (Some(e), _) => Some(e.to_string()),
        (None, Some(d)) if status == Status::Inaccurate => Some(TestSetRun::digits_reason(d)),
        _ => None,
    };
    let mut files = Artifacts::default();
    files.add(out.join("final.csv"), final_csv(&solution));
    files.add_json(
        out.join("summary.json"),
        &Summary {
            problem: problem.name,
            title: problem.title,
            reference: problem.source,
            solver: solver.name(),
            rtol: run.rtol,
            atol: run.atol,
            h0: run.h0,
            t_end: run.t_end,
            status: status.name(),
            reason: reason.clone(),
            error: failure.as_ref().map(|e| e.to_string()),
            t_reached: solution.last().map(|(t, _)| t),
            stats: Counts {
                counts: TestSetCounts::of(&solution.stats),
                scd,
            },
            method_switches: &solution.method_switches,
            wall_time_s,
        },
    )?;
    let mut notes = Vec::new();
    if let Some(scd) = scd {
        notes.push(format!(
            "{} by {}: {scd:.2} significant correct digits, {} steps, {} evaluations of f",
            problem.name,
            solver.name(),
            solution.stats.steps,
            solution.stats.rhs_evals
        ));
    }
    let warnings = (status == Status::Inaccurate)
        .then(|| format!("the run is inaccurate: {}", reason.unwrap_or_default()))
        .into_iter()
        .collect();
    Ok(Made {
        files,
        notes,
        warnings,
        failure: failure.map(AppError::Solver),
        ..Made::default()
    })
}

/// `t,y1,…,yn` and one row at the end time (none where the run did not reach it).
fn final_csv(solution: &Solution) -> Vec<u8> {
    let n = solution.dim;
    let mut text = String::from("t");
    for i in 1..=n {
        text += &format!(",y{i}");
    }
    text.push('\n');
    if let Some((t, y)) = solution.last() {
        text += &format!("{t:e}");
        for v in y {
            text += &format!(",{v:e}");
        }
        text.push('\n');
    }
    text.into_bytes()
}
