//! `friction-lab simulate SCENARIO --model MODEL --solver SOLVER --out DIR`: one scenario,
//! written as `trajectory.csv`, `summary.json` and figures (time histories of x, v and
//! friction; phase portrait; friction against velocity and against displacement).

use crate::options::{LimitArgs, ModelOptions, SchemeArgs};
use clap::Args;
use friction_lab::artifacts::Made;
use friction_lab::error::AppError;
use friction_lab::laws::ModelChoice;
use friction_lab::ranges;
use friction_lab::simulate::simulate_rig;
use friction_lab::trajectory::TrajectoryAs;
use friction_lab::warnings::unread_warnings;
use integrators::{Solver, StepControl};
use scenarios::{Limits, RunSpec, Scenario, SwitchingKind};
use std::path::PathBuf;

/// Options that choose and tune the solver, shared by every command that integrates.
#[derive(Args, Clone, Debug)]
pub struct SolverOptions {
    /// The scheme, and the treatment of v = 0 under the event-driven one.
    #[command(flatten)]
    pub scheme: SchemeArgs,
    /// The solver of event-driven integration (its help lists the built-in solvers).
    #[arg(
        long,
        value_name = "SOLVER",
        help = crate::options::solver_help(
            "The solver of event-driven integration",
            "[default: dopri5; refused under time-stepping]"
        )
    )]
    pub solver: Option<Solver>,
    /// θ of --scheme time-stepping: the weight of the step's end on the smooth forces,
    /// 0.5 (trapezoidal, second order) to 1 (implicit Euler, first order) [default: 0.5;
    /// refused under the event-driven scheme, which has no θ].
    #[arg(long, value_name = "THETA", allow_hyphen_values = true)]
    pub theta: Option<f64>,
    /// Fixed step of rk4 and of time-stepping (default 1e-3 s, the paper's), or the initial
    /// step of the adaptive solvers (the fixed step with --fixed-step).
    #[arg(long, value_name = "H", allow_hyphen_values = true)]
    pub dt: Option<f64>,
    /// Integrate dopri5 or implicit-euler with fixed steps of --dt.
    #[arg(long)]
    pub fixed_step: bool,
    /// Relative tolerance of the adaptive solvers.
    #[arg(
        long,
        value_name = "R",
        allow_hyphen_values = true,
        default_value = "1e-8"
    )]
    pub rtol: f64,
    /// Absolute tolerance of the adaptive solvers.
    #[arg(
        long,
        value_name = "A",
        allow_hyphen_values = true,
        default_value = "1e-10"
    )]
    pub atol: f64,
    /// The bounds of the run.
    #[command(flatten)]
    pub limits: LimitArgs,
}

/// The paper's time step, RK4's default.
pub const PAPER_DT: f64 = 1e-3;

impl SolverOptions {
    /// The step control these options ask for, every value checked against its range, also
    /// those the chosen solver does not use; `--fixed-step` only with a solver that takes
    /// fixed steps.
    pub fn checked_step(&self) -> Result<StepControl, AppError> {
        ranges::RTOL.check(self.rtol)?;
        ranges::ATOL.check(self.atol)?;
        if let Some(theta) = self.theta {
            ranges::THETA.check(theta)?;
        }
        if let Some(dt) = self.dt {
            ranges::DT.check(dt)?;
        }
        let switching = self.checked_switching()?;
        if let (Some(theta), false) = (self.theta, switching.is_time_stepping()) {
            return Err(AppError::Usage(format!(
                "option `--theta {}` applies to --scheme time-stepping, the weight of its \
                 θ-method: the event-driven solvers have none; drop --theta, or choose \
                 --scheme time-stepping",
                ranges::show(theta)
            )));
        }
        if let (Some(solver), true) = (self.solver, switching.is_time_stepping()) {
            return Err(AppError::Usage(format!(
                "option `--solver {}` does not apply to --scheme time-stepping: Moreau–Jean's \
                 scheme takes no ODE solver (its step is --dt, its weight --theta); drop \
                 --solver, or choose --scheme event-driven",
                solver.name()
            )));
        }
        if self.fixed_step && !self.solver().takes_fixed_steps() && !switching.is_time_stepping() {
            let fixed: Vec<_> = Solver::ALL
                .iter()
                .filter(|s| s.takes_fixed_steps())
                .map(|s| s.name())
                .collect();
            return Err(AppError::Usage(format!(
                "option `fixed-step` does not apply to solver `{}`: it chooses its own steps \
                 from --rtol and --atol; allowed with {}",
                self.solver().name(),
                fixed.join(", ")
            )));
        }
        Ok(self.step())
    }

