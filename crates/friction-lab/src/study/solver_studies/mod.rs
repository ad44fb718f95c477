//! The four solver studies as a front end asks for them: a [`Problem`] (a rig, the chain or a
//! system file, with its model, scheme, end time and bounds) and each study's own settings
//! ([`ConvergeRequest`], [`IndependenceRequest`], [`WorkPrecisionRequest`], [`StiffnessRequest`]), checked here and run
//! into their files and the lines a front end prints. Every run of a study is independent;
//! they run on a pool of threads and are collected in order, so the files do not depend on the
//! thread count (wall times, which cannot be reproduced, go to a separate `*-timing.csv`).

mod branches;
mod closed_loop;
mod compare;
mod converge;
mod independence;
mod named;
mod orbit;
mod stiffness;
mod work_precision;

pub use branches::ContinueRequest;
pub use closed_loop::ClosedLoopRequest;
pub use compare::CompareRequest;
pub use converge::{ConvergeRequest, CONVERGE_SOLVERS};
pub use independence::IndependenceRequest;
pub use named::{
    Declared, NamedStudy, Runs, StudyRequest, CLOSED_LOOP, COMPARE, CONTINUE, CONVERGE,
    INDEPENDENCE, ORBIT, STIFFNESS, STUDIES, WORK_PRECISION,
};
pub use orbit::OrbitRequest;
pub use stiffness::{StiffnessRequest, STIFFNESS_SOLVERS};
pub use work_precision::{
    WorkPrecisionRequest, TESTSET_SOLVERS, TESTSET_TOLERANCES, WP_TOLERANCES,
};

use crate::artifacts::Artifacts;
use crate::error::{field, setting, AppError};
use crate::laws::ModelChoice;
use crate::made::Made;
use crate::ranges;
use crate::settings::{ModelSettings, RunLimits, SchemeChoice};
use crate::simulate;
use crate::simulate::chosen_bodies;
use crate::simulate::request::{bodies_of_a_rig, derived_t_end, rig_law, study_t_end, system_of};
use crate::study::Output;
use crate::warnings::{diverged_line, unread_warnings};
use friction_models::params::show;
use friction_systems::file::SystemSource;
use friction_systems::{Scheme, Switching};
use integrators::Solver;
use scenarios::run::DEFAULT_THETA;
use scenarios::studies::{Case, Method, StepKind, StudyCase, StudyRun, SystemCase};
use scenarios::Scenario;
use std::path::Path;

/// The problem a solver study runs, with the settings every study shares; its `Default` is
/// the declared defaults, with no problem named.
#[derive(clap::Args, Clone, Debug)]
pub struct Problem {
    /// The rig or the chain ([`Problem::target`] with `system`); neither is refused
    /// (work–precision also takes a problem of the stiff test set instead).
    #[arg(
        help = simulate::scenario_help(
            "The rig",
            "or chain (the Burridge–Knopoff chain of docs/systems.md, its parameters by --set); \
             omit it with --system (or, for work-precision, --testset)",
        ),
        value_name = "SCENARIO",
        conflicts_with = "system"
    )]
    pub scenario: Option<simulate::Target>,
    /// A system file (TOML or JSON, docs/systems.md) to study instead of a scenario, or the
    /// system itself as JSON text (starting with `{`).
    #[arg(long, value_name = "FILE.toml")]
    pub system: Option<SystemSource>,
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
    pub scheme: SchemeChoice,
    /// End time, s [default: the scenario's; 10 for the chain (its horizon of predictability:
    /// docs/studies.md); 20 for a system file].
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub t_end: Option<f64>,
    /// The bounds of each run (a run past them fails, and the study says which).
    #[command(flatten)]
    pub limits: RunLimits,
    /// Worker threads (default: all cores; more than the machine has are capped to its cores).
    /// The results do not depend on it.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub threads: Option<i64>,
    /// The model's parameters and reading.
    #[command(flatten)]
    pub model_settings: ModelSettings,
}

