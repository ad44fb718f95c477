//! One run as a front end asks for it ([`SimulationRequest`]): a rig, the chain or a system file,
//! its model, solver settings, end time, output points and recorded bodies; checked and run
//! here for the command line, Python and a Rust user alike.

use crate::error::{field, AppError};
use crate::laws::ModelChoice;
use crate::made::Made;
use crate::params::ParamSource;
use crate::ranges;
use crate::settings::{ModelSettings, SolverSettings};
use crate::simulate::{chosen_bodies, load, simulate_rig, simulate_system, Described, SystemRun};
use crate::sweep::RECORD_LIMIT;
use crate::trajectory::RecordAs;
use crate::warnings::unread_warnings;
use crate::window::Window;
use friction_systems::chain::{ChainParams, CHAIN_PARAMETERS};
use friction_systems::file::SystemSource;
use integrators::Options;
use scenarios::chain::ChainSource;
use scenarios::{RunSpec, Scenario};
use std::path::Path;

/// Bodies written to the trajectory when none are chosen: all of a chain this long or shorter,
/// otherwise this many evenly spaced.
pub const DEFAULT_TRAJECTORY_BODIES: usize = 20;
/// The largest number of recorded numbers (points × unknowns) by default: about 80 MB.
pub const RECORD_BUDGET: usize = 10_000_000;
/// Default end time of the chain, s.
pub const CHAIN_T_END: f64 = 50.0;
/// Default end time of a system file, s.
pub const FILE_T_END: f64 = 20.0;
/// Default output points of a rig.
pub const RIG_POINTS: usize = 2001;

/// Default end time of a solver study of the chain, s: within its horizon of predictability.
/// Over [`CHAIN_T_END`] a perturbation of the size of a step's error grows to the size of the
/// motion (the chain of 10 blocks with CS, CVS or Karnopp's law: fixed-step errors near a
/// saturated level, fitted "orders" of RK4 from −0.07 to 1.2), and a convergence study
/// measures that growth, not the solvers; over 10 s RK4 shows 3.7–4.3 and Dormand–Prince
/// 4.2–5.4 on every measure (docs/studies.md).
pub const CHAIN_STUDY_T_END: f64 = 10.0;

/// What a run integrates.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Target {
    /// A rig of docs/scenarios.md.
    Rig(Scenario),
    /// The Burridge–Knopoff chain of docs/systems.md.
    Chain,
    /// A system file (TOML or JSON, docs/systems.md), or a system given as JSON text.
    System(SystemSource),
}

/// A rig or the chain by name ([`Target::named`]).
impl std::str::FromStr for Target {
    type Err = String;
    fn from_str(name: &str) -> Result<Target, String> {
        Target::named(name)
    }
}

impl Target {
    /// The target a request's `scenario` (a rig or the chain) or `system` names; `None` for
    /// neither, refused for both.
    pub fn of(
        scenario: Option<&Target>,
        system: Option<&SystemSource>,
    ) -> Result<Option<Target>, AppError> {
        match (scenario, system) {
            (Some(_), Some(_)) => Err(AppError::Usage(
                "give a scenario or a `system`, not both".into(),
            )),
            (Some(target), None) => Ok(Some(target.clone())),
            (None, system) => Ok(system.cloned().map(Target::System)),
        }
    }

    /// The rig named `name`, or the chain (`chain`); the message of another name lists both.
    pub fn named(name: &str) -> Result<Target, String> {
        if name == "chain" {
            return Ok(Target::Chain);
        }
        Scenario::from_name(name)
            .map(Target::Rig)
            .map_err(|e| format!("{e}, chain"))
    }

    /// The system's source, if the target is a system.
    pub fn system(&self) -> Option<&SystemSource> {
        match self {
            Target::System(source) => Some(source),
            _ => None,
        }
    }

    /// The target's name: the rig's, `chain`, or the file's path.
    pub fn name(&self) -> String {
        match self {
            Target::Rig(s) => s.name().to_string(),
            Target::Chain => "chain".into(),
            Target::System(source) => source.name(),
        }
    }
}

/// The help of a target argument: the names in [`scenarios::SCENARIOS`] (the rigs the
/// argument takes, from the one registry of rigs), then `then` (the other targets).
pub fn scenario_help(what: &str, then: &str) -> String {
    format!(
        "{what}: {} (one contact each), {then}",
        scenarios::SCENARIOS.names().join(", ")
    )
}

