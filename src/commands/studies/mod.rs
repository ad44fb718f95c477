//! The solver studies: `converge`, `independence`, `work-precision`, `stiffness`. Every
//! run of a study is independent; they run on a pool of `--threads` workers and are
//! collected in order, so the files do not depend on the thread count (wall times, which
//! cannot be reproduced, go to a separate `*-timing.csv`).

use crate::commands::simulate::Target as Problem;
use crate::options::{LimitArgs, ModelOptions, SchemeArgs};
use clap::Args;
use friction_lab::artifacts::{Artifacts, Made};
use friction_lab::error::AppError;
use friction_lab::laws::ModelChoice;
use friction_lab::ranges;
use friction_lab::simulate::chosen_bodies;
use friction_lab::simulate::request::{derived_t_end, study_t_end, system_of};
use friction_lab::study::Target;
use friction_lab::warnings::{diverged_line, unread_warnings};
use friction_models::params::show;
use integrators::Solver;
use scenarios::run::DEFAULT_THETA;
use scenarios::studies::{Case, StepKind, StudyCase, StudyRun, SystemCase};
use scenarios::{Scenario, SwitchingKind};
use std::path::PathBuf;

mod converge;
mod independence;
mod stiffness;
mod work_precision;

pub use converge::{converge, ConvergeArgs};
pub use independence::{independence, IndependenceArgs};
pub use stiffness::{stiffness, StiffnessArgs};
pub use work_precision::{work_precision, WorkPrecisionArgs};

/// The problem a study runs.
#[derive(Args, Debug, Clone)]
pub struct CaseArgs {
    /// A scenario (paper-block, belt, free-vibration, …), or chain (the Burridge–Knopoff
    /// chain of docs/systems.md, its parameters by --set); omit it with --system (or, for
    /// work-precision, --testset).
    #[arg(value_name = "SCENARIO", conflicts_with = "system")]
    pub scenario: Option<Problem>,
    /// A system file (TOML or JSON, docs/systems.md) to study instead of a scenario.
    #[arg(long, value_name = "FILE.toml")]
    pub system: Option<PathBuf>,
    /// The friction model (scenarios and chain), as `friction-lab models` lists it, or a law
    /// registered by name (from Python: docs/python.md).
    #[arg(long, value_name = "MODEL")]
    pub model: Option<ModelChoice>,
    /// Systems: the bodies whose trajectories, event times and stick phases are measured
    /// (names or 1-based indices) [default: the first body]; the final state is measured on
    /// every body.
    #[arg(long, value_name = "LIST", value_delimiter = ',')]
    pub bodies: Vec<String>,
    /// The scheme, and the treatment of v = 0 under the event-driven one.
    #[command(flatten)]
    pub scheme: SchemeArgs,
    /// End time, s [default: the scenario's; 10 for the chain (its horizon of predictability:
    /// docs/studies.md); 20 for a system file].
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub t_end: Option<f64>,
    /// Folder to write into (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// The bounds of each run (a run past them fails, and the study says which).
    #[command(flatten)]
    pub limits: LimitArgs,
    /// Worker threads (default: all cores; more than the machine has are capped to its cores).
    /// The results do not depend on it.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub threads: Option<i64>,
    /// The model's parameters and reading.
    #[command(flatten)]
    pub model_options: ModelOptions,
}

impl CaseArgs {
    /// The study case: a rig, the chain, or a system file.
    pub fn case(&self) -> Result<Box<dyn StudyCase>, AppError> {
        if self.scenario.is_none() && self.system.is_none() {
            return Err(AppError::Usage(
                "the study needs a problem: a SCENARIO, or --system FILE.toml (work-precision \
                 also takes --testset PROBLEM)"
                    .into(),
            ));
        }
        let check_t_end = |t_end: f64| ranges::T_END.check(t_end);
        let scenario = match self.scenario {
            Some(Problem::Rig(s)) => s,
            _ => {
                let described = system_of(
                    self.system.as_deref(),
                    self.model.as_ref(),
                    &self.model_options.settings(),
                )?;
                described.system.validate()?;
                let bodies = if self.bodies.is_empty() {
                    vec![0]
                } else {
                    chosen_bodies(&described.system, &self.bodies)?
                };
                return Ok(Box::new(SystemCase {
                    name: described.name,
                    system: described.system,
                    switching: self.treatment()?,
                    epsilon: described.friction.epsilon,
                    t_end: check_t_end(
                        self.t_end
                            .unwrap_or_else(|| study_t_end(self.system.as_deref())),
                    )?,
                    bodies,
                    limits: self.limits.limits()?,
                    chain: described.source,
                }));
            }
        };
        if scenario == Scenario::VelocitySweep {
            return Err(AppError::Usage(
                "the studies integrate trajectories: velocity-sweep has none; use another scenario"
                    .into(),
            ));
        }
        if !self.bodies.is_empty() {
            return Err(AppError::Usage(
                "option `--bodies` applies to systems (chain, --system), not to a rig".into(),
            ));
        }
        let model = self.model.as_ref().ok_or_else(|| {
            AppError::Usage(format!(
                "option `--model` is required for scenario {scenario}: e.g. --model CS"
            ))
        })?;
        let (friction, params) = self
            .model_options
            .params
            .source()
            .resolve_for(Some(scenario))?;
        let t_end = match self.t_end {
            Some(t) => check_t_end(t)?,
            None => check_t_end(derived_t_end(scenario, &params, &friction)?)?,
        };
        Ok(Box::new(Case {
            scenario,
            law: model.law(self.model_options.variant),
            friction,
            params,
            switching: self.treatment()?,
            t_end,
            limits: self.limits.limits()?,
        }))
    }
}

