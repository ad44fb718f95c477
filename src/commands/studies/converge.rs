//! `converge`: observed orders of every solver against a reference.

use super::CaseArgs;
use clap::Args;
use friction_lab::study::Converge;
use integrators::Solver;

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
        help = friction_lab::settings::solver_help(
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

impl ConvergeArgs {
    /// The study as the library takes it.
    pub fn study(&self) -> Converge {
        Converge {
            problem: self.case.problem(),
            solvers: self.solvers.clone(),
            dt_list: self.dt_list.clone(),
            tol_list: self.tol_list.clone(),
        }
    }
}
