//! `converge`: observed orders of every solver against a reference.

use super::{failures, CaseArgs};
use clap::Args;
use friction_lab::artifacts::Made;
use friction_lab::error::AppError;
use friction_lab::study::{conduct, ConvergenceStudy};
use integrators::Solver;

/// The solvers `converge` compares by default.
const CONVERGE_SOLVERS: [Solver; 3] = [Solver::RK4, Solver::DOPRI5, Solver::IMPLICIT_EULER];

/// Options of `converge`.
#[derive(Args, Debug)]
pub struct ConvergeArgs {
    /// The problem.
    #[command(flatten)]
    pub case: CaseArgs,
    /// Solvers, comma-separated (its help lists the built-in solvers).
    #[arg(
        long,
        value_delimiter = ',',
        help = crate::options::solver_help(
            "Solvers, comma-separated, of",
            "[default: rk4,dopri5,implicit-euler; refused under --scheme time-stepping, whose one method \
             is Moreau–Jean's scheme]"
        )
    )]
    pub solvers: Vec<Solver>,
    /// Step sizes of rk4, dopri5 and implicit-euler (fixed steps), coarse to fine.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "0.02,0.01,0.005,0.0025"
    )]
    pub dt_list: Vec<f64>,
    /// Tolerances of diffsol's adaptive methods, loose to tight.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "1e-4,1e-6,1e-8"
    )]
    pub tol_list: Vec<f64>,
}

/// Runs `converge`; its files in memory.
pub fn converge(a: &ConvergeArgs) -> Result<Made, AppError> {
    a.case.make(|t, case| {
        let study = ConvergenceStudy {
            case,
            solvers: &a.case.solvers("solvers", &a.solvers, &CONVERGE_SOLVERS)?,
            steps: &a.dt_list,
            tols: &a.tol_list,
        };
        let c = conduct(&study, t, "converge")?;
        // The order over the asymptotic range, or why there is none (docs/studies.md,
        // "Observed orders").
        let orders =
            (c.orders.iter()).map(|o| format!("{:15} {:16} {}", o.solver, o.measure, o.verdict()));
        let limit = c.reference_limit.clone();
        Ok(orders
            .chain(failures(&c.runs, "converge.csv"))
            .chain(limit)
            .collect())
    })
}
