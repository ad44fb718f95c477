//! The step-size independence study: successive differences over refinement levels, the
//! Richardson estimate of the error left, and the verdict.

use super::{batch, Measures, Method, StepKind, StudyCase};
use crate::error::ScenarioError;
use serde::Serialize;

/// One output of an independence study across the refinement levels.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OutputCheck {
    /// Which output.
    pub name: String,
    /// Its value at each level, coarse to fine.
    pub values: Vec<f64>,
    /// |q_i − q_(i+1)|.
    pub differences: Vec<f64>,
    /// Observed order from the last two differences.
    pub order: Option<f64>,
    /// Richardson estimate of the error left in the finest value:
    /// d_last/(r^p − 1), with p the observed order but at most the method's
    /// ([`Method::order_bound`]), or d_last when no positive order can be observed.
    pub remaining_error: f64,
    /// remaining_error ≤ tol·max(|q|, 1e-9).
    pub independent: bool,
}

/// A step-size independence study.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Independence {
    /// The method's label ([`Method::label`]).
    pub solver: String,
    /// Which the resolutions are: `fixed` (step sizes) or `adaptive` (tolerances).
    pub step: StepKind,
    /// The resolutions judged, coarse to fine (each the previous divided by `ratio`): every
    /// level asked for, or, when some failed, the longest unbroken run of finished ones.
    pub resolutions: Vec<f64>,
    /// The index of the first judged level among the levels asked for (0 unless the coarsest
    /// failed).
    pub first_level: usize,
    /// The levels that failed, none judged: the study then is not independent.
    pub failed: Vec<FailedLevel>,
    /// The refinement ratio.
    pub ratio: f64,
    /// The relative tolerance of the verdict.
    pub tolerance: f64,
    /// Each output.
    pub outputs: Vec<OutputCheck>,
    /// Whether every level finished and every output is independent of the resolution to
    /// the tolerance.
    pub independent: bool,
    /// x on the common grid at every judged level, for the overlay plot.
    #[serde(skip)]
    pub trajectories: Vec<Vec<f64>>,
}

/// A level of an independence study whose run failed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FailedLevel {
    /// Its index among the levels asked for, 0 the coarsest.
    pub level: usize,
    /// Its step size or tolerance.
    pub resolution: f64,
    /// The solver's error.
    pub failure: String,
    /// Whether it failed as an explicit method with a fixed step past its stability limit
    /// ([`crate::run::diverged`]).
    #[serde(skip)]
    pub diverged: bool,
}

/// The longest unbroken run of `true` in `finished`, the later (finer) one on a tie.
fn longest_run(finished: &[bool]) -> std::ops::Range<usize> {
    let mut best = 0..0;
    let mut start = 0;
    for (i, &ok) in finished.iter().enumerate() {
        if !ok {
            start = i + 1;
        } else if i + 1 - start >= best.len() {
            best = start..i + 1;
        }
    }
    best
}

/// Judges one output over the levels. An observed order above the method's `order_bound`
/// is not the asymptotic rate (levels before the asymptotic range, where the differences fall
/// faster than the method can: an explicit method coming back from beyond its stability
/// limit falls by 1e68 in one halving), so the estimate takes at most that bound, as Roache's
/// grid convergence index takes the lesser of the observed and the formal order.
fn check(
    name: String,
    values: Vec<f64>,
    ratio: f64,
    tolerance: f64,
    order_bound: f64,
) -> OutputCheck {
    let differences: Vec<f64> = values.windows(2).map(|w| (w[0] - w[1]).abs()).collect();
    let n = differences.len();
    let last = differences.last().copied().unwrap_or(f64::INFINITY);
    let order = (n >= 2 && differences[n - 2] > 0.0 && last > 0.0)
        .then(|| (differences[n - 2] / last).ln() / ratio.ln());
    let remaining_error = match order {
        Some(p) if p > 0.0 => last / (ratio.powf(p.min(order_bound)) - 1.0),
        _ => last,
    };
    let value = values.last().copied().unwrap_or(f64::NAN);
    OutputCheck {
        independent: remaining_error <= tolerance * value.abs().max(1e-9),
        name,
        values,
        differences,
        order,
        remaining_error,
    }
}

