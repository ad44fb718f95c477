//! `work-precision`: error against work and wall time for every solver and peer, on a problem
//! or on a problem of the stiff test set.

use super::{failures, or_default, Problem};
use crate::artifacts::Artifacts;
use crate::error::AppError;
use crate::made::Made;
use crate::ranges;
use crate::study::{conduct, Output, TestSetStudy, WorkPrecisionStudy};
use integrators::Solver;
use std::path::Path;

/// The tolerances of a study of a rig or a system: 1e-3 to 1e-8, three a decade.
pub const WP_TOLERANCES: [f64; 16] = [
    1e-3, 4.64e-4, 2.15e-4, 1e-4, 4.64e-5, 2.15e-5, 1e-5, 4.64e-6, 2.15e-6, 1e-6, 4.64e-7, 2.15e-7,
    1e-7, 4.64e-8, 2.15e-8, 1e-8,
];

/// The tolerances of a study of the test set: 1e-4 to 1e-10, two a decade.
pub const TESTSET_TOLERANCES: [f64; 13] = [
    1e-4, 3.16e-5, 1e-5, 3.16e-6, 1e-6, 3.16e-7, 1e-7, 3.16e-8, 1e-8, 3.16e-9, 1e-9, 3.16e-10,
    1e-10,
];

/// The solvers of a study of the test set: the implicit ones that take tolerances, and
/// `auto` (an explicit method would take millions of steps on its stiff problems).
pub const TESTSET_SOLVERS: [Solver; 6] = [
    Solver::RADAU5,
    Solver::RODAS,
    Solver::AUTO,
    Solver::BDF,
    Solver::TR_BDF2,
    Solver::ESDIRK34,
];

/// Error against work and wall time of each solver on a problem, or on a problem of the stiff
/// test set (`friction-lab work-precision`).
#[derive(clap::Args, Clone, Debug)]
pub struct WorkPrecisionRequest {
    /// The problem (its bounds and threads also those of a test-set study).
    #[command(flatten)]
    pub problem: Problem,
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
    /// The solvers; empty: every built-in solver, or [`TESTSET_SOLVERS`] on the test set.
    #[arg(
        long,
        value_delimiter = ',',
        help = crate::settings::solver_help(
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
    // Empty: WP_TOLERANCES, or TESTSET_TOLERANCES on the test set.
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

impl WorkPrecisionRequest {
    /// The study of `problem` with every other setting at its declared default.
    pub fn new(problem: Problem) -> WorkPrecisionRequest {
        WorkPrecisionRequest {
            problem,
            ..crate::settings::declared_defaults()
        }
    }

    /// Checks and runs the study: its files in `out` (in memory), and a line per method with
    /// failed runs.
    pub fn run(&self, out: &Path) -> Result<Made, AppError> {
        if let Some(name) = &self.testset {
            return self.testset(name, out);
        }
        self.problem.make(out, |t, setup| {
            let studied = (self.problem).methods(setup, "solvers", &self.solvers, &Solver::ALL)?;
            let methods = setup.with_peers(studied);
            let study = WorkPrecisionStudy {
                case: setup.case.as_ref(),
                methods: &methods,
                steps: &self.dt_list,
                tols: &or_default(&self.tol_list, &WP_TOLERANCES),
                repeats: ranges::REPEATS.count(self.repeats)?,
            };
            let w = conduct(&study, t, "work-precision")?;
            Ok(failures(&w.runs, "work-precision.csv")
                .into_iter()
                .chain(w.reference_limit)
                .collect())
        })
    }

    /// The study of the test set's problem `name`.
    fn testset(&self, name: &str, out: &Path) -> Result<Made, AppError> {
        let problem = integrators::testset::named(name).map_err(AppError::Usage)?;
        let study = TestSetStudy {
            problem,
            solvers: &or_default(&self.solvers, &TESTSET_SOLVERS),
            tols: &or_default(&self.tol_list, &TESTSET_TOLERANCES),
            repeats: ranges::REPEATS.count(self.repeats)?,
            limits: self.problem.limits.limits()?,
        };
        let mut files = Artifacts::default();
        let mut target = Output {
            files: &mut files,
            dir: out,
            threads: ranges::threads(self.problem.threads)?,
            failure: None,
        };
        let w = conduct(&study, &mut target, "work-precision")?;
        let failure = target.failure;
        let notes = (w.runs.iter())
            .filter_map(|r| Some((r, r.failure.as_ref()?)))
            .map(|(r, e)| format!("{:10} at tol = {:e} failed: {e}", r.solver, r.tol))
            .collect();
        Ok(Made {
            files,
            notes,
            failure,
            ..Made::default()
        })
    }
}
