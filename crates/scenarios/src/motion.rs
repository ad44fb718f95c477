//! Prescribed motion: the surface is fixed and the body's motion x(t) is imposed, so only the
//! friction model's internal state is integrated, with two accumulators:
//! `W = ∫F·v dt` (the work done against friction) and `H = ∫F·a dt = ∮F dv` (the area of the
//! friction–velocity loop, zero for any single-valued map F(v)).
//!
//! State: `y = [z, W, H]` for a model with an internal state, `[W, H]` without one.

use friction_models::{Direction, FrictionModel, StatePartials, MAX_STATES};
use friction_systems::{Switching, SLIP_NEGATIVE, SLIP_POSITIVE};
use integrators::{Control, Crossing, Entry, EventSpec, Mode, OdeProblem};

/// An imposed motion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Motion {
    /// The paper's `X(t) = t³/3 + t²/2`, or its mirror image.
    Paper {
        /// X → −X.
        mirrored: bool,
    },
    /// `x = amplitude·sin(omega·t)`.
    Sine {
        /// Amplitude, m.
        amplitude: f64,
        /// Angular frequency, rad/s.
        omega: f64,
    },
    /// `v = mean + amplitude·cos(omega·t)`, x(0) = 0.
    VelocityOscillation {
        /// Mean velocity, m/s.
        mean: f64,
        /// Velocity amplitude, m/s.
        amplitude: f64,
        /// Angular frequency, rad/s.
        omega: f64,
    },
    /// `v` constant, x(0) = 0.
    Constant {
        /// Velocity, m/s.
        v: f64,
    },
}

impl Motion {
    /// Displacement, velocity and acceleration at t.
    pub fn at(&self, t: f64) -> (f64, f64, f64) {
        match *self {
            Motion::Paper { mirrored } => {
                let s = if mirrored { -1.0 } else { 1.0 };
                (
                    s * (t.powi(3) / 3.0 + t * t / 2.0),
                    s * t * (t + 1.0),
                    s * (2.0 * t + 1.0),
                )
            }
            Motion::Sine { amplitude, omega } => {
                let (sn, cs) = (omega * t).sin_cos();
                (
                    amplitude * sn,
                    amplitude * omega * cs,
                    -amplitude * omega * omega * sn,
                )
            }
            Motion::VelocityOscillation {
                mean,
                amplitude,
                omega,
            } => {
                let (sn, cs) = (omega * t).sin_cos();
                (
                    mean * t + amplitude * sn / omega,
                    mean + amplitude * cs,
                    -amplitude * omega * sn,
                )
            }
            Motion::Constant { v } => (v * t, v, 0.0),
        }
    }
}

/// A friction model driven along an imposed motion.
pub struct Kinematic<'a> {
    /// The friction law.
    pub model: &'a dyn FrictionModel,
    /// The motion.
    pub motion: Motion,
    /// The treatment of v = 0.
    pub switching: Switching,
}

const POSITIVE_EVENT: EventSpec = EventSpec {
    name: "reversal",
    crossing: Crossing::Falling,
};
const NEGATIVE_EVENT: EventSpec = EventSpec {
    name: "reversal",
    crossing: Crossing::Rising,
};

impl Kinematic<'_> {
    /// Index of the first accumulator (W) in the state.
    pub fn work_index(&self) -> usize {
        self.model.n_states()
    }

    /// The direction of motion at t: the sign of v, or of a where v = 0.
    pub fn mode_at(&self, t: f64) -> Mode {
        let (_, v, a) = self.motion.at(t);
        match Direction::of(v).or(Direction::of(a)) {
            Some(Direction::Negative) => SLIP_NEGATIVE,
            _ => SLIP_POSITIVE,
        }
    }

    /// The internal states in y.
    pub fn z<'y>(&self, y: &'y [f64]) -> &'y [f64] {
        &y[..self.work_index()]
    }

    /// The friction force at (t, y) in `mode`.
    pub fn friction(&self, t: f64, y: &[f64], mode: Mode) -> f64 {
        let (x, v, _) = self.motion.at(t);
        self.model.force(x, v, self.z(y), self.switching.law(mode))
    }
}

impl Kinematic<'_> {
    /// The number of unknowns of a prescribed motion of `model`: its internal states, then the
    /// two accumulators (the work against friction and the loop area).
    pub fn dim_of(model: &dyn FrictionModel) -> usize {
        model.n_states() + 2
    }
}

impl OdeProblem for Kinematic<'_> {
    fn dim(&self) -> usize {
        Kinematic::dim_of(self.model)
    }

    fn rhs(&self, t: f64, y: &[f64], modes: &[Mode], dy: &mut [f64]) {
        let (x, v, a) = self.motion.at(t);
        let w = self.work_index();
        let force =
            self.model
                .response(x, v, self.z(y), self.switching.law(modes[0]), &mut dy[..w]);
        dy[w] = force * v;
        dy[w + 1] = force * a;
    }

    fn jacobian(&self, t: f64, y: &[f64], modes: &[Mode], jac: &mut Vec<Entry>) -> bool {
        let (x, v, a) = self.motion.at(t);
        let w = self.work_index();
        let states = &mut [StatePartials::default(); MAX_STATES][..w];
        self.model
            .partials(x, v, self.z(y), self.switching.law(modes[0]), states);
        for (i, d) in states.iter().enumerate() {
            jac.extend([
                (i, i, d.rate_dz),
                (w, i, d.force_dz * v),
                (w + 1, i, d.force_dz * a),
            ]);
        }
        true
    }

    fn n_events(&self) -> usize {
        usize::from(self.switching == Switching::Event)
    }

    fn event_spec(&self, _i: usize, modes: &[Mode]) -> Option<EventSpec> {
        Some(if modes[0] == SLIP_NEGATIVE {
            NEGATIVE_EVENT
        } else {
            POSITIVE_EVENT
        })
    }

    fn event(&self, _i: usize, t: f64, _y: &[f64], _modes: &[Mode]) -> f64 {
        self.motion.at(t).1
    }

    fn on_events(&self, _fired: &[usize], _t: f64, _y: &mut [f64], modes: &mut [Mode]) -> Control {
        modes[0] = if modes[0] == SLIP_POSITIVE {
            SLIP_NEGATIVE
        } else {
            SLIP_POSITIVE
        };
        Control::Continue
    }
}
