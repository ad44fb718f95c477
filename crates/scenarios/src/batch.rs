//! A study's runs as one list on the pool: every case of the study (one, or one per value of
//! a stiffness sweep), the reference runs of each, each (method, step) and its timing repeats,
//! handed to the workers by a greedy list schedule ([`schedule::in_order`]): the references
//! first (a reference that fails ends the study, and no run starts after it), then the longest
//! expected first (Graham 1969's LPT rule: a makespan of at most 4/3 of the optimum). A study
//! that ran its cases one after the other, or its reference beside its runs, or its timing
//! repeats after them, waited at each of those barriers for its longest run.
//!
//! The expected cost only orders the list: every result depends on its run alone, so the
//! results are the same for any number of threads and any order.

use crate::cases::{Measured, Measures, StudyCase};
use crate::error::ScenarioError;
use crate::method::{resolution, Method, StepKind};
use crate::schedule;
use crate::study_run::{Errors, Reference, StudyRun, WallTimes, REFERENCE_TOLERANCE};
use crate::verdict::Verdict;
use friction_systems::{Scheme, Switching};
use integrators::{Solver, StepControl};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

/// The steps a run is expected to take, to order the list: `T/h` with a fixed step;
/// `T·tol^(−1/(p+1))` with a tolerance, for a method of order p whose error per step is
/// held at the tolerance (steps ∝ h⁻¹, local error ∝ h^(p+1)), on a unit time scale.
pub fn expected_steps(method: &Method, step: StepControl, t_span: f64) -> f64 {
    let order = method.order();
    match step {
        StepControl::Fixed { h } => t_span / h,
        StepControl::Adaptive { rtol, .. } => t_span * rtol.powf(-1.0 / (order as f64 + 1.0)),
    }
}

/// How a case's reference is obtained.
enum Plan {
    /// Its closed form.
    Exact(Reference, Box<Measures>),
    /// Tight runs of two explicit 5(4) pairs under a treatment of v = 0, the first the
    /// reference and the second its cross-check; and, if Dormand–Prince's stiffness test
    /// fires in either, a tight run of an implicit method that becomes the reference.
    Runs {
        switching: Switching,
        solver: Solver,
        check: Solver,
    },
}

/// The step of a reference run.
const REFERENCE_STEP: StepControl = StepControl::Adaptive {
    rtol: REFERENCE_TOLERANCE,
    atol: REFERENCE_TOLERANCE,
    h0: None,
};

/// The implicit method a stiff case's reference is computed with: diffsol's variable-order
/// BDF (orders 1 to 5), even where it is studied. Of diffsol's implicit methods at
/// rtol = atol = 1e-13 it alone comes close to Dormand–Prince's tight run: within 1.6e-9
/// relative on the belt with CS regularised at ε = 1e-4 and 1.7e-8 with LuGre at σ0 = 1e7,
/// against 7.2e-8 and 3.2e-7 for ESDIRK34 and 5.5e-7 and 2.2e-6 for TR-BDF2 (docs/studies.md).
const STIFF_REFERENCE: Solver = Solver::BDF;

/// The reference of `case` for a study of `methods`: the closed form where one
/// exists; otherwise a run at rtol = atol = [`REFERENCE_TOLERANCE`] of Dormand–Prince, or,
/// when Dormand–Prince itself is one of the studied solvers (and Tsit45 not), of diffsol's Tsit45 (an independent
/// 5(4) pair, its own error control and dense output), always cross-checked by a tight run of
/// the other: their largest difference on the time grid is the reference's estimated error.
/// Where Dormand–Prince's stiffness test (Hairer & Wanner II, §IV.2) fires in its tight run
/// the case is stiff: an explicit method's tight run is then limited by its stability, not its
/// accuracy, and the reference is a tight run of an implicit method ([`STIFF_REFERENCE`]),
/// cross-checked by the explicit one (another family: one-step explicit against implicit).
/// Event switching for a naive or a time-stepped study (the exact solution of the
/// discontinuous problem both approximate), the studied methods' switching otherwise.
fn plan(case: &dyn StudyCase, methods: &[Method]) -> Plan {
    if let Some((name, m)) = case.closed_form() {
        return Plan::Exact(Reference::ClosedForm(name), Box::new(m));
    }
    let studied = Method::own_solvers(methods);
    let (dopri5, tsit45) = (Solver::DOPRI5, Solver::TSIT45);
    let (solver, check) = match (studied.contains(&dopri5), studied.contains(&tsit45)) {
        (true, false) => (tsit45, dopri5),
        _ => (dopri5, tsit45),
    };
    // Naive stepping and time-stepping approximate the discontinuous problem, whose exact
    // solution event switching computes (time-stepping takes no tolerance, so it could not
    // compute a tight reference of its own); a regularized problem is its own (smooth) ODE.
    // (Time-stepping's modes are event switching's.)
    let switching = match Method::studied_switching(methods) {
        Switching::Naive => Switching::Event,
        other => other,
    };
    Plan::Runs {
        switching,
        solver,
        check,
    }
}

