//! The periodic orbit of a rig's body or of a system, found by shooting on the hybrid system
//! with events at v_rel = 0 ([`periodic`]): a run from the declared initial state settles onto
//! its cycle, the recurrence of its switches gives the guess (period, and a state in the
//! middle of the cycle's longest smooth segment), and Newton on (y₀, T) closes the orbit to a
//! residual of 1e-10 of its scale. Its Floquet multipliers, through the saltation matrices of
//! its switches, give its stability.

use crate::cases::StudyCase;
use crate::error::ScenarioError;
use friction_systems::{mode_name, simulate, FrictionSystem, Scheme, Switching, System};
use integrators::{OdeProblem, Options, Output, Solver};
use periodic::{
    continue_cycles, continue_equilibria, cycle_at, equilibrium_at, find_orbit, guess_from_run,
    ContinuationOptions, CyclePoint, EquilibriumPoint, Family, Floquet, Guess, OrbitError,
    PeriodicOrbit, ShootingOptions, SpecialPoint,
};
use serde::Serialize;

/// How an orbit is looked for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrbitSettings {
    /// The length of the run that settles onto the cycle, s.
    pub settle: f64,
    /// Newton's settings and the flow's integration.
    pub shooting: ShootingOptions,
    /// Points of the orbit sampled evenly over its period (for plotting).
    pub samples: usize,
}

/// One smooth segment of the orbit: the contacts' modes, its span from the orbit's start and
/// the switch that ends it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OrbitSegment {
    /// Start, s after the orbit's start.
    pub t0: f64,
    /// End, s after the orbit's start.
    pub t1: f64,
    /// Each contact's mode (`slip+`, `slip-`, `stick`).
    pub modes: Vec<&'static str>,
    /// The event that ends it (`v_rel=0`, `break-away+`, …); `None` for the last, which ends
    /// where the orbit closes.
    pub ends_with: Option<&'static str>,
}

/// A periodic orbit found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Orbit {
    /// The period, s.
    pub period: f64,
    /// The period of the settled run's cycle, the guess, s.
    pub guessed_period: f64,
    /// Where the settled run's guessed state lay, s.
    pub guessed_at: f64,
    /// `‖φ_T(y₀) − y₀‖∞ / max(1, ‖y₀‖∞)`.
    pub residual: f64,
    /// Newton iterations.
    pub iterations: usize,
    /// The Floquet multipliers and the stability.
    pub floquet: Floquet,
    /// The segments, in order.
    pub segments: Vec<OrbitSegment>,
    /// The names of the bodies.
    pub bodies: Vec<String>,
    /// The orbit sampled: times from its start, s.
    pub t: Vec<f64>,
    /// Per body, its displacement at each sample, m.
    pub x: Vec<Vec<f64>>,
    /// Per body, its velocity at each sample, m/s.
    pub v: Vec<Vec<f64>>,
}

impl Orbit {
    /// Half the peak-to-peak displacement of body `i` over the orbit, m.
    pub fn amplitude(&self, i: usize) -> f64 {
        let x = &self.x[i];
        let (lo, hi) = x
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        0.5 * (hi - lo)
    }
}

/// The periodic orbit of `system` near the cycle its run from the declared initial state
/// settles onto within `settings.settle`, with the guess it started from.
pub fn shoot(
    system: &System,
    settings: &OrbitSettings,
) -> Result<(PeriodicOrbit, Guess), ScenarioError> {
    let run = settled_state(system, settings.settle)?;
    let problem = FrictionSystem::new(system, Switching::Event);
    let n = problem.dim() - problem.quadratures();
    let guess = guess_from_run(&run, n).map_err(|e| {
        ScenarioError::RunFailed(format!(
            "the run from the declared initial state to t = {} s settles onto no cycle with \
             switches to start from ({e}): a steady state, or a run too short to settle",
            settings.settle
        ))
    })?;
    let found = find_orbit(
        &problem,
        guess.t,
        (&guess.y, &guess.modes, guess.period),
        &settings.shooting,
    )?;
    Ok((found, guess))
}

