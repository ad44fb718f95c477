//! Where the belt rig sticks and slips: the stick–slip map over belt speed × stiffness, the
//! linear stability boundary of steady sliding drawn over it, and the bifurcation diagram of
//! the settled oscillation against belt speed from rest and from steady sliding.
//!
//! Steady sliding: the body at rest, v_rel = −v_b, held at `x_s = −F(−v_b)/k`. Linearised,
//! `m·δẍ + (c + F'(−v_b))·δẋ + k·δx = 0`: steady sliding is unstable where the effective
//! damping `c + dF/dv` at v = −v_b is negative (a falling friction branch stronger than the
//! damper), whatever k and m. Where it is stable, stick–slip from rest can still coexist with
//! it (a subcritical Hopf bifurcation): the two initial states of the bifurcation diagram show
//! where.

use crate::analysis::closed_loop::ClosedLoop;
use crate::analysis::settled::{Settled, Trace};
use crate::error::ScenarioError;
use crate::run::{Limits, Outcome, RunSpec};
use crate::scenario::Scenario;
use crate::spans::run_until;
use friction_models::{steady, Direction, FrictionModel, SignLaw};
use friction_models::{FrictionParams, ModelId};
use friction_systems::Scheme;
use integrators::{Solver, StepControl};
use rayon::prelude::*;
use serde::Serialize;

/// The belt with `model` at `friction` as the map and the diagram run it: 40 s (the last half
/// measured), event switching, Dormand–Prince at rtol 1e-8, 4001 output points.
pub fn belt_run(model: ModelId, friction: &FrictionParams) -> RunSpec {
    RunSpec {
        scenario: Scenario::BELT,
        law: model.into(),
        friction: *friction,
        params: Scenario::BELT.defaults(),
        scheme: Scheme::events(Solver::DOPRI5),
        step: StepControl::Adaptive {
            rtol: 1e-8,
            atol: 1e-10,
            h0: None,
        },
        t_end: Some(40.0),
        output_points: 4001,
        limits: Limits::default(),
    }
}

/// Stick phases per cycle from which a settled run counts as stick–slip.
pub const STICK_SLIP_THRESHOLD: f64 = 0.5;

/// A velocity amplitude (relative to the belt speed) below which the settled state counts as
/// steady sliding.
pub const STEADY_AMPLITUDE: f64 = 1e-6;

/// The settled state of the belt at one point.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub enum Regime {
    /// Sustained stick–slip: at least [`STICK_SLIP_THRESHOLD`] stick phases per cycle.
    StickSlip,
    /// A sustained oscillation that never sticks.
    Oscillation,
    /// Stuck all along: carried by the belt through the whole window (a cycle longer than
    /// the run), or a closed loop's body that never moved off its reference.
    Stuck,
    /// Steady sliding: no oscillation left (a velocity amplitude below
    /// [`STEADY_AMPLITUDE`] of the belt speed).
    SteadySliding,
    /// Not settled ([`Settled::settled`]): an oscillation still growing or dying out, or a
    /// first stick phase that fills half the window. A transient is no regime.
    Unsettled,
    /// A closed loop's limit cycle around its reference ([`ClosedLoop::hunting`]).
    Hunting,
    /// A closed loop at rest at its set point.
    Converged,
    /// A closed loop at rest off its set point after it moved: the friction holds the body
    /// within the dead zone |e| ≤ F_s/k_p of a loop without integral action.
    DeadZone,
}

impl Regime {
    /// The regime of a run on a belt at `v_belt`: carried by the belt, at rest relative to
    /// it, not settled, or by its stick phases per cycle.
    pub fn of(s: &Settled, v_belt: f64) -> Regime {
        let carried = s.v_amplitude <= 1e-12 * v_belt.abs().max(1.0)
            && (s.v_mean - v_belt).abs() <= 1e-9 * v_belt.abs().max(1.0);
        if carried {
            Regime::Stuck
        } else if s.v_amplitude <= STEADY_AMPLITUDE * v_belt.abs().max(1e-3) {
            Regime::SteadySliding
        } else if !s.settled {
            Regime::Unsettled
        } else if s.stick_per_cycle >= STICK_SLIP_THRESHOLD {
            Regime::StickSlip
        } else {
            Regime::Oscillation
        }
    }

    /// The regime of a closed loop ([`ClosedLoop`]): hunting; at rest at its set point
    /// (converged), off it after moving (dead zone) or without ever moving (stuck); or not
    /// settled.
    pub fn of_closed_loop(c: &ClosedLoop) -> Regime {
        match c.hunting {
            Some(true) => Regime::Hunting,
            Some(false) if c.stuck => Regime::Stuck,
            Some(false) if c.off_reference() => Regime::DeadZone,
            Some(false) => Regime::Converged,
            None => Regime::Unsettled,
        }
    }

    /// Whether a longer run could change it: a transient, or a first stick phase longer than
    /// the run.
    pub fn is_transient(self) -> bool {
        matches!(self, Regime::Unsettled | Regime::Stuck)
    }
}

/// dF/dv of steady sliding at v_rel = −v_b (the slope of the friction curve there, with the
/// internal state at its steady value).
pub fn sliding_slope(model: &dyn FrictionModel, v_belt: f64) -> f64 {
    steady::slope(model, -v_belt, SignLaw::Frozen(Direction::Negative))
}

