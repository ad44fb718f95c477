//! The built-in rigs of `docs/scenarios.md`, each a [`crate::rig::Rig`]: the ones that
//! integrate a body (`body.rs`) and the ones that impose a motion (`motion.rs`).

mod body;
mod motion;

pub use body::{Belt, ForceRamp, FreeVibration, PaperBlock, Presliding};
pub use motion::{Oscillation, PrescribedMotion, VelocityOscillation, VelocitySweep};
