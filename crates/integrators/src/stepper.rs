//! The interface every one-step method implements, and the problem as a method sees it.

use crate::error::SolverError;
use crate::options::Options;
use crate::problem::{Mode, OdeProblem};
use crate::solution::{EventRecord, MethodSwitch};
use crate::stats::Stats;

/// The problem in fixed modes, as the methods see it.
#[derive(Clone, Copy)]
pub struct Ode<'a> {
    /// The problem.
    pub problem: &'a dyn OdeProblem,
    /// The modes the right-hand side is evaluated in.
    pub modes: &'a [Mode],
}

impl Ode<'_> {
    /// `dy = f(t, y)`, counted in `stats`.
    pub fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64], stats: &mut Stats) {
        stats.rhs_evals += 1;
        self.problem.rhs(t, y, self.modes, dy);
    }

    /// `dy = M⁻¹·f(t, y)` for explicit methods, counted in `stats`; `M` must be regular.
    pub fn explicit_rhs(&self, t: f64, y: &[f64], dy: &mut [f64], stats: &mut Stats) {
        self.rhs(t, y, dy, stats);
        if let Some(mass) = self.problem.mass() {
            dy.iter_mut().zip(mass).for_each(|(d, m)| *d /= m);
        }
    }

    /// Rejects a singular mass matrix for a method that needs `M⁻¹`.
    pub fn require_regular_mass(&self, solver: &'static str) -> Result<(), SolverError> {
        match self.problem.mass() {
            Some(mass) if mass.contains(&0.0) => Err(SolverError::Unsupported {
                solver,
                why: "an explicit method needs a regular mass matrix, and this one has zeros \
                      on its diagonal (a DAE): use implicit-euler or bdf"
                    .into(),
            }),
            _ => Ok(()),
        }
    }
}

/// Where a one-step method stands after an accepted step, as diffsol's `OdeSolverState`:
/// the step `[t_prev, t]` just taken, the state `y(t)`, and the step size `h` it would try
/// next. A method keeps one and updates it as it steps; the driver reads it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StepperState {
    /// Start of the last accepted step.
    pub t_prev: f64,
    /// Current time (end of the last accepted step).
    pub t: f64,
    /// Current state.
    pub y: Vec<f64>,
    /// The step size the method would try next.
    pub h: f64,
}

impl StepperState {
    /// At rest at t = 0 with `dim` unknowns, zero, and no step size yet.
    pub fn new(dim: usize) -> Self {
        StepperState {
            y: vec![0.0; dim],
            ..StepperState::default()
        }
    }
}

/// A one-step method, driven step by step by [`crate::Integrator`].
pub trait Stepper {
    /// The method's name as the command line takes it.
    fn name(&self) -> &'static str;

    /// (Re)starts at (t, y) in the given modes: any stage reused across steps (FSAL), any
    /// history and any Jacobian are forgotten.
    fn start(&mut self, ode: &Ode, t: f64, y: &[f64]) -> Result<(), SolverError>;

    /// Takes one accepted step ending at or before `t_stop` (landing on it exactly when it
    /// is within reach). Rejected attempts are retried inside and counted.
    fn step(&mut self, ode: &Ode, t_stop: f64) -> Result<(), SolverError>;

    /// Where the method stands: the last accepted step, the state at its end, the next step
    /// size.
    fn state(&self) -> &StepperState;

    /// The method's dense output at `t` in `[t_prev, t]`.
    fn dense_output(&self, t: f64, y: &mut [f64]);

    /// Work done so far.
    fn stats(&self) -> Stats;

    /// Where a stiffness test (Hairer's, in Dormand–Prince) first found the problem stiff.
    fn stiffness_detected_at(&self) -> Option<f64> {
        None
    }

    /// The switches of method within the run so far (`auto`; none for a single method).
    fn method_switches(&self) -> &[MethodSwitch] {
        &[]
    }

    /// Whether the driver locates the problem's events on the method's dense output and
    /// applies their actions: true for every method but one that settles the modes itself at
    /// the end of each step (time-stepping, which locates no event).
    fn locates_events(&self) -> bool {
        true
    }

    /// A method that settles the modes itself: the switches of its last step, as an event
    /// record at the step's end, taken once (`None` when it switched nothing, and always for
    /// the methods whose events the driver locates). Its [`Stepper::stats`] then count the
    /// steps that switched as its events.
    fn take_switches(&mut self) -> Option<EventRecord> {
        None
    }

    /// The modes reported at an output point strictly inside the last step, whose modes were
    /// `before` at its start and `after` at its end: `before` by default (a located event
    /// ends the step, so the modes hold through it).
    fn modes_inside(&self, before: &[Mode], after: &[Mode], out: &mut [Mode]) {
        let _ = after;
        out.copy_from_slice(before);
    }

    /// A copy of the method as it stands, for [`crate::Integrator::extend`] to continue the
    /// run from; `None` (the default) for a method that cannot be copied, whose runs are then
    /// extended by running them again from the start.
    fn copy(&self) -> Option<Box<dyn Stepper>> {
        None
    }

