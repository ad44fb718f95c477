//! The solver studies: convergence order, step-size independence, work–precision and the
//! explicit/implicit crossover. Every study is a list of independent runs evaluated on
//! rayon's pool and collected in order, so its results do not depend on the thread count.

use crate::batch;
pub use crate::batch::reference;
pub use crate::cases::{Case, Measured, Measures, StudyCase, SystemCase, GRID_POINTS};
use crate::run::{ScenarioError, SwitchingKind};
use crate::schedule;
use integrators::{Solver, Stats, StepControl};
use serde::Serialize;

/// How a study integrates its case: a solver under the case's own treatment of v = 0, or a
/// peer under another one (regularised BDF, or Moreau–Jean time-stepping, beside event-driven
/// solvers: one system, several schemes, as Siconos runs one declared system event-driven or
/// time-stepped).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Method {
    /// The solver (not used under time-stepping).
    pub solver: Solver,
    /// The treatment of v = 0; `None` for the case's own.
    pub switching: Option<SwitchingKind>,
}

impl Method {
    /// `solver` under the case's own treatment.
    pub fn of(solver: Solver) -> Method {
        Method {
            solver,
            switching: None,
        }
    }

    /// The solvers of `methods` that run under the case's own treatment of v = 0: those its
    /// reference must be independent of (a peer's or time-stepping's placeholder solver is
    /// not one).
    pub fn own_solvers(methods: &[Method]) -> Vec<Solver> {
        methods
            .iter()
            .filter(|m| m.switching.is_none())
            .map(|m| m.solver)
            .collect()
    }

    /// The methods a study of `solvers` runs on `case`: each solver under the case's own
    /// treatment of v = 0, or, for a time-stepped case, the one scheme that treatment is
    /// (Moreau–Jean takes no solver: every solver would name the same runs), labelled
    /// `moreau-jean (timestepping)` and stepped over the study's step sizes.
    pub fn studied(case: &dyn StudyCase, solvers: &[Solver]) -> Vec<Method> {
        match case.switching() {
            s @ SwitchingKind::TimeStepping { .. } => vec![Method {
                solver: Solver::Rk4,
                switching: Some(s),
            }],
            _ => solvers.iter().map(|&s| Method::of(s)).collect(),
        }
    }

    /// The name tables and legends give it: the solver's (`dopri5`), or a peer's with its
    /// treatment (`bdf (regularized)`, `moreau-jean (timestepping)`).
    pub fn label(&self) -> String {
        match self.switching {
            None => self.solver.name().to_string(),
            Some(s) => format!("{} ({})", s.method(self.solver), s.name()),
        }
    }

    /// Whether it takes the study's step sizes rather than its tolerances.
    pub fn is_fixed_step(&self) -> bool {
        self.solver.is_fixed_step() || self.switching.is_some_and(|s| s.is_time_stepping())
    }

    /// The order at which its error can fall with its resolution: the formal order in the
    /// step size of a method with fixed steps (Moreau–Jean's: 2 at θ = 1/2, else 1), and 1 in
    /// the tolerance of an adaptive one (tolerance proportionality, the aim of its error
    /// control).
    pub fn order_bound(&self) -> f64 {
        match self.switching {
            Some(SwitchingKind::TimeStepping { theta: 0.5 }) => 2.0,
            Some(SwitchingKind::TimeStepping { .. }) => 1.0,
            _ if self.is_fixed_step() => self.solver.order() as f64,
            _ => 1.0,
        }
    }

    /// Whether it solves an implicit problem per step (time-stepping does).
    pub fn is_implicit(&self) -> bool {
        self.solver.is_implicit() || self.switching.is_some_and(|s| s.is_time_stepping())
    }

    /// One run of `case` by this method with `step`.
    pub fn measure(
        &self,
        case: &dyn StudyCase,
        step: StepControl,
    ) -> Result<Measured, ScenarioError> {
        match self.switching {
            None => case.measure(self.solver, step),
            Some(s) => case.with_switching(s).measure(self.solver, step),
        }
    }

