//! `friction-lab simulate SCENARIO --model MODEL --solver SOLVER --out DIR`: one scenario,
//! written as `trajectory.csv`, `summary.json` and figures (time histories of x, v and
//! friction; phase portrait; friction against velocity and against displacement).

use crate::artifacts::{Artifacts, Made};
use crate::error::AppError;
use crate::laws::ModelChoice;
use crate::options::{LimitArgs, ModelOptions, SchemeArgs, SchemeName};
use crate::output::{Cell, Table};
use crate::plot::{Corner, Marker, Plot, Series, BLUE, RED};
use crate::progress::Progress;
use crate::ranges;
use crate::run_record::{
    event_counts, scheme_parameters, Integrated, RunRecord, RunSetup, RunSummary, StiffnessSummary,
    RIG_BODY,
};
use crate::trajectory::{Trajectory, TrajectoryAs};
use crate::warnings::{coarse_step_warning, failure_warnings, stiffness_warning, unread_warnings};
use clap::Args;
use friction_models::Parameters;
use friction_systems::{BodyState, ContactEvent, StiffnessPoint};
use integrators::{Solver, StepControl};
use scenarios::run::Outcome;
use scenarios::{Limits, RunSpec, Scenario, SwitchingKind};
use std::path::{Path, PathBuf};

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
    /// A rig of `scenarios.md`.
    Rig(Scenario),
    /// The Burridge–Knopoff chain of `systems.md`.
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
    /// systems.md, parameters n_bodies, m, k_chain, k_driver, v_driver, spread by --set).
    #[arg(
        value_name = "SCENARIO",
        required_unless_present = "system",
        conflicts_with = "system"
    )]
    pub scenario: Option<Target>,
    /// A system file (TOML, shared/spec/systems.md) to integrate instead of a scenario.
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
    let (friction, params) = args.model_options.params.resolve_for(Some(scenario))?;
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

/// The one run record of a rig's `outcome` (a system of one body, named `body`, and one
/// contact), described by `setup`.
fn rig_record(outcome: &Outcome, setup: RunSetup, has_state: bool) -> RunRecord {
    let state = |r: &scenarios::Row| BodyState {
        t: r.t,
        x: r.x,
        v: r.v,
        friction: r.friction,
        mode: Some(r.mode),
        z: r.z,
    };
    let events: Vec<ContactEvent> = outcome
        .events
        .iter()
        .map(|e| ContactEvent {
            t: e.t,
            contact: 0,
            body: 0,
            from: e.from,
            to: e.to,
        })
        .collect();
    let integrated = Integrated {
        error: outcome.error.clone(),
        t_reached: outcome.last().map(|r| r.t),
        event_counts: event_counts(&events),
        stats: outcome.stats.into(),
        wall_time_s: outcome.wall_time_s,
        energy_residual: outcome.energy.map(|e| e.residual),
        energy: outcome.energy,
        friction_work: outcome.friction_work,
        loop_area: outcome.loop_area,
        stiffness_detected_at: outcome.stiffness_detected_at,
        method_switches: outcome.method_switches.clone(),
        stiffness: StiffnessSummary::of(&outcome.stiffness),
        instability: outcome.instability,
    };
    RunRecord {
        summary: RunSummary::new(setup, integrated),
        bodies: vec![RIG_BODY.to_string()],
        trajectory: Trajectory::of_outcome(outcome, has_state),
        finals: outcome.last().map(state).into_iter().collect(),
        events,
    }
}

/// The rows a figure draws: the trajectory's, with the body just before each switch put
/// before the row at the switch, so that a jump of the friction is drawn where it happens (at
/// the switch's x, v and t) and not as a line from the last point before the switch.
fn drawn_rows(o: &Outcome) -> Vec<&scenarios::Row> {
    let mut before = o.before_switches.iter().peekable();
    let mut out = Vec::with_capacity(o.rows.len() + o.before_switches.len());
    for r in &o.rows {
        while let Some(b) = before.next_if(|b| b.t <= r.t) {
            out.push(b);
        }
        out.push(r);
    }
    out
}

