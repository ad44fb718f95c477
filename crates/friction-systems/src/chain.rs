//! The built-in Burridge–Knopoff chain of `docs/systems.md`: `n_bodies` blocks of mass `m`,
//! neighbours joined by springs `k_chain`, each block pulled by its own spring `k_driver`
//! from one driver anchor moving at `v_driver`, each on the floor with its own friction.
//! So that the blocks do not move in lock step, every force level of block i (F_c, F_s, C1,
//! C2) is multiplied by `1 + spread·sin(i)`, `i = 1..N`.

use crate::system::{End, System, SystemError};
use friction_models::{FrictionModel, FrictionParams};
use serde::Serialize;
use std::sync::Arc;

/// The chain's parameters.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ChainParams {
    /// Number of blocks N, 1 to [`MAX_BODIES`].
    pub n_bodies: usize,
    /// Mass of each block, kg.
    pub m: f64,
    /// Stiffness of the springs between neighbours, N/m.
    pub k_chain: f64,
    /// Stiffness of each block's driver spring, N/m.
    pub k_driver: f64,
    /// Velocity of the driver, m/s.
    pub v_driver: f64,
    /// Relative variation of the friction levels along the chain, in [0, 1).
    pub spread: f64,
}

/// The largest chain that can be generated.
pub const MAX_BODIES: usize = 1_000_000;

impl Default for ChainParams {
    /// `docs/systems.md`: N = 10, m = 1, k_chain = 100, k_driver = 10, v_driver = 0.1, spread = 0.1.
    fn default() -> Self {
        ChainParams {
            n_bodies: 10,
            m: 1.0,
            k_chain: 100.0,
            k_driver: 10.0,
            v_driver: 0.1,
            spread: 0.1,
        }
    }
}

/// The chain's parameters by name, with their allowed ranges and units as messages give them
/// (for `--set`), and their SI units ("" for a count or a ratio).
pub const CHAIN_PARAMETERS: [(&str, &str, &str); 6] = [
    ("n_bodies", "[1, 1000000], a whole number", ""),
    ("m", "(0, inf) kg", "kg"),
    ("k_chain", "[0, inf) N/m", "N/m"),
    ("k_driver", "[0, inf) N/m", "N/m"),
    ("v_driver", "(-inf, inf) m/s", "m/s"),
    ("spread", "[0, 1)", ""),
];

impl ChainParams {
    /// Sets the parameter `name` to `value`, checking its range; `Ok(false)` if `name` is
    /// not a chain parameter.
    pub fn set(&mut self, name: &str, value: f64) -> Result<bool, SystemError> {
        let Some(&(key, allowed, _)) = CHAIN_PARAMETERS.iter().find(|p| p.0 == name) else {
            return Ok(false);
        };
        let ok = value.is_finite()
            && match key {
                "n_bodies" => value >= 1.0 && value <= MAX_BODIES as f64 && value.fract() == 0.0,
                "m" => value > 0.0,
                "k_chain" | "k_driver" => value >= 0.0,
                "spread" => (0.0..1.0).contains(&value),
                _ => true,
            };
        if !ok {
            return Err(SystemError::OutOfRange {
                what: "chain".into(),
                key,
                value,
                allowed,
            });
        }
        match key {
            "n_bodies" => self.n_bodies = value as usize,
            "m" => self.m = value,
            "k_chain" => self.k_chain = value,
            "k_driver" => self.k_driver = value,
            "v_driver" => self.v_driver = value,
            _ => self.spread = value,
        }
        Ok(true)
    }

    /// The factor of block i's force levels (i = 1..N): `1 + spread·sin(i)`.
    pub fn level(&self, i: usize) -> f64 {
        1.0 + self.spread * (i as f64).sin()
    }

    /// The chain, block i's friction law built by `model` from `friction` with its force
    /// levels scaled by [`ChainParams::level`].
    pub fn build<E>(
        &self,
        friction: &FrictionParams,
        model: impl Fn(&FrictionParams) -> Result<Arc<dyn FrictionModel>, E>,
    ) -> Result<System, E> {
        let mut s = System::default();
        let driver = s.add_anchor("driver", 0.0, self.v_driver);
        for i in 1..=self.n_bodies {
            let body = s.add_body(format!("b{i}"), self.m, 0.0, 0.0);
            s.add_spring(End::Anchor(driver), End::Body(body), self.k_driver, 0.0);
            if i > 1 {
                s.add_spring(End::Body(body - 1), End::Body(body), self.k_chain, 0.0);
            }
            s.add_contact(body, 0.0, model(&scale_levels(friction, self.level(i)))?);
        }
        Ok(s)
    }
}

/// `p` with every force level (F_s, F_c, C1, C2) multiplied by `factor`.
pub fn scale_levels(p: &FrictionParams, factor: f64) -> FrictionParams {
    FrictionParams {
        f_s: p.f_s * factor,
        f_c: p.f_c * factor,
        c1: p.c1 * factor,
        c2: p.c2 * factor,
        ..*p
    }
}
