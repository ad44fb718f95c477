//! `work-precision`: error against work and wall time for every solver and peer.

use super::{failures, CaseArgs};
use crate::artifacts::Made;
use crate::error::AppError;
use crate::ranges;
use crate::study::{conduct, WorkPrecisionStudy};
use clap::Args;
use integrators::Solver;

/// Options of `work-precision`.
#[derive(Args, Debug)]
pub struct WorkPrecisionArgs {
    /// The problem.
    #[command(flatten)]
    pub case: CaseArgs,
    /// Solvers, comma-separated (its help lists the built-in solvers).
    #[arg(
        long,
        value_delimiter = ',',
        help = crate::options::solver_help(
            "Solvers, comma-separated, of",
            "[default: rk4,dopri5,implicit-euler,bdf,tr-bdf2,esdirk34,tsit45; refused under --scheme time-stepping, whose one method \
             is Moreau–Jean's scheme]"
        )
    )]
    pub solvers: Vec<Solver>,
    /// Step sizes of rk4, coarse to fine.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "0.01,0.00464,0.00215,0.001,0.000464,0.000215"
    )]
    pub dt_list: Vec<f64>,
    /// Tolerances of the adaptive solvers, loose to tight.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "0.001,0.000464,0.000215,0.0001,4.64e-5,2.15e-5,1e-5,4.64e-6,2.15e-6,1e-6,4.64e-7,2.15e-7,1e-7,4.64e-8,2.15e-8,1e-8"
    )]
    pub tol_list: Vec<f64>,
    /// Timings of each run: the median wall time, its extremes and quartiles (five at least
    /// for a spread worth quoting).
    #[arg(
        long,
        value_name = "N",
        default_value_t = 5,
        allow_hyphen_values = true
    )]
    pub repeats: i64,
}

/// Runs `work-precision`; its files in memory.
pub fn work_precision(a: &WorkPrecisionArgs) -> Result<Made, AppError> {
    a.case.make(|t, case| {
        let study = WorkPrecisionStudy {
            case,
            solvers: &a.case.solvers("solvers", &a.solvers, &Solver::ALL)?,
            steps: &a.dt_list,
            tols: &a.tol_list,
            repeats: ranges::REPEATS.count(a.repeats)?,
        };
        let w = conduct(&study, t, "work-precision")?;
        Ok(failures(&w.runs, "work-precision.csv")
            .into_iter()
            .chain(w.reference_limit)
            .collect())
    })
}
