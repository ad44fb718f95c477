//! `stiffness`: the cost to reach a target error across a stiffness parameter, and where
//! the implicit solvers overtake the explicit ones.

use super::Problem;
use crate::error::AppError;
use crate::laws::ModelChoice;
use crate::made::Made;
use crate::scheme::{SchemeName, SwitchingName};
use crate::simulate::Target as Run;
use crate::study::{conduct, StiffnessStudy};
use integrators::Solver;
use scenarios::studies::{self, Method};
use std::path::Path;

/// The solvers `stiffness` compares by default: two explicit, three implicit.
pub const STIFFNESS_SOLVERS: [Solver; 5] = [
    Solver::DOPRI5,
    Solver::TSIT45,
    Solver::IMPLICIT_EULER,
    Solver::BDF,
    Solver::ESDIRK34,
];

/// The cost of each solver to reach a target error across the values of a parameter
/// (`friction-lab stiffness`).
#[derive(clap::Args, Clone, Debug)]
pub struct StiffnessRequest {
    /// The problem.
    #[command(flatten)]
    pub problem: Problem,
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
    /// The solvers; empty: [`STIFFNESS_SOLVERS`].
    #[arg(
        long,
        value_delimiter = ',',
        help = crate::settings::solver_help(
            "Solvers, comma-separated, of",
            "[default: dopri5,tsit45,implicit-euler,bdf,esdirk34; refused under --scheme time-stepping, whose one method \
             is Moreau–Jean's scheme]"
        )
    )]
    pub solvers: Vec<Solver>,
    /// The error to reach, in (0, 1): `grid_relative`, the largest error on the time grid over
    /// the solution's scale in each quantity (dimensionless).
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

impl StiffnessRequest {
    /// The study of `problem` over ε = 1e-1 … 1e-4 with every other setting at its declared
    /// default.
    pub fn new(problem: Problem) -> StiffnessRequest {
        StiffnessRequest {
            problem,
            ..crate::settings::declared_defaults()
        }
    }

    /// Checks and runs the study: its files in `out` (in memory), its verdict, and the
    /// reference's limit at each value where it bounds the errors. Without a switching, a rig
    /// swept over `epsilon` is regularized: the width changes nothing else (under event
    /// switching every value would give the same runs), while a system keeps event switching,
    /// whose regularised BDF peer is the method that depends on it.
    pub fn run(&self, out: &Path) -> Result<Made, AppError> {
        let mut problem = self.problem.clone();
        let rig = matches!(problem.scenario, Some(Run::Rig(_)));
        if problem.scheme.switching.is_none()
            && problem.scheme.scheme == SchemeName::EventDriven
            && self.parameter == "epsilon"
            && rig
        {
            problem.scheme.switching = Some(SwitchingName::Regularized);
        }
        // A rig's run reads only what its model and switching read. On a system the study
        // checks epsilon against its methods (under event switching the regularised peer reads
        // it), and the case any other parameter (`StudyCase::with_parameter`: on the chain the
        // chain's parameters and its law's).
        if rig {
            crate::laws::check_read(
                "parameter",
                &self.parameter,
                problem.model.as_ref().and_then(ModelChoice::catalog),
                problem.scheme.unread_epsilon(),
            )?;
        }
        problem.make(out, |t, setup| {
            let studied = problem.methods(setup, "solvers", &self.solvers, &STIFFNESS_SOLVERS)?;
            let methods = setup.with_peers(studied);
            if self.parameter == "epsilon" && !methods.iter().any(Method::reads_epsilon) {
                return Err(AppError::Usage(format!(
                    "parameter `epsilon` is read on a system only under {} regularized, or \
                     event (by its regularised BDF peer); not {}: every value would give the \
                     same runs",
                    crate::error::field("switching"),
                    Method::treatment_name(&methods)
                )));
            }
            // The swept parameter named where the case refuses it, before any run (a value out
            // of every range is left to `--values`' own check; `epsilon`, the methods' width,
            // is swept on the methods, not on the case).
            let first = (self.values.first())
                .filter(|v| v.is_finite() && **v > 0.0 && self.parameter != "epsilon");
            if let Some(&first) = first {
                setup
                    .case
                    .with_parameter(&self.parameter, first)
                    .map_err(|e| {
                        AppError::Usage(format!(
                            "option `{}`: {e}",
                            crate::error::field("parameter")
                        ))
                    })?;
            }
            let sweep = studies::Sweep {
                parameter: &self.parameter,
                values: &self.values,
                target: self.target,
            };
            let study = StiffnessStudy {
                case: setup.case.as_ref(),
                sweep,
                methods: &methods,
                steps: &self.dt_list,
                tols: &self.tol_list,
            };
            let s = conduct(&study, t, "stiffness")?;
            let limits = (s.points.iter()).filter_map(|p| {
                Some(format!(
                    "at {} = {}: {}",
                    s.parameter,
                    p.value,
                    p.reference_limit.as_ref()?
                ))
            });
            Ok(std::iter::once(s.verdict()).chain(limits).collect())
        })
    }
}