/// `n` values from `lo` to `hi` (both > 0), evenly spaced in log.
pub fn log_space(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| (lo.ln() + (hi.ln() - lo.ln()) * i as f64 / (n - 1) as f64).exp())
        .collect()
}

/// The belt speeds in `[lo, hi]` where `c + dF/dv` changes sign (the linear stability
/// boundary of steady sliding), located by bisection between `n` log-spaced samples.
pub fn stability_boundary(
    model: &dyn FrictionModel,
    c: f64,
    lo: f64,
    hi: f64,
    n: usize,
) -> Vec<f64> {
    let g = |v: f64| c + sliding_slope(model, v);
    let samples = log_space(lo, hi, n);
    samples
        .windows(2)
        .filter(|w| g(w[0]).signum() != g(w[1]).signum())
        .map(|w| {
            let (mut a, mut b) = (w[0], w[1]);
            for _ in 0..100 {
                let m = 0.5 * (a + b);
                if g(m).signum() == g(a).signum() {
                    a = m;
                } else {
                    b = m;
                }
            }
            0.5 * (a + b)
        })
        .collect()
}

/// One run of the map.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct MapPoint {
    /// Belt speed, m/s.
    pub v_belt: f64,
    /// Spring stiffness, N/m.
    pub k: f64,
    /// Its settled state.
    pub settled: Settled,
    /// Its regime.
    pub regime: Regime,
    /// Whether linear theory calls steady sliding unstable there (c + dF/dv < 0).
    pub linearly_unstable: bool,
}

/// Where the belt's body starts to follow steady sliding (at rest, v0 = 0, the belt under it
/// at `v_belt`): the equilibrium of the spring `k` against the steady friction force at
/// v_rel = −v_belt, x_s = −F(−v_belt)/k, moved by 1e-6 of itself so that an unstable
/// equilibrium is left rather than kept by exact arithmetic.
pub fn sliding_start(model: &dyn FrictionModel, v_belt: f64, k: f64) -> f64 {
    let force = steady::force(model, -v_belt, SignLaw::Frozen(Direction::Negative));
    -force / k * (1.0 + 1e-6)
}

fn belt_spec(base: &RunSpec, v_belt: f64, k: f64, x0: f64) -> RunSpec {
    let mut spec = base.clone();
    spec.scenario = Scenario::BELT;
    spec.params.v_belt = v_belt;
    spec.params.k = k;
    spec.params.x0 = x0;
    spec.params.v0 = 0.0;
    spec
}

/// The settled state of the belt run `spec` over the last `settle` of its span, which is
/// doubled while the run has not settled ([`Regime::is_transient`]; [`run_until`]).
fn settled(spec: &RunSpec, settle: f64) -> Result<Settled, ScenarioError> {
    let measured = |o: &Outcome| Settled::of(&Trace::of_outcome(o), settle);
    let o = run_until(spec, &mut |o| {
        o.error.is_some() || !Regime::of(&measured(o), spec.params.v_belt).is_transient()
    })?;
    if let Some(error) = o.error {
        return Err(ScenarioError::Solver {
            what: format!(
                "the belt at v_belt = {}, k = {}",
                spec.params.v_belt, spec.params.k
            ),
            error,
        });
    }
    Ok(measured(&o))
}

/// The map over `v_belts` × `ks` from rest (the base's other parameters), in parallel, rows
/// in grid order (v_belt slowest); `progress` is called after each point.
pub fn map(
    base: &RunSpec,
    v_belts: &[f64],
    ks: &[f64],
    settle: f64,
    progress: &(dyn Fn() + Sync),
) -> Result<Vec<MapPoint>, ScenarioError> {
    let model = base.law.build(&base.friction)?;
    let points: Vec<(f64, f64)> = v_belts
        .iter()
        .flat_map(|&v| ks.iter().map(move |&k| (v, k)))
        .collect();
    points
        .par_iter()
        .map(|&(v_belt, k)| {
            let s = settled(&belt_spec(base, v_belt, k, 0.0), settle)?;
            progress();
            Ok(MapPoint {
                v_belt,
                k,
                settled: s,
                regime: Regime::of(&s, v_belt),
                linearly_unstable: base.params.c + sliding_slope(model.as_ref(), v_belt) < 0.0,
            })
        })
        .collect()
}

/// One belt speed of the bifurcation diagram: the settled state from rest and from steady
/// sliding (displaced by 1e-6 of its deflection, so that an unstable equilibrium is left).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Branches {
    /// Belt speed, m/s.
    pub v_belt: f64,
    /// From rest (x0 = 0).
    pub from_rest: Settled,
    /// From steady sliding.
    pub from_sliding: Settled,
}

/// The bifurcation diagram at the base's k, in parallel; `progress` is called after each run
/// (two a belt speed).
pub fn bifurcation(
    base: &RunSpec,
    v_belts: &[f64],
    settle: f64,
    progress: &(dyn Fn() + Sync),
) -> Result<Vec<Branches>, ScenarioError> {
    let model = base.law.build(&base.friction)?;
    let k = base.params.k;
    v_belts
        .par_iter()
        .map(|&v_belt| {
            let x_s = sliding_start(model.as_ref(), v_belt, k);
            let from = |x0: f64| {
                let s = settled(&belt_spec(base, v_belt, k, x0), settle);
                progress();
                s
            };
            let (from_rest, from_sliding) = rayon::join(|| from(0.0), || from(x_s));
            Ok(Branches {
                v_belt,
                from_rest: from_rest?,
                from_sliding: from_sliding?,
            })
        })
        .collect()
}