/// One run (`friction-lab simulate`): what is integrated, with which model and settings, how
/// long, and what is recorded. [`SimulationRequest::run`] checks it and makes its files.
#[derive(clap::Args, Clone, Debug)]
pub struct SimulationRequest {
    /// The rig (docs/scenarios.md) or the chain: [`SimulationRequest::target`] with `system`.
    #[arg(
        help = scenario_help(
            "The rig",
            "or chain (the Burridge–Knopoff chain of docs/systems.md, parameters n_bodies, m, \
             k_chain, k_driver, v_driver, spread by --set)",
        ),
        value_name = "SCENARIO",
        required_unless_present = "system",
        conflicts_with = "system"
    )]
    pub scenario: Option<Target>,
    /// A system file (TOML or JSON, docs/systems.md) to integrate instead of a scenario, or
    /// the system itself as JSON text (starting with `{`).
    #[arg(long, value_name = "FILE.toml")]
    pub system: Option<SystemSource>,
    /// The friction model, as `friction-lab models` lists it, or a law registered by name
    /// (from Python: docs/python.md) (rigs and chain).
    #[arg(long, value_name = "MODEL")]
    pub model: Option<ModelChoice>,
    /// End time, s [default: the scenario's; 50 for the chain; 20 for a system file].
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub t_end: Option<f64>,
    /// Evenly spaced output points (events are recorded besides) [default: 2001; for a
    /// system, fewer when 2001 states would exceed 1e7 numbers].
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub points: Option<i64>,
    /// Systems: the bodies written to trajectory.csv, as names or 1-based indices,
    /// comma-separated; velocity.png, the phase portraits and the spectra draw at most four of
    /// them, spread evenly [default: all up to 20 bodies, else 20 evenly spaced].
    #[arg(long, value_name = "LIST", value_delimiter = ',')]
    pub bodies: Vec<String>,
    /// The span of time the figures draw, T0:T1 in seconds (time histories, phase portraits,
    /// friction plots, space-time pictures, stiffness), and the spectra measure [default: the
    /// whole run; the spectra its last half]. The data files keep every point.
    #[arg(long, value_name = "T0:T1", allow_hyphen_values = true)]
    pub window: Option<String>,
    /// The scheme, solver, step control and bounds.
    #[command(flatten)]
    pub solver: SolverSettings,
    /// The model's parameters (friction and scenario parameters alike) and reading.
    #[command(flatten)]
    pub model_settings: ModelSettings,
}

impl SimulationRequest {
    /// A run of `target` with `model` and every setting at its default.
    pub fn new(target: Target, model: Option<ModelChoice>) -> SimulationRequest {
        let (scenario, system) = match target {
            Target::System(source) => (None, Some(source)),
            named => (Some(named), None),
        };
        SimulationRequest {
            scenario,
            system,
            model,
            model_settings: ModelSettings::default(),
            solver: SolverSettings::default(),
            t_end: None,
            points: None,
            bodies: Vec::new(),
            window: None,
        }
    }

    /// What the run integrates: the rig or the chain `scenario` names, or the file `system`.
    pub fn target(&self) -> Result<Target, AppError> {
        Target::of(self.scenario.as_ref(), self.system.as_ref())?.ok_or_else(|| {
            AppError::Usage(
                "a scenario (a rig's name or \"chain\") or a `system` is required".into(),
            )
        })
    }

    /// `window`, checked against a run that ends at `t_end`.
    pub fn checked_window(&self, t_end: f64) -> Result<Option<Window>, AppError> {
        (self.window.as_deref())
            .map(|text| Window::parse(text, t_end))
            .transpose()
    }

    /// `t_end`, checked.
    pub fn checked_t_end(&self) -> Result<Option<f64>, AppError> {
        self.t_end.map(|t| ranges::T_END.check(t)).transpose()
    }

    /// `points`, checked.
    pub fn checked_points(&self) -> Result<Option<usize>, AppError> {
        self.points.map(|n| ranges::POINTS.count(n)).transpose()
    }

    /// The model of a run of rig `scenario`, and where its parameters come from
    /// ([`rig_law`]).
    fn rig_law(&self, scenario: Scenario) -> Result<(ModelChoice, ParamSource), AppError> {
        rig_law(scenario, self.model.as_ref(), &self.model_settings.params)
    }

    /// The spec of a run of rig `scenario`, every setting checked.
    pub fn rig_spec(&self, scenario: Scenario) -> Result<RunSpec, AppError> {
        let (model, params) = self.rig_law(scenario)?;
        if !self.bodies.is_empty() {
            return Err(bodies_of_a_rig());
        }
        let (friction, params) = params.resolve_for(Some(scenario))?;
        if self.checked_t_end()?.is_none() {
            derived_t_end(scenario, &params, &friction)?;
        }
        let step = self.solver.checked_step()?;
        Ok(RunSpec {
            scenario,
            law: model.law(self.model_settings.variant),
            friction,
            params,
            scheme: self.solver.scheme(friction.epsilon)?,
            step,
            t_end: self.t_end,
            output_points: self.checked_points()?.unwrap_or(RIG_POINTS),
            limits: self.solver.checked_limits()?,
        })
    }

