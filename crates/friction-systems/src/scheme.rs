//! How a system is integrated, as a Siconos `Simulation` chooses it: the scheme, and with it
//! the one-step integrator and the treatment of v_rel = 0.
//!
//! - [`Scheme::EventDriven`]: a solver of `integrators` steps the smooth dynamics between
//!   events, which are located; v_rel = 0 is treated by a [`Switching`] (event location with
//!   stick/slip modes, regularisation, or the discontinuous law stepped through).
//! - [`Scheme::TimeStepping`]: Moreau–Jean's scheme ([`crate::moreau_jean`]) takes fixed steps,
//!   locates no event, and finds each contact's force and mode at the end of every step from
//!   its set-valued law; between steps the modes mean what they mean under
//!   [`Switching::Event`]. No solver of `integrators` takes part.

use crate::switching::Switching;
use integrators::Solver;

/// How a system is integrated: event-driven by a solver under a treatment of v_rel = 0, or
/// time-stepped by Moreau–Jean's θ-method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scheme {
    /// A one-step solver between located events.
    EventDriven {
        /// The solver.
        solver: Solver,
        /// The treatment of v_rel = 0.
        switching: Switching,
    },
    /// Moreau–Jean time-stepping, the θ-method on the smooth forces.
    TimeStepping {
        /// Weight θ of the end of the step, in [1/2, 1].
        theta: f64,
    },
}

impl Scheme {
    /// Event-driven integration by `solver` with event location at v_rel = 0
    /// ([`Switching::Event`]).
    pub fn events(solver: Solver) -> Scheme {
        Scheme::EventDriven {
            solver,
            switching: Switching::Event,
        }
    }

    /// The solver of the event-driven scheme; `None` under time-stepping, which takes none.
    pub fn solver(self) -> Option<Solver> {
        match self {
            Scheme::EventDriven { solver, .. } => Some(solver),
            Scheme::TimeStepping { .. } => None,
        }
    }

    /// Whether it is Moreau–Jean time-stepping.
    pub fn is_time_stepping(self) -> bool {
        matches!(self, Scheme::TimeStepping { .. })
    }

    /// The scheme's name: `event-driven` or `time-stepping`.
    pub fn name(self) -> &'static str {
        match self {
            Scheme::EventDriven { .. } => "event-driven",
            Scheme::TimeStepping { .. } => "time-stepping",
        }
    }

    /// The name of its treatment of v_rel = 0 as summaries and study files write it:
    /// [`Switching::name`], or `timestepping`.
    pub fn treatment_name(self) -> &'static str {
        match self {
            Scheme::EventDriven { switching, .. } => switching.name(),
            Scheme::TimeStepping { .. } => "timestepping",
        }
    }

    /// The parameter of its treatment, with its name: the regularisation width `epsilon`
    /// (m/s) of [`Switching::Regularized`], or `theta`, the weight of time-stepping's
    /// θ-method; `None` for event location and naive stepping.
    pub fn parameter(self) -> Option<(&'static str, f64)> {
        match self {
            Scheme::EventDriven {
                switching: Switching::Regularized { epsilon },
                ..
            } => Some(("epsilon", epsilon)),
            Scheme::TimeStepping { theta } => Some(("theta", theta)),
            Scheme::EventDriven { .. } => None,
        }
    }

    /// The treatment of v_rel = 0 the problem is built with: the event-driven scheme's own;
    /// [`Switching::Event`]'s modes under time-stepping.
    pub fn switching(self) -> Switching {
        match self {
            Scheme::EventDriven { switching, .. } => switching,
            Scheme::TimeStepping { .. } => Switching::Event,
        }
    }

    /// The name of the method that integrates: the solver's, or `moreau-jean`.
    pub fn method_name(self) -> &'static str {
        match self {
            Scheme::EventDriven { solver, .. } => solver.name(),
            Scheme::TimeStepping { .. } => crate::moreau_jean::NAME,
        }
    }
}
