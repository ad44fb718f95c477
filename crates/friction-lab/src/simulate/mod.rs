//! One run simulated and written: a rig ([`simulate_rig`]) or a system of many bodies
//! ([`simulate_system`]), its files and figures in memory ([`Made`](crate::made::Made)),
//! for the command line, Python and a Rust user alike; [`SimulationRequest`] is the run as a front
//! end asks for it, checked.

mod bodies;
mod delivered;
mod motion;
pub mod request;
mod rig;
mod space_time;
mod spectra;
mod stiffness;
mod system;

pub use bodies::chosen_bodies;
pub use motion::{spread, LINE_BODIES};
pub use request::{scenario_help, SimulationRequest, Target};
pub use rig::simulate_rig;
pub use stiffness::add_stiffness;
pub use system::{load, simulate_system, Described, SystemRun};
