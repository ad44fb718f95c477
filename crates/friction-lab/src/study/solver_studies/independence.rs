//! `independence`: one solver at a ladder of resolutions, with a Richardson estimate of the
//! error left and a verdict.

use super::Problem;
use crate::error::AppError;
use crate::made::Made;
use crate::study::{conduct, IndependenceStudy, Refinement};
use crate::warnings::diverged_line;
use integrators::Solver;
use std::path::Path;

/// Step-size independence of one solver on a problem (`friction-lab independence`).
#[derive(clap::Args, Clone, Debug)]
pub struct IndependenceRequest {
    /// The problem.
    #[command(flatten)]
    pub problem: Problem,
    /// The solver; `None`: RK4.
    #[arg(
        long,
        value_name = "SOLVER",
        help = crate::settings::solver_help(
            "The solver",
            "[default: rk4; refused under --scheme time-stepping, whose one method is \
             Moreau–Jean's scheme]"
        )
    )]
    pub solver: Option<Solver>,
    /// The ladder of resolutions and the verdict's tolerance.
    #[command(flatten)]
    pub refinement: Refinement,
}

impl IndependenceRequest {
    /// The study of `problem` with every other setting at its default
    /// ([`Refinement::default`]).
    pub fn new(problem: Problem) -> IndependenceRequest {
        IndependenceRequest {
            problem,
            solver: None,
            refinement: Refinement::default(),
        }
    }

    /// Checks and runs the study: its files in `out` (in memory), and one line per output
    /// with its remaining error, the failed levels, and the verdict.
    pub fn run(&self, out: &Path) -> Result<Made, AppError> {
        self.problem.make(out, |t, setup| {
            let methods =
                (self.problem).methods(setup, "solver", self.solver.as_slice(), &[Solver::RK4])?;
            let study = IndependenceStudy {
                case: setup.case.as_ref(),
                method: methods[0],
                refinement: self.refinement,
            };
            let s = conduct(&study, t, "independence")?;
            let mut notes: Vec<String> = (s.outputs.iter())
                .map(|o| {
                    let verdict = if o.independent {
                        "independent"
                    } else {
                        "NOT independent"
                    };
                    format!(
                        "{:24} remaining error {:.3e} {verdict}",
                        o.name, o.remaining_error
                    )
                })
                .collect();
            let verdict = if s.independent {
                "independent of"
            } else {
                "not independent of"
            };
            notes.extend(s.failed.iter().map(|f| {
                format!(
                    "level {} ({:e}) failed, not judged: {}",
                    f.level, f.resolution, f.failure
                )
            }));
            if s.failed.iter().any(|f| f.diverged) {
                notes.push(diverged_line(&crate::error::field("start")));
            }
            notes.push(format!("verdict: {verdict} the step size"));
            Ok(notes)
        })
    }
}
