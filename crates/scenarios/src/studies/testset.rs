//! Work–precision on the standard stiff test set ([`integrators::testset`]): every solver at
//! every tolerance on one problem, each run measured as the test set measures a code, by its
//! significant correct digits at the end time against the published reference
//! ([`TestProblem::scd`]), beside the work it took and its wall time.

use crate::error::ScenarioError;
use crate::run::Limits;
use crate::schedule;
use crate::study_run::{message, WallTimes};
use crate::verdict::Status;
use integrators::testset::TestProblem;
use integrators::{Mode, Options, Output, Solution, Solver, SolverError, Stats, StepControl};
use serde::Serialize;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

/// One run of a test problem: the solution as far as it went, the solver's error if it
/// failed, and the wall time of the integration, s.
pub struct TestRun {
    /// What the solver computed: the state at the end time, or the last before a failure.
    pub solution: Solution,
    /// The solver's error, if it failed.
    pub failure: Option<SolverError>,
    /// Wall time of the integration, s.
    pub wall_time_s: f64,
}

impl TestRun {
    /// Significant correct digits where the run ended ([`TestProblem::scd_at`]: the problem's
    /// end time, or another time with published values); `None` for a run that failed or
    /// ended where no values are published.
    pub fn scd(&self, problem: &TestProblem) -> Option<f64> {
        match (&self.failure, self.solution.last()) {
            (None, Some((t, y))) => problem.scd_at(t, y),
            _ => None,
        }
    }
}

/// Integrates `problem` with `solver` from t = 0 to `t_end` at tolerances `rtol`, `atol`
/// (first step `h0`, or the solver's choice), recording the state at `t_end` only, within
/// `limits`. A solver that cannot be set up (a fixed-step one) or fails on the way says why in
/// [`TestRun::failure`], beside what it computed.
pub fn solve(
    problem: &TestProblem,
    solver: Solver,
    (rtol, atol, h0): (f64, f64, Option<f64>),
    t_end: f64,
    limits: &Limits,
) -> TestRun {
    let mut options = Options::adaptive(0.0, t_end, rtol, atol);
    options.step = StepControl::Adaptive { rtol, atol, h0 };
    options.max_steps = limits.max_steps;
    options.time_limit = limits.time_limit;
    options.time_limit_since = limits.time_limit_since;
    options.output = Output::GridOnly(vec![t_end]);
    let clock = Instant::now();
    let result = solver.solve(problem.problem, problem.y0, &[Mode(0)], options);
    let wall_time_s = clock.elapsed().as_secs_f64();
    let (solution, failure) = match result {
        Ok(s) => (s, None),
        Err(f) => (*f.solution, Some(f.error)),
    };
    TestRun {
        solution,
        failure,
        wall_time_s,
    }
}

/// A run's counts in the test set's terms: attempted steps, then accepted and rejected ones,
/// and the evaluations and linear algebra.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TestSetCounts {
    /// Attempted steps: accepted and rejected.
    pub steps: usize,
    /// Accepted steps.
    pub accepted: usize,
    /// Rejected steps, whatever the cause.
    pub rejected: usize,
    /// Evaluations of f.
    pub rhs_evals: usize,
    /// Evaluations of the Jacobian.
    pub jacobian_evals: usize,
    /// Real LU factorisations.
    pub lu_factorizations: usize,
    /// Real back-solves.
    pub linear_solves: usize,
    /// Newton iterations.
    pub newton_iterations: usize,
}

impl TestSetCounts {
    /// The names of the counts, in the order of [`TestSetCounts::values`].
    pub const NAMES: [&'static str; 8] = [
        "steps",
        "accepted",
        "rejected",
        "rhs_evals",
        "jacobian_evals",
        "lu_factorizations",
        "linear_solves",
        "newton_iterations",
    ];

    /// The counts of a run with statistics `s`.
    pub fn of(s: &Stats) -> TestSetCounts {
        TestSetCounts {
            steps: s.steps + s.rejected(),
            accepted: s.steps,
            rejected: s.rejected(),
            rhs_evals: s.rhs_evals,
            jacobian_evals: s.jacobian_evals,
            lu_factorizations: s.lu_factorizations,
            linear_solves: s.linear_solves,
            newton_iterations: s.newton_iterations,
        }
    }

    /// The counts in the order of [`TestSetCounts::NAMES`].
    pub fn values(&self) -> [usize; 8] {
        [
            self.steps,
            self.accepted,
            self.rejected,
            self.rhs_evals,
            self.jacobian_evals,
            self.lu_factorizations,
            self.linear_solves,
            self.newton_iterations,
        ]
    }
}

