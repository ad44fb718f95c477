//! What a solver integrates: `M·y' = f(t, y)` with an optional analytic Jacobian, a constant
//! diagonal mass matrix (identity by default; zeros on the diagonal make a semi-explicit
//! index-1 DAE), a discrete mode, and event functions with their actions.

use serde::Serialize;

/// A discrete mode of a hybrid system (for friction: `slip+`, `slip-`, `stick`). Problems
/// without modes use `Mode(0)` throughout.
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

/// An event function g(t, y) of one mode: its name (as recorded) and the crossing watched.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct EventSpec {
    /// Name recorded with each occurrence (e.g. `stick`, `break-away+`).
    pub name: &'static str,
    /// The sign change that triggers it.
    pub crossing: Crossing,
}

/// What the integration does after an event handler has run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Control {
    /// Go on in the same mode (from the state the handler left, which it may have reset).
    Continue,
    /// Go on in another mode (from the state the handler left).
    Switch(Mode),
    /// End the integration at the event.
    Stop,
}

/// A Jacobian entry: row, column, value.
pub type Entry = (usize, usize, f64);

/// An initial value problem `M·y' = f(t, y)` with modes and events.
pub trait OdeProblem: Sync {
    /// Number of unknowns.
    fn dim(&self) -> usize;

    /// The right-hand side `dy = f(t, y)` in `mode`.
    fn rhs(&self, t: f64, y: &[f64], mode: Mode, dy: &mut [f64]);

    /// The analytic Jacobian ∂f/∂y as entries pushed onto `jac` (cleared by the caller);
    /// returns `false` when there is none, and the solvers use finite differences.
    fn jacobian(&self, _t: f64, _y: &[f64], _mode: Mode, _jac: &mut Vec<Entry>) -> bool {
        false
    }

    /// The diagonal of a constant mass matrix M; `None` for the identity.
    fn mass(&self) -> Option<&[f64]> {
        None
    }

    /// The event functions watched in `mode`.
    fn events(&self, _mode: Mode) -> &[EventSpec] {
        &[]
    }

    /// Value of event function `index` of `mode` at (t, y).
    fn event(&self, _index: usize, _t: f64, _y: &[f64], _mode: Mode) -> f64 {
        0.0
    }

    /// Handles event `index` of `mode` at time `t`: may reset `y`, and says how to go on.
    fn on_event(&self, _index: usize, _t: f64, _y: &mut [f64], _mode: Mode) -> Control {
        Control::Stop
    }
}
