//! `closed-loop`: the closed loop of the servo rig or of a system file with a controller, at
//! one's own gains, plant and set point: the loop's simulated measures and regime beside the
//! describing function's prediction of its hunting cycle ([`LoopStudy`]).

use super::Problem;
use crate::error::AppError;
use crate::made::Made;
use crate::study::{conduct, loop_lines, LoopStudy};
use scenarios::phenomena::thresholds::{HUNTING_POINTS, HUNTING_T_END};
use std::path::Path;

/// The closed loop of a problem (`friction-lab closed-loop`): its run under the hunting
/// protocol (diffsol's BDF at rtol 1e-10, atol 1e-12, event-driven), 800 s long unless
/// --t-end says otherwise, measured as Table 2's hunting runs are (the scheme options are not
/// read).
#[derive(clap::Args, Clone, Debug)]
pub struct ClosedLoopRequest {
    /// The problem: the servo rig (its gains, mass and set point by --set kp=…, --set ki=…,
    /// kd, m, x_ref) or a system file with a controller; its end time is 800 s, the hunting
    /// protocol's, unless --t-end is given.
    #[command(flatten)]
    pub problem: Problem,
    /// Output points over the run, evenly spaced: the loop's period and amplitude are read off
    /// them.
    #[arg(
        long,
        value_name = "N",
        default_value_t = HUNTING_POINTS as i64,
        allow_hyphen_values = true
    )]
    pub points: i64,
}

/// The fewest and most output points of a closed-loop run.
pub const POINTS_RANGE: (i64, i64) = (101, 10_000_000);

impl ClosedLoopRequest {
    /// Checks and analyses the loop: its files in `out` (in memory), and its measures and
    /// prediction as lines; an unsettled loop is a warning.
    pub fn run(&self, out: &Path) -> Result<Made, AppError> {
        self.problem.refuse_scheme(
            "closed-loop",
            "the loop is run event-driven under the hunting protocol",
        )?;
        let (lo, hi) = POINTS_RANGE;
        if !(lo..=hi).contains(&self.points) {
            return Err(AppError::Invalid(crate::error::Invalid {
                field: "points",
                value: self.points.to_string(),
                allowed: format!("[{lo}, {hi}]"),
                list: false,
            }));
        }
        let problem = Problem {
            t_end: Some(self.problem.t_end.unwrap_or(HUNTING_T_END)),
            ..self.problem.clone()
        };
        let mut unsettled = None;
        let mut made = problem.make(out, |t, setup| {
            let study = LoopStudy {
                case: setup.case.as_ref(),
                points: self.points as usize,
            };
            let result = conduct(&study, t, "closed-loop")?;
            let c = &result.analysis.simulated;
            unsettled = c.hunting.is_none().then(|| c.to_string());
            Ok(loop_lines(&result))
        })?;
        made.warnings.extend(unsettled);
        Ok(made)
    }
}
