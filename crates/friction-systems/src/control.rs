//! A PID controller on one body's position, the actuator of a closed loop
//! (`docs/systems.md`, `[[controller]]`):
//!
//! `u = sat(kp·e + ki·I + kd·ė + F̂(v_c))`, with `e = r(t) − x`, `ė = ṙ(t) − v`, `İ = e`,
//!
//! the integral `I` a state of the system, `F̂` an optional feed-forward friction compensation
//! (a model's steady friction at the reference velocity `ṙ` or the measured one `v`), and
//! `sat` an optional clamp to `±saturation`. The force `u` acts on the body like an external
//! force: a sticking contact's stick test sees it, and its work `∫u·v dt` is the actuator's,
//! counted with the external work of the energy balance.

use friction_models::{steady, FrictionModel, SignLaw};
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// The reference position r(t) a controller tracks; in a system file
/// `reference = { kind = "constant", x = 1.0 }` (or `ramp`, `sinusoid`, `table`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum Reference {
    /// `r = x`.
    Constant {
        /// Set point, m.
        x: f64,
    },
    /// `r = x0 + v·t`.
    Ramp {
        /// Position at t = 0, m.
        x0: f64,
        /// Velocity, m/s.
        v: f64,
    },
    /// `r = x0 + amplitude·sin(omega·t)`.
    Sinusoid {
        /// Mean position, m.
        x0: f64,
        /// Amplitude, m.
        amplitude: f64,
        /// Angular frequency, rad/s.
        omega: f64,
    },
    /// Points (t_k, x_k) joined linearly; before the first and after the last, their x.
    Table {
        /// Times, s, strictly increasing.
        t: Vec<f64>,
        /// Positions, m, one per time.
        x: Vec<f64>,
    },
}

impl Reference {
    /// The reference position and velocity at t (on a table, the slope of the piece t lies
    /// on, the later piece at a point; zero outside the points).
    pub fn at(&self, t: f64) -> (f64, f64) {
        match self {
            Reference::Constant { x } => (*x, 0.0),
            Reference::Ramp { x0, v } => (x0 + v * t, *v),
            Reference::Sinusoid {
                x0,
                amplitude,
                omega,
            } => {
                let (s, c) = (omega * t).sin_cos();
                (x0 + amplitude * s, amplitude * omega * c)
            }
            Reference::Table { t: times, x } => {
                let last = times.len() - 1;
                if t < times[0] {
                    return (x[0], 0.0);
                }
                if t >= times[last] {
                    return (x[last], 0.0);
                }
                // The piece [t_k, t_{k+1}) holding t.
                let k = times.partition_point(|&tk| tk <= t) - 1;
                let slope = (x[k + 1] - x[k]) / (times[k + 1] - times[k]);
                (x[k] + slope * (t - times[k]), slope)
            }
        }
    }

    /// The numbers of the reference with their keys (`reference.x0`), for the checks of a
    /// declaration.
    pub fn numbers(&self) -> Vec<(&'static str, f64)> {
        match self {
            Reference::Constant { x } => vec![("reference.x", *x)],
            Reference::Ramp { x0, v } => vec![("reference.x0", *x0), ("reference.v", *v)],
            Reference::Sinusoid {
                x0,
                amplitude,
                omega,
            } => vec![
                ("reference.x0", *x0),
                ("reference.amplitude", *amplitude),
                ("reference.omega", *omega),
            ],
            Reference::Table { t, x } => (t.iter().map(|&t| ("reference.t", t)))
                .chain(x.iter().map(|&x| ("reference.x", x)))
                .collect(),
        }
    }
}

/// Which velocity a friction compensation is evaluated at (`velocity = "reference"` or
/// `"measured"` in a system file).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CompensatedAt {
    /// The reference's, ṙ(t): a feed-forward that needs no measurement.
    #[default]
    Reference,
    /// The body's measured velocity relative to its contact's surface.
    Measured,
}

/// A feed-forward friction compensation: a model's steady friction `F̂(v)` added to the
/// control force. The model may differ from the plant's law (a mismatched compensator).
#[derive(Clone, Debug)]
pub struct Compensation {
    /// The model the controller believes in, with its parameters.
    pub model: Arc<dyn FrictionModel>,
    /// The velocity it is evaluated at.
    pub at: CompensatedAt,
}

impl Compensation {
    /// `F̂(v)`, the model's steady friction at relative velocity v under `law`, and its slope
    /// dF̂/dv there.
    pub fn force(&self, v: f64, law: SignLaw) -> (f64, f64) {
        let model = self.model.as_ref();
        (steady::force(model, v, law), steady::slope(model, v, law))
    }
}

/// A PID controller on one body's position.
#[derive(Clone, Debug)]
pub struct Controller {
    /// The body, by index.
    pub body: usize,
    /// Proportional gain kp, N/m.
    pub kp: f64,
    /// Integral gain ki, N/(m·s).
    pub ki: f64,
    /// Derivative gain kd, N·s/m.
    pub kd: f64,
    /// The reference position.
    pub reference: Reference,
    /// The actuator's largest force, N (`None`: unbounded).
    pub saturation: Option<f64>,
    /// A feed-forward friction compensation.
    pub compensation: Option<Compensation>,
}

/// The control force at one instant, with its partial derivatives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Actuation {
    /// The force u on the body, N.
    pub force: f64,
    /// ∂u/∂x, ∂u/∂v, ∂u/∂I (zero where the actuator is saturated).
    pub partials: (f64, f64, f64),
}

impl Controller {
    /// The control force at time t for the body's position x and velocity v and the integral
    /// I of the error; a compensation at the measured velocity reads the body's velocity
    /// relative to its surface, `v_rel`, under the sign law `law` (sign(0) = 0, or tanh(v/ε)
    /// where the system's contacts are regularised).
    pub fn actuation(
        &self,
        t: f64,
        (x, v): (f64, f64),
        integral: f64,
        v_rel: f64,
        law: SignLaw,
    ) -> Actuation {
        let (r, r_dot) = self.reference.at(t);
        let mut force = self.kp * (r - x) + self.ki * integral + self.kd * (r_dot - v);
        let mut dv = -self.kd;
        if let Some(c) = &self.compensation {
            match c.at {
                CompensatedAt::Reference => force += c.force(r_dot, law).0,
                CompensatedAt::Measured => {
                    let (f, slope) = c.force(v_rel, law);
                    force += f;
                    dv += slope;
                }
            }
        }
        match self.saturation {
            Some(limit) if force.abs() > limit => Actuation {
                force: limit.copysign(force),
                partials: (0.0, 0.0, 0.0),
            },
            _ => Actuation {
                force,
                partials: (-self.kp, dv, self.ki),
            },
        }
    }

    /// The rate of the integral state: the position error `r(t) − x`.
    pub fn error(&self, t: f64, x: f64) -> f64 {
        self.reference.at(t).0 - x
    }
}
