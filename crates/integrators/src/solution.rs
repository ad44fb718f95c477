//! What a run produces: the recorded points with their modes, the events with the mode
//! switches they made, the statistics; and, for a failed run, the error beside everything
//! computed before it.

use crate::error::SolverError;
use crate::problem::Mode;
use crate::stats::Stats;
use serde::Serialize;
use std::fmt;

/// One mode component switched by an event: `q[component]` went from `from` to `to`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct ModeSwitch {
    /// Which component of the discrete state (for a friction system: which contact).
    pub component: usize,
    /// Mode before the event.
    pub from: Mode,
    /// Mode after it.
    pub to: Mode,
}

/// One event instant: when, which event functions fired there, and which modes switched.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EventRecord {
    /// Time located.
    pub t: f64,
    /// The event functions that fired, ascending.
    pub fired: Vec<usize>,
    /// Their names, in the same order.
    pub names: Vec<&'static str>,
    /// The mode components the handler switched, ascending by component.
    pub switches: Vec<ModeSwitch>,
}

/// A computed trajectory.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Solution {
    /// The method.
    pub solver: &'static str,
    /// Number of unknowns.
    pub dim: usize,
    /// Number of mode components.
    pub n_modes: usize,
    /// Recorded times (an event appears twice: before and after its action).
    pub t: Vec<f64>,
    /// Recorded states, `dim` numbers per time, flattened.
    pub y: Vec<f64>,
    /// Modes at each recorded time, `n_modes` per time, flattened.
    pub modes: Vec<Mode>,
    /// Every event instant, in order.
    pub events: Vec<EventRecord>,
    /// Work done.
    pub stats: Stats,
    /// Where Hairer's stiffness test first judged the problem stiff (Dormand–Prince, and
    /// `auto`'s first switch to Radau IIA).
    pub stiffness_detected_at: Option<f64>,
    /// Every switch of method within the run (`auto`), in order.
    pub method_switches: Vec<MethodSwitch>,
}

/// A switch of method within a run (`auto`): where, to which method, the rule that decided
/// it and the stiffness estimate `h·ρ̂` there.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct MethodSwitch {
    /// Time of the switch, s.
    pub t: f64,
    /// The method that takes the steps from there.
    pub to: &'static str,
    /// The rule that decided it.
    pub rule: SwitchRule,
    /// `h·ρ̂`: the step times the estimated spectral radius of the Jacobian (Hairer's
    /// estimate of Dormand–Prince's last step on a switch to Radau IIA; `h·‖J‖∞` of Radau
    /// IIA's last step on a switch back).
    pub estimate: f64,
}

/// Why `auto` switched method ([`crate::auto`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SwitchRule {
    /// LSODA's rule: a trial step of Radau IIA `RATIO` = 5 times Dormand–Prince's was
    /// accepted.
    StepRatio,
    /// Hairer's stiffness test of dopri5.f: `h·ρ̂ > 3.25` fifteen times in a row.
    StiffnessTest,
    /// Back to Dormand–Prince: `h·‖J‖∞ ≤ 3.25` for fifteen Radau IIA steps in a row.
    StabilityBound,
}

impl Solution {
    /// An empty solution for `dim` unknowns and `n_modes` mode components.
    pub fn new(solver: &'static str, dim: usize, n_modes: usize) -> Self {
        Solution {
            solver,
            dim,
            n_modes,
            t: Vec::new(),
            y: Vec::new(),
            modes: Vec::new(),
            events: Vec::new(),
            stats: Stats::default(),
            stiffness_detected_at: None,
            method_switches: Vec::new(),
        }
    }

    /// Appends a point.
    pub fn push(&mut self, t: f64, y: &[f64], modes: &[Mode]) {
        self.t.push(t);
        self.y.extend_from_slice(y);
        self.modes.extend_from_slice(modes);
    }

    /// Number of recorded points.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// Whether nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// The state at recorded point `i`.
    pub fn y_at(&self, i: usize) -> &[f64] {
        &self.y[i * self.dim..(i + 1) * self.dim]
    }

    /// The modes at recorded point `i`.
    pub fn modes_at(&self, i: usize) -> &[Mode] {
        &self.modes[i * self.n_modes..(i + 1) * self.n_modes]
    }

    /// Keeps the first `len` recorded points and the events up to the last of them: what a
    /// run had computed before a point that is not to be kept.
    pub fn truncate(&mut self, len: usize) {
        let len = len.min(self.len());
        let last = if len == 0 {
            f64::NEG_INFINITY
        } else {
            self.t[len - 1]
        };
        self.t.truncate(len);
        self.y.truncate(len * self.dim);
        self.modes.truncate(len * self.n_modes);
        self.events.retain(|e| e.t <= last);
    }

    /// Keeps the first `points` recorded points and the first `events` events, drops the
    /// rest: the solution as it stood when it held that many.
    pub fn keep_first(&mut self, points: usize, events: usize) {
        self.t.truncate(points);
        self.y.truncate(points * self.dim);
        self.modes.truncate(points * self.n_modes);
        self.events.truncate(events);
    }

    /// The last recorded time and state.
    pub fn last(&self) -> Option<(f64, &[f64])> {
        let n = self.len();
        (n > 0).then(|| (self.t[n - 1], self.y_at(n - 1)))
    }
}

/// A run that failed: the error, and the solution up to the failure.
#[derive(Clone, Debug, PartialEq)]
pub struct Failure {
    /// Why and where it failed.
    pub error: SolverError,
    /// Everything computed before the failure (boxed: a failure travels in `Result`s).
    pub solution: Box<Solution>,
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} ({} points kept)", self.error, self.solution.len())
    }
}

impl std::error::Error for Failure {}