/// The periodic orbit of `system` near the cycle its run settles onto ([`shoot`]), described.
pub fn periodic_orbit(system: &System, settings: &OrbitSettings) -> Result<Orbit, ScenarioError> {
    let (found, guess) = shoot(system, settings)?;
    let problem = FrictionSystem::new(system, Switching::Event);
    let t0 = found.t0;
    let segments = (found.flow.segments.iter())
        .map(|s| OrbitSegment {
            t0: s.t0 - t0,
            t1: s.t1 - t0,
            modes: s.modes.iter().map(|&m| mode_name(m)).collect(),
            ends_with: s.switch.as_ref().map(|w| w.name),
        })
        .collect();
    let sampled = sample(
        &problem,
        (t0, &found.y0, &found.modes0, found.period),
        settings.samples,
    )?;
    Ok(Orbit {
        period: found.period,
        guessed_period: guess.period,
        guessed_at: guess.t,
        residual: found.residual,
        iterations: found.iterations,
        floquet: found.floquet,
        segments,
        bodies: system.bodies.iter().map(|b| b.name.clone()).collect(),
        t: sampled.t,
        x: sampled.x,
        v: sampled.v,
    })
}

/// A case's problem at each value of one of its parameters: the case with the parameter set
/// ([`StudyCase::with_parameter`]), its system under event switching.
pub struct CaseFamily<'a> {
    /// The case.
    pub case: &'a dyn StudyCase,
    /// The parameter's name.
    pub parameter: &'a str,
}

impl CaseFamily<'_> {
    /// The case's system at `p`.
    pub fn system(&self, p: f64) -> Result<System, ScenarioError> {
        let case = self.case.with_parameter(self.parameter, p)?;
        case.system()?.ok_or_else(|| {
            ScenarioError::Invalid(format!(
                "{} imposes a motion on its contact: it has no body whose orbits to follow",
                self.case.describe()
            ))
        })
    }
}

impl Family for CaseFamily<'_> {
    fn with_problem(
        &self,
        p: f64,
        f: &mut dyn FnMut(&dyn OdeProblem) -> Result<(), OrbitError>,
    ) -> Result<(), OrbitError> {
        let system = self
            .system(p)
            .map_err(|e| OrbitError::Unsupported(e.to_string()))?;
        f(&FrictionSystem::new(&system, Switching::Event))
    }
}

/// A point of a branch as the files write it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BranchRow {
    /// `equilibrium` or `cycle`.
    pub kind: &'static str,
    /// The parameter's value.
    pub p: f64,
    /// Whether the row was computed at a value asked for (`--at`) rather than by a step of
    /// the continuation.
    pub at: bool,
    /// The period, s (none for an equilibrium).
    pub period: Option<f64>,
    /// Half the peak-to-peak displacement of the first body over the orbit, m (0 for an
    /// equilibrium).
    pub amplitude: f64,
    /// The Floquet multipliers (a cycle's, the trivial one first) or the eigenvalues (an
    /// equilibrium's), as (re, im).
    pub spectrum: Vec<(f64, f64)>,
    /// Whether it is asymptotically stable.
    pub stable: bool,
    /// The cycle's segments as the first contact's modes (`stick slip- stick`); empty for an
    /// equilibrium.
    pub segments: String,
}

/// The branches of a case over a parameter's range.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Branches {
    /// The parameter's name.
    pub parameter: String,
    /// Every computed point, equilibria first, each branch in the order it was followed.
    pub rows: Vec<BranchRow>,
    /// The special points, with the kind of branch they lie on.
    pub special: Vec<(&'static str, SpecialPoint)>,
    /// What was found and why a branch is missing or ended.
    pub notes: Vec<String>,
}