    /// The system of the chain or the system file, described.
    pub fn described(&self) -> Result<Described, AppError> {
        system_of(
            self.system.as_ref(),
            self.model.as_ref(),
            &self.model_settings,
        )
    }

    /// The end time of a system: `t_end`, or the default of its kind.
    pub fn system_t_end(&self) -> Result<f64, AppError> {
        Ok(self
            .checked_t_end()?
            .unwrap_or_else(|| default_t_end(self.system.as_ref())))
    }

    /// The output points of a system of `dim` unknowns: `points`, checked against its range
    /// and against [`RECORD_LIMIT`] numbers in all, or [`default_points`].
    pub fn system_points(&self, dim: usize) -> Result<usize, AppError> {
        let Some(points) = self.checked_points()? else {
            return Ok(default_points(dim));
        };
        if points.saturating_mul(dim) > RECORD_LIMIT {
            return Err(AppError::Usage(format!(
                "option `{}` = {points} would record {} numbers for the system's {dim} \
                 unknowns: allowed at most {} numbers, so at most {} points",
                field("points"),
                ranges::show((points as f64) * (dim as f64)),
                ranges::show(RECORD_LIMIT as f64),
                RECORD_LIMIT / dim.max(1)
            )));
        }
        Ok(points)
    }

    /// The integrator's options of a system run: the step control and bounds, checked, and
    /// `points` evenly spaced output times on [0, t_end].
    pub fn grid_options(&self, t_end: f64, points: usize) -> Result<Options, AppError> {
        let limits = self.solver.checked_limits()?;
        Ok(crate::sweep::grid_options(
            self.solver.checked_step()?,
            &limits,
            t_end,
            points,
        ))
    }

    /// The advice on settings the run does not read, and on former spellings.
    pub fn warnings(&self) -> Vec<String> {
        // A rig's own default law where no model is named.
        let model = match (&self.scenario, &self.model) {
            (Some(Target::Rig(scenario)), None) => scenario.default_law().map(|(m, _)| m),
            _ => self.model.as_ref().and_then(ModelChoice::catalog),
        };
        unread_warnings(
            &self.model_settings.params.set,
            model,
            self.solver.scheme.unread_epsilon(),
        )
        .into_iter()
        .chain(self.solver.scheme.spelling_notes())
        .collect()
    }

    /// Checks the run, runs it and makes its files in `out` (in memory), the trajectory as a
    /// file or as columns.
    pub fn run(&self, out: &Path, record_as: RecordAs) -> Result<Made, AppError> {
        let mut made = match self.target()? {
            Target::Rig(scenario) => {
                let spec = self.rig_spec(scenario)?;
                let window = self.checked_window(spec.end_time())?;
                let model = self.rig_law(scenario)?.0;
                simulate_rig(&spec, &model, out, record_as, window)?
            }
            _ => self.run_system(out, record_as)?,
        };
        made.warnings.extend(self.warnings());
        Ok(made)
    }

    /// [`SimulationRequest::run`] of the chain or a system file.
    fn run_system(&self, out: &Path, record_as: RecordAs) -> Result<Made, AppError> {
        let described = self.described()?;
        self.solver.checked_step()?;
        described.system.validate()?;
        let bodies = chosen_bodies(&described.system, &self.bodies)?;
        let t_end = self.system_t_end()?;
        let window = self.checked_window(t_end)?;
        let points = self.system_points(friction_systems::Layout::of(&described.system).dim())?;
        let run = SystemRun {
            described: &described,
            scheme: self.solver.scheme(described.friction.epsilon)?,
            options: self.grid_options(t_end, points)?,
            bodies: &bodies,
            variant: (self.model.as_ref())
                .and_then(ModelChoice::catalog)
                .map(|_| self.model_settings.variant),
            window,
        };
        simulate_system(run, out, record_as)
    }
}

/// The error of `bodies` given with a rig: the option chooses among a system's bodies.
pub fn bodies_of_a_rig() -> AppError {
    AppError::Usage(format!(
        "option `{}` applies to systems (chain, {}), not to a rig",
        field("bodies"),
        field("system")
    ))
}

