//! The built-in experiments of Table 2, one struct a row: at rest and at break-away
//! ([`at_rest`]), in steady sliding ([`steady`]), in motion ([`motion`]), in closed loop
//! ([`closed_loop`]).

mod at_rest;
mod closed_loop;
mod motion;
mod steady;

pub use at_rest::{Presliding, RisingStaticFriction, Stiction};
pub use closed_loop::Hunting;
pub use motion::{Hysteresis, StickSlip};
pub use steady::{Stribeck, Viscous};
