//! `friction-lab testset PROBLEM --solver S --rtol R --atol A --out DIR`: one problem of the
//! standard stiff test set (`integrators::testset`) integrated by one solver: `final.csv` (the
//! state at the end time) and `summary.json` (the counts and the significant correct digits
//! against the published reference).

use crate::options::LimitArgs;
use clap::Args;
use friction_lab::artifacts::{Artifacts, Made};
use friction_lab::error::AppError;
use friction_lab::ranges;
use integrators::testset::{self, TestProblem};
use integrators::{MethodSwitch, Solution, Solver};
use scenarios::studies::{self, TestRun, TestSetCounts};
use serde::Serialize;
use std::path::PathBuf;

/// Options of `testset`.
#[derive(Args, Debug)]
pub struct TestsetArgs {
    /// The problem: van-der-pol, robertson, hires, orego or pollution.
    #[arg(value_name = "PROBLEM")]
    pub problem: String,
    /// The solver (its help lists the built-in solvers).
    #[arg(
        long,
        value_name = "SOLVER",
        help = crate::options::solver_help("The solver", "[default: radau5]")
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
    /// Absolute tolerance.
    #[arg(
        long,
        value_name = "A",
        allow_hyphen_values = true,
        default_value = "1e-6"
    )]
    pub atol: f64,
    /// Initial step, s [default: the solver's choice].
    #[arg(long, value_name = "H", allow_hyphen_values = true)]
    pub h0: Option<f64>,
    /// End time [default: the problem's, where its reference is given]; `scd` is null at a
    /// time without published values (Robertson has them at 40 too).
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub t_end: Option<f64>,
    /// Folder to write into (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// The run's step cap and wall-clock limit.
    #[command(flatten)]
    pub limits: LimitArgs,
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
    error: Option<String>,
    /// The end time when reached; null for a run that recorded nothing.
    t_reached: Option<f64>,
    stats: Counts,
    /// `auto`'s switches of method (empty for the other solvers).
    method_switches: &'a [MethodSwitch],
    wall_time_s: f64,
}

/// Runs `testset`; its files in memory.
pub fn make(args: &TestsetArgs) -> Result<Made, AppError> {
    let problem = testset::named(&args.problem).map_err(AppError::Usage)?;
    let solver = args.solver.unwrap_or(Solver::RADAU5);
    if solver.is_fixed_step() {
        return Err(AppError::Usage(format!(
            "option `--solver {}` takes a fixed step: the test set is run with tolerances; \
             choose an adaptive solver",
            solver.name()
        )));
    }
    let rtol = ranges::RTOL.check(args.rtol)?;
    let atol = ranges::ATOL.check(args.atol)?;
    let h0 = args.h0.map(|h| ranges::DT.check(h)).transpose()?;
    let t_end = match args.t_end {
        Some(t) => ranges::TESTSET_T_END.check(t)?,
        None => problem.t_end,
    };
    let limits = args.limits.limits()?;
    let run = studies::solve_test_problem(problem, solver, (rtol, atol, h0), t_end, &limits);
    let scd = run.scd(problem);
    let TestRun {
        solution,
        failure,
        wall_time_s,
    } = run;
    let mut files = Artifacts::default();
    files.add(args.out.join("final.csv"), final_csv(&solution));
    files.add_json(
        args.out.join("summary.json"),
        &summary(args, problem, solver, &solution, &failure, scd, wall_time_s),
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
    Ok(Made {
        files,
        notes,
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

fn summary<'a>(
    args: &TestsetArgs,
    problem: &'a TestProblem,
    solver: Solver,
    solution: &'a Solution,
    failure: &Option<integrators::SolverError>,
    scd: Option<f64>,
    wall_time_s: f64,
) -> Summary<'a> {
    Summary {
        problem: problem.name,
        title: problem.title,
        reference: problem.source,
        solver: solver.name(),
        rtol: args.rtol,
        atol: args.atol,
        h0: args.h0,
        t_end: args.t_end.unwrap_or(problem.t_end),
        status: if failure.is_some() { "failed" } else { "ok" },
        error: failure.as_ref().map(|e| e.to_string()),
        t_reached: solution.last().map(|(t, _)| t),
        stats: Counts {
            counts: TestSetCounts::of(&solution.stats),
            scd,
        },
        method_switches: &solution.method_switches,
        wall_time_s,
    }
}
