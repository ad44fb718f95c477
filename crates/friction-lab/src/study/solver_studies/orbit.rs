//! `orbit`: the periodic orbit of a rig's body or a system, found by shooting on the hybrid
//! system from the cycle its run settles onto ([`scenarios::orbit`]).

use super::Problem;
use crate::error::AppError;
use crate::made::Made;
use crate::study::{conduct, orbit_lines, OrbitStudy};
use periodic::ShootingOptions;
use scenarios::orbit::OrbitSettings;
use std::path::Path;

/// The periodic orbit of a problem (`friction-lab orbit`). Its run from the declared initial
/// state to --t-end settles onto the cycle whose switches give the guess; the orbit is
/// computed event-driven, with events at v_rel = 0 (the scheme options are not read).
#[derive(clap::Args, Clone, Debug)]
pub struct OrbitRequest {
    /// The problem (its end time is the settling run's).
    #[command(flatten)]
    pub problem: Problem,
    /// Points of the orbit sampled evenly over its period (`orbit.csv`, the phase portrait).
    #[arg(
        long,
        value_name = "N",
        default_value_t = 401,
        allow_hyphen_values = true
    )]
    pub samples: i64,
}

/// The most points an orbit is sampled at.
pub const MAX_SAMPLES: i64 = 1_000_000;

/// `--samples`, checked: 2 to [`MAX_SAMPLES`].
pub fn samples(samples: i64) -> Result<usize, AppError> {
    match (2..=MAX_SAMPLES).contains(&samples) {
        true => Ok(samples as usize),
        false => Err(AppError::Invalid(crate::error::Invalid {
            field: "samples",
            value: samples.to_string(),
            allowed: format!("[2, {MAX_SAMPLES}]"),
            list: false,
        })),
    }
}

impl OrbitRequest {
    /// Checks and finds the orbit: its files in `out` (in memory), and its period and
    /// multipliers as lines.
    pub fn run(&self, out: &Path) -> Result<Made, AppError> {
        self.problem.refuse_scheme(
            "orbit",
            "the orbit is found event-driven, with events at v_rel = 0",
        )?;
        let samples = samples(self.samples)?;
        self.problem.make(out, |t, setup| {
            let study = OrbitStudy {
                case: setup.case.as_ref(),
                settings: OrbitSettings {
                    settle: setup.case.t_end(),
                    shooting: ShootingOptions::default(),
                    samples,
                },
            };
            let orbit = conduct(&study, t, "orbit")?;
            Ok(orbit_lines(&orbit))
        })
    }
}