    /// Whether the next step may read where the run ends, `t_stop`: be shortened to land on
    /// it, or size a step by it. The driver of a run that may be extended keeps a
    /// [`Stepper::copy`] before every such step. True by default.
    fn may_read_end(&self, t_stop: f64) -> bool {
        let _ = t_stop;
        true
    }

    /// Readies a copy to continue the run to a later end under `options` (its largest step
    /// and step cap taken over): `false` where a step taken so far read the old end (was
    /// shortened to it, or bounded by a largest step that was the old span), so that a run from
    /// the start to the later end would have stepped otherwise. False by default.
    fn resume(&mut self, options: &Options) -> bool {
        let _ = options;
        false
    }
}

/// `Σ ((e_i / (atol + rtol·max(|a_i|, |b_i|)))²) / n` square-rooted: the weighted RMS norm
/// of Hairer's codes (`dopri5.f`, error estimation).
pub fn wrms(e: &[f64], a: &[f64], b: &[f64], rtol: f64, atol: f64) -> f64 {
    let sum: f64 = e
        .iter()
        .zip(a.iter().zip(b))
        .map(|(e, (a, b))| {
            let sk = atol + rtol * a.abs().max(b.abs());
            (e / sk).powi(2)
        })
        .sum();
    (sum / e.len() as f64).sqrt()
}

/// Where the next fixed step of size `h` ends: the grid point `t_start + k·h` after `t`,
/// or `t_stop` when that lies closer than a relative `1e-10·h` beyond it (so the last step
/// is shortened, never overshot, and never followed by a sliver).
pub fn next_grid_point(t_start: f64, h: f64, t: f64, t_stop: f64) -> f64 {
    let k = ((t - t_start) / h).round() + 1.0;
    let candidate = t_start + k * h;
    if candidate >= t_stop - 1e-10 * h {
        t_stop
    } else {
        candidate
    }
}

/// Checks that every component of `y` is finite.
pub fn check_finite(y: &[f64], t: f64, h: f64, what: &str) -> Result<(), SolverError> {
    match y.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(SolverError::NonFinite {
            t,
            h,
            what: format!("{what}, component {i} = {}", y[i]),
        }),
    }
}

/// The unit round-off dopri5.f assumes (UROUND, WORK(1)); the step-size underflow test of
/// every adaptive method here uses it.
pub const UROUND: f64 = 2.3e-16;

/// The checks every adaptive step attempt makes first (DOPCOR of dopri5.f): no more than
/// `max_steps` attempts, and a step size that t can still resolve ([`check_step_size`]).
pub fn check_limits(attempts: usize, max_steps: usize, t: f64, h: f64) -> Result<(), SolverError> {
    if attempts > max_steps {
        return Err(SolverError::TooManySteps {
            t,
            h,
            max: max_steps,
        });
    }
    check_step_size(t, h)
}

/// dopri5.f's floor of the step size, relative to t: `0.1·|h| > UROUND·|t|`, else
/// [`SolverError::StepSizeUnderflow`].
pub fn check_step_size(t: f64, h: f64) -> Result<(), SolverError> {
    if 0.1 * h.abs() <= t.abs() * UROUND {
        return Err(SolverError::StepSizeUnderflow { t, h });
    }
    Ok(())
}

/// The linear interpolant between (t0, y0) and (t1, y1), at t.
pub fn linear_interpolation(t0: f64, y0: &[f64], t1: f64, y1: &[f64], t: f64, out: &mut [f64]) {
    let h = t1 - t0;
    let th = if h == 0.0 { 1.0 } else { (t - t0) / h };
    for (i, o) in out.iter_mut().enumerate() {
        *o = y0[i] + th * (y1[i] - y0[i]);
    }
}

/// The cubic Hermite interpolant of (t0, y0, f0) and (t1, y1, f1) at t (Hairer, Nørsett,
/// Wanner, *Solving ODEs I*, sec. II.6, eq. (6.7)), with θ = (t − t0)/h, h = t1 − t0:
/// `u(θ) = (1−θ)·y0 + θ·y1 + θ(θ−1)·((1−2θ)(y1−y0) + (θ−1)·h·f0 + θ·h·f1)`; y1 when h = 0.
/// The dense output of third order of any method that knows f at both ends of its step.
pub fn hermite_cubic(
    (t0, y0, f0): (f64, &[f64], &[f64]),
    (t1, y1, f1): (f64, &[f64], &[f64]),
    t: f64,
    out: &mut [f64],
) {
    let h = t1 - t0;
    if h == 0.0 {
        out.copy_from_slice(y1);
        return;
    }
    let th = (t - t0) / h;
    for (i, o) in out.iter_mut().enumerate() {
        let (a, b) = (y0[i], y1[i]);
        *o = (1.0 - th) * a
            + th * b
            + th * (th - 1.0)
                * ((1.0 - 2.0 * th) * (b - a) + (th - 1.0) * h * f0[i] + th * h * f1[i]);
    }
}
