//! `converge`: observed orders of every solver against a reference.

use super::{failures, Problem};
use crate::error::AppError;
use crate::made::Made;
use crate::study::{conduct, ConvergenceStudy};
use integrators::Solver;
use std::path::Path;

/// The solvers `converge` compares by default.
pub const CONVERGE_SOLVERS: [Solver; 3] = [Solver::RK4, Solver::DOPRI5, Solver::IMPLICIT_EULER];
/// Observed orders of each solver on a problem against a reference (`friction-lab converge`).
#[derive(clap::Args, Clone, Debug)]
pub struct ConvergeRequest {
    /// The problem.
    #[command(flatten)]
    pub problem: Problem,
    /// The solvers; empty: [`CONVERGE_SOLVERS`].
    #[arg(
        long,
        value_delimiter = ',',
        help = crate::settings::solver_help(
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

impl ConvergeRequest {
    /// The study of `problem` with every other setting at its declared default.
    pub fn new(problem: Problem) -> ConvergeRequest {
        ConvergeRequest {
            problem,
            ..crate::settings::declared_defaults()
        }
    }

    /// Checks and runs the study: its files in `out` (in memory), and one line per solver
    /// and measure with its observed order, or why there is none.
    pub fn run(&self, out: &Path) -> Result<Made, AppError> {
        self.problem.make(out, |t, setup| {
            let methods =
                (self.problem).methods(setup, "solvers", &self.solvers, &CONVERGE_SOLVERS)?;
            let study = ConvergenceStudy {
                case: setup.case.as_ref(),
                methods: &methods,
                steps: &self.dt_list,
                tols: &self.tol_list,
            };
            let c = conduct(&study, t, "converge")?;
            // The order over the asymptotic range, or why there is none (docs/studies.md,
            // "Observed orders").
            let orders = (c.orders.iter())
                .map(|o| format!("{:15} {:16} {}", o.solver, o.measure, o.verdict()));
            let limit = c.reference_limit.clone();
            Ok(orders
                .chain(failures(&c.runs, "converge.csv"))
                .chain(limit)
                .collect())
        })
    }
}