/// One tight run of a reference by `solver` under `switching`; a failure is the study's
/// error.
fn reference_run(
    case: &dyn StudyCase,
    switching: Switching,
    solver: Solver,
) -> Result<Measured, ScenarioError> {
    let o = case.measure(Scheme::EventDriven { solver, switching }, REFERENCE_STEP)?;
    match o.error {
        Some(error) => Err(ScenarioError::Solver {
            what: format!("the reference run ({})", solver.name()),
            error,
        }),
        None => Ok(o),
    }
}

/// The reference of `case` for a study of `methods`: the closed form where one exists;
/// otherwise a run at rtol = atol = [`REFERENCE_TOLERANCE`] of Dormand–Prince (of Tsit45 when
/// Dormand–Prince is studied and Tsit45 not) under the studied treatment of v = 0,
/// cross-checked by a tight run of the other, whose difference is its estimated error. Its
/// runs are concurrent.
pub fn reference(
    case: &dyn StudyCase,
    methods: &[Method],
) -> Result<(Reference, Measures), ScenarioError> {
    let posed = Posed {
        case,
        reference_for: Some(methods),
        jobs: &[],
    };
    let mut out = run_cases(&[posed], 0, &|| {})?;
    Ok(out.remove(0).reference.expect("a reference was asked for"))
}

/// The reference a plan gives with its tight runs (`tight`: the first explicit solver's,
/// then the cross-check's; `implicit_run`: the implicit method's, run where the case is
/// stiff), and the cross-check's relative difference on the time grid.
fn reference_of(
    plan: Plan,
    tight: Vec<Measured>,
    implicit_run: Option<Measures>,
) -> (Reference, Measures) {
    match plan {
        Plan::Exact(r, m) => (r, *m),
        Plan::Runs { solver, check, .. } => {
            let [first, second]: [Measured; 2] =
                tight.try_into().expect("two explicit reference runs");
            let stiffness_detected_at =
                first.stiffness_detected_at.or(second.stiffness_detected_at);
            let (solver, measures, check, checked) = match implicit_run {
                Some(m) => (STIFF_REFERENCE, m, solver, first.measures),
                None => (solver, first.measures, check, second.measures),
            };
            let cross_check = (
                check.name(),
                Errors::between(&checked, &measures).grid_relative,
            );
            let reference = Reference::Run {
                solver: solver.name(),
                step: REFERENCE_STEP,
                cross_check,
                stiffness_detected_at,
            };
            (reference, measures)
        }
    }
}

/// Measures `run`'s errors against the reference's measures `reference` and judges it by
/// them ([`Verdict::against_reference`]). A failed run ends early: its last state is not a
/// state at the end, and it has no error against the reference.
pub fn judge(run: &mut StudyRun, reference: &Measures) {
    if run.failure.is_none() {
        run.errors = Errors::between(&run.measures, reference);
        let largest = run.errors.grid_relative.max(run.errors.final_relative);
        run.verdict = (run.verdict.clone()).and(Verdict::against_reference(largest));
    }
}

/// A case and the runs a study makes of it.
#[derive(Clone, Copy)]
pub struct Posed<'a> {
    /// The case.
    pub case: &'a dyn StudyCase,
    /// The methods the case's reference is computed for ([`reference()`]: their treatment of
    /// v = 0, solvers other than theirs), beside the runs; `None`: no reference.
    pub reference_for: Option<&'a [Method]>,
    /// Every (method, step) to run.
    pub jobs: &'a [(Method, StepControl)],
}

/// `jobs` on `case` without a reference, each `1 + repeats` times ([`run_cases`]): the runs,
/// their errors not measured.
pub fn run_jobs(
    case: &dyn StudyCase,
    jobs: &[(Method, StepControl)],
    repeats: usize,
    progress: &(dyn Fn() + Sync),
) -> Result<Vec<StudyRun>, ScenarioError> {
    let posed = Posed {
        case,
        reference_for: None,
        jobs,
    };
    Ok(run_cases(&[posed], repeats, progress)?.remove(0).runs)
}

/// What a study computed on one case.
pub struct CaseRuns {
    /// The reference and its measures, if one was asked for.
    pub reference: Option<(Reference, Measures)>,
    /// Every (method, step) in the order of the jobs, errors measured against the
    /// reference (NaN without one).
    pub runs: Vec<StudyRun>,
}

/// One entry of the list.
#[derive(Clone, Copy)]
enum Task {
    /// A reference run of case `case` by `solver`.
    Reference { case: usize, solver: Solver },
    /// Job `job` of case `case`, its `repeat`-th time (0: the measured run; after it,
    /// timing repeats).
    Run {
        case: usize,
        job: usize,
        repeat: usize,
    },
}

