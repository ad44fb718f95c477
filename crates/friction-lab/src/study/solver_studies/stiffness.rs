//! `stiffness`: the cost to reach a target error across a stiffness parameter, and where
//! the implicit solvers overtake the explicit ones.

use super::Problem;
use crate::artifacts::Made;
use crate::error::AppError;
use crate::laws::ModelChoice;
use crate::scheme::SchemeName;
use crate::simulate::Target as Run;
use crate::study::{conduct, StiffnessStudy};
use integrators::Solver;
use scenarios::studies;
use scenarios::SwitchingKind;
use std::path::Path;

/// The solvers `stiffness` compares by default: two explicit, three implicit.
pub const STIFFNESS_SOLVERS: [Solver; 5] = [
    Solver::DOPRI5,
    Solver::TSIT45,
    Solver::IMPLICIT_EULER,
    Solver::BDF,
    Solver::ESDIRK34,
];

/// The step sizes of RK4 by default, coarse to fine (three a decade).
pub const STIFFNESS_STEPS: [f64; 7] = [0.01, 0.00464, 0.00215, 0.001, 0.000464, 0.000215, 0.0001];

/// The tolerances tried by default, loose to tight (three a decade: the cost at the target is
/// interpolated between the two that bracket it).
pub const STIFFNESS_TOLERANCES: [f64; 16] = [
    0.01, 0.00464, 0.00215, 0.001, 0.000464, 0.000215, 0.0001, 4.64e-5, 2.15e-5, 1e-5, 4.64e-6,
    2.15e-6, 1e-6, 4.64e-7, 2.15e-7, 1e-7,
];

/// The cost of each solver to reach a target error across the values of a parameter.
#[derive(Clone, Debug)]
pub struct Stiffness {
    /// The problem.
    pub problem: Problem,
    /// The parameter swept: epsilon, sigma, sigma0, k, or any other the run reads (on the
    /// chain: k_chain, m, …, or its law's; on a system file: epsilon).
    pub parameter: String,
    /// Its values, in sweep order.
    pub values: Vec<f64>,
    /// The solvers; empty: [`STIFFNESS_SOLVERS`].
    pub solvers: Vec<Solver>,
    /// The error to reach: `grid_relative`, the largest error on the time grid over the
    /// solution's scale in each quantity (dimensionless).
    pub target: f64,
    /// Step sizes of RK4, coarse to fine.
    pub dt_list: Vec<f64>,
    /// Tolerances tried, loose to tight.
    pub tol_list: Vec<f64>,
}

impl Stiffness {
    /// The study of `problem` over ε = 1e-1 … 1e-4 with every other setting at its default.
    pub fn new(problem: Problem) -> Stiffness {
        Stiffness {
            problem,
            parameter: "epsilon".into(),
            values: vec![1e-1, 1e-2, 1e-3, 1e-4],
            solvers: Vec::new(),
            target: 1e-3,
            dt_list: STIFFNESS_STEPS.to_vec(),
            tol_list: STIFFNESS_TOLERANCES.to_vec(),
        }
    }

    /// Checks and runs the study: its files in `out` (in memory), its verdict, and the
    /// reference's limit at each value where it bounds the errors. Without a switching, a rig
    /// swept over `epsilon` is regularized: the width changes nothing else (under event
    /// switching every value would give the same runs), while a system keeps event switching,
    /// whose regularised BDF peer is the method that depends on it.
    pub fn run(&self, out: &Path) -> Result<Made, AppError> {
        let mut problem = self.problem.clone();
        let rig = matches!(problem.target, Some(Run::Rig(_)));
        if problem.scheme.switching.is_none()
            && problem.scheme.scheme == SchemeName::EventDriven
            && self.parameter == "epsilon"
            && rig
        {
            problem.scheme.switching = Some(SwitchingKind::Regularized);
        }
        // A rig's run reads only what its model and switching read. A system's case checks
        // its parameter itself (`StudyCase::with_parameter`): epsilon, which under event
        // switching its regularised peer reads, and on the chain the chain's parameters and
        // its law's.
        if rig {
            crate::laws::check_read(
                "parameter",
                &self.parameter,
                problem.model.as_ref().and_then(ModelChoice::catalog),
                problem.treatment()?,
            )?;
        }
        problem.make(out, |t, case| {
            let sweep = studies::Sweep {
                parameter: &self.parameter,
                values: &self.values,
                target: self.target,
            };
            let study = StiffnessStudy {
                case,
                sweep,
                solvers: &(self.problem).solvers("solvers", &self.solvers, &STIFFNESS_SOLVERS)?,
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
