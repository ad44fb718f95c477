//! What a run produces: the recorded points, the events with both sides, the statistics;
//! and, for a failed run, the error beside everything computed before it.

use crate::error::SolverError;
use crate::problem::Mode;
use crate::stats::Stats;
use serde::Serialize;
use std::fmt;

/// One event: when, which, and the state just before and just after its action.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EventRecord {
    /// Time located.
    pub t: f64,
    /// The event function's name.
    pub name: &'static str,
    /// Its index among the events of `mode_before`.
    pub index: usize,
    /// Mode before the event.
    pub mode_before: Mode,
    /// Mode after it.
    pub mode_after: Mode,
    /// State on the dense output at `t`, before the action.
    pub y_left: Vec<f64>,
    /// State after the action.
    pub y_right: Vec<f64>,
}

/// A computed trajectory.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Solution {
    /// The method.
    pub solver: &'static str,
    /// Number of unknowns.
    pub dim: usize,
    /// Recorded times (an event appears twice: before and after its action).
    pub t: Vec<f64>,
    /// Recorded states, `dim` numbers per time, flattened.
    pub y: Vec<f64>,
    /// Mode at each recorded time.
    pub mode: Vec<Mode>,
    /// Every event, in order.
    pub events: Vec<EventRecord>,
    /// Work done.
    pub stats: Stats,
    /// Where Hairer's stiffness test first judged the problem stiff (Dormand–Prince only).
    pub stiffness_detected_at: Option<f64>,
}

impl Solution {
    /// An empty solution for `dim` unknowns.
    pub fn new(solver: &'static str, dim: usize) -> Self {
        Solution {
            solver,
            dim,
            t: Vec::new(),
            y: Vec::new(),
            mode: Vec::new(),
            events: Vec::new(),
            stats: Stats::default(),
            stiffness_detected_at: None,
        }
    }

    /// Appends a point.
    pub fn push(&mut self, t: f64, y: &[f64], mode: Mode) {
        self.t.push(t);
        self.y.extend_from_slice(y);
        self.mode.push(mode);
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
