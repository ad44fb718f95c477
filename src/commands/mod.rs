//! One module per command of `friction-lab`.

pub mod curve;
pub mod models;
pub mod phenomena;
pub mod reproduce;
pub mod simulate;
pub mod studies;
pub mod sweep;
pub mod testset;