/// The figures of a simulation: (file stem, title, x label, y label, points).
fn figures(o: &Outcome, name: &str) -> Vec<(&'static str, Plot)> {
    type Pick = fn(&scenarios::Row) -> f64;
    let specs: [(&str, &str, &str, &str, Pick, Pick); 6] = [
        (
            "history-x",
            "displacement",
            "time t (s)",
            "displacement x (m)",
            |r| r.t,
            |r| r.x,
        ),
        (
            "history-v",
            "velocity",
            "time t (s)",
            "velocity v (m/s)",
            |r| r.t,
            |r| r.v,
        ),
        (
            "history-friction",
            "friction force",
            "time t (s)",
            "friction force F (N)",
            |r| r.t,
            |r| r.friction,
        ),
        (
            "phase-portrait",
            "phase portrait",
            "displacement x (m)",
            "velocity v (m/s)",
            |r| r.x,
            |r| r.v,
        ),
        (
            "friction-velocity",
            "friction against velocity",
            "velocity v (m/s)",
            "friction force F (N)",
            |r| r.v,
            |r| r.friction,
        ),
        (
            "friction-displacement",
            "friction against displacement",
            "displacement x (m)",
            "friction force F (N)",
            |r| r.x,
            |r| r.friction,
        ),
    ];
    let rows = drawn_rows(o);
    specs
        .into_iter()
        .map(|(stem, what, xl, yl, fx, fy)| {
            (
                stem,
                Plot {
                    title: format!("{name}: {what}"),
                    x_label: xl.into(),
                    y_label: yl.into(),
                    series: vec![Series {
                        label: None,
                        points: rows.iter().map(|r| (fx(r), fy(r))).collect(),
                        color: BLUE,
                        width: 2,
                        marker: Marker::None,
                    }],
                    legend: Corner::default(),
                    log: false,
                },
            )
        })
        .collect()
}

/// `log10(h·ρ)` against t, with Dormand–Prince's stability boundary on the negative real axis
/// (h·ρ ≈ 3.3) as a line: above it an explicit step of that size is unstable on the stiffest
/// mode.
fn stiffness_plot(stiffness: &[StiffnessPoint], name: &str) -> Plot {
    let points: Vec<(f64, f64)> = (stiffness.iter())
        .filter(|p| p.h_rho > 0.0)
        .map(|p| (p.t, p.h_rho.log10()))
        .collect();
    let (t0, t1) = (
        points.first().map_or(0.0, |p| p.0),
        points.last().map_or(0.0, |p| p.0),
    );
    let boundary = DOPRI5_BOUNDARY.log10();
    Plot {
        title: format!("{name}: stiffness along the run"),
        x_label: "time t (s)".into(),
        y_label: "log10(h·ρ), h the step, ρ the spectral radius of ∂f/∂y".into(),
        series: vec![
            Series {
                label: Some("h·ρ at the recorded points".into()),
                points,
                color: BLUE,
                width: 2,
                marker: Marker::None,
            },
            Series {
                label: Some("dopri5's stability boundary, 3.3".into()),
                points: vec![(t0, boundary), (t1, boundary)],
                color: RED,
                width: 1,
                marker: Marker::None,
            },
        ],
        legend: Corner::default(),
        log: false,
    }
}

/// `stiffness.csv` (t, h, ρ and h·ρ at each point of `stiffness`) and its figure
/// `stiffness.png`/`.svg`, for the run `name` (none for a run without points).
pub fn add_stiffness(
    files: &mut Artifacts,
    out: &Path,
    stiffness: &[StiffnessPoint],
    name: &str,
) -> Result<(), AppError> {
    if stiffness.is_empty() {
        return Ok(());
    }
    let path = out.join("stiffness.csv");
    let mut table = Table::new(&["t", "h", "rho", "h_rho"]);
    for p in stiffness {
        table
            .rows
            .push([p.t, p.h, p.rho, p.h_rho].map(Cell::Num).to_vec());
    }
    files.add(path.clone(), table.to_csv(&path)?);
    files.add_plot(&out.join("stiffness"), &stiffness_plot(stiffness, name))
}

/// Dormand–Prince's stability boundary on the negative real axis (Hairer & Wanner, *Solving
/// ODEs I*, Fig. IV.2.1): about 3.3.
const DOPRI5_BOUNDARY: f64 = 3.3;

