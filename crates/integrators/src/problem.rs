//! What a solver integrates: `M·y' = f(t, y, q)` with an optional analytic Jacobian, a
//! constant diagonal mass matrix (identity by default; zeros on the diagonal make a
//! semi-explicit index-1 DAE), a discrete state `q` (one [`Mode`] per component: for a
//! friction system, one per contact), and event functions with their actions.
//!
//! A hybrid problem has a fixed number of event functions `g_k(t, y, q)`, `k = 0..n_events`;
//! which of them are watched, and for which sign change, depends on the modes
//! ([`OdeProblem::event_spec`]). Every function whose root lies at the same instant is
//! handed to [`OdeProblem::on_events`] in one call, which may reset `y` and switch any modes.

use serde::Serialize;

/// One component of the discrete state of a hybrid system (for a friction contact:
/// `slip+`, `slip-`, `stick`). Problems without modes use one component `Mode(0)`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub struct Mode(pub u8);

/// Which sign changes of an event function count as events.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Crossing {
    /// From negative to positive.
    Rising,
    /// From positive to negative.
    Falling,
    /// Either way.
    Either,
}

impl Crossing {
    /// Whether going from `before` to `after` is a crossing in this direction (a value of
    /// exactly zero counts as having arrived).
    pub fn crossed(self, before: f64, after: f64) -> bool {
        let rising = before < 0.0 && after >= 0.0;
        let falling = before > 0.0 && after <= 0.0;
        match self {
            Crossing::Rising => rising,
            Crossing::Falling => falling,
            Crossing::Either => rising || falling,
        }
    }

    /// The side an event function is taken to be on when it starts at zero: just before
    /// the crossing it watches for (so that leaving zero the other way is a crossing at once).
    pub fn side_before(self) -> f64 {
        match self {
            Crossing::Rising => -1.0,
            Crossing::Falling | Crossing::Either => 1.0,
        }
    }
}

/// An event function as watched in the current modes: its name (as recorded) and the
/// crossing that triggers it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct EventSpec {
    /// Name recorded with each occurrence (e.g. `stick`, `break-away+`).
    pub name: &'static str,
    /// The sign change that triggers it.
    pub crossing: Crossing,
}

/// What the integration does after the event handler has run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Control {
    /// Go on, from the state and modes the handler left.
    Continue,
    /// End the integration at the event.
    Stop,
}

/// A Jacobian entry: row, column, value.
pub type Entry = (usize, usize, f64);

/// An initial value problem `M·y' = f(t, y, q)` with discrete modes `q` and events.
pub trait OdeProblem: Sync {
    /// Number of unknowns.
    fn dim(&self) -> usize;

    /// The right-hand side `dy = f(t, y, q)` in the modes `q`.
    fn rhs(&self, t: f64, y: &[f64], modes: &[Mode], dy: &mut [f64]);

    /// The analytic Jacobian ∂f/∂y as entries pushed onto `jac` (cleared by the caller; an
    /// entry repeated is summed); returns `false` when there is none, and the solvers use
    /// finite differences.
    fn jacobian(&self, _t: f64, _y: &[f64], _modes: &[Mode], _jac: &mut Vec<Entry>) -> bool {
        false
    }

    /// Number of quadratures: the last components of y, which no component of f reads and
    /// whose rows [`jacobian`](OdeProblem::jacobian) leaves out (energy accumulators,
    /// `y_q' = f_q(t, y)`). An implicit method judges Newton's convergence on the other
    /// components only and then sets these from the converged state, `y_q,k+1 = y_q,k +
    /// h·f_q(t_k+1, y_k+1)` for implicit Euler: with their rows left out, Newton's
    /// corrections of them are the whole change of f_q between iterates, which need not
    /// shrink from the first iterate to the second where the power varies fast within a step.
    fn quadratures(&self) -> usize {
        0
    }

    /// The diagonal of a constant mass matrix M; `None` for the identity.
    fn mass(&self) -> Option<&[f64]> {
        None
    }

    /// Number of event functions `g_k`, whatever the modes.
    fn n_events(&self) -> usize {
        0
    }

    /// How event function `index` is watched in `modes`; `None` when it is not watched there.
    fn event_spec(&self, _index: usize, _modes: &[Mode]) -> Option<EventSpec> {
        None
    }

    /// Value of event function `index` at (t, y) in `modes`.
    fn event(&self, _index: usize, _t: f64, _y: &[f64], _modes: &[Mode]) -> f64 {
        0.0
    }

    /// Handles the event functions `fired` (ascending), whose roots all lie at `t`: may reset
    /// `y`, may switch any of the `modes`, and says how to go on.
    fn on_events(&self, _fired: &[usize], _t: f64, _y: &mut [f64], _modes: &mut [Mode]) -> Control {
        Control::Stop
    }

    /// The shortest time scale of the problem, s (for a mechanical system, its shortest
    /// natural period): the chattering guard measures its window in it. `None` when the
    /// problem has none, and the guard's window is taken in seconds.
    fn time_scale(&self) -> Option<f64> {
        None
    }
}