    /// The steps or tolerances a study runs it at (see [`steps_for`]).
    pub fn steps(&self, step_sizes: &[f64], tolerances: &[f64], fixed: bool) -> Vec<StepControl> {
        if self.switching.is_some_and(|s| s.is_time_stepping()) {
            step_sizes
                .iter()
                .map(|&h| StepControl::Fixed { h })
                .collect()
        } else {
            steps_for(self.solver, step_sizes, tolerances, fixed)
        }
    }

    /// Every (method, step) of a study of `methods`.
    pub fn jobs(
        methods: &[Method],
        step_sizes: &[f64],
        tolerances: &[f64],
        fixed: bool,
    ) -> Vec<(Method, StepControl)> {
        methods
            .iter()
            .flat_map(|&m| {
                m.steps(step_sizes, tolerances, fixed)
                    .into_iter()
                    .map(move |c| (m, c))
            })
            .collect()
    }
}

/// Errors of a run against the reference.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Errors {
    /// max |Δx|, |Δv| over every body at the end.
    pub final_state: f64,
    /// max |Δx|, |Δv| of the measured bodies over the common grid.
    pub grid_max: f64,
    /// max |Δt| over the events (NaN when the numbers of events differ).
    pub event_times: f64,
    /// max |Δ| over the stick durations (NaN when their numbers differ).
    pub stick_durations: f64,
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    if a.len() != b.len() {
        return f64::NAN;
    }
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

impl Errors {
    /// Not measured (yet): every error NaN.
    pub const UNMEASURED: Errors = Errors {
        final_state: f64::NAN,
        grid_max: f64::NAN,
        event_times: f64::NAN,
        stick_durations: f64::NAN,
    };

    /// The errors of `m` against `reference`.
    pub fn between(m: &Measures, reference: &Measures) -> Errors {
        let grid_max = if m.grid.len() == reference.grid.len() {
            m.grid
                .iter()
                .zip(&reference.grid)
                .map(|(a, b)| max_diff(a, b))
                .fold(0.0, f64::max)
        } else {
            f64::NAN
        };
        Errors {
            final_state: max_diff(&m.final_state, &reference.final_state),
            grid_max,
            event_times: max_diff(&m.event_times, &reference.event_times),
            stick_durations: max_diff(&m.stick_durations, &reference.stick_durations),
        }
    }
}

/// Where the reference comes from.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Reference {
    /// An exact solution, by name.
    ClosedForm(String),
    /// A much tighter run of a solver.
    Run {
        /// The solver.
        solver: &'static str,
        /// Its step control.
        step: StepControl,
        /// A second tight run by an independent solver, where the first one is also studied:
        /// the solver, and the largest difference of the two on the time grid (a bound on the
        /// reference's own error).
        cross_check: Option<(&'static str, f64)>,
    },
}

/// The tolerance of a reference run, rtol = atol.
pub const REFERENCE_TOLERANCE: f64 = 1e-13;

/// The resolution of a run: its step size (fixed steps, s) or its tolerance (adaptive: rtol,
/// equal to atol in the studies).
pub fn resolution(step: StepControl) -> f64 {
    match step {
        StepControl::Fixed { h } => h,
        StepControl::Adaptive { rtol, .. } => rtol,
    }
}

/// Which a resolution is: `fixed` (a step size) or `adaptive` (a tolerance).
pub fn step_kind(step: StepControl) -> &'static str {
    match step {
        StepControl::Fixed { .. } => "fixed",
        StepControl::Adaptive { .. } => "adaptive",
    }
}

/// One run of a study.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StudyRun {
    /// The method's label ([`Method::label`]): the solver, or a peer with its treatment.
    pub solver: String,
    /// The step size (fixed-step runs) or the tolerance (adaptive runs).
    pub resolution: f64,
    /// Which the resolution is: `fixed` (a step size, s) or `adaptive` (rtol = atol).
    pub step: &'static str,
    /// Errors against the reference.
    pub errors: Errors,
    /// The run's measures.
    #[serde(skip)]
    pub measures: Measures,
    /// Work done.
    pub stats: Stats,
    /// Work in right-hand-side evaluations ([`Stats::work`] at the problem's dimension).
    pub work: usize,
    /// The solver's error, if it failed.
    pub failure: Option<String>,
    /// Whether it failed as an explicit method with a fixed step past its stability limit
    /// ([`crate::run::diverged`]).
    #[serde(skip)]
    pub diverged: bool,
    /// Wall time of the run, s: the median over it and its timing repeats (not
    /// deterministic: kept out of the study's main files).
    #[serde(skip)]
    pub wall_time_s: f64,
}

