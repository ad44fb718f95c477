//! What a run's result says, computed from it after the run: its settled state as a sweep
//! measures it ([`settled`]), what a closed loop did ([`closed_loop`]), the
//! describing-function prediction of a hunting cycle to set beside it
//! ([`describing_function`]; both for any system's loop: [`servo_loop`]), and the amplitude spectrum of a signal ([`spectrum`]). Nothing
//! here integrates a rig or writes a file.

pub mod closed_loop;
pub mod describing_function;
pub mod servo_loop;
pub mod settled;
pub mod spectrum;