    /// The bounds of a run: `--max-steps` and `--time-limit`, checked.
    pub fn checked_limits(&self) -> Result<Limits, AppError> {
        self.limits.limits()
    }

    /// The treatment of v = 0 that `--scheme` and `--switching` ask for, θ from `--theta`
    /// ([`SchemeArgs::treatment`]; checked by [`SolverOptions::checked_step`]).
    pub fn checked_switching(&self) -> Result<SwitchingKind, AppError> {
        self.scheme.treatment(self.theta())
    }

    /// θ of time-stepping: `--theta`, or the trapezoidal rule's 1/2.
    pub fn theta(&self) -> f64 {
        self.theta.unwrap_or(scenarios::run::DEFAULT_THETA)
    }

    /// The treatment of v = 0, once [`SolverOptions::checked_step`] has passed.
    pub fn switching(&self) -> SwitchingKind {
        self.checked_switching()
            .unwrap_or(SwitchingKind::TimeStepping {
                theta: self.theta(),
            })
    }

    /// The solver of event-driven integration: `--solver`, or Dormand–Prince.
    pub fn solver(&self) -> Solver {
        self.solver.unwrap_or(Solver::DOPRI5)
    }

    /// The step control these options ask for.
    pub fn step(&self) -> StepControl {
        let fixed = self.solver().is_fixed_step() || self.fixed_step;
        if fixed || self.switching().is_time_stepping() {
            StepControl::Fixed {
                h: self.dt.unwrap_or(PAPER_DT),
            }
        } else {
            StepControl::Adaptive {
                rtol: self.rtol,
                atol: self.atol,
                h0: self.dt,
            }
        }
    }
}

/// What `simulate` integrates: a single-body rig, or the built-in chain of blocks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// A rig of `docs/scenarios.md`.
    Rig(Scenario),
    /// The Burridge–Knopoff chain of `docs/systems.md`.
    Chain,
}

impl std::str::FromStr for Target {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        if s == "chain" {
            return Ok(Target::Chain);
        }
        Scenario::from_name(s)
            .map(Target::Rig)
            .map_err(|e| format!("{e}, chain"))
    }
}

/// Options of `simulate`.
#[derive(Args, Clone, Debug)]
pub struct SimulateArgs {
    /// paper-block, prescribed-motion, velocity-sweep, belt, free-vibration, oscillation,
    /// velocity-oscillation, force-ramp, presliding (one body), or chain (the Burridge–Knopoff chain of
    /// docs/systems.md, parameters n_bodies, m, k_chain, k_driver, v_driver, spread by --set).
    #[arg(
        value_name = "SCENARIO",
        required_unless_present = "system",
        conflicts_with = "system"
    )]
    pub scenario: Option<Target>,
    /// A system file (TOML or JSON, docs/systems.md) to integrate instead of a scenario.
    #[arg(long, value_name = "FILE.toml")]
    pub system: Option<PathBuf>,
    /// The friction model, as `friction-lab models` lists it, or a law registered by name
    /// (from Python: docs/python.md) (rigs and chain).
    #[arg(long, value_name = "MODEL")]
    pub model: Option<ModelChoice>,
    /// Folder to write into (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// End time, s [default: the scenario's; 50 for the chain; 20 for a system file].
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub t_end: Option<f64>,
    /// Evenly spaced output points (events are recorded besides) [default: 2001; for a
    /// system, fewer when 2001 states would exceed 1e7 numbers].
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub points: Option<i64>,
    /// Systems: the bodies written to trajectory.csv and drawn in velocity.png, as names or
    /// 1-based indices, comma-separated [default: all up to 20 bodies, else 20 evenly spaced].
    #[arg(long, value_name = "LIST", value_delimiter = ',')]
    pub bodies: Vec<String>,
    /// The solver.
    #[command(flatten)]
    pub solver: SolverOptions,
    /// The model's parameters (friction and scenario parameters alike) and reading.
    #[command(flatten)]
    pub model_options: ModelOptions,
}