/// Runs `simulate` on a rig: its files in memory, its trajectory as the file or as columns
/// (a chain or a system file is [`crate::commands::system::make`]).
pub fn make_rig(
    args: &SimulateArgs,
    scenario: Scenario,
    trajectory_as: TrajectoryAs,
) -> Result<Made, AppError> {
    let spec = spec(args, scenario)?;
    let (model, variant) = (model_of(args, scenario)?, args.model_options.variant);
    let t_end = spec
        .t_end
        .unwrap_or_else(|| spec.scenario.default_t_end(&spec.params, &spec.friction));
    let method = spec.switching.method(spec.solver);
    let what = format!("{} {model} {method}", spec.scenario);
    let bar = Progress::time(t_end, &what);
    let outcome = scenarios::run_measuring_stiffness(&spec, &mut |t| {
        if t_end > 0.0 {
            bar.at(t);
        }
    })
    .map_err(AppError::from)?;
    bar.finish();

    let has_state = spec.law.build(&spec.friction)?.n_states() > 0;
    let name = format!(
        "{} with {model} ({method}, {} switching)",
        spec.scenario,
        spec.switching.name()
    );
    let mut files = Artifacts::default();
    for (stem, p) in figures(&outcome, &name) {
        files.add_plot(&args.out.join(stem), &p)?;
    }
    add_stiffness(&mut files, &args.out, &outcome.stiffness, &name)?;
    let mut parameters = model.parameters_read(&spec.friction);
    for &p in spec.scenario.parameters() {
        let value = spec.params.value(p).expect("scenario parameters exist");
        parameters.insert(p.to_string(), value);
    }
    parameters.extend(scheme_parameters(spec.switching, &spec.friction));
    let setup = RunSetup {
        system: spec.scenario.name().to_string(),
        model: Some(model.name().to_string()),
        variant: model.catalog().map(|_| variant),
        n_bodies: 1,
        n_contacts: 1,
        scheme: SchemeName::of(spec.switching).name(),
        solver: method,
        switching: spec.switching.name(),
        step: spec.step,
        t_end,
        parameters,
    };
    let record = rig_record(&outcome, setup, has_state);
    let (failure, caution) = (record.summary.failure(), record.summary.caution());
    let columns = record.add_files(&mut files, &args.out, trajectory_as)?;
    Ok(Made {
        files,
        trajectory: columns,
        notes: Vec::new(),
        warnings: outcome
            .stiffness_detected_at
            .map(|t| stiffness_warning(spec.solver.name(), t))
            .into_iter()
            .chain(coarse_step_warning(spec.step, outcome.time_scale))
            .chain(failure_warnings(
                spec.solver,
                spec.switching,
                spec.step,
                t_end,
                outcome.time_scale,
                outcome.error.as_ref(),
            ))
            .chain(unread_warnings(
                &args.model_options.params.set,
                model.catalog(),
                spec.switching,
            ))
            .chain(args.solver.scheme.spelling_notes())
            .chain(caution)
            .collect(),
        failure,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use friction_models::{FrictionParams, ModelId};
    use scenarios::RunSpec;

    #[test]
    fn a_figure_draws_each_switch_as_a_jump_at_the_switch() {
        // The belt's stick–slip with the paper's CVS, output every 10 ms: at a re-stick the
        // friction jumps from about −7.5 N to the holding force. Drawn from the trajectory
        // alone, the line ran from the last point of the slip phase to the point at the switch,
        // through states that never were.
        let spec = RunSpec {
            t_end: Some(20.0),
            output_points: 2001,
            ..scenarios::stick_slip::belt_run(ModelId::Cvs, &FrictionParams::paper())
        };
        let o = scenarios::run(&spec, &mut |_| {}).unwrap();
        let drawn = drawn_rows(&o);
        let switches = o.rows.windows(2).filter(|w| w[0].mode != w[1].mode).count();
        assert!(switches >= 30, "{switches} switches");
        assert_eq!(o.before_switches.len(), switches);
        assert_eq!(drawn.len(), o.rows.len() + switches);
        // Every change of mode between two drawn points is at one instant and one state.
        for w in drawn.windows(2) {
            if w[0].mode != w[1].mode {
                assert_eq!((w[0].t, w[0].x, w[0].v), (w[1].t, w[1].x, w[1].v));
            }
        }
        // The friction before a re-stick is CVS's at v_rel = 0⁻: −(F_c + C2) = −7.5 N.
        let p = FrictionParams::paper();
        for b in o
            .before_switches
            .iter()
            .filter(|b| b.mode != friction_systems::STICK)
        {
            assert!((b.friction + p.f_c + p.c2).abs() < 1e-9, "{b:?}");
        }
    }
}
