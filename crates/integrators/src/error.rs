//! Why a solver stopped short: each error says where (t, h) and why.

use thiserror::Error;

/// A time as the messages show it: positional between 1e-3 and 1e6, with an exponent outside
/// (the rule of `friction_models::params::show`; this crate depends on no other of ours).
pub(crate) fn shown(t: &f64) -> String {
    if t.is_finite() && *t != 0.0 && !(1e-3..1e6).contains(&t.abs()) {
        format!("{t:e}")
    } else {
        t.to_string()
    }
}

/// A failed integration. The solution computed up to the failure is kept by the caller
/// (see [`crate::Failure`]).
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SolverError {
    /// The step size fell below what the floating-point time can resolve.
    #[error("step size underflow at t = {}: h = {h:e} is below the resolution of t", shown(.t))]
    StepSizeUnderflow {
        /// Time reached.
        t: f64,
        /// The step size that was too small.
        h: f64,
    },
    /// More steps than allowed.
    #[error("too many steps: {max} steps taken by t = {} (h = {h:e}) without reaching the end", shown(.t))]
    TooManySteps {
        /// Time reached.
        t: f64,
        /// Current step size.
        h: f64,
        /// The limit.
        max: usize,
    },
    /// The wall-clock limit was reached.
    #[error("time limit: {limit} s of wall time used by t = {} without reaching the end", shown(.t))]
    TimeLimit {
        /// Time reached.
        t: f64,
        /// The limit, s.
        limit: f64,
    },
    /// A stop was requested from outside ([`crate::interrupt`]: Ctrl-C in the Python package).
    #[error("interrupted at t = {}", shown(.t))]
    Interrupted {
        /// Time reached.
        t: f64,
    },
    /// Newton's iteration failed even after the step was cut repeatedly.
    #[error(
        "Newton iteration diverged at t = {} with h = {h:e} after {cuts} step-size cuts: {why}", shown(.t)
    )]
    NewtonDivergence {
        /// Time of the step's start.
        t: f64,
        /// The last step size tried.
        h: f64,
        /// How many times the step was cut.
        cuts: usize,
        /// What was seen (contraction factor, iteration count).
        why: String,
    },
    /// The iteration matrix could not be factorised.
    #[error("singular iteration matrix at t = {} with h = {h:e}", shown(.t))]
    SingularMatrix {
        /// Time of the step's start.
        t: f64,
        /// Step size.
        h: f64,
    },
    /// A NaN or infinity appeared in the state.
    #[error("non-finite state at t = {} (h = {h:e}): {what}", shown(.t))]
    NonFinite {
        /// Time of the step's start.
        t: f64,
        /// Step size.
        h: f64,
        /// Which quantity.
        what: String,
    },
    /// The state grew beyond a bound the problem's own scales set (found by the caller that
    /// knows the problem, after the solver ended: `friction_systems::Reach`): the
    /// integration, not the problem, made the motion.
    #[error("at t = {} {what}", shown(.t))]
    Runaway {
        /// Time of the first recorded state beyond the bound.
        t: f64,
        /// Which quantity, its value and the bound.
        what: String,
    },
    /// A failure reported by another process, as its message: a part of a study made
    /// elsewhere (a Dask worker) and merged, whose failure travelled as text.
    #[error("{message}")]
    Reported {
        /// The failure's message as it was reported.
        message: String,
    },
    /// Events accumulate: too many in too short a time (chattering or a Zeno point).
    #[error("too many events: {count} events within {window:e} s before t = {} (chattering or Zeno behaviour); last event: {last}", shown(.t))]
    TooManyEvents {
        /// Time of the last event.
        t: f64,
        /// Events counted in the window.
        count: usize,
        /// Length of the window, s.
        window: f64,
        /// Name of the last event.
        last: String,
    },
    /// An option outside its range.
    #[error("invalid option `{name}` = {}: allowed {allowed}", shown(.value))]
    InvalidOption {
        /// Option name.
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// Allowed range.
        allowed: &'static str,
    },
    /// The end time lies before the start.
    #[error("t_end = {t_end} lies before t0 = {t0}: integration runs forward in time")]
    EndBeforeStart {
        /// Start time.
        t0: f64,
        /// End time.
        t_end: f64,
    },
    /// A solver that cannot take the problem (an explicit method and a singular mass matrix).
    #[error("{solver} cannot integrate this problem: {why}")]
    Unsupported {
        /// The solver.
        solver: &'static str,
        /// Why.
        why: String,
    },
    /// The contact problem of a time step (the set-valued friction laws with the momentum
    /// balance) was not solved.
    #[error("contact problem of the step at t = {} (h = {h:e}) not solved: {why}", shown(.t))]
    ContactProblem {
        /// Time of the step's start.
        t: f64,
        /// Step size.
        h: f64,
        /// What failed, and at which contact.
        why: String,
    },
    /// diffsol reported an error.
    #[error("diffsol {solver} failed at t = {}: {message}", shown(.t))]
    Diffsol {
        /// Which diffsol method.
        solver: &'static str,
        /// Time reached.
        t: f64,
        /// diffsol's message.
        message: String,
    },
}
