//! `stiffness`: the cost to reach a target error across a stiffness parameter, and where
//! the implicit solvers overtake the explicit ones.

use super::CaseArgs;
use clap::Args;
use friction_lab::study::Stiffness;
use integrators::Solver;

/// Options of `stiffness`.
#[derive(Args, Debug)]
pub struct StiffnessArgs {
    /// The problem.
    #[command(flatten)]
    pub case: CaseArgs,
    /// The parameter swept: epsilon, sigma, sigma0, k, or any other the run reads (on the
    /// chain: k_chain, m, …, or its law's; on a system file: epsilon). A rig swept over
    /// epsilon without --switching is regularized.
    #[arg(long, value_name = "NAME", default_value = "epsilon")]
    pub parameter: String,
    /// Its values, in sweep order.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "1e-1,1e-2,1e-3,1e-4"
    )]
    pub values: Vec<f64>,
    /// Solvers, comma-separated (its help lists the built-in solvers).
    #[arg(
        long,
        value_delimiter = ',',
        help = friction_lab::settings::solver_help(
            "Solvers, comma-separated, of",
            "[default: dopri5,tsit45,implicit-euler,bdf,esdirk34; refused under --scheme time-stepping, whose one method \
             is Moreau–Jean's scheme]"
        )
    )]
    pub solvers: Vec<Solver>,
    /// The error to reach: `grid_relative`, the largest error on the time grid over the
    /// solution's scale in each quantity (dimensionless).
    #[arg(
        long,
        value_name = "E",
        default_value_t = 1e-3,
        allow_hyphen_values = true
    )]
    pub target: f64,
    /// Step sizes of rk4, coarse to fine (three a decade).
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "0.01,0.00464,0.00215,0.001,0.000464,0.000215,0.0001"
    )]
    pub dt_list: Vec<f64>,
    /// Tolerances tried, loose to tight (three a decade: the cost at the target is
    /// interpolated between the two that bracket it).
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "0.01,0.00464,0.00215,0.001,0.000464,0.000215,0.0001,4.64e-5,2.15e-5,1e-5,4.64e-6,2.15e-6,1e-6,4.64e-7,2.15e-7,1e-7"
    )]
    pub tol_list: Vec<f64>,
}

impl StiffnessArgs {
    /// The study as the library takes it.
    pub fn study(&self) -> Stiffness {
        Stiffness {
            problem: self.case.problem(),
            parameter: self.parameter.clone(),
            values: self.values.clone(),
            solvers: self.solvers.clone(),
            target: self.target,
            dt_list: self.dt_list.clone(),
            tol_list: self.tol_list.clone(),
        }
    }
}