crate::settings::default_as_declared!(Problem);

/// A study's case, with what its methods read beside it.
pub struct CaseSetup {
    /// The case.
    pub case: Box<dyn StudyCase>,
    /// The width ε of a regularised method (the friction parameter `epsilon`), m/s.
    pub epsilon: f64,
    /// Whether it is a system (the chain or a system file): studied event-driven, it has
    /// peers ([`CaseSetup::with_peers`]).
    pub system: bool,
}

impl CaseSetup {
    /// `methods` and, for a system studied event-driven with event switching, its peers
    /// ([`system_peers`] at the case's ε).
    pub fn with_peers(&self, mut methods: Vec<Method>) -> Vec<Method> {
        let event = Method::first_studied(&methods).is_some_and(|m| {
            matches!(
                m.scheme,
                Scheme::EventDriven {
                    switching: Switching::Event,
                    ..
                }
            )
        });
        if self.system && event {
            methods.extend(system_peers(self.epsilon));
        }
        methods
    }
}

/// The peers drawn beside event-driven solvers on a system of many contacts: diffsol's BDF
/// on the regularised system (sparse Jacobian and LU, width `epsilon`) and Moreau–Jean
/// time-stepping at θ = 1/2 — the two other ways to integrate many contacts.
pub fn system_peers(epsilon: f64) -> [Method; 2] {
    [
        Method::peer(Scheme::EventDriven {
            solver: Solver::BDF,
            switching: Switching::Regularized { epsilon },
        }),
        Method::peer(Scheme::TimeStepping {
            theta: DEFAULT_THETA,
        }),
    ]
}

impl Problem {
    /// The problem `scenario` or `system` names: a rig, the chain or a system file; `None`
    /// for neither.
    pub fn target(&self) -> Result<Option<simulate::Target>, AppError> {
        simulate::Target::of(self.scenario.as_ref(), self.system.as_ref())
    }

    /// The study case: a rig, the chain, or a system file.
    pub fn case(&self) -> Result<CaseSetup, AppError> {
        let Some(target) = &self.target()? else {
            return Err(AppError::Usage(format!(
                "the study needs a problem: a SCENARIO, or {} FILE.toml (work-precision also \
                 takes {} PROBLEM)",
                field("system"),
                field("testset")
            )));
        };
        let check_t_end = |t_end: f64| ranges::T_END.check(t_end);
        let scenario = match target {
            simulate::Target::Rig(s) => *s,
            _ => {
                let described =
                    system_of(target.system(), self.model.as_ref(), &self.model_settings)?;
                described.system.validate()?;
                let bodies = if self.bodies.is_empty() {
                    vec![0]
                } else {
                    chosen_bodies(&described.system, &self.bodies)?
                };
                let case = SystemCase {
                    name: described.name,
                    system: described.system,
                    t_end: check_t_end(self.t_end.unwrap_or_else(|| study_t_end(target.system())))?,
                    bodies,
                    limits: self.limits.limits()?,
                    chain: described.source,
                };
                return Ok(CaseSetup {
                    case: Box::new(case),
                    epsilon: described.friction.epsilon,
                    system: true,
                });
            }
        };
        if scenario == Scenario::VELOCITY_SWEEP {
            return Err(AppError::Usage(
                "the studies integrate trajectories: velocity-sweep has none; use another scenario"
                    .into(),
            ));
        }
        if !self.bodies.is_empty() {
            return Err(bodies_of_a_rig());
        }
        let (model, params) = rig_law(scenario, self.model.as_ref(), &self.model_settings.params)?;
        let (friction, params) = params.resolve_for(Some(scenario))?;
        let t_end = match self.t_end {
            Some(t) => check_t_end(t)?,
            None => check_t_end(derived_t_end(scenario, &params, &friction)?)?,
        };
        let case = Case {
            scenario,
            law: model.law(self.model_settings.variant),
            friction,
            params,
            t_end,
            limits: self.limits.limits()?,
        };
        Ok(CaseSetup {
            case: Box::new(case),
            epsilon: friction.epsilon,
            system: false,
        })
    }

