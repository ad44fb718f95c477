//! `continue`: the branches of equilibria and periodic orbits of a rig or the chain over one
//! parameter, by pseudo-arclength continuation ([`scenarios::orbit::follow`]).

use super::Problem;
use crate::error::{field, AppError};
use crate::made::Made;
use crate::study::{branches_lines, conduct, BranchesStudy};
use friction_models::params::show;
use periodic::ShootingOptions;
use scenarios::orbit::OrbitSettings;
use std::path::Path;

/// The branches of a problem over one parameter (`friction-lab continue`): from the start of
/// --range, the cycle its run to --t-end settles onto and the steady sliding, each followed to
/// the end of the range, event-driven with events at v_rel = 0.
#[derive(clap::Args, Clone, Debug)]
pub struct ContinueRequest {
    /// The problem (its end time is the settling run's at the start of the range).
    #[command(flatten)]
    pub problem: Problem,
    /// The parameter followed: any the run reads (a rig's `v_belt`, `k`, `c`, `kp`, …, a
    /// friction parameter `F_s`, …; on the chain its own).
    #[arg(long, value_name = "NAME")]
    pub parameter: String,
    /// The range A:B: the branches start at A and are followed towards B (A > B follows them
    /// downwards).
    #[arg(long, value_name = "A:B", allow_hyphen_values = true)]
    pub range: String,
    /// Values of the parameter at which each branch that passes them adds a row computed
    /// exactly there (Newton at that value), besides the continuation's own steps.
    #[arg(
        long,
        value_name = "LIST",
        value_delimiter = ',',
        allow_hyphen_values = true
    )]
    pub at: Vec<f64>,
    /// Points of each orbit sampled for its amplitude.
    #[arg(
        long,
        value_name = "N",
        default_value_t = 201,
        allow_hyphen_values = true
    )]
    pub samples: i64,
}

impl ContinueRequest {
    /// The range, checked: two finite numbers, different.
    fn range(&self) -> Result<(f64, f64), AppError> {
        let bad = |why: &str| {
            AppError::Usage(format!(
                "option `{}` = `{}`: {why}",
                field("range"),
                self.range
            ))
        };
        let (a, b) =
            (self.range.split_once(':')).ok_or_else(|| bad("expected A:B, such as 0.01:0.5"))?;
        let number = |s: &str| {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| bad(&format!("`{s}` is not a finite number")))
        };
        let (a, b) = (number(a)?, number(b)?);
        if a == b {
            return Err(bad("the two ends are equal: allowed A ≠ B"));
        }
        Ok((a, b))
    }

    /// Checks and follows the branches: their files in `out` (in memory), and the special
    /// points as lines.
    pub fn run(&self, out: &Path) -> Result<Made, AppError> {
        self.problem.refuse_scheme(
            "continue",
            "the branches are followed event-driven, with events at v_rel = 0",
        )?;
        let range = self.range()?;
        if let Some(v) = self.at.iter().find(|v| !v.is_finite()) {
            return Err(AppError::Invalid(crate::error::Invalid {
                field: "at",
                value: show(*v),
                allowed: "finite values".into(),
                list: true,
            }));
        }
        let samples = super::orbit::samples(self.samples)?;
        self.problem.make(out, |t, setup| {
            // The parameter at both ends of the range, before anything runs.
            for end in [range.0, range.1] {
                setup
                    .case
                    .with_parameter(&self.parameter, end)
                    .map_err(|e| {
                        AppError::Usage(format!("option `{}`: {e}", field("parameter")))
                    })?;
            }
            let study = BranchesStudy {
                case: setup.case.as_ref(),
                parameter: &self.parameter,
                range,
                at: &self.at,
                settings: OrbitSettings {
                    settle: setup.case.t_end(),
                    shooting: ShootingOptions::default(),
                    samples,
                },
            };
            let branches = conduct(&study, t, "continue")?;
            Ok(branches_lines(&branches))
        })
    }
}