/// Follows the branches of `case` over `parameter` ∈ `range`, from its start `range.0`: the
/// cycle its run settles onto there ([`shoot`]) and, where every contact's surface moves, the
/// steady sliding (every body at rest, every contact slipping) by Newton from the run's end at
/// rest. Each value of `at` that a branch passes adds a row computed exactly there (Newton at
/// that value from the branch's two points around it).
pub fn follow(
    case: &dyn StudyCase,
    parameter: &str,
    (range, at): ((f64, f64), &[f64]),
    settings: &OrbitSettings,
) -> Result<Branches, ScenarioError> {
    let family = CaseFamily { case, parameter };
    let system = family.system(range.0)?;
    let options = ContinuationOptions {
        shooting: settings.shooting,
        ..ContinuationOptions::over(range)
    };
    let increasing = range.1 > range.0;
    let mut out = Branches {
        parameter: parameter.to_string(),
        rows: Vec::new(),
        special: Vec::new(),
        notes: Vec::new(),
    };
    // Steady sliding.
    match steady_sliding_guess(&system, settings.settle) {
        None => out.notes.push(
            "no steady sliding: a contact's surface is at rest (an equilibrium there is a \
             continuum of stuck states)"
                .into(),
        ),
        Some((y, modes)) => {
            match continue_equilibria(&family, range.0, (&y, &modes), increasing, &options) {
                Ok(branch) => {
                    out.notes.push(format!(
                        "equilibria: {} points; {}",
                        branch.points.len(),
                        branch.ended
                    ));
                    out.rows
                        .extend(branch.points.iter().map(|e| equilibrium_row(e, false)));
                    for (a, b, value) in bracketed(&branch.points, |e| e.p, at) {
                        let y: Vec<f64> = (a.y.iter().zip(&b.y))
                            .map(|(u, w)| u + (value - a.p) / (b.p - a.p) * (w - u))
                            .collect();
                        let e = equilibrium_at(&family, value, &y, &modes, &settings.shooting)?;
                        out.rows.push(equilibrium_row(&e, true));
                    }
                    out.special
                        .extend(branch.special.into_iter().map(|s| ("equilibrium", s)));
                }
                Err(e) => out
                    .notes
                    .push(format!("no steady sliding at the start: {e}")),
            }
        }
    }
    // Cycles.
    match shoot(&system, settings) {
        Err(e) => out.notes.push(format!("no cycle at the start: {e}")),
        Ok((found, _)) => {
            let modes = found.modes0.clone();
            let branch = continue_cycles(
                &family,
                range.0,
                (&found.y0, &modes, found.period),
                increasing,
                &options,
            )?;
            out.notes.push(format!(
                "cycles: {} points; {}",
                branch.points.len(),
                branch.ended
            ));
            for c in &branch.points {
                out.rows
                    .push(cycle_row(&family, c, &modes, (false, settings.samples))?);
            }
            for (a, b, value) in bracketed(&branch.points, |c| c.p, at) {
                let w = (value - a.p) / (b.p - a.p);
                let y: Vec<f64> = (a.y0.iter().zip(&b.y0))
                    .map(|(u, v)| u + w * (v - u))
                    .collect();
                let period = a.period + w * (b.period - a.period);
                let c = cycle_at(&family, value, (&y, &modes, period), &settings.shooting)?;
                out.rows
                    .push(cycle_row(&family, &c, &modes, (true, settings.samples))?);
            }
            out.special
                .extend(branch.special.into_iter().map(|s| ("cycle", s)));
        }
    }
    Ok(out)
}

/// For each value of `at`, the first two consecutive `points` whose parameters (`p`) bracket
/// it, and the value.
fn bracketed<'a, P>(
    points: &'a [P],
    p: impl Fn(&P) -> f64,
    at: &[f64],
) -> Vec<(&'a P, &'a P, f64)> {
    (at.iter())
        .filter_map(|&value| {
            points.windows(2).find_map(|w| {
                let (lo, hi) = (p(&w[0]).min(p(&w[1])), p(&w[0]).max(p(&w[1])));
                (lo <= value && value <= hi && lo < hi).then_some((&w[0], &w[1], value))
            })
        })
        .collect()
}

/// An equilibrium as a row (`at`: computed at a value asked for).
fn equilibrium_row(e: &EquilibriumPoint, at: bool) -> BranchRow {
    BranchRow {
        kind: "equilibrium",
        p: e.p,
        at,
        period: None,
        amplitude: 0.0,
        spectrum: e.eigenvalues.clone(),
        stable: e.stable,
        segments: String::new(),
    }
}

