//! The built-in experiments of Table 2, one struct a row: at rest and at break-away
//! ([`at_rest`]), in steady sliding ([`steady`]), in motion ([`motion`]).

mod at_rest;
mod motion;
mod steady;

pub use at_rest::{Presliding, RisingStaticFriction, Stiction};
pub use motion::{Hysteresis, StickSlip};
pub use steady::{Stribeck, Viscous};
