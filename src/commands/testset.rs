//! `friction-lab testset PROBLEM --solver S --rtol R --atol A --out DIR`: one problem of the
//! standard stiff test set (`integrators::testset`) integrated by one solver: `final.csv` (the
//! state at the end time) and `summary.json` (the counts and the significant correct digits
//! against the published reference).

use clap::Args;
use friction_lab::artifacts::Made;
use friction_lab::error::AppError;
use friction_lab::ranges;
use friction_lab::settings::RunLimits;
use friction_lab::testset::{solve_test_problem, TestSetRun};
use integrators::testset;
use integrators::Solver;
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
        help = friction_lab::settings::solver_help("The solver", "[default: radau5]")
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
    pub limits: RunLimits,
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
    let run = TestSetRun {
        problem,
        solver,
        rtol: ranges::RTOL.check(args.rtol)?,
        atol: ranges::ATOL.check(args.atol)?,
        h0: args.h0.map(|h| ranges::DT.check(h)).transpose()?,
        t_end: match args.t_end {
            Some(t) => ranges::TESTSET_T_END.check(t)?,
            None => problem.t_end,
        },
        limits: args.limits.limits()?,
    };
    solve_test_problem(&run, &args.out)
}
