//! Moreau–Jean time-stepping (Moreau 1988; Jean 1999; Acary & Brogliato 2008, ch. 10;
//! Siconos's `MoreauJeanOSI`) for a friction [`crate::System`]: fixed steps, no event
//! located, every contact's friction impulse and mode found at the end of each step from its
//! set-valued law.
//!
//! One step from t_k to t_{k+1} = t_k + h, for every body i, with θ ∈ [1/2, 1]:
//!
//! ```text
//! m_i·(v_i' − v_i) = h·[θ·F_o,i(t_{k+1}, x', v') + (1−θ)·F_o,i(t_k, x, v)] − P_i
//! x_i'             = x_i + h·[θ·v_i' + (1−θ)·v_i]
//! z_i'             = z_i + h·[θ·g(x_i', u_i', z_i') + (1−θ)·g(x_i, u_i, z_i)]
//! ```
//!
//! with primes at t_{k+1}, `F_o` the springs, dampers and external forces, `u = v − v_s` and
//! `P_i` the friction impulse of the step. `F_o` is linear in (x, v), so eliminating x' leaves
//! one equation per body in the end velocities, `Ŵ·v' = b − P`, with
//! `Ŵ = M − h·θ·(C + h·θ·K)`: the pattern of the springs, symmetric, diagonally dominant.
//! Each contact's impulse obeys its set-valued law at the end of the step (the private module `local`):
//! at rest if the force that holds the body lies in the stick interval, otherwise sliding with
//! `P = h·F(u')`; a contact that slid the same way through the previous step and still does
//! has the θ-method on its friction too, `P = h·[θ·F(u') + (1−θ)·F(u)]` (identical for a
//! constant sliding force, as Coulomb's; second order at θ = 1/2 for a velocity-dependent one).
//!
//! The coupled problem is solved by nonsmooth Gauss–Seidel (Jean 1999; Acary & Brogliato
//! 2008, §13.4; Siconos's NSGS): each body's problem solved exactly with its neighbours'
//! velocities fixed, colour by colour (red–black on a chain: see `colour_order`), sweeping
//! until no velocity changes by more than
//! [`SWEEP_ATOL`]` + `[`SWEEP_RTOL`]`·|v|`; only the neighbours of a body that moved are
//! visited again. One sweep costs one pass over the springs and contacts: O(N) on a chain.
//! Where the coupling is stiff (h²θ²k ≳ m) Gauss–Seidel contracts slowly; after
//! [`CORRECT_AFTER`] sweeps each further sweep starts from Newton's correction of all the
//! velocities with the modes held (`correction`: a sparse symmetric solve, O(N) on a chain).
//!
//! The energy accumulators of [`crate::energy`] are the work of each step's impulses on the
//! mean velocity `(v + v')/2`; at θ = 1/2 the discrete balance then holds to rounding and to
//! the sweeps' tolerance (the scheme conserves what the system conserves; the sweeps leave
//! each body's momentum equation off by less than `Ŵ_i·(SWEEP_ATOL + SWEEP_RTOL·|v_i|)`), for
//! θ > 1/2 its residual is the scheme's own numerical dissipation. Points between step ends (a grid output) are linear interpolations.

mod contact_problem;
mod step;

use crate::hybrid::FrictionSystem;
use crate::local;
use crate::switching::{SLIP_NEGATIVE, STICK};
use crate::system::{System, SystemError};
use friction_models::params::show;
use friction_models::{Direction, FrictionModel, SignLaw};
use integrators::{EventRecord, Failure, Integrator, Mode, ModeSwitch, Options, Solution};
use step::TimeStepper;

/// Relative change of a velocity in one sweep below which Gauss–Seidel has converged (the
/// momentum residual it leaves is a coupling, at most h²θ²k, times this: far below rounding
/// of the balance).
pub const SWEEP_RTOL: f64 = 1e-12;
/// Absolute change of a velocity in one sweep below which Gauss–Seidel has converged, m/s.
pub const SWEEP_ATOL: f64 = 1e-14;
/// Most Gauss–Seidel sweeps in one step.
pub const MAX_SWEEPS: usize = 10_000;
/// Sweeps of a step after which every further sweep starts from Newton's correction of the
/// velocities (the private module `correction`, docs/timestepping.md), as long as each
/// correction leaves the sweep after it a smaller largest change than the one before. Weakly
/// coupled bodies (h²θ²k ≪ m: the chain's defaults) converge in fewer sweeps and never pay
/// for a factorisation.
pub const CORRECT_AFTER: usize = 3;

/// The scheme's name in solutions and summaries.
pub const NAME: &str = "moreau-jean";

/// A static law whose sliding force at v_rel = 0± lies outside its stick interval beyond
/// rounding: Moreau–Jean cannot time-step it ([`check_contacts`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlidingOutsideStick {
    /// The side of rest: `0+` or `0-`.
    pub side: &'static str,
    /// The sliding force there, N.
    pub force: f64,
    /// The stick interval at rest, N.
    pub interval: (f64, f64),
}