/// The model of a run of rig `scenario` and where its parameters come from: `model` with
/// `params`, or without a model the rig's default law, read at its parameter set unless
/// `params` names one ([`scenarios::Rig::default_law`]); a rig without a default law requires a
/// model.
pub fn rig_law(
    scenario: Scenario,
    model: Option<&ModelChoice>,
    params: &ParamSource,
) -> Result<(ModelChoice, ParamSource), AppError> {
    let mut params = params.clone();
    if let Some(model) = model {
        return Ok((model.clone(), params));
    }
    let (model, set) = scenario.default_law().ok_or_else(|| {
        let model = field("model");
        AppError::Usage(format!(
            "option `{model}` is required for scenario {scenario}: e.g. {model} CS"
        ))
    })?;
    params.param_set.get_or_insert_with(|| set.to_string());
    Ok((ModelChoice::Catalog(model), params))
}

/// The end time `scenario` derives from its parameters where none is given, checked against
/// the range of `t_end`; out of it, the message blames the parameters it is derived from (the
/// user set those, not `t_end`).
pub fn derived_t_end(
    scenario: Scenario,
    params: &scenarios::ScenarioParams,
    friction: &friction_models::FrictionParams,
) -> Result<f64, AppError> {
    let end = scenario.end_time(params, friction);
    let t_end = end.value();
    match end.rule() {
        Some(rule) if ranges::T_END.check(t_end).is_err() => Err(AppError::Usage(format!(
            "the end time of scenario {scenario}, {rule}, is {t_end:.3e} s: allowed {} s; \
             choose these parameters so that it falls within, or give {}",
            ranges::T_END.range,
            field("t_end")
        ))),
        _ => Ok(t_end),
    }
}

/// The default end time of a system: [`FILE_T_END`] for a declared `system`, else (the
/// chain) [`CHAIN_T_END`].
pub fn default_t_end(system: Option<&SystemSource>) -> f64 {
    system.map_or(CHAIN_T_END, |_| FILE_T_END)
}

/// The default end time of a solver study of a system: [`FILE_T_END`] for a declared
/// `system`, else (the chain) [`CHAIN_STUDY_T_END`].
pub fn study_t_end(system: Option<&SystemSource>) -> f64 {
    system.map_or(CHAIN_STUDY_T_END, |_| FILE_T_END)
}

/// The default number of output points for a system of `dim` unknowns: 2001, fewer for a
/// large system so that the recorded states stay within [`RECORD_BUDGET`] numbers.
pub fn default_points(dim: usize) -> usize {
    (RECORD_BUDGET / dim.max(1)).clamp(101, 2001)
}

/// The system declared by `system` (a file or JSON text) or, without one, the chain with
/// `model` and the parameters of `settings` (chain parameters among them).
pub fn system_of(
    system: Option<&SystemSource>,
    model: Option<&ModelChoice>,
    settings: &ModelSettings,
) -> Result<Described, AppError> {
    if let Some(source) = system {
        if model.is_some() {
            return Err(AppError::Usage(format!(
                "option `{}` does not apply to {}: each [[contact]] of the file names its model",
                field("model"),
                field("system")
            )));
        }
        settings.params.check_for_system_file()?;
        if settings.variant != friction_models::Variant::Odd {
            return Err(AppError::Usage(format!(
                "option `{}` does not apply to {}: each [[contact]] of the file names its \
                 variant",
                field("variant"),
                field("system")
            )));
        }
        let assignments = settings.params.file_assignments()?;
        return Ok(Described {
            system: load(source, &assignments)?,
            name: source.name(),
            // The numbers of the file that were set, by their paths.
            parameters: assignments.into_iter().collect(),
            friction: settings.params.without_file_paths().resolve()?,
            source: None,
        });
    }
    let model = model.ok_or_else(|| {
        let model = field("model");
        AppError::Usage(format!(
            "option `{model}` is required for the chain: e.g. {model} coulomb"
        ))
    })?;
    let mut chain = ChainParams::default();
    let names = CHAIN_PARAMETERS.map(|(name, _, _)| name);
    let friction =
        (settings.params).resolve_with(&names, |name, value| Ok(chain.set(name, value)?))?;
    let source = ChainSource {
        chain,
        law: model.law(settings.variant),
        friction,
    };
    let system = source.build()?;
    let mut reported = model.parameters_read(&friction);
    for (name, _, _) in CHAIN_PARAMETERS {
        let value = match name {
            "n_bodies" => chain.n_bodies as f64,
            "m" => chain.m,
            "k_chain" => chain.k_chain,
            "k_driver" => chain.k_driver,
            "v_driver" => chain.v_driver,
            _ => chain.spread,
        };
        reported.insert(name.to_string(), value);
    }
    Ok(Described {
        system,
        name: source.name(),
        parameters: reported,
        friction,
        source: Some(source),
    })
}