/// Runs `case` with each (method, step) against its reference for a study of `studied`
/// solvers, the reference runs and the runs in one list ([`batch`]).
pub fn run_against_reference(
    case: &dyn StudyCase,
    studied: &[Solver],
    jobs: &[(Method, StepControl)],
    progress: &(dyn Fn() + Sync),
) -> Result<(Reference, Measures, Vec<StudyRun>), ScenarioError> {
    let c = batch::run_cases(&[case], Some(studied), jobs, 0, progress)?.remove(0);
    let (reference, measures) = c.reference.expect("a reference was asked for");
    Ok((reference, measures, c.runs))
}

/// The observed order between two refinements: log(e_i/e_(i+1)) / log(h_i/h_(i+1)), which
/// does not assume halving.
pub fn observed_order(e: (f64, f64), h: (f64, f64)) -> f64 {
    (e.0 / e.1).ln() / (h.0 / h.1).ln()
}

/// The order of one refinement pair, with what may make it unreliable.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PairOrder {
    /// Coarser resolution.
    pub from: f64,
    /// Finer resolution.
    pub to: f64,
    /// Observed order.
    pub order: f64,
    /// The finer error is at the round-off floor (below 1e-12 of the solution's scale), or an
    /// error of the pair is missing (not finite): the pair says nothing of the order.
    pub round_off: bool,
    /// Above that floor, the finer error did not decrease: the refinement has not reached the
    /// asymptotic range, or the error has saturated (a limit cycle's phase drift, for one,
    /// holds it at the cycle's amplitude): the pair says nothing of the order either.
    pub stalled: bool,
    /// Outside the asymptotic range: the coarser error is as large as the solution's scale
    /// (the run has no correct digit: an unstable or unresolved step), or the order differs by
    /// more than 0.5 from the median of the other usable pairs.
    pub pre_asymptotic: bool,
}

/// Orders of successive pairs of (resolution, error), and the least-squares slope of
/// log(error) against log(resolution) over the pairs that are neither round-off, stalled nor
/// pre-asymptotic (see [`PairOrder`]; `scale` is the solution's).
pub fn orders(points: &[(f64, f64)], scale: f64) -> (Vec<PairOrder>, Option<f64>) {
    let mut pairs: Vec<PairOrder> = points
        .windows(2)
        .map(|w| {
            let round_off = w[1].1 <= 1e-12 * scale || !(w[0].1.is_finite() && w[1].1.is_finite());
            let stalled = !round_off && w[1].1 >= w[0].1;
            PairOrder {
                from: w[0].0,
                to: w[1].0,
                order: observed_order((w[0].1, w[1].1), (w[0].0, w[1].0)),
                round_off,
                stalled,
                pre_asymptotic: !round_off && !stalled && w[0].1 >= scale,
            }
        })
        .collect();
    let usable = |p: &PairOrder| !p.round_off && !p.stalled && !p.pre_asymptotic;
    let mut orders: Vec<f64> = pairs
        .iter()
        .filter(|p| usable(p))
        .map(|p| p.order)
        .collect();
    orders.sort_by(f64::total_cmp);
    if let Some(&median) = orders.get(orders.len() / 2) {
        for p in pairs.iter_mut().filter(|p| usable(p)) {
            p.pre_asymptotic = (p.order - median).abs() > 0.5;
        }
    }
    // Least squares over the points joined by good pairs.
    let mut xs = Vec::new();
    for (i, p) in pairs.iter().enumerate() {
        if !p.round_off && !p.stalled && !p.pre_asymptotic {
            for point in [points[i], points[i + 1]] {
                let xy = (point.0.ln(), point.1.ln());
                if !xs.contains(&xy) {
                    xs.push(xy);
                }
            }
        }
    }
    let slope = (xs.len() >= 2).then(|| slope(&xs));
    (pairs, slope)
}