impl SlidingOutsideStick {
    /// Why the law cannot be time-stepped, and the least F_s that would mend a catalog law.
    pub fn describe(&self, model: &str) -> String {
        format!(
            "model `{model}`: its sliding force at v_rel = {}, {} N, lies outside its stick \
             interval [{}, {}] N; a holding force between them has neither rest nor sliding, \
             so time-stepping (Moreau-Jean) needs the sliding force at rest within the stick \
             interval: widen it (for the catalog's laws, F_s >= {})",
            self.side,
            show(self.force),
            show(self.interval.0),
            show(self.interval.1),
            show(self.force.abs())
        )
    }
}

/// Whether `model` is a static map that ignores x (`local::invariant_at_rest`) whose sliding
/// force at v_rel = 0± lies outside its stick interval beyond rounding (CS or CVS with F_s
/// below F_c + C1; static or Karnopp with F_s below F_c): a holding force between the
/// interval's bound and that sliding force has neither rest nor sliding as a solution.
pub fn sliding_outside_stick(model: &dyn FrictionModel) -> Option<SlidingOutsideStick> {
    if !local::invariant_at_rest(model) {
        return None;
    }
    let interval = model.stick_interval(0.0, &[]);
    [Direction::Positive, Direction::Negative]
        .into_iter()
        .find_map(|d| {
            let (force, _) = model.evaluate(0.0, 0.0, &[], SignLaw::Frozen(d), &mut [], &mut []);
            let (bound, beyond) = match d {
                Direction::Positive => (interval.upper, force > interval.upper),
                Direction::Negative => (interval.lower, force < interval.lower),
            };
            let rounding = 4.0 * f64::EPSILON * (force.abs() + bound.abs());
            (beyond && (force - bound).abs() > rounding).then_some(SlidingOutsideStick {
                side: if d == Direction::Positive { "0+" } else { "0-" },
                force,
                interval: (interval.lower, interval.upper),
            })
        })
}

/// Refuses, with a clear error, a contact the scheme cannot solve
/// ([`sliding_outside_stick`]): the step that meets its gap could only fail.
pub fn check_contacts(system: &System) -> Result<(), SystemError> {
    for (j, c) in system.contacts.iter().enumerate() {
        let model = c.model.as_ref();
        if let Some(outside) = sliding_outside_stick(model) {
            return Err(SystemError::Invalid {
                what: format!("[[contact]] {}", j + 1),
                why: format!(
                    "{}, or integrate it event-driven (event or regularized switching)",
                    outside.describe(model.name())
                ),
            });
        }
    }
    Ok(())
}

/// Moreau–Jean time-stepping with weight θ of the end of the step on the smooth forces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MoreauJean {
    /// θ ∈ [1/2, 1]: 1/2 the trapezoidal rule (second order, energy-conserving), 1 implicit
    /// Euler (first order, dissipative).
    pub theta: f64,
}

impl MoreauJean {
    /// The allowed range of θ, as messages print it.
    pub const THETA_RANGE: &'static str = "[0.5, 1]";

    /// Integrates `problem` (built with [`Switching::Event`](crate::Switching)'s modes, as
    /// [`crate::Scheme::TimeStepping`] builds it) from `y0` in `modes0` with the fixed step
    /// of `options`, telling `observe` the time after every step but the last. The steps run on
    /// the driver of every method ([`Integrator`]: its step cap, time limit, interrupt and
    /// output), which locates no event for this method: it settles each contact's mode at the
    /// end of every step (`TimeStepper`). A failure keeps everything recorded before it.
    pub fn solve(
        &self,
        problem: &FrictionSystem,
        y0: &[f64],
        modes0: &[Mode],
        options: &Options,
        observe: &mut dyn FnMut(f64),
    ) -> Result<Solution, Failure> {
        let failed = |error| Failure {
            error,
            solution: Box::new(Solution::new(NAME, y0.len(), modes0.len())),
        };
        let stepper = TimeStepper::new(problem, self.theta, options, y0, modes0).map_err(failed)?;
        Integrator::new(problem, Box::new(stepper), y0, modes0, options.clone())
            .map_err(failed)?
            .solve_observed(observe)
    }

    /// The scheme's one-step map: the state one step h after (t, y) in `modes`, the scheme
    /// started afresh there (each controller's force held at its value at t); `None` where the
    /// step's contact problem does not converge.
    pub fn step_map(
        &self,
        problem: &FrictionSystem,
        (t, h): (f64, f64),
        y: &[f64],
        modes: &[Mode],
    ) -> Option<Vec<f64>> {
        TimeStepper::one_step(problem, self.theta, (t, h), y, modes).ok()
    }
}

/// A step's switches as an event record with the names of event switching: `v_rel=0` for a
/// contact that came to rest or reversed, `break-away±` for one that left rest.
fn event_record(t: f64, switches: Vec<ModeSwitch>) -> EventRecord {
    let (fired, names) = switches
        .iter()
        .map(|s| match (s.from, s.to) {
            (STICK, SLIP_NEGATIVE) => (2 * s.component + 1, "break-away-"),
            (STICK, _) => (2 * s.component, "break-away+"),
            _ => (2 * s.component, "v_rel=0"),
        })
        .unzip();
    EventRecord {
        t,
        fired,
        names,
        switches,
    }
}
