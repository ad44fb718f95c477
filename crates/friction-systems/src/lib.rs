//! Friction systems: many bodies on one line, joined by springs and dampers, driven by
//! anchors and external forces, each on its own friction contact (`docs/systems.md`).
//!
//! The layers, as in Siconos, keep the declaration apart from the scheme that integrates it:
//!
//! - [`system`]: the declaration ([`System`]: bodies, anchors, springs, contacts, forces,
//!   controllers ([`control`])),
//!   built in code or read from a TOML file ([`mod@file`]), or generated ([`chain`]);
//! - [`hybrid`]: the system as a hybrid ODE ([`FrictionSystem`], an
//!   [`integrators::OdeProblem`]): the state layout ([`layout`]), one stick/slip mode per
//!   contact, two event functions per contact, the analytic sparse Jacobian, the energy
//!   accumulators ([`energy`]);
//! - [`scheme`]: how the system is integrated ([`Scheme`]): event-driven by a solver with a
//!   treatment of v_rel = 0 ([`switching`]: event location, regularised, naive), or
//!   time-stepped;
//! - [`moreau_jean`]: the same system time-stepped by Moreau–Jean's scheme, each step's
//!   contact problem solved by nonsmooth Gauss–Seidel ([`MoreauJean`]), with Newton's
//!   correction where the coupling is stiff (`correction`);
//! - [`run`]: one integration by any solver of `integrators`, or by time-stepping, read per
//!   body and per contact.
//!
//! Any [`friction_models::FrictionModel`], also one written in another crate, can sit at a
//! contact.

pub mod chain;
pub mod control;
mod correction;
pub mod energy;
pub mod file;
pub mod hybrid;
pub mod layout;
mod local;
pub mod moreau_jean;
pub mod reach;
pub mod run;
pub mod scheme;
mod springs;
pub mod switching;
pub mod system;

pub use chain::ChainParams;
pub use control::{CompensatedAt, Compensation, Controller, Reference};
pub use energy::EnergyBalance;
pub use hybrid::FrictionSystem;
pub use layout::Layout;
pub use moreau_jean::MoreauJean;
pub use reach::{Reach, RUNAWAY_FACTOR};
pub use run::{simulate, simulate_spans, BodyState, ContactEvent, Run, StiffnessPoint};
pub use scheme::Scheme;
pub use switching::{mode_name, Switching, SLIP_NEGATIVE, SLIP_POSITIVE, STICK};
pub use system::{Anchor, Body, Contact, End, Force, Profile, Spring, System, SystemError};
