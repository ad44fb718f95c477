//! `independence`: one solver at a ladder of resolutions, with a Richardson estimate of the
//! error left and a verdict.

use super::CaseArgs;
use clap::Args;
use friction_lab::artifacts::Made;
use friction_lab::error::AppError;
use friction_lab::study::{conduct, IndependenceStudy, Refinement};
use friction_lab::warnings::diverged_line;
use integrators::Solver;

/// Options of `independence`.
#[derive(Args, Debug)]
pub struct IndependenceArgs {
    /// The problem.
    #[command(flatten)]
    pub case: CaseArgs,
    /// The solver (its help lists the built-in solvers).
    #[arg(
        long,
        value_name = "SOLVER",
        help = crate::options::solver_help(
            "The solver",
            "[default: rk4; refused under --scheme time-stepping, whose one method is \
             Moreau–Jean's scheme]"
        )
    )]
    pub solver: Option<Solver>,
    /// The coarsest step size (rk4) or tolerance (adaptive solvers).
    #[arg(
        long,
        value_name = "H",
        default_value_t = 1e-3,
        allow_hyphen_values = true
    )]
    pub start: f64,
    /// Refinement ratio between levels.
    #[arg(
        long,
        value_name = "R",
        default_value_t = 2.0,
        allow_hyphen_values = true
    )]
    pub ratio: f64,
    /// Number of levels.
    #[arg(
        long,
        value_name = "N",
        default_value_t = 4,
        allow_hyphen_values = true
    )]
    pub levels: i64,
    /// Relative tolerance of the verdict.
    #[arg(
        long,
        value_name = "TOL",
        default_value = "1e-6",
        allow_hyphen_values = true
    )]
    pub tol: f64,
}

/// Runs `independence`; its files in memory.
pub fn independence(a: &IndependenceArgs) -> Result<Made, AppError> {
    a.case.make(|t, case| {
        let r = Refinement {
            start: a.start,
            ratio: a.ratio,
            levels: a.levels,
            tol: a.tol,
        };
        let study = IndependenceStudy {
            case,
            solver: a
                .case
                .solvers("solver", a.solver.as_slice(), &[Solver::RK4])?[0],
            refinement: r,
        };
        let s = conduct(&study, t, "independence")?;
        let mut notes: Vec<String> = s
            .outputs
            .iter()
            .map(|o| {
                let verdict = if o.independent {
                    "independent"
                } else {
                    "NOT independent"
                };
                format!(
                    "{:24} remaining error {:.3e} {verdict}",
                    o.name, o.remaining_error
                )
            })
            .collect();
        let verdict = if s.independent {
            "independent of"
        } else {
            "not independent of"
        };
        notes.extend(s.failed.iter().map(|f| {
            format!(
                "level {} ({:e}) failed, not judged: {}",
                f.level, f.resolution, f.failure
            )
        }));
        if s.failed.iter().any(|f| f.diverged) {
            notes.push(diverged_line("--start"));
        }
        notes.push(format!("verdict: {verdict} the step size"));
        Ok(notes)
    })
}
