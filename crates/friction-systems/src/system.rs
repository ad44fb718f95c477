//! A friction system as `docs/systems.md` declares it, apart from any scheme that
//! integrates it: bodies on one line, anchors, linear springs with parallel dampers, at most
//! one friction contact per body, external forces, and at most one PID controller per body
//! ([`crate::control`]).
//!
//! Equations: `m_i·v̇_i = Σ_springs [k·(x_b − x_a) + c·(v_b − v_a)] + F_ext,i(t) + u_i − F_f,i`,
//! with `F_f,i = F(x_i, v_i − v_surf,i, z_i)` and `ż_i = g(x_i, v_i − v_surf,i, z_i)` at a
//! contact, and an anchor's position `x0 + v·t`.

use crate::control::{Controller, Reference};
use friction_models::{FrictionModel, MAX_STATES};
use serde::Serialize;
use std::sync::Arc;
use thiserror::Error;

/// A body: mass and initial state.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Body {
    /// Unique name.
    pub name: String,
    /// Mass m, kg.
    pub m: f64,
    /// Initial displacement from the rest position, m.
    pub x0: f64,
    /// Initial velocity, m/s.
    pub v0: f64,
}

/// A point moving at constant velocity: `x(t) = x0 + v·t` (a wall has v = 0).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Anchor {
    /// Unique name.
    pub name: String,
    /// Position at t = 0, m.
    pub x0: f64,
    /// Velocity, m/s.
    pub v: f64,
}

impl Anchor {
    /// Position and velocity at t.
    pub fn at(&self, t: f64) -> (f64, f64) {
        (self.x0 + self.v * t, self.v)
    }
}

/// One end of a spring.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum End {
    /// Body by index.
    Body(usize),
    /// Anchor by index.
    Anchor(usize),
}

/// A linear spring with a parallel damper from `a` to `b`: the force on `a` is
/// `k·(x_b − x_a) + c·(v_b − v_a)`, on `b` the opposite.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Spring {
    /// First end.
    pub a: End,
    /// Second end.
    pub b: End,
    /// Stiffness k, N/m.
    pub k: f64,
    /// Damping c, N·s/m.
    pub c: f64,
}

/// A time-dependent external force.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub enum Profile {
    /// No time-dependent part.
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
    /// `amplitude·sin(omega·t)`.
    Sine {
        /// Amplitude, N.
        amplitude: f64,
        /// Angular frequency, rad/s.
        omega: f64,
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
            Profile::Sine { amplitude, omega } => amplitude * (omega * t).sin(),
        }
    }
}

/// An external force on a body: `F_ext(t) = constant + profile(t)`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Force {
    /// The body, by index.
    pub body: usize,
    /// Constant part, N.
    pub constant: f64,
    /// Time-dependent part.
    pub profile: Profile,
}

/// A friction contact between a body and a surface moving at `surface_velocity`.
#[derive(Clone, Debug)]
pub struct Contact {
    /// The body, by index.
    pub body: usize,
    /// Velocity of the surface, m/s (0 for the floor).
    pub surface_velocity: f64,
    /// The friction law (any [`FrictionModel`], also one from another crate).
    pub model: Arc<dyn FrictionModel>,
}

/// Bodies, anchors, springs, contacts, external forces and controllers.
#[derive(Clone, Debug, Default)]
pub struct System {
    /// The bodies.
    pub bodies: Vec<Body>,
    /// The anchors.
    pub anchors: Vec<Anchor>,
    /// The springs (with their dampers).
    pub springs: Vec<Spring>,
    /// The friction contacts, at most one per body.
    pub contacts: Vec<Contact>,
    /// The external forces.
    pub forces: Vec<Force>,
    /// The controllers, at most one per body.
    pub controllers: Vec<Controller>,
}

/// A system that cannot be integrated as declared.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SystemError {
    /// A value outside its allowed range.
    #[error("{what}: `{key}` = {} is out of range: allowed {allowed}", friction_models::params::show(*.value))]
    OutOfRange {
        /// Which item (`body "b1"`, `spring 3`).
        what: String,
        /// The key.
        key: &'static str,
        /// The rejected value.
        value: f64,
        /// The allowed range.
        allowed: &'static str,
    },
    /// Anything else that makes the declaration inconsistent.
    #[error("{what}: {why}")]
    Invalid {
        /// Which item.
        what: String,
        /// Why.
        why: String,
    },
}

fn check(
    what: impl Fn() -> String,
    key: &'static str,
    value: f64,
    positive: bool,
) -> Result<(), SystemError> {
    let ok = value.is_finite() && (!positive || value > 0.0);
    if ok {
        Ok(())
    } else {
        Err(SystemError::OutOfRange {
            what: what(),
            key,
            value,
            allowed: if positive {
                "(0, inf)"
            } else {
                "(-inf, inf), finite"
            },
        })
    }
}