impl CaseArgs {
    /// The solvers a study compares: those `given` by `option`, or `defaults` when none are. Under
    /// time-stepping the study's one method is Moreau–Jean's scheme, which takes no solver:
    /// naming one is refused rather than ignored.
    pub fn solvers(
        &self,
        option: &str,
        given: &[Solver],
        defaults: &[Solver],
    ) -> Result<Vec<Solver>, AppError> {
        if !given.is_empty() && self.treatment()?.is_time_stepping() {
            return Err(AppError::Usage(format!(
                "option `--{option} {}` does not apply to --scheme time-stepping: the study's one \
                 method is Moreau–Jean's scheme over the study's step sizes, which takes no ODE \
                 solver; drop the solvers, or choose --scheme event-driven",
                given.iter().map(|s| s.name()).collect::<Vec<_>>().join(",")
            )));
        }
        Ok(or_default(given, defaults))
    }

    /// The treatment of v = 0 that `--scheme` and `--switching` ask for (time-stepping at
    /// θ = 1/2).
    pub fn treatment(&self) -> Result<SwitchingKind, AppError> {
        self.scheme.choice().treatment(DEFAULT_THETA)
    }

    /// Sets up the case, runs `study` (which returns its lines for the terminal), and keeps
    /// its files in memory.
    fn make(
        &self,
        study: impl FnOnce(&mut Target, &dyn StudyCase) -> Result<Vec<String>, AppError>,
    ) -> Result<Made, AppError> {
        let case = self.case()?;
        let case = case.as_ref();
        let mut files = Artifacts::default();
        let mut target = Target {
            files: &mut files,
            dir: &self.out,
            threads: ranges::threads(self.threads)?,
            failure: None,
        };
        let notes = study(&mut target, case)?;
        let failure = target.failure;
        // A study of a system under event switching also runs its regularised peer (BDF on
        // the regularised system), which reads epsilon.
        let switching = match (self.scenario, self.treatment()?) {
            (Some(Problem::Rig(_)), s) => s,
            (_, SwitchingKind::Event) => SwitchingKind::Regularized,
            (_, s) => s,
        };
        Ok(Made {
            files,
            notes,
            warnings: unread_warnings(
                &self.model_options.params.set,
                self.model.as_ref().and_then(ModelChoice::catalog),
                switching,
            )
            .into_iter()
            .chain(self.scheme.choice().spelling_notes())
            .collect(),
            failure,
            trajectory: None,
        })
    }
}

/// `given` (a list option), or `defaults` when none are given.
pub fn or_default<T: Copy>(given: &[T], defaults: &[T]) -> Vec<T> {
    if given.is_empty() { defaults } else { given }.to_vec()
}

/// One line for each method with failed runs of a study (an unstable step, a limit): how many,
/// and the first's resolution and error (their status in the study's `csv`). Their errors are
/// missing, which `converge`'s order lines count with round-off; this says why. A last line
/// says why, when a run of an explicit method diverged with its fixed step.
pub fn failures(runs: &[StudyRun], csv: &str) -> Vec<String> {
    let diverged = runs
        .iter()
        .any(|r| r.diverged)
        .then(|| diverged_line("step in --dt-list"));
    // A study's runs come method by method (`Method::jobs`), each method once.
    runs.chunk_by(|a, b| a.solver == b.solver)
        .filter_map(|mine| {
            let failed: Vec<&StudyRun> = mine.iter().filter(|r| r.failure.is_some()).collect();
            let first = failed.first()?;
            let at = if first.step == StepKind::Fixed {
                "h"
            } else {
                "tol"
            };
            Some(format!(
                "{:15} {} of {} runs failed (status in {csv}); the first, at {at} = {}: {}",
                first.solver,
                failed.len(),
                mine.len(),
                show(first.resolution),
                first
                    .failure
                    .as_ref()
                    .map(|e| e.to_string())
                    .unwrap_or_default()
            ))
        })
        .chain(diverged)
        .collect()
}
