//! The built-in rigs of `docs/scenarios.md`, each a [`crate::rig::Rig`]: the ones that
//! integrate a body (`body.rs`), the closed loop (`servo.rs`) and the ones that impose a motion
//! (`motion.rs`).

mod body;
mod motion;
mod servo;

pub use body::{Belt, ForceRamp, FreeVibration, PaperBlock, Presliding};
pub use motion::{Oscillation, PrescribedMotion, VelocityOscillation, VelocitySweep};
pub use servo::Servo;