/// What an entry of the list gave.
enum Done {
    Reference(Box<Measured>),
    Run(Box<StudyRun>),
    /// A timing repeat's wall time; `None` for the repeat of a run that failed, not run.
    Time(Option<f64>),
}

/// Refuses two different methods with the same label.
fn check_labels(jobs: &[(Method, StepControl)]) -> Result<(), ScenarioError> {
    for (i, (a, _)) in jobs.iter().enumerate() {
        if let Some((b, _)) = jobs[..i]
            .iter()
            .find(|(b, _)| b != a && b.label() == a.label())
        {
            return Err(ScenarioError::Invalid(format!(
                "two methods of the study are both named `{}` ({:?} and {:?}): give a method of \
                 your own a name no other method of the study has",
                a.label(),
                b.scheme,
                a.scheme
            )));
        }
    }
    Ok(())
}

/// The run of `method` at `step` a measurement `o` gives, on a case of `dim` unknowns: its
/// errors not yet measured ([`judge`]), its wall time `o`'s alone.
fn study_run(method: &Method, step: StepControl, o: Measured, dim: usize) -> StudyRun {
    StudyRun {
        solver: method.label(),
        resolution: resolution(step),
        step: StepKind::of(step),
        errors: Errors::UNMEASURED,
        measures: o.measures,
        stats: o.stats,
        work: o.stats.work(dim),
        diverged: crate::run::diverged(!method.is_implicit(), step, o.error.as_ref()),
        verdict: Verdict::of_error(o.error.as_ref())
            .unwrap_or(Verdict::OK)
            .with_instability(o.instability.as_ref()),
        failure: o.error,
        wall_time: WallTimes::of(&[o.wall_time_s]),
    }
}

/// One (`method`, `step`) of `case` on the calling thread, then timed `repeats` times more
/// where its first run neither failed (its repeats would stop alike, and a partial run's
/// time measures nothing) nor took [`TIMED_ONCE_FROM`] counted work or more; its errors not
/// yet measured ([`judge`]). `progress` is told of the run and of every repeat, made or not.
/// The repeats depend only on the run's own counts, so they are the same on every machine.
pub fn run_timed(
    case: &dyn StudyCase,
    method: &Method,
    step: StepControl,
    repeats: usize,
    progress: &(dyn Fn() + Sync),
) -> Result<StudyRun, ScenarioError> {
    let o = case.measure(method.scheme, step)?;
    progress();
    let mut run = study_run(method, step, o, case.dim()?);
    let mut times = vec![run.wall_time.median];
    for _ in 0..repeats {
        if run.failure.is_none() && (run.work as f64) < TIMED_ONCE_FROM {
            times.push(case.measure(method.scheme, step)?.wall_time_s);
        }
        progress();
    }
    run.wall_time = WallTimes::of(&times);
    Ok(run)
}

/// The counted work ([`integrators::Stats::work`]) from which [`run_timed`] times a run once:
/// about 8 ms at the 82 ns a unit of work that `reproduce`'s comparisons take on the
/// two-core machine (median over their 2,583 runs; 23 to 230 ns from the 10th to the 90th
/// percentile). Their three timings spread by about 10 % of the median whatever the run's
/// length (9 % at 1e5 to 1e6 units, 10 % past 1e6), and a longer run's time is set beside
/// errors spanning decades, so one timing serves; the runs past it took 90 % of the
/// comparisons' time, two thirds of it in repeats (docs/performance.md).
pub const TIMED_ONCE_FROM: f64 = 1e5;