/// Refuses the first of `values` (key, value) of `what` that is not in [0, inf).
fn non_negative(
    what: impl Fn() -> String,
    values: &[(&'static str, f64)],
) -> Result<(), SystemError> {
    match values.iter().find(|(_, v)| !(v.is_finite() && *v >= 0.0)) {
        Some(&(key, value)) => Err(SystemError::OutOfRange {
            what: what(),
            key,
            value,
            allowed: "[0, inf)",
        }),
        None => Ok(()),
    }
}

impl System {
    /// Adds a body and returns its index.
    pub fn add_body(&mut self, name: impl Into<String>, m: f64, x0: f64, v0: f64) -> usize {
        self.bodies.push(Body {
            name: name.into(),
            m,
            x0,
            v0,
        });
        self.bodies.len() - 1
    }

    /// Adds an anchor and returns its index.
    pub fn add_anchor(&mut self, name: impl Into<String>, x0: f64, v: f64) -> usize {
        self.anchors.push(Anchor {
            name: name.into(),
            x0,
            v,
        });
        self.anchors.len() - 1
    }

    /// Adds a spring with a parallel damper between `a` and `b`.
    pub fn add_spring(&mut self, a: End, b: End, k: f64, c: f64) {
        self.springs.push(Spring { a, b, k, c });
    }

    /// Puts `body` on a surface moving at `surface_velocity` with friction `model`.
    pub fn add_contact(
        &mut self,
        body: usize,
        surface_velocity: f64,
        model: Arc<dyn FrictionModel>,
    ) {
        self.contacts.push(Contact {
            body,
            surface_velocity,
            model,
        });
    }

    /// Adds an external force `constant + profile(t)` on `body`.
    pub fn add_force(&mut self, body: usize, constant: f64, profile: Profile) {
        self.forces.push(Force {
            body,
            constant,
            profile,
        });
    }

    /// Puts a controller on its body.
    pub fn add_controller(&mut self, controller: Controller) {
        self.controllers.push(controller);
    }

    /// Checks that the names of bodies and anchors are unique.
    pub fn check_names(&self) -> Result<(), SystemError> {
        let mut names = std::collections::BTreeSet::new();
        let named = self
            .bodies
            .iter()
            .map(|b| ("body", &b.name))
            .chain(self.anchors.iter().map(|a| ("anchor", &a.name)));
        for (table, name) in named {
            if !names.insert(name.as_str()) {
                return Err(SystemError::Invalid {
                    what: format!("[[{table}]] \"{name}\""),
                    why: "the name is used twice: names of bodies and anchors must be unique"
                        .into(),
                });
            }
        }
        Ok(())
    }

    /// The shortest natural period `2π·√(m_i / K_i)` over the bodies with `K_i > 0`, where
    /// `K_i` is the stiffness holding body i: the sum of its springs' `k`, and with
    /// `controllers` also its controller's proportional gain `kp` (a spring to the
    /// reference). `None` where no body is held.
    pub fn shortest_period(&self, controllers: bool) -> Option<f64> {
        let mut stiffness = vec![0.0; self.bodies.len()];
        for s in &self.springs {
            for end in [s.a, s.b] {
                if let End::Body(i) = end {
                    stiffness[i] += s.k;
                }
            }
        }
        if controllers {
            for c in &self.controllers {
                stiffness[c.body] += c.kp.abs();
            }
        }
        (self.bodies.iter().zip(&stiffness))
            .filter(|(_, &k)| k > 0.0)
            .map(|(b, &k)| 2.0 * std::f64::consts::PI * (b.m / k).sqrt())
            .reduce(f64::min)
    }

    /// Checks the declaration: at least one body, positive masses, finite values,
    /// non-negative stiffness and damping, ends and bodies that exist, a spring between two
    /// different ends and not between two anchors, unique names, at most one contact a body.
    pub fn validate(&self) -> Result<(), SystemError> {
        if self.bodies.is_empty() {
            return Err(SystemError::Invalid {
                what: "system".into(),
                why: "it has no body: declare at least one [[body]]".into(),
            });
        }
        self.check_names()?;
        for b in &self.bodies {
            let what = || format!("[[body]] \"{}\"", b.name);
            check(what, "m", b.m, true)?;
            check(what, "x0", b.x0, false)?;
            check(what, "v0", b.v0, false)?;
        }
        for a in &self.anchors {
            let what = || format!("[[anchor]] \"{}\"", a.name);
            check(what, "x0", a.x0, false)?;
            check(what, "v", a.v, false)?;
        }
        for (i, s) in self.springs.iter().enumerate() {
            let what = || format!("[[spring]] {}", i + 1);
            non_negative(what, &[("k", s.k), ("c", s.c)])?;
            for end in [s.a, s.b] {
                let exists = match end {
                    End::Body(j) => j < self.bodies.len(),
                    End::Anchor(j) => j < self.anchors.len(),
                };
                if !exists {
                    return Err(SystemError::Invalid {
                        what: what(),
                        why: format!("its end {end:?} does not exist"),
                    });
                }
            }
            if s.a == s.b || matches!((s.a, s.b), (End::Anchor(_), End::Anchor(_))) {
                let name = |end: End| match end {
                    End::Body(j) => &self.bodies[j].name,
                    End::Anchor(j) => &self.anchors[j].name,
                };
                return Err(SystemError::Invalid {
                    what: what(),
                    why: format!(
                        "`between` = [\"{}\", \"{}\"]: a spring joins two different bodies, or \
                         a body and an anchor",
                        name(s.a),
                        name(s.b)
                    ),
                });
            }
        }
        let mut has_contact = vec![false; self.bodies.len()];
        for (i, c) in self.contacts.iter().enumerate() {
            let what = || format!("[[contact]] {}", i + 1);
            let Some(seen) = has_contact.get_mut(c.body) else {
                return Err(SystemError::Invalid {
                    what: what(),
                    why: format!("body index {} does not exist", c.body),
                });
            };
            if *seen {
                return Err(SystemError::Invalid {
                    what: what(),
                    why: format!(
                        "body \"{}\" has a contact already: a body has at most one contact",
                        self.bodies[c.body].name
                    ),
                });
            }
            *seen = true;
            check(what, "surface_velocity", c.surface_velocity, false)?;
            let states = c.model.n_states();
            if states > MAX_STATES {
                return Err(SystemError::Invalid {
                    what: what(),
                    why: format!(
                        "model `{}` has {states} internal states; allowed at most {MAX_STATES}",
                        c.model.name()
                    ),
                });
            }
        }
        for (i, f) in self.forces.iter().enumerate() {
            let what = || format!("[[force]] {}", i + 1);
            if f.body >= self.bodies.len() {
                return Err(SystemError::Invalid {
                    what: what(),
                    why: format!("body index {} does not exist", f.body),
                });
            }
            check(what, "constant", f.constant, false)?;
            match f.profile {
                Profile::Ramp { rate } => check(what, "rate", rate, false)?,
                Profile::Sine { amplitude, omega } => {
                    check(what, "amplitude", amplitude, false)?;
                    check(what, "omega", omega, false)?;
                }
                Profile::None | Profile::Trapezoid { .. } => {}
            }
        }
        self.validate_controllers()
    }

    /// Checks the controllers: bodies that exist, at most one a body, gains in [0, inf), a
    /// positive saturation, finite reference values, a reference table of at least one point
    /// whose times strictly increase.
    fn validate_controllers(&self) -> Result<(), SystemError> {
        let mut controlled = vec![false; self.bodies.len()];
        for (i, c) in self.controllers.iter().enumerate() {
            let what = || format!("[[controller]] {}", i + 1);
            let invalid = |why: String| SystemError::Invalid { what: what(), why };
            let Some(seen) = controlled.get_mut(c.body) else {
                return Err(invalid(format!("body index {} does not exist", c.body)));
            };
            if *seen {
                return Err(invalid(format!(
                    "body \"{}\" has a controller already: a body has at most one controller",
                    self.bodies[c.body].name
                )));
            }
            *seen = true;
            non_negative(what, &[("kp", c.kp), ("ki", c.ki), ("kd", c.kd)])?;
            if let Some(limit) = c.saturation {
                check(what, "saturation", limit, true)?;
            }
            for (key, value) in c.reference.numbers() {
                check(what, key, value, false)?;
            }
            if let Reference::Table { t, x } = &c.reference {
                if t.is_empty() || t.len() != x.len() {
                    return Err(invalid(format!(
                        "`reference.t` has {} times and `reference.x` {} positions: allowed \
                         one position a time, at least one",
                        t.len(),
                        x.len()
                    )));
                }
                if let Some(k) = (1..t.len()).find(|&k| t[k] <= t[k - 1]) {
                    return Err(invalid(format!(
                        "`reference.t` does not increase: t = {} after t = {}; allowed \
                         strictly increasing times",
                        t[k],
                        t[k - 1]
                    )));
                }
            }
        }
        Ok(())
    }
}