/// A cycle as a row, its amplitude from the orbit sampled at `samples` points.
fn cycle_row(
    family: &CaseFamily,
    c: &CyclePoint,
    modes: &[integrators::Mode],
    (at, samples): (bool, usize),
) -> Result<BranchRow, ScenarioError> {
    let system = family.system(c.p)?;
    let problem = FrictionSystem::new(&system, Switching::Event);
    let sampled = sample(&problem, (0.0, &c.y0, modes, c.period), samples)?;
    let first_contact = |modes: &[integrators::Mode]| modes.first().map_or("", |&m| mode_name(m));
    Ok(BranchRow {
        kind: "cycle",
        p: c.p,
        at,
        period: Some(c.period),
        amplitude: half_range(&sampled.x[0]),
        spectrum: c.floquet.multipliers.clone(),
        stable: c.floquet.stability == periodic::Stability::Stable,
        segments: (c.flow.segments.iter())
            .map(|s| first_contact(&s.modes))
            .collect::<Vec<_>>()
            .join(" "),
    })
}

/// Half the peak-to-peak of `x`.
fn half_range(x: &[f64]) -> f64 {
    let (lo, hi) = x
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    0.5 * (hi - lo)
}

/// The run of `system` from its declared state to `settle`, event-driven, tight.
fn settled_state(system: &System, settle: f64) -> Result<integrators::Solution, ScenarioError> {
    let options = Options::adaptive(0.0, settle, 1e-10, 1e-12);
    let run = simulate(system, Scheme::events(Solver::DOPRI5), options, &mut |_| {})?;
    match run.error {
        Some(error) => Err(ScenarioError::Solver {
            what: format!("the run that settles onto the cycle (to t = {settle} s)"),
            error,
        }),
        None => Ok(run.solution),
    }
}

/// A guess of the steady sliding of `system`: the end of its settling run with every body at
/// rest, every contact slipping against its surface; `None` where a surface is at rest.
fn steady_sliding_guess(
    system: &System,
    settle: f64,
) -> Option<(Vec<f64>, Vec<integrators::Mode>)> {
    use friction_systems::{SLIP_NEGATIVE, SLIP_POSITIVE};
    if system.contacts.iter().any(|c| c.surface_velocity == 0.0) {
        return None;
    }
    let run = settled_state(system, settle).ok()?;
    let (_, end) = run.last()?;
    let layout = friction_systems::Layout::of(system);
    let mut y = end.to_vec();
    for i in 0..system.bodies.len() {
        y[layout.v(i)] = 0.0;
    }
    // The body at rest slips against a surface moving forward: v_rel = −v_s.
    let modes = (system.contacts.iter())
        .map(|c| match c.surface_velocity > 0.0 {
            true => SLIP_NEGATIVE,
            false => SLIP_POSITIVE,
        })
        .collect();
    Some((y, modes))
}

/// An orbit sampled evenly over its period: the times from its start, each body's x and v.
struct Sampled {
    t: Vec<f64>,
    x: Vec<Vec<f64>>,
    v: Vec<Vec<f64>>,
}

/// The orbit of `problem` from (t0, y₀, modes₀) over its period, sampled at `samples` points
/// as the event-driven run integrates it.
fn sample(
    problem: &FrictionSystem,
    (t0, y0, modes0, period): (f64, &[f64], &[integrators::Mode], f64),
    samples: usize,
) -> Result<Sampled, ScenarioError> {
    let grid = integrators::even_grid(t0, t0 + period, samples.max(2));
    let options = Options {
        output: Output::GridOnly(grid),
        ..Options::adaptive(t0, t0 + period, 1e-12, 1e-14)
    };
    let s = Solver::DOPRI5
        .solve(problem, y0, modes0, options)
        .map_err(|f| ScenarioError::Solver {
            what: "the orbit's sampling".into(),
            error: f.error,
        })?;
    let layout = &problem.layout;
    let bodies = problem.system.bodies.len();
    let column = |index: usize| -> Vec<f64> { (0..s.len()).map(|k| s.y_at(k)[index]).collect() };
    Ok(Sampled {
        t: s.t.iter().map(|t| t - t0).collect(),
        x: (0..bodies).map(|i| column(layout.x[i])).collect(),
        v: (0..bodies).map(|i| column(layout.v(i))).collect(),
    })
}