/// Runs each case's jobs, each `1 + repeats` times (the repeats only for their wall time:
/// [`StudyRun::wall_time`] is their median and spread), with each case's reference where it
/// asks for one ([`Posed::reference_for`]), as one list (see the module). `progress` is told
/// of every run and repeat (not of the reference runs). Errors: the first failing reference
/// (by case), then the first run that could not be set up; before any run, two different
/// methods under one label (an own method named like a built-in one), whose rows no table could
/// tell apart.
pub fn run_cases(
    cases: &[Posed],
    repeats: usize,
    progress: &(dyn Fn() + Sync),
) -> Result<Vec<CaseRuns>, ScenarioError> {
    for c in cases {
        check_labels(c.jobs)?;
    }
    let plans: Vec<Option<Plan>> = (cases.iter())
        .map(|c| c.reference_for.map(|m| plan(c.case, m)))
        .collect();
    let dims = cases
        .iter()
        .map(|c| c.case.dim())
        .collect::<Result<Vec<_>, _>>()?;
    let mut tasks = Vec::new();
    for (case, p) in plans.iter().enumerate() {
        if let Some(Plan::Runs { solver, check, .. }) = p {
            for solver in [*solver, *check] {
                tasks.push(Task::Reference { case, solver });
            }
        }
    }
    for (case, c) in cases.iter().enumerate() {
        for job in 0..c.jobs.len() {
            for repeat in 0..=repeats {
                tasks.push(Task::Run { case, job, repeat });
            }
        }
    }
    let cost = |t: &Task| match *t {
        Task::Reference { case, solver } => {
            let method = Method::of(Scheme::events(solver));
            expected_steps(&method, REFERENCE_STEP, cases[case].case.t_end())
        }
        Task::Run { case, job, .. } => {
            let (method, step) = cases[case].jobs[job];
            expected_steps(&method, step, cases[case].case.t_end())
        }
    };
    // The references first: every error is measured against them, so a reference that fails
    // (or is interrupted) ends the study, and no run starts after it; and a study stopped
    // after its references keeps its finished runs.
    let is_reference = |i: usize| matches!(tasks[i], Task::Reference { .. });
    let mut order: Vec<usize> = (0..tasks.len()).collect();
    order.sort_by(|&a, &b| {
        let longer = cost(&tasks[b]).total_cmp(&cost(&tasks[a]));
        is_reference(b).cmp(&is_reference(a)).then(longer)
    });
    // Whether each (case, job)'s first run failed: its timing repeats are then not run (a
    // step cap would stop them alike, and a partial run's time measures nothing; a repeat
    // taken beside its first run still runs).
    let first_job: Vec<usize> = (cases.iter())
        .scan(0, |n, c| {
            let first = *n;
            *n += c.jobs.len();
            Some(first)
        })
        .collect();
    let failed: Vec<AtomicBool> = (cases.iter())
        .flat_map(|c| c.jobs)
        .map(|_| AtomicBool::new(false))
        .collect();
    let done = schedule::in_order(&order, is_reference, |i| match tasks[i] {
        Task::Reference { case, solver } => {
            let Some(Plan::Runs { switching, .. }) = plans[case] else {
                unreachable!("reference tasks come from run plans")
            };
            reference_run(cases[case].case, switching, solver).map(|m| Done::Reference(Box::new(m)))
        }
        Task::Run { case, job, repeat } => {
            let (method, step) = cases[case].jobs[job];
            let first_failed = &failed[first_job[case] + job];
            if repeat > 0 && first_failed.load(Ordering::Relaxed) {
                progress();
                return Ok(Done::Time(None));
            }
            let o = cases[case].case.measure(method.scheme, step)?;
            progress();
            if repeat > 0 {
                return Ok(Done::Time(Some(o.wall_time_s)));
            }
            if o.error.is_some() {
                first_failed.store(true, Ordering::Relaxed);
            }
            Ok(Done::Run(Box::new(study_run(&method, step, o, dims[case]))))
        }
    })?;
    let mut done = done.into_iter().map(|(_, d)| d);
    let mut tight: Vec<Vec<Measured>> = (0..cases.len()).map(|_| Vec::new()).collect();
    for t in &tasks {
        if let Task::Reference { case, .. } = *t {
            let Some(Done::Reference(m)) = done.next() else {
                unreachable!("results come back in the order of the tasks")
            };
            tight[case].push(*m);
        }
    }
    // A stiff case's reference is an implicit method's tight run (see `plan`).
    let implicit_runs: Vec<Option<Measures>> = (plans.par_iter().zip(&tight).zip(cases))
        .map(|((plan, tight), c)| match plan {
            Some(Plan::Runs { switching, .. })
                if tight.iter().any(|m| m.stiffness_detected_at.is_some()) =>
            {
                reference_run(c.case, *switching, STIFF_REFERENCE).map(|m| Some(m.measures))
            }
            _ => Ok(None),
        })
        .collect::<Result<_, _>>()?;
    let mut out: Vec<CaseRuns> = Vec::with_capacity(cases.len());
    for (((plan, tight), implicit_run), c) in
        (plans.into_iter().zip(tight).zip(implicit_runs)).zip(cases)
    {
        let reference = plan.map(|p| reference_of(p, tight, implicit_run));
        let mut runs = Vec::with_capacity(c.jobs.len());
        for _ in c.jobs {
            let Some(Done::Run(mut run)) = done.next() else {
                unreachable!("results come back in the order of the tasks")
            };
            let mut times = vec![run.wall_time.median];
            times.extend(done.by_ref().take(repeats).filter_map(|d| match d {
                Done::Time(t) => t,
                _ => unreachable!("results come back in the order of the tasks"),
            }));
            run.wall_time = WallTimes::of(&times);
            if let Some((_, m)) = &reference {
                judge(&mut run, m);
            }
            runs.push(*run);
        }
        out.push(CaseRuns { reference, runs });
    }
    Ok(out)
}
