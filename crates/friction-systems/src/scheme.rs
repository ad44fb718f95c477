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
