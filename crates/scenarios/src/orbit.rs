//! The periodic orbit of a rig's body or of a system, found by shooting on the hybrid system
//! with events at v_rel = 0 ([`periodic`]): a run from the declared initial state settles onto
//! its cycle, the recurrence of its switches gives the guess (period, and a state in the
//! middle of the cycle's longest smooth segment), and Newton on (y₀, T) closes the orbit to a
//! residual of 1e-10 of its scale. Its Floquet multipliers, through the saltation matrices of
//! its switches, give its stability.

use crate::error::ScenarioError;
use friction_systems::{mode_name, simulate, FrictionSystem, Scheme, Switching, System};
use integrators::{OdeProblem, Options, Output, Solver};
use periodic::{find_orbit, guess_from_run, Floquet, ShootingOptions};
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
/// settles onto within `settings.settle`.
pub fn periodic_orbit(system: &System, settings: &OrbitSettings) -> Result<Orbit, ScenarioError> {
    let scheme = Scheme::events(Solver::DOPRI5);
    let settle = Options::adaptive(0.0, settings.settle, 1e-10, 1e-12);
    let run = simulate(system, scheme, settle, &mut |_| {})?;
    if let Some(error) = run.error {
        return Err(ScenarioError::Solver {
            what: format!(
                "the run that settles onto the cycle (to t = {} s)",
                settings.settle
            ),
            error,
        });
    }
    let problem = FrictionSystem::new(system, Switching::Event);
    let n = problem.dim() - problem.quadratures();
    let guess = guess_from_run(&run.solution, n).map_err(|e| {
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
    let t0 = found.t0;
    let segments = (found.flow.segments.iter())
        .map(|s| OrbitSegment {
            t0: s.t0 - t0,
            t1: s.t1 - t0,
            modes: s.modes.iter().map(|&m| mode_name(m)).collect(),
            ends_with: s.switch.as_ref().map(|w| w.name),
        })
        .collect();
    // The orbit sampled, from its start, as the event-driven run integrates it.
    let grid = integrators::even_grid(t0, t0 + found.period, settings.samples.max(2));
    let sampling = Options {
        output: Output::GridOnly(grid),
        ..Options::adaptive(t0, t0 + found.period, 1e-12, 1e-14)
    };
    let sampled = Solver::DOPRI5
        .solve(&problem, &found.y0, &found.modes0, sampling)
        .map_err(|f| ScenarioError::Solver {
            what: "the orbit's sampling".into(),
            error: f.error,
        })?;
    let layout = &problem.layout;
    let column =
        |index: usize| -> Vec<f64> { (0..sampled.len()).map(|k| sampled.y_at(k)[index]).collect() };
    Ok(Orbit {
        period: found.period,
        guessed_period: guess.period,
        guessed_at: guess.t,
        residual: found.residual,
        iterations: found.iterations,
        floquet: found.floquet,
        segments,
        bodies: system.bodies.iter().map(|b| b.name.clone()).collect(),
        t: sampled.t.iter().map(|t| t - t0).collect(),
        x: (0..system.bodies.len())
            .map(|i| column(layout.x[i]))
            .collect(),
        v: (0..system.bodies.len())
            .map(|i| column(layout.v(i)))
            .collect(),
    })
}