/// Runs `method` at `levels` resolutions, each `ratio` times finer, and judges whether the
/// final state, the first events, the stick durations and the peak friction are independent
/// of the resolution to the relative `tolerance`. A failed level is kept in
/// [`Independence::failed`] and the longest unbroken run of finished levels is judged; with
/// fewer than two finished in a row there is nothing to judge, and the study fails.
pub fn independence(
    case: &dyn StudyCase,
    method: Method,
    start: f64,
    ratio: f64,
    levels: usize,
    tolerance: f64,
    progress: &(dyn Fn() + Sync),
) -> Result<Independence, ScenarioError> {
    let resolutions: Vec<f64> = (0..levels).map(|i| start / ratio.powi(i as i32)).collect();
    let jobs = Method::jobs(&[method], &resolutions, &resolutions, false);
    let runs = batch::run_jobs(case, &jobs, 0, progress)?;
    let failed: Vec<FailedLevel> = runs
        .iter()
        .enumerate()
        .filter_map(|(level, r)| {
            r.failure.as_ref().map(|failure| FailedLevel {
                level,
                resolution: resolutions[level],
                failure: failure.to_string(),
                diverged: r.diverged,
            })
        })
        .collect();
    let judged = longest_run(&runs.iter().map(|r| r.failure.is_none()).collect::<Vec<_>>());
    if let (true, Some(f)) = (judged.len() < 2, failed.first()) {
        return Err(ScenarioError::RunFailed(format!(
            "a run of the independence study failed at level {} ({:e}), leaving fewer than \
             two levels in a row to compare: {}",
            f.level, f.resolution, f.failure
        )));
    }
    let m: Vec<&Measures> = runs[judged.clone()].iter().map(|r| &r.measures).collect();
    let judge = |name, values| check(name, values, ratio, tolerance, method.order_bound());
    let mut outputs = vec![
        judge(
            "final x (m)".into(),
            m.iter().map(|m| m.final_state[0]).collect(),
        ),
        judge(
            "final v (m/s)".into(),
            m.iter().map(|m| m.final_state[1]).collect(),
        ),
        judge(
            "peak friction (N)".into(),
            m.iter().map(|m| m.peak_friction).collect(),
        ),
    ];
    let events = m.iter().map(|m| m.event_times.len()).min().unwrap_or(0);
    let same_events = m
        .iter()
        .all(|x| x.event_times.len() == m[0].event_times.len());
    for k in 0..events.min(3) {
        outputs.push(judge(
            format!("event {} time (s)", k + 1),
            m.iter().map(|m| m.event_times[k]).collect(),
        ));
    }
    let sticks = m.iter().map(|m| m.stick_durations.len()).min().unwrap_or(0);
    for k in 0..sticks.min(2) {
        outputs.push(judge(
            format!("stick {} duration (s)", k + 1),
            m.iter().map(|m| m.stick_durations[k]).collect(),
        ));
    }
    if !same_events {
        outputs.push(OutputCheck {
            name: "number of events".into(),
            values: m.iter().map(|m| m.event_times.len() as f64).collect(),
            differences: m
                .windows(2)
                .map(|w| (w[0].event_times.len() as f64 - w[1].event_times.len() as f64).abs())
                .collect(),
            order: None,
            remaining_error: f64::INFINITY,
            independent: false,
        });
    }
    Ok(Independence {
        solver: method.label(),
        step: runs.first().map_or(StepKind::Fixed, |r| r.step),
        independent: failed.is_empty() && outputs.iter().all(|o| o.independent),
        resolutions: resolutions[judged.clone()].to_vec(),
        first_level: judged.start,
        failed,
        ratio,
        tolerance,
        trajectories: m
            .iter()
            .map(|m| m.grid.iter().map(|p| p[0]).collect())
            .collect(),
        outputs,
    })
}
