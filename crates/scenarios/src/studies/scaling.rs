//! Cost against size: every method at one resolution on systems of growing size.

use super::{resolution, slope, Method, StepKind, StudyCase};
use crate::error::ScenarioError;
use crate::schedule;
use integrators::{SolverError, Stats, StepControl};
use serde::Serialize;

/// One run of a cost-against-size study.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ScalingRun {
    /// Number of bodies.
    pub size: usize,
    /// The method's label.
    pub solver: String,
    /// Its step size or tolerance.
    pub resolution: f64,
    /// Which the resolution is: `fixed` or `adaptive`.
    pub step: StepKind,
    /// Work done.
    pub stats: Stats,
    /// Work in right-hand-side evaluations ([`Stats::work`]).
    pub work: usize,
    /// Work per accepted step.
    pub work_per_step: f64,
    /// The solver's error, if it failed (written as its message).
    #[serde(serialize_with = "crate::study_run::message")]
    pub failure: Option<SolverError>,
    /// Wall time of the run, s (not deterministic: kept out of the study's main files).
    #[serde(skip)]
    pub wall_time_s: f64,
}

/// Cost against the number of bodies: every method at one resolution on each case.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Scaling {
    /// Every run, by size then method.
    pub runs: Vec<ScalingRun>,
    /// Per method, the least-squares slope of log(work per step) against log(size): 1 for a
    /// cost linear in the number of bodies.
    pub exponents: Vec<(String, f64)>,
}

/// Runs every (method, step) on each (size, case), in parallel, the largest cases first; the
/// timings are then taken one run after another, so that they do not compete for the cores
/// (measured here: two runs side by side on this two-core machine inflate even each other's
/// thread CPU time by up to 60 %).
pub fn scaling(
    cases: &[(usize, Box<dyn StudyCase>)],
    methods: &[(Method, StepControl)],
    progress: &(dyn Fn() + Sync),
) -> Result<Scaling, ScenarioError> {
    let jobs: Vec<(usize, usize)> = (0..cases.len())
        .flat_map(|c| (0..methods.len()).map(move |m| (c, m)))
        .collect();
    let mut order: Vec<usize> = (0..jobs.len()).collect();
    order.sort_by_key(|&j| std::cmp::Reverse(cases[jobs[j].0].0));
    let run = |j: usize| -> Result<ScalingRun, ScenarioError> {
        let (c, m) = jobs[j];
        let (size, case) = (&cases[c].0, cases[c].1.as_ref());
        let (method, step) = methods[m];
        let o = case.measure(method.scheme, step)?;
        progress();
        let work = o.stats.work(case.dim()?);
        let run = ScalingRun {
            size: *size,
            solver: method.label(),
            resolution: resolution(step),
            step: StepKind::of(step),
            stats: o.stats,
            work,
            work_per_step: work as f64 / o.stats.steps.max(1) as f64,
            failure: o.error,
            wall_time_s: o.wall_time_s,
        };
        Ok(run)
    };
    let runs = schedule::in_order(&order, |_| false, run)?;
    let mut runs: Vec<ScalingRun> = runs.into_iter().map(|(_, r)| r).collect();
    for (j, r) in runs.iter_mut().enumerate() {
        r.wall_time_s = run(j)?.wall_time_s;
    }
    let exponents = methods
        .iter()
        .map(|(m, _)| {
            let label = m.label();
            let points: Vec<(f64, f64)> = runs
                .iter()
                .filter(|r| r.solver == label && r.failure.is_none())
                .map(|r| ((r.size as f64).ln(), r.work_per_step.ln()))
                .collect();
            (label, slope(&points))
        })
        .collect();
    Ok(Scaling { runs, exponents })
}