/// A test-set run with fewer significant correct digits than this is `inaccurate`
/// ([`TestSetRun::status`]): its largest relative error exceeds a tenth of the solution.
pub const MIN_CORRECT_DIGITS: f64 = 1.0;

/// One (solver, tolerance) of a test-set work–precision study.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TestSetRun {
    /// The solver's name.
    pub solver: &'static str,
    /// The tolerance asked for.
    pub tol: f64,
    /// The relative tolerance the run took (`tol`).
    pub rtol: f64,
    /// The absolute tolerance the run took ([`TestProblem::tolerances`]).
    pub atol: f64,
    /// Significant correct digits at the end time: −log10 of the largest relative error
    /// against the reference; `None` (null) for a run that failed.
    pub scd: Option<f64>,
    /// What its result is worth ([`TestSetRun::status`]).
    pub status: Status,
    /// The counts of the run.
    pub stats: Stats,
    /// Work in right-hand-side evaluations ([`Stats::work`] at the problem's dimension).
    pub work: usize,
    /// The solver's error, if it failed (written as its message).
    #[serde(serialize_with = "message")]
    pub failure: Option<SolverError>,
    /// Wall time over the run and its timing repeats (not deterministic: kept out of the
    /// study's main files).
    #[serde(skip)]
    pub wall_time: WallTimes,
}

impl TestSetRun {
    /// What a result of `scd` digits is worth: `failed` where the solver stopped, `inaccurate`
    /// where it has less than [`MIN_CORRECT_DIGITS`] correct digit (an error above a tenth of
    /// the solution), else `ok`.
    pub fn status(scd: Option<f64>) -> Status {
        match scd {
            None => Status::Failed,
            Some(d) if d < MIN_CORRECT_DIGITS || d.is_nan() => Status::Inaccurate,
            Some(_) => Status::Ok,
        }
    }

    /// Why the run is not `ok`: the solver's error, or its digits
    /// ([`TestSetRun::digits_reason`]); `None` for an `ok` run.
    pub fn reason(&self) -> Option<String> {
        match (&self.failure, self.status) {
            (Some(e), _) => Some(e.to_string()),
            (None, Status::Inaccurate) => self.scd.map(TestSetRun::digits_reason),
            _ => None,
        }
    }

    /// The reason of a run `inaccurate` by its `scd` digits: "0.32 significant correct digits,
    /// fewer than 1: the largest relative error against the published reference, 4.79e-1, is
    /// above 0.1".
    pub fn digits_reason(scd: f64) -> String {
        format!(
            "{scd:.2} significant correct digits, fewer than {MIN_CORRECT_DIGITS}: the largest \
             relative error against the published reference, {:.2e}, is above {}",
            10f64.powf(-scd),
            10f64.powf(-MIN_CORRECT_DIGITS),
        )
    }

    /// The largest relative error at the end time, 10^−scd (NaN for a failed run).
    pub fn relative_error(&self) -> f64 {
        self.scd.map_or(f64::NAN, |d| 10f64.powf(-d))
    }
}

/// A work–precision study of one test problem.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TestSetWorkPrecision {
    /// The problem's name (`hires`).
    pub problem: &'static str,
    /// What it models.
    pub title: &'static str,
    /// Its end time.
    pub t_end: f64,
    /// Where its reference solution is published.
    pub reference: &'static str,
    /// Every (solver, tolerance), solver by solver, tolerances in the order given.
    pub runs: Vec<TestSetRun>,
}

