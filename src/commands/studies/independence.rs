//! `independence`: one solver at a ladder of resolutions, with a Richardson estimate of the
//! error left and a verdict.

use super::CaseArgs;
use clap::Args;
use friction_lab::study::{Independence, Refinement};
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
        help = friction_lab::settings::solver_help(
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

impl IndependenceArgs {
    /// The study as the library takes it.
    pub fn study(&self) -> Independence {
        Independence {
            problem: self.case.problem(),
            solver: self.solver,
            refinement: Refinement {
                start: self.start,
                ratio: self.ratio,
                levels: self.levels,
                tol: self.tol,
            },
        }
    }
}
