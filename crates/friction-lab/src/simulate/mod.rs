//! One run simulated and written: a rig ([`simulate_rig`]) or a system of many bodies
//! ([`simulate_system`]), its files and figures in memory ([`Made`](crate::artifacts::Made)),
//! for the command line, Python and a Rust user alike.

mod rig;
mod stiffness;
mod system;

pub use rig::simulate_rig;
pub use stiffness::add_stiffness;
pub use system::{load, simulate_system, Described, SystemRun, DRAWN_BODIES};