impl SimulateArgs {
    /// `--t-end`, checked.
    pub fn checked_t_end(&self) -> Result<Option<f64>, AppError> {
        self.t_end.map(|t| ranges::T_END.check(t)).transpose()
    }

    /// `--points`, checked.
    pub fn checked_points(&self) -> Result<Option<usize>, AppError> {
        self.points.map(|n| ranges::POINTS.count(n)).transpose()
    }
}

/// The model `--model` names, which a rig requires.
fn model_of(args: &SimulateArgs, scenario: Scenario) -> Result<&ModelChoice, AppError> {
    args.model.as_ref().ok_or_else(|| {
        AppError::Usage(format!(
            "option `--model` is required for scenario {scenario}: e.g. --model CS"
        ))
    })
}

/// The end time `scenario` derives from its parameters where `--t-end` is not given, checked
/// against `--t-end`'s range; out of it, the message blames the parameters it is derived from
/// (the user set those, not `--t-end`).
pub fn derived_t_end(
    scenario: Scenario,
    params: &scenarios::ScenarioParams,
    friction: &friction_models::FrictionParams,
) -> Result<f64, AppError> {
    let t_end = scenario.default_t_end(params, friction);
    match scenario.t_end_rule(params, friction) {
        Some(rule) if ranges::T_END.check(t_end).is_err() => Err(AppError::Usage(format!(
            "the end time of scenario {scenario}, {rule}, is {t_end:.3e} s: allowed {} s; \
             choose these parameters so that it falls within, or give --t-end",
            ranges::T_END.range
        ))),
        _ => Ok(t_end),
    }
}

/// The spec of a run of rig `scenario` from the command line.
pub fn spec(args: &SimulateArgs, scenario: Scenario) -> Result<RunSpec, AppError> {
    let model = model_of(args, scenario)?;
    if !args.bodies.is_empty() {
        return Err(AppError::Usage(
            "option `--bodies` applies to systems (chain, --system), not to a rig".into(),
        ));
    }
    let (friction, params) = args
        .model_options
        .params
        .source()
        .resolve_for(Some(scenario))?;
    if args.checked_t_end()?.is_none() {
        derived_t_end(scenario, &params, &friction)?;
    }
    let step = args.solver.checked_step()?;
    Ok(RunSpec {
        scenario,
        law: model.law(args.model_options.variant),
        friction,
        params,
        solver: args.solver.solver(),
        switching: args.solver.switching(),
        step,
        t_end: args.t_end,
        output_points: args.checked_points()?.unwrap_or(2001),
        limits: args.solver.checked_limits()?,
    })
}

/// Runs `simulate` on a rig: its files in memory, its trajectory as the file or as columns
/// (a chain or a system file is [`crate::commands::system::make`]).
pub fn make_rig(
    args: &SimulateArgs,
    scenario: Scenario,
    trajectory_as: TrajectoryAs,
) -> Result<Made, AppError> {
    let spec = spec(args, scenario)?;
    let model = model_of(args, scenario)?;
    let mut made = simulate_rig(&spec, model, &args.out, trajectory_as)?;
    made.warnings.extend(
        unread_warnings(
            &args.model_options.params.set,
            model.catalog(),
            spec.switching,
        )
        .into_iter()
        .chain(args.solver.scheme.spelling_notes()),
    );
    Ok(made)
}