/// Runs every solver of `solvers` at every tolerance of `tols` on `problem` to its end time,
/// `repeats` times each (at least once) for the median wall time, within `limits`; the runs
/// and their repeats in one list on rayon's pool, the longest first (the tightest tolerance,
/// the explicit solvers), collected in order, so the result bar the wall times is the same
/// for any number of threads. A run that fails is kept with its error; its repeats are not
/// run. Error: a solver that takes no tolerance (a fixed-step one).
pub fn testset_work_precision(
    problem: &'static TestProblem,
    solvers: &[Solver],
    tols: &[f64],
    repeats: usize,
    limits: &Limits,
    progress: &(dyn Fn() + Sync),
) -> Result<TestSetWorkPrecision, ScenarioError> {
    if let Some(s) = solvers.iter().find(|s| s.is_fixed_step()) {
        return Err(ScenarioError::Invalid(format!(
            "solver `{}` takes a fixed step: the test set is run at tolerances",
            s.name()
        )));
    }
    let repeats = repeats.max(1);
    // (solver, tol, repeat), solver by solver.
    let tasks: Vec<(usize, usize, usize)> = (0..solvers.len())
        .flat_map(|s| (0..tols.len()).flat_map(move |k| (0..repeats).map(move |r| (s, k, r))))
        .collect();
    let cost = |&(s, k, _): &(usize, usize, usize)| {
        let explicit = if solvers[s].is_implicit() { 1.0 } else { 1e3 };
        explicit / tols[k]
    };
    let mut order: Vec<usize> = (0..tasks.len()).collect();
    order.sort_by(|&a, &b| cost(&tasks[b]).total_cmp(&cost(&tasks[a])));
    let failed: Vec<AtomicBool> = (0..solvers.len() * tols.len())
        .map(|_| AtomicBool::new(false))
        .collect();
    let done = schedule::in_order(
        &order,
        |_| false,
        |i| {
            let (s, k, repeat) = tasks[i];
            let first_failed = &failed[s * tols.len() + k];
            if repeat > 0 && first_failed.load(Ordering::Relaxed) {
                progress();
                return Ok::<_, ScenarioError>(None);
            }
            let (rtol, atol) = problem.tolerances(tols[k]);
            let run = solve(
                problem,
                solvers[s],
                (rtol, atol, None),
                problem.t_end,
                limits,
            );
            if run.failure.is_some() {
                first_failed.store(true, Ordering::Relaxed);
            }
            progress();
            Ok(Some(run))
        },
    )?;
    let dim = problem.problem.dim();
    let mut runs = Vec::with_capacity(solvers.len() * tols.len());
    for chunk in done.chunks(repeats) {
        let (i, first) = &chunk[0];
        let (s, k, _) = tasks[*i];
        let first = first.as_ref().expect("a first run is always made");
        let times: Vec<f64> = chunk
            .iter()
            .filter_map(|(_, r)| r.as_ref().map(|r| r.wall_time_s))
            .collect();
        let (rtol, atol) = problem.tolerances(tols[k]);
        let scd = first.scd(problem);
        runs.push(TestSetRun {
            solver: solvers[s].name(),
            tol: tols[k],
            rtol,
            atol,
            scd,
            status: TestSetRun::status(scd),
            stats: first.solution.stats,
            work: first.solution.stats.work(dim),
            failure: first.failure.clone(),
            wall_time: WallTimes::of(&times),
        });
    }
    Ok(TestSetWorkPrecision {
        problem: problem.name,
        title: problem.title,
        t_end: problem.t_end,
        reference: problem.source,
        runs,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use integrators::testset;

    #[test]
    fn tighter_tolerances_give_more_correct_digits_and_the_repeats_only_time() {
        let hires = testset::named("hires").unwrap();
        let w = testset_work_precision(
            hires,
            &[Solver::RADAU5, Solver::RODAS],
            &[1e-4, 1e-7],
            3,
            &Limits::default(),
            &|| {},
        )
        .unwrap();
        assert_eq!(w.runs.len(), 4);
        for pair in w.runs.chunks(2) {
            let [loose, tight] = pair else { unreachable!() };
            assert_eq!(loose.solver, tight.solver);
            let (l, t) = (loose.scd.unwrap(), tight.scd.unwrap());
            // Three decades of tolerance give at least two more correct digits.
            assert!(
                t > l + 2.0,
                "{}: scd {l} at 1e-4, {t} at 1e-7",
                loose.solver
            );
            assert_eq!(tight.wall_time.repeats, 3);
            assert_eq!(tight.work, tight.stats.work(8));
        }
        // The same counts as a single run of the command's path.
        let one = solve(
            hires,
            Solver::RODAS,
            (1e-7, 1e-7, None),
            hires.t_end,
            &Limits::default(),
        );
        assert_eq!(w.runs[3].stats, one.solution.stats);
        assert_eq!(w.runs[3].scd, one.scd(hires));
    }

    #[test]
    fn a_run_that_fails_is_kept_with_its_error_and_no_digits() {
        let robertson = testset::named("robertson").unwrap();
        let limits = Limits {
            max_steps: 50,
            ..Limits::default()
        };
        // On one thread the repeat comes after its first run (two threads may take both at once).
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let w = pool
            .install(|| {
                testset_work_precision(robertson, &[Solver::RADAU5], &[1e-6], 2, &limits, &|| {})
            })
            .unwrap();
        let run = &w.runs[0];
        assert!(run.failure.is_some());
        assert_eq!(run.scd, None);
        assert!(run.relative_error().is_nan());
        // Its repeat is not run: one wall time.
        assert_eq!(run.wall_time.repeats, 1);
    }

    #[test]
    fn a_fixed_step_solver_is_refused() {
        let vdp = testset::named("van-der-pol").unwrap();
        let e = testset_work_precision(vdp, &[Solver::RK4], &[1e-6], 1, &Limits::default(), &|| {})
            .unwrap_err();
        assert!(e.to_string().contains("`rk4` takes a fixed step"), "{e}");
    }
}