/// The steps or tolerances a study runs a solver at: a fixed-step method (RK4) always takes
/// the step sizes; with `fixed`, so does every method that can (Dormand–Prince, implicit Euler,
/// for observed orders); otherwise they and diffsol's methods take the tolerances.
pub fn steps_for(
    solver: Solver,
    step_sizes: &[f64],
    tolerances: &[f64],
    fixed: bool,
) -> Vec<StepControl> {
    let steps = solver.is_fixed_step() || (fixed && solver.takes_fixed_steps());
    match steps {
        true => step_sizes
            .iter()
            .map(|&h| StepControl::Fixed { h })
            .collect(),
        false => tolerances
            .iter()
            .map(|&tol| StepControl::Adaptive {
                rtol: tol,
                atol: tol,
                h0: None,
            })
            .collect(),
    }
}

/// The scale of the solution: the largest |x| or |v| of the reference.
fn scale(reference: &Measures) -> f64 {
    reference
        .grid
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0, |a: f64, b| a.max(b.abs()))
        .max(f64::MIN_POSITIVE)
}

/// Orders for one solver and one error measure.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OrderTable {
    /// The method's label ([`Method::label`]).
    pub solver: String,
    /// Which error: `final_state`, `grid_max`, `event_times`, `stick_durations`.
    pub measure: &'static str,
    /// Each refinement pair.
    pub pairs: Vec<PairOrder>,
    /// Least-squares slope over the reliable pairs.
    pub fitted_slope: Option<f64>,
}

impl OrderTable {
    /// Why there is no fitted slope (`None` when there is one): how many pairs were stalled,
    /// pre-asymptotic, or at round-off or undefined (see [`PairOrder`]), e.g. "of 3 pairs: 2
    /// stalled, 1 pre-asymptotic".
    pub fn unfitted(&self) -> Option<String> {
        if self.fitted_slope.is_some() {
            return None;
        }
        if self.pairs.is_empty() {
            return Some("fewer than two resolutions".into());
        }
        let count = |flag: fn(&PairOrder) -> bool| self.pairs.iter().filter(|p| flag(p)).count();
        let kinds = [
            (count(|p| p.stalled), "stalled"),
            (count(|p| p.pre_asymptotic), "pre-asymptotic"),
            (count(|p| p.round_off), "at round-off or undefined"),
        ];
        let named: Vec<String> = kinds
            .iter()
            .filter(|(n, _)| *n > 0)
            .map(|(n, kind)| format!("{n} {kind}"))
            .collect();
        Some(format!(
            "of {} pairs: {}",
            self.pairs.len(),
            named.join(", ")
        ))
    }
}

/// A convergence study.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Convergence {
    /// The reference.
    pub reference: Reference,
    /// Every run, solver by solver, coarse to fine.
    pub runs: Vec<StudyRun>,
    /// Observed orders.
    pub orders: Vec<OrderTable>,
}

/// Runs each solver over the step sizes (or tolerances) against the reference and reports
/// the observed orders of every error measure.
pub fn convergence(
    case: &dyn StudyCase,
    solvers: &[Solver],
    step_sizes: &[f64],
    tolerances: &[f64],
    progress: &(dyn Fn() + Sync),
) -> Result<Convergence, ScenarioError> {
    let methods = Method::studied(case, solvers);
    let jobs = Method::jobs(&methods, step_sizes, tolerances, true);
    let own = Method::own_solvers(&methods);
    let (reference, ref_measures, runs) = run_against_reference(case, &own, &jobs, progress)?;
    let sc = scale(&ref_measures);
    let mut tables = Vec::new();
    for method in &methods {
        let label = method.label();
        let mine: Vec<&StudyRun> = runs.iter().filter(|r| r.solver == label).collect();
        type Pick = fn(&Errors) -> f64;
        let measures: [(&str, Pick); 4] = [
            ("final_state", |e| e.final_state),
            ("grid_max", |e| e.grid_max),
            ("event_times", |e| e.event_times),
            ("stick_durations", |e| e.stick_durations),
        ];
        for (name, pick) in measures {
            let points: Vec<(f64, f64)> = mine
                .iter()
                .map(|r| (r.resolution, pick(&r.errors)))
                .collect();
            if points.iter().all(|p| p.1.is_nan() || p.1 == 0.0) {
                continue;
            }
            let (pairs, fitted_slope) = orders(&points, sc);
            tables.push(OrderTable {
                solver: label.clone(),
                measure: name,
                pairs,
                fitted_slope,
            });
        }
    }
    Ok(Convergence {
        reference,
        runs,
        orders: tables,
    })
}

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
    pub step: &'static str,
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

