//! A body on a moving surface with friction, as an [`OdeProblem`], with the three
//! treatments of v_rel = 0 that the studies compare:
//!
//! - [`Switching::Event`]: modes `slip+`, `slip-`, `stick`. In a slip mode the direction of
//!   friction is frozen (`SignLaw::Frozen`: no sign(v) inside a step) and the event is
//!   v_rel = 0; in `stick` the body moves with the surface, the internal state is frozen,
//!   and the events are the needed friction force leaving the model's stick interval.
//! - [`Switching::Regularized`]: sign(v) ≈ tanh(v/ε), one smooth ODE.
//! - [`Switching::Naive`]: the discontinuous law stepped through blindly (sign(0) = 0, and
//!   the stick rule of eqs. (6)–(7) only when v_rel is exactly zero or inside a Karnopp band).
//!
//! State: `y = [x, v]`, or `[x, v, z]` for a model with an internal state. Equation:
//! `m·v' = F_app(t, x, v) − F(x, v − v_surf, z)`, `z' = g(x, v − v_surf, z)`.

use crate::problem::{Control, Crossing, Entry, EventSpec, Mode, OdeProblem};
use friction_models::{Direction, FrictionModel, SignLaw, StickInterval};
use serde::Serialize;

/// Sliding with v_rel > 0.
pub const SLIP_POSITIVE: Mode = Mode(0);
/// Sliding with v_rel < 0.
pub const SLIP_NEGATIVE: Mode = Mode(1);
/// Moving with the surface.
pub const STICK: Mode = Mode(2);

/// The name of a friction mode as trajectories write it.
pub fn mode_name(mode: Mode) -> &'static str {
    match mode {
        SLIP_POSITIVE => "slip+",
        SLIP_NEGATIVE => "slip-",
        _ => "stick",
    }
}

/// A force that depends on time only.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub enum Profile {
    /// No time-dependent force.
    #[default]
    None,
    /// `rate·t`.
    Ramp {
        /// Rate, N/s.
        rate: f64,
    },
    /// Rises linearly to `peak` over `rise` s, holds it for `hold` s, falls back to zero over
    /// `fall` s, and stays at zero.
    Trapezoid {
        /// Peak force, N.
        peak: f64,
        /// Rise time, s.
        rise: f64,
        /// Hold time, s.
        hold: f64,
        /// Fall time, s.
        fall: f64,
    },
}

impl Profile {
    /// The force at time t.
    pub fn at(&self, t: f64) -> f64 {
        match *self {
            Profile::None => 0.0,
            Profile::Ramp { rate } => rate * t,
            Profile::Trapezoid {
                peak,
                rise,
                hold,
                fall,
            } => {
                if t < rise {
                    peak * t / rise
                } else if t < rise + hold {
                    peak
                } else if t < rise + hold + fall {
                    peak * (rise + hold + fall - t) / fall
                } else {
                    0.0
                }
            }
        }
    }
}

/// The force applied to the body besides friction:
/// `F_app(t, x, v) = constant + profile(t) − stiffness·x − damping·v`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct AppliedForce {
    /// Constant force, N.
    pub constant: f64,
    /// Time-dependent force.
    pub profile: Profile,
    /// Spring stiffness k (spring anchored at x = 0), N/m.
    pub stiffness: f64,
    /// Linear damping c, N·s/m.
    pub damping: f64,
}

impl AppliedForce {
    /// The force at (t, x, v).
    pub fn at(&self, t: f64, x: f64, v: f64) -> f64 {
        self.constant + self.profile.at(t) - self.stiffness * x - self.damping * v
    }
}

/// How v_rel = 0 is treated.
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

