//! Where each unknown of a system lives in the state vector `y`: per body `x_i`, `v_i` and,
//! at a contact whose model has them, the internal states `z_i`, body after body (so that the
//! Jacobian of a chain is banded); then the integral of the error of each controller (see
//! [`crate::control`]); then the three energy accumulators (see [`crate::energy`]).

use crate::system::System;
use std::ops::Range;

/// The state layout of a system.
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    /// Index of `x_i`; `v_i` follows it, then the states `z_i`.
    pub x: Vec<usize>,
    /// Indices of the internal states of each body's contact model (empty without one).
    pub z: Vec<Range<usize>>,
    /// The contact of each body, by index.
    pub contact: Vec<Option<usize>>,
    /// Index of each controller's integral of the error, in the order of the controllers.
    pub integral: Vec<usize>,
    /// Index of the first energy accumulator; the state has three more unknowns.
    pub accumulators: usize,
}

impl Layout {
    /// The layout of `system` (which must be valid).
    pub fn of(system: &System) -> Layout {
        let n = system.bodies.len();
        let mut contact = vec![None; n];
        for (j, c) in system.contacts.iter().enumerate() {
            contact[c.body] = Some(j);
        }
        let (mut x, mut z, mut next) = (Vec::with_capacity(n), Vec::with_capacity(n), 0);
        for c in &contact {
            x.push(next);
            next += 2;
            let states = c.map_or(0, |j| system.contacts[j].model.n_states());
            z.push(next..next + states);
            next += states;
        }
        let integral = (next..next + system.controllers.len()).collect();
        next += system.controllers.len();
        Layout {
            x,
            z,
            contact,
            integral,
            accumulators: next,
        }
    }

    /// Index of `v_i`.
    pub fn v(&self, body: usize) -> usize {
        self.x[body] + 1
    }

    /// The internal states of body `i`'s contact in `y`.
    pub fn states<'y>(&self, i: usize, y: &'y [f64]) -> &'y [f64] {
        &y[self.z[i].clone()]
    }

    /// Whether some contact has an internal state.
    pub fn has_states(&self) -> bool {
        self.z.iter().any(|z| !z.is_empty())
    }

    /// Number of unknowns, accumulators included.
    pub fn dim(&self) -> usize {
        self.accumulators + 3
    }
}
