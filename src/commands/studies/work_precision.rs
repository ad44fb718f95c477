//! `work-precision`: error against work and wall time for every solver and peer.

use super::CaseArgs;
use clap::Args;
use friction_lab::study::WorkPrecision;
use integrators::Solver;

/// Options of `work-precision`.
#[derive(Args, Debug)]
pub struct WorkPrecisionArgs {
    /// The problem.
    #[command(flatten)]
    pub case: CaseArgs,
    /// A problem of the stiff test set (van-der-pol, robertson, hires, orego, pollution),
    /// studied instead of a scenario: the largest relative error at its end time against the
    /// published reference (10^−scd) against work and wall time, rtol = atol = each tolerance
    /// (Robertson: atol = 1e-14·tol).
    #[arg(
        long,
        value_name = "PROBLEM",
        conflicts_with_all = [
            "scenario", "system", "model", "bodies", "t_end", "dt_list", "set", "params",
            "param_set", "switching"
        ]
    )]
    pub testset: Option<String>,
    /// Solvers, comma-separated (its help lists the built-in solvers).
    #[arg(
        long,
        value_delimiter = ',',
        help = friction_lab::settings::solver_help(
            "Solvers, comma-separated, of",
            "[default: all ten; with --testset radau5,rodas,auto,bdf,tr-bdf2,esdirk34, \
             the adaptive ones taken; refused under --scheme time-stepping, whose one method \
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
    /// Tolerances of the adaptive solvers, loose to tight [default: 1e-3 to 1e-8, three a
    /// decade; with --testset 1e-4 to 1e-10, two a decade].
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
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

impl WorkPrecisionArgs {
    /// The study as the library takes it.
    pub fn study(&self) -> WorkPrecision {
        WorkPrecision {
            problem: self.case.problem(),
            testset: self.testset.clone(),
            solvers: self.solvers.clone(),
            dt_list: self.dt_list.clone(),
            tol_list: self.tol_list.clone(),
            repeats: self.repeats,
        }
    }
}
