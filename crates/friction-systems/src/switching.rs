//! How v_rel = 0 is treated at a contact, and the three modes of a contact.
//!
//! - [`Switching::Event`]: modes `slip+`, `slip-`, `stick` per contact. In a slip mode the
//!   direction of friction is frozen (`SignLaw::Frozen`: no sign(v) inside a step) and the
//!   event is v_rel = 0; in `stick` the body moves with its surface, its internal state is
//!   frozen, and the events are the needed friction force leaving the model's stick interval.
//! - [`Switching::Regularized`]: sign(v) ≈ tanh(v/ε), one smooth ODE.
//! - [`Switching::Naive`]: the discontinuous law stepped through blindly (sign(0) = 0, and
//!   the stick rule of eqs. (6)–(7) only when v_rel is exactly zero or inside a Karnopp band).
//!
//! These are the treatments of event-driven integration; time-stepping is a scheme of its own
//! ([`crate::Scheme`]), whose modes between steps mean what they mean under `Event`.

use friction_models::{Direction, SignLaw};
use integrators::Mode;
use serde::Serialize;

/// Sliding with v_rel > 0.
pub const SLIP_POSITIVE: Mode = Mode(0);
/// Sliding with v_rel < 0.
pub const SLIP_NEGATIVE: Mode = Mode(1);
/// Moving with the surface.
pub const STICK: Mode = Mode(2);

/// The name of a contact mode as trajectories and event logs write it.
pub fn mode_name(mode: Mode) -> &'static str {
    match mode {
        SLIP_POSITIVE => "slip+",
        SLIP_NEGATIVE => "slip-",
        _ => "stick",
    }
}

/// The mode reported for a relative velocity when no mode is integrated (regularised and
/// naive treatments): its sign, and `stick` only at exactly zero.
pub fn mode_of_velocity(v_rel: f64) -> Mode {
    match Direction::of(v_rel) {
        Some(Direction::Positive) => SLIP_POSITIVE,
        Some(Direction::Negative) => SLIP_NEGATIVE,
        None => STICK,
    }
}

/// How v_rel = 0 is treated under event-driven integration.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub enum Switching {
    /// Event location with stick/slip mode switching.
    Event,
    /// sign(v) ≈ tanh(v/ε).
    Regularized {
        /// Width ε, m/s.
        epsilon: f64,
    },
    /// The discontinuous law stepped through blindly.
    Naive,
}

impl Switching {
    /// Its name, as `--switching` takes it: `event`, `regularized` or `naive`.
    pub fn name(self) -> &'static str {
        match self {
            Switching::Event => "event",
            Switching::Regularized { .. } => "regularized",
            Switching::Naive => "naive",
        }
    }

    /// The law sign(v) is evaluated by in a sliding `mode`.
    pub fn law(self, mode: Mode) -> SignLaw {
        match self {
            Switching::Event if mode == SLIP_NEGATIVE => SignLaw::Frozen(Direction::Negative),
            Switching::Event => SignLaw::Frozen(Direction::Positive),
            Switching::Regularized { epsilon } => SignLaw::Smooth { epsilon },
            Switching::Naive => SignLaw::Discontinuous,
        }
    }

    /// Whether every contact carries a stick/slip mode (event switching, and so time-stepping);
    /// otherwise the mode is only read off the sign of v_rel.
    pub fn has_modes(self) -> bool {
        self == Switching::Event
    }
}