/// A body of mass m on a surface moving at `surface_velocity`, with friction and an
/// applied force.
pub struct FrictionBody<'a> {
    /// Mass m, kg.
    pub mass: f64,
    /// The friction law.
    pub model: &'a dyn FrictionModel,
    /// The applied force.
    pub applied: AppliedForce,
    /// Velocity of the surface (a belt), m/s.
    pub surface_velocity: f64,
    /// The treatment of v_rel = 0.
    pub switching: Switching,
}

const SLIP_POSITIVE_EVENTS: [EventSpec; 1] = [EventSpec {
    name: "v_rel=0",
    crossing: Crossing::Falling,
}];
const SLIP_NEGATIVE_EVENTS: [EventSpec; 1] = [EventSpec {
    name: "v_rel=0",
    crossing: Crossing::Rising,
}];
const STICK_EVENTS: [EventSpec; 2] = [
    EventSpec {
        name: "break-away+",
        crossing: Crossing::Falling,
    },
    EventSpec {
        name: "break-away-",
        crossing: Crossing::Falling,
    },
];

impl FrictionBody<'_> {
    fn z(&self, y: &[f64]) -> f64 {
        if self.model.n_states() > 0 {
            y[2]
        } else {
            0.0
        }
    }

    /// The friction force needed to hold the body on the surface at (t, x): with the body
    /// moving at the (constant) surface velocity, all of the applied force.
    pub fn needed_force(&self, t: f64, x: f64) -> f64 {
        self.applied.at(t, x, self.surface_velocity)
    }

    /// The admissible friction forces at rest relative to the surface.
    pub fn stick_interval(&self, y: &[f64]) -> StickInterval {
        self.model.stick_interval(y[0], self.z(y))
    }

    /// The mode the body is in at (t, y): by the sign of v_rel, and at v_rel = 0 by the stick
    /// law: `stick` while the needed force lies inside a stick interval of positive width,
    /// otherwise sliding in the direction of the needed force.
    pub fn mode_at(&self, t: f64, y: &[f64]) -> Mode {
        let v_rel = y[1] - self.surface_velocity;
        match Direction::of(v_rel) {
            Some(Direction::Positive) => SLIP_POSITIVE,
            Some(Direction::Negative) => SLIP_NEGATIVE,
            None => {
                let s = self.stick_interval(y);
                let f = self.needed_force(t, y[0]);
                if s.upper > s.lower && s.contains(f) {
                    STICK
                } else if f > s.upper {
                    SLIP_POSITIVE
                } else {
                    SLIP_NEGATIVE
                }
            }
        }
    }

    /// The mode to report at state y: the integration's own mode under event switching;
    /// otherwise the sign of v_rel (`stick` only at exactly zero).
    pub fn reported_mode(&self, mode: Mode, y: &[f64]) -> Mode {
        if self.switching == Switching::Event {
            return mode;
        }
        match Direction::of(y[1] - self.surface_velocity) {
            Some(Direction::Positive) => SLIP_POSITIVE,
            Some(Direction::Negative) => SLIP_NEGATIVE,
            None => STICK,
        }
    }

    /// The friction force at (t, y) in `mode`, as the right-hand side uses it.
    pub fn friction(&self, t: f64, y: &[f64], mode: Mode) -> f64 {
        self.friction_and_rate(t, y, mode).0
    }

    /// Friction force and internal-state rate.
    fn friction_and_rate(&self, t: f64, y: &[f64], mode: Mode) -> (f64, f64) {
        let (x, v, z) = (y[0], y[1], self.z(y));
        let v_rel = v - self.surface_velocity;
        let law = match self.switching {
            Switching::Event => match mode {
                STICK => return (self.needed_force(t, x), 0.0),
                SLIP_POSITIVE => SignLaw::Frozen(Direction::Positive),
                _ => SignLaw::Frozen(Direction::Negative),
            },
            Switching::Regularized { epsilon } => SignLaw::Smooth { epsilon },
            Switching::Naive => {
                if v_rel == 0.0 || v_rel.abs() < self.model.stick_band() {
                    let held = self
                        .model
                        .stick_interval(x, z)
                        .clamp(self.applied.at(t, x, v));
                    return (held, 0.0);
                }
                SignLaw::Discontinuous
            }
        };
        let r = self.model.response(x, v_rel, z, law);
        (r.force, r.state_rate)
    }

    /// The right-hand side `dy = f(t, y)` in `mode`, returning the friction force it used
    /// (so that callers who need both evaluate the model once).
    pub fn rhs_with_friction(&self, t: f64, y: &[f64], mode: Mode, dy: &mut [f64]) -> f64 {
        let (force, rate) = self.friction_and_rate(t, y, mode);
        if self.switching == Switching::Event && mode == STICK {
            dy[0] = self.surface_velocity;
            dy[1..].iter_mut().for_each(|d| *d = 0.0);
            return force;
        }
        dy[0] = y[1];
        dy[1] = (self.applied.at(t, y[0], y[1]) - force) / self.mass;
        if let Some(d) = dy.get_mut(2) {
            *d = rate;
        }
        force
    }

    fn law(&self, mode: Mode) -> SignLaw {
        match self.switching {
            Switching::Event if mode == SLIP_POSITIVE => SignLaw::Frozen(Direction::Positive),
            Switching::Event => SignLaw::Frozen(Direction::Negative),
            Switching::Regularized { epsilon } => SignLaw::Smooth { epsilon },
            Switching::Naive => SignLaw::Discontinuous,
        }
    }
}