    /// The methods a study compares on `setup`: each solver `given` by `option` (or of
    /// `defaults` when none are) under the scheme's treatment of v = 0 (regularised at the
    /// case's ε), or under time-stepping the study's one method, Moreau–Jean's scheme at
    /// θ = 1/2, which takes no solver: naming one is refused rather than ignored.
    pub fn methods(
        &self,
        setup: &CaseSetup,
        option: &str,
        given: &[Solver],
        defaults: &[Solver],
    ) -> Result<Vec<Method>, AppError> {
        if !given.is_empty() && self.scheme.is_time_stepping() {
            let scheme = field("scheme");
            let names: Vec<&str> = given.iter().map(|s| s.name()).collect();
            return Err(AppError::Usage(format!(
                "option `{}` does not apply to {scheme} time-stepping: the study's one method is \
                 Moreau–Jean's scheme over the study's step sizes, which takes no ODE solver; \
                 drop the solvers, or choose {scheme} event-driven",
                setting(option, &names.join(","))
            )));
        }
        let solvers = or_default(given, defaults);
        let schemes = self
            .scheme
            .schemes(&solvers, setup.epsilon, DEFAULT_THETA)?;
        Ok(Method::studied(&schemes))
    }

    /// Refuses `--scheme` and `--switching` for the study `study`, which chooses its schemes
    /// itself (`how`: how it does).
    fn refuse_scheme(&self, study: &str, how: &str) -> Result<(), AppError> {
        let scheme = &self.scheme;
        if scheme.switching.is_none() && !scheme.is_time_stepping() {
            return Ok(());
        }
        let option = match scheme.switching {
            Some(_) => "switching",
            None => "scheme",
        };
        Err(AppError::Usage(format!(
            "option `{}` does not apply to {study}: {how}",
            field(option)
        )))
    }

    /// Sets up the case, runs `study` (which returns its lines for the terminal), and keeps
    /// its files, in `out`, in memory.
    fn make(
        &self,
        out: &Path,
        study: impl FnOnce(&mut Output, &CaseSetup) -> Result<Vec<String>, AppError>,
    ) -> Result<Made, AppError> {
        let setup = self.case()?;
        let mut files = Artifacts::default();
        let mut target = Output {
            files: &mut files,
            dir: out,
            threads: ranges::threads(self.threads)?,
            failure: None,
        };
        let notes = study(&mut target, &setup)?;
        let failure = target.failure;
        // A study of a system under event switching also runs its regularised peer (BDF on
        // the regularised system), which reads epsilon.
        let unread_epsilon = match (setup.system, self.scheme.unread_epsilon()) {
            (true, Some("event")) => None,
            (_, unread) => unread,
        };
        Ok(Made {
            files,
            notes,
            warnings: unread_warnings(
                &self.model_settings.params.set,
                self.model.as_ref().and_then(ModelChoice::catalog),
                unread_epsilon,
            )
            .into_iter()
            .chain(self.scheme.spelling_notes())
            .collect(),
            failure,
            run: None,
        })
    }
}

/// `given` (a list setting), or `defaults` when none are given.
pub fn or_default<T: Copy>(given: &[T], defaults: &[T]) -> Vec<T> {
    if given.is_empty() { defaults } else { given }.to_vec()
}

/// One line for each method with failed runs of a study (an unstable step, a limit): how many,
/// and the first's resolution and error (their status in the study's `csv`). Their errors are
/// missing, which `converge`'s order lines count with round-off; this says why. A last line
/// says why, when a run of an explicit method diverged with its fixed step.
fn failures(runs: &[StudyRun], csv: &str) -> Vec<String> {
    let diverged = runs
        .iter()
        .any(|r| r.diverged)
        .then(|| diverged_line(&format!("step in {}", field("dt_list"))));
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