/// Runs `solver` at `levels` resolutions, each `ratio` times finer, and judges whether the
/// final state, the first events, the stick durations and the peak friction are independent
/// of the resolution to the relative `tolerance`. A failed level is kept in
/// [`Independence::failed`] and the longest unbroken run of finished levels is judged; with
/// fewer than two finished in a row there is nothing to judge, and the study fails.
pub fn independence(
    case: &dyn StudyCase,
    solver: Solver,
    start: f64,
    ratio: f64,
    levels: usize,
    tolerance: f64,
    progress: &(dyn Fn() + Sync),
) -> Result<Independence, ScenarioError> {
    let resolutions: Vec<f64> = (0..levels).map(|i| start / ratio.powi(i as i32)).collect();
    let method = Method::studied(case, &[solver]);
    let jobs = Method::jobs(&method, &resolutions, &resolutions, false);
    let runs = batch::run_cases(&[case], None, &jobs, 0, progress)?
        .remove(0)
        .runs;
    let failed: Vec<FailedLevel> = runs
        .iter()
        .enumerate()
        .filter_map(|(level, r)| {
            r.failure.clone().map(|failure| FailedLevel {
                level,
                resolution: resolutions[level],
                failure,
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
    let judge = |name, values| check(name, values, ratio, tolerance, method[0].order_bound());
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
        solver: method[0].label(),
        step: runs.first().map_or("fixed", |r| r.step),
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

/// A work–precision study: every solver at every resolution, with the work it took.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WorkPrecision {
    /// The reference.
    pub reference: Reference,
    /// Every run, its wall time the median over the repetitions.
    pub runs: Vec<StudyRun>,
}

/// Runs every method over its step sizes or tolerances, `repeats` times each for the
/// median wall time, the repetitions in the same list as the runs (each run alone on its
/// core: see docs/performance.md for what a neighbour costs a small problem). The reference is the one of the methods' solvers under the case's own
/// treatment.
pub fn work_precision(
    case: &dyn StudyCase,
    methods: &[Method],
    step_sizes: &[f64],
    tolerances: &[f64],
    repeats: usize,
    progress: &(dyn Fn() + Sync),
) -> Result<WorkPrecision, ScenarioError> {
    let jobs = Method::jobs(methods, step_sizes, tolerances, false);
    let own = Method::own_solvers(methods);
    let c = batch::run_cases(&[case], Some(&own), &jobs, repeats.max(1) - 1, progress)?.remove(0);
    let (reference, _) = c.reference.expect("a reference was asked for");
    Ok(WorkPrecision {
        reference,
        runs: c.runs,
    })
}

/// The cheapest run of one solver that met the target at one stiffness value.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Cost {
    /// The method's label.
    pub solver: String,
    /// Whether it is implicit.
    pub implicit: bool,
    /// The resolution that first met the target (None: none did).
    pub resolution: Option<f64>,
    /// Which that resolution is: `fixed` or `adaptive` (None: none met the target).
    pub step: Option<&'static str>,
    /// Its error.
    pub error: f64,
    /// Its statistics.
    pub stats: Stats,
    /// Its work ([`Stats::work`]).
    pub work: usize,
}

/// The costs at one value of the stiffness parameter.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StiffnessPoint {
    /// The parameter's value.
    pub value: f64,
    /// One cost per solver.
    pub costs: Vec<Cost>,
    /// Whether the cheapest implicit solver beats the cheapest explicit one in work
    /// ([`Stats::work`]).
    pub implicit_wins: bool,
}

/// A stiffness sweep.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Stiffness {
    /// The swept parameter.
    pub parameter: String,
    /// The target error (grid maximum).
    pub target: f64,
    /// Every value.
    pub points: Vec<StiffnessPoint>,
    /// The crossover ([`crossover`]), as the verdict names it.
    pub crossover: Option<f64>,
}

impl StiffnessPoint {
    /// Whether some method met the target at this value (where none did, neither kind wins).
    pub fn decided(&self) -> bool {
        self.costs.iter().any(|c| c.resolution.is_some())
    }
}

/// The first value (in sweep order) from which the implicit solvers win, where the explicit
/// ones won before it and the implicit ones win at every value from it on (values at which no
/// method met the target are passed over); `None` where one
/// kind wins at every value or the winner changes more than once (as [`Stiffness::verdict`]
/// says).
pub fn crossover(points: &[StiffnessPoint]) -> Option<f64> {
    let decided: Vec<&StiffnessPoint> = points.iter().filter(|p| p.decided()).collect();
    let k = decided.iter().position(|p| p.implicit_wins)?;
    (k > 0 && decided[k..].iter().all(|p| p.implicit_wins)).then(|| decided[k].value)
}

impl Stiffness {
    /// The study's conclusion in words: a crossover only where the winner changes inside the
    /// sweep; "no crossover in this range" where one kind wins at every value; no winner where
    /// only one kind of method was studied, or at a value where no method met the target
    /// (named after the verdict).
    pub fn verdict(&self) -> String {
        let studied = |implicit: bool| {
            let mut names: Vec<&str> = Vec::new();
            for c in self.points.iter().flat_map(|p| &p.costs) {
                if c.implicit == implicit && !names.contains(&c.solver.as_str()) {
                    names.push(&c.solver);
                }
            }
            names
        };
        let (implicit, explicit) = (studied(true), studied(false));
        if !self.points.is_empty() && (implicit.is_empty() || explicit.is_empty()) {
            let (kind, names) = if implicit.is_empty() {
                ("explicit", explicit)
            } else {
                ("implicit", implicit)
            };
            return format!(
                "only {kind} methods were studied ({}): nothing to compare them with; their cost \
                 against {} is in stiffness.csv",
                names.join(", "),
                self.parameter
            );
        }
        let undecided: Vec<String> = self
            .points
            .iter()
            .filter(|p| !p.decided())
            .map(|p| p.value.to_string())
            .collect();
        let decided: Vec<&StiffnessPoint> = self.points.iter().filter(|p| p.decided()).collect();
        if !self.points.is_empty() && decided.is_empty() {
            return format!(
                "no method met the target at any {} of the sweep",
                self.parameter
            );
        }
        let verdict = self.winners(&decided);
        if undecided.is_empty() {
            verdict
        } else {
            format!(
                "{verdict}; no method met the target at {} = {}",
                self.parameter,
                undecided.join(", ")
            )
        }
    }

    /// Which kind wins over the `decided` values: everywhere, from a crossover on, or by turns.
    fn winners(&self, decided: &[&StiffnessPoint]) -> String {
        let wins: Vec<bool> = decided.iter().map(|p| p.implicit_wins).collect();
        let values = |implicit: bool| {
            decided
                .iter()
                .filter(|p| p.implicit_wins == implicit)
                .map(|p| p.value.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        };
        match (wins.iter().all(|&w| w), wins.iter().any(|&w| w)) {
            _ if wins.is_empty() => "no values were swept".into(),
            (true, _) => format!(
                "the implicit solvers win at every {} of the sweep: no crossover in this range",
                self.parameter
            ),
            (false, false) => format!(
                "the explicit solvers win at every {} of the sweep: no crossover in this range",
                self.parameter
            ),
            _ => {
                let k = wins.iter().position(|&w| w).expect("some value is won");
                if wins[k..].iter().all(|&w| w) {
                    format!(
                        "the implicit solvers overtake the explicit ones from {} = {}",
                        self.parameter, decided[k].value
                    )
                } else {
                    format!(
                        "the winner changes more than once: implicit solvers win at {} = {}, \
                         explicit ones at {}",
                        self.parameter,
                        values(true),
                        values(false)
                    )
                }
            }
        }
    }
}

/// What a stiffness study sweeps, and the error each solver must reach.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sweep<'a> {
    /// The parameter (a friction or a scenario parameter).
    pub parameter: &'a str,
    /// Its values, in sweep order.
    pub values: &'a [f64],
    /// The error to reach (maximum over the time grid).
    pub target: f64,
}

/// Sweeps the parameter over its values (every value's runs in one list) and finds, for each solver, the cheapest
/// resolution in `step_sizes` (or `tolerances`) whose grid error meets the target.
pub fn stiffness(
    case: &dyn StudyCase,
    sweep: Sweep,
    methods: &[Method],
    step_sizes: &[f64],
    tolerances: &[f64],
    progress: &(dyn Fn() + Sync),
) -> Result<Stiffness, ScenarioError> {
    let own = Method::own_solvers(methods);
    let Sweep {
        parameter,
        values,
        target,
    } = sweep;
    let cases = values
        .iter()
        .map(|&value| case.with_parameter(parameter, value))
        .collect::<Result<Vec<_>, _>>()?;
    let cases: Vec<&dyn StudyCase> = cases.iter().map(|c| c.as_ref()).collect();
    let jobs = Method::jobs(methods, step_sizes, tolerances, false);
    // Every value's runs and references in one list: no value waits for the last run of
    // the one before.
    let done = batch::run_cases(&cases, Some(&own), &jobs, 0, progress)?;
    let mut points = Vec::new();
    for (&value, batch::CaseRuns { runs, .. }) in values.iter().zip(done) {
        let costs: Vec<Cost> = methods
            .iter()
            .map(|m| {
                let label = m.label();
                let met = runs
                    .iter()
                    .filter(|r| {
                        r.solver == label && r.failure.is_none() && r.errors.grid_max <= target
                    })
                    .min_by_key(|r| r.work);
                Cost {
                    solver: label,
                    implicit: m.is_implicit(),
                    resolution: met.map(|r| r.resolution),
                    step: met.map(|r| r.step),
                    error: met.map_or(f64::NAN, |r| r.errors.grid_max),
                    stats: met.map_or(Stats::default(), |r| r.stats),
                    work: met.map_or(0, |r| r.work),
                }
            })
            .collect();
        let best = |implicit: bool| {
            costs
                .iter()
                .filter(|c| c.implicit == implicit && c.resolution.is_some())
                .map(|c| c.work)
                .min()
        };
        let implicit_wins = match (best(true), best(false)) {
            (Some(i), Some(e)) => i < e,
            (Some(_), None) => true,
            _ => false,
        };
        points.push(StiffnessPoint {
            value,
            costs,
            implicit_wins,
        });
    }
    Ok(Stiffness {
        parameter: parameter.to_string(),
        target,
        crossover: crossover(&points),
        points,
    })
}

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
    pub step: &'static str,
    /// Work done.
    pub stats: Stats,
    /// Work in right-hand-side evaluations ([`Stats::work`]).
    pub work: usize,
    /// Work per accepted step.
    pub work_per_step: f64,
    /// The solver's error, if it failed.
    pub failure: Option<String>,
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
        let o = method.measure(case, step)?;
        progress();
        let work = o.stats.work(case.dim()?);
        let run = ScalingRun {
            size: *size,
            solver: method.label(),
            resolution: resolution(step),
            step: step_kind(step),
            stats: o.stats,
            work,
            work_per_step: work as f64 / o.stats.steps.max(1) as f64,
            failure: o.error.map(|e| e.to_string()),
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

/// The least-squares slope of `points` (NaN for fewer than two).
pub fn slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    if points.len() < 2 {
        return f64::NAN;
    }
    let (mx, my) = (
        points.iter().map(|p| p.0).sum::<f64>() / n,
        points.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    sxy / sxx
}