impl OdeProblem for FrictionBody<'_> {
    fn dim(&self) -> usize {
        2 + self.model.n_states()
    }

    fn rhs(&self, t: f64, y: &[f64], mode: Mode, dy: &mut [f64]) {
        self.rhs_with_friction(t, y, mode, dy);
    }

    fn jacobian(&self, _t: f64, y: &[f64], mode: Mode, jac: &mut Vec<Entry>) -> bool {
        if self.switching == Switching::Event && mode == STICK {
            return true;
        }
        let (x, v, z) = (y[0], y[1], self.z(y));
        let p = self
            .model
            .partials(x, v - self.surface_velocity, z, self.law(mode));
        let m = self.mass;
        jac.push((0, 1, 1.0));
        jac.push((1, 0, (-self.applied.stiffness - p.force_dx) / m));
        jac.push((1, 1, (-self.applied.damping - p.force_dv) / m));
        if self.model.n_states() > 0 {
            jac.push((1, 2, -p.force_dz / m));
            jac.push((2, 0, p.rate_dx));
            jac.push((2, 1, p.rate_dv));
            jac.push((2, 2, p.rate_dz));
        }
        true
    }

    fn events(&self, mode: Mode) -> &[EventSpec] {
        match (self.switching, mode) {
            (Switching::Event, SLIP_POSITIVE) => &SLIP_POSITIVE_EVENTS,
            (Switching::Event, SLIP_NEGATIVE) => &SLIP_NEGATIVE_EVENTS,
            (Switching::Event, _) => &STICK_EVENTS,
            _ => &[],
        }
    }

    fn event(&self, index: usize, t: f64, y: &[f64], mode: Mode) -> f64 {
        if mode != STICK {
            return y[1] - self.surface_velocity;
        }
        let s = self.stick_interval(y);
        let f = self.needed_force(t, y[0]);
        if index == 0 {
            s.upper - f
        } else {
            f - s.lower
        }
    }

    fn on_event(&self, index: usize, t: f64, y: &mut [f64], mode: Mode) -> Control {
        if mode == STICK {
            // The needed force has crossed a bound of the stick interval outwards.
            return Control::Switch(if index == 0 {
                SLIP_POSITIVE
            } else {
                SLIP_NEGATIVE
            });
        }
        // v_rel = 0 reached: remove the residual of the location, then decide by the stick
        // law.
        y[1] = self.surface_velocity;
        Control::Switch(self.mode_at(t, y))
    }
}
