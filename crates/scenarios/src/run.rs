//! One simulation of a scenario: the rig built from the parameters, integrated by a solver
//! with a treatment of v = 0, and turned into trajectory rows, events, statistics and the
//! energy balance. A solver failure keeps what was computed before it.

use crate::error::ScenarioError;
use crate::motion::{Kinematic, Motion};
use crate::params::ScenarioParams;
use crate::rig::Apparatus;
use crate::scenario::Scenario;
use friction_models::{FrictionModel, FrictionParams, ModelId, ParamError, Parameters, Variant};
use friction_systems::{EnergyBalance, Reference, Scheme, System, STICK};
use integrators::stability::Instability;
use integrators::{
    Failure, Mode, OdeProblem, Options, Output, Solution, SolverError, Stats, StepControl,
};
use serde::Serialize;
use std::sync::Arc;
use std::time::Instant;

/// θ of time-stepping unless `--theta` says otherwise: the trapezoidal rule.
pub const DEFAULT_THETA: f64 = 0.5;

/// Whether a run diverged: its state went beyond the system's reach (`SolverError::Runaway`,
/// any method), or an explicit method (`explicit`: not implicit, not time-stepped) with a
/// fixed step ended past its stability limit in a non-finite state. There h times the
/// problem's fastest decay rate |λ| exceeds the method's bound on the negative real axis, about
/// 2.8 for RK4 and 3.3 for Dormand–Prince (Hairer & Wanner, Solving ODEs II, §IV.2), and every
/// step multiplies the state.
pub fn diverged(explicit: bool, step: StepControl, error: Option<&SolverError>) -> bool {
    match error {
        Some(SolverError::Runaway { .. }) => true,
        Some(SolverError::NonFinite { .. }) => {
            explicit && matches!(step, StepControl::Fixed { .. })
        }
        _ => false,
    }
}

/// The friction law at a rig's contact: a model of the catalog, built from the run's friction
/// parameters, or a law of the user's own (see `examples/own_friction_law.rs`).
#[derive(Clone, Debug)]
pub enum Law {
    /// A model `friction-lab models` lists, in one of its readings.
    Catalog {
        /// The model.
        model: ModelId,
        /// Its reading.
        variant: Variant,
    },
    /// A law written outside friction-lab; the run's friction parameters then set only the
    /// rig's scales (its default end time, the protocols' rates and speeds).
    Own(Arc<dyn FrictionModel>),
}

impl Law {
    /// The law, built from `p` for a model of the catalog.
    pub fn build(&self, p: &FrictionParams) -> Result<Arc<dyn FrictionModel>, ParamError> {
        match self {
            Law::Catalog { model, variant } => Ok(Arc::from(model.build(*variant, p)?)),
            Law::Own(law) => Ok(Arc::clone(law)),
        }
    }

    /// The model of the catalog, if the law is one.
    pub fn catalog(&self) -> Option<ModelId> {
        match self {
            Law::Catalog { model, .. } => Some(*model),
            Law::Own(_) => None,
        }
    }
}

/// A model of the catalog in its sign-consistent reading.
impl From<ModelId> for Law {
    fn from(model: ModelId) -> Law {
        Law::Catalog {
            model,
            variant: Variant::Odd,
        }
    }
}

/// Laws of the catalog are equal when model and reading are; an own law only to itself.
impl PartialEq for Law {
    fn eq(&self, other: &Law) -> bool {
        match (self, other) {
            (
                Law::Catalog {
                    model: a,
                    variant: u,
                },
                Law::Catalog {
                    model: b,
                    variant: w,
                },
            ) => a == b && u == w,
            (Law::Own(a), Law::Own(b)) => Arc::ptr_eq(a, b),
            _ => false,
        }
    }
}

/// The model's name as `friction-lab models` lists it (with `(as printed)` for the printed
/// reading of a model that has one), or the own law's name.
impl std::fmt::Display for Law {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Law::Catalog {
                model,
                variant: Variant::Printed,
            } if model.has_printed_form() => write!(f, "{model} (as printed)"),
            Law::Catalog { model, .. } => write!(f, "{model}"),
            Law::Own(law) => f.write_str(law.name()),
        }
    }
}

/// Everything a simulation needs.
#[derive(Clone, Debug, PartialEq)]
pub struct RunSpec {
    /// The rig.
    pub scenario: Scenario,
    /// The friction law at its contact.
    pub law: Law,
    /// Friction parameters (of a law of the catalog, and the rig's scales).
    pub friction: FrictionParams,
    /// Scenario parameters.
    pub params: ScenarioParams,
    /// The scheme: a solver under a treatment of v = 0 (its regularisation width ε is the
    /// scheme's; `friction.epsilon` is not read by a run), or time-stepping at θ.
    pub scheme: Scheme,
    /// Step control (time-stepping's step h when it is fixed).
    pub step: StepControl,
    /// End time (the scenario's default when `None`).
    pub t_end: Option<f64>,
    /// Number of evenly spaced output points (events are recorded besides).
    pub output_points: usize,
    /// Bounds of the run.
    pub limits: Limits,
}

impl RunSpec {
    /// The end time, s: its own, or its rig's default ([`Scenario::default_t_end`]).
    pub fn end_time(&self) -> f64 {
        (self.t_end).unwrap_or_else(|| self.scenario.default_t_end(&self.params, &self.friction))
    }
}

/// What bounds one run: a step cap and an optional wall-clock limit, both ending the run with
/// an error that keeps what was computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// Most steps, accepted and rejected.
    pub max_steps: usize,
    /// Wall-clock limit, s.
    pub time_limit: Option<f64>,
    /// When the wall-clock limit starts counting: `None` for the start of each run, or the
    /// start of a command, whose runs it then bounds together.
    pub time_limit_since: Option<std::time::Instant>,
}

impl Default for Limits {
    /// 10 million steps, no time limit.
    fn default() -> Self {
        Limits {
            max_steps: 10_000_000,
            time_limit: None,
            time_limit_since: None,
        }
    }
}

/// One row of `trajectory.csv`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Row {
    /// Time, s.
    pub t: f64,
    /// Displacement, m.
    pub x: f64,
    /// Velocity, m/s.
    pub v: f64,
    /// Friction force, N.
    pub friction: f64,
    /// The contact's mode: [`friction_systems::SLIP_POSITIVE`], `SLIP_NEGATIVE` or `STICK`
    /// (written `slip+`, `slip-`, `stick` by [`friction_systems::mode_name`]).
    pub mode: Mode,
    /// Internal state (Dahl or LuGre), when the model has one.
    pub z: Option<f64>,
}

impl Row {
    /// Whether every number of the row is finite. A failed run's last states are finite (the
    /// solvers check them) but the friction there may not be: the law overflows at a state
    /// that only the next step would have rejected. The rows end before the first such row,
    /// so that a partial trajectory never holds a non-finite value.
    pub fn is_finite(&self) -> bool {
        [self.t, self.x, self.v, self.friction, self.z.unwrap_or(0.0)]
            .iter()
            .all(|x| x.is_finite())
    }
}

/// A switch of the rig's contact: its mode before and after (for a prescribed motion, a
/// reversal of the motion is a switch between `slip+` and `slip-`). `from` equals `to` where
/// v_rel touched zero and the contact slid on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EventEntry {
    /// Time, s.
    pub t: f64,
    /// The mode before.
    pub from: Mode,
    /// The mode after.
    pub to: Mode,
}

/// What a simulation produced.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// Trajectory rows.
    pub rows: Vec<Row>,
    /// The body just before each switch of its mode, with the mode it leaves and its friction
    /// there, `F(t_e⁻)` (the row at the switch holds `F(t_e⁺)`): what a figure needs to draw
    /// the jump at the switch ([`friction_systems::Run::before_switches`]). Empty for the
    /// prescribed motions and the velocity sweep.
    pub before_switches: Vec<Row>,
    /// Events.
    pub events: Vec<EventEntry>,
    /// Solver statistics.
    pub stats: Stats,
    /// The solver's error, if it failed (the rows before it are kept).
    pub error: Option<SolverError>,
    /// Energy balance (body scenarios).
    pub energy: Option<EnergyBalance>,
    /// ∫F·v dt: the work done against friction (prescribed-motion scenarios).
    pub friction_work: Option<f64>,
    /// ∮F dv: the friction–velocity loop area (prescribed-motion scenarios).
    pub loop_area: Option<f64>,
    /// Wall time of the integration, s.
    pub wall_time_s: f64,
    /// Where Hairer's stiffness test (Dormand–Prince) first judged the problem stiff.
    pub stiffness_detected_at: Option<f64>,
    /// `auto`'s switches of method, in order.
    pub method_switches: Vec<integrators::MethodSwitch>,
    /// The stiffness along the run, `h·ρ` at the recorded points (body scenarios run by
    /// [`run_measuring_stiffness`]; empty otherwise): [`friction_systems::Run::stiffness`].
    pub stiffness: Vec<friction_systems::StiffnessPoint>,
    /// The body's shortest natural period `2π·√(m/(k + kp))` (body scenarios held by a
    /// spring or a controller, [`friction_systems::System::shortest_period`]; `None`
    /// otherwise): the scale a fixed step is judged against.
    pub natural_period: Option<f64>,
    /// The decaying mode at the start that an explicit method's fixed step amplifies, if any
    /// ([`friction_systems::Run::instability`]; body scenarios).
    pub instability: Option<Instability>,
    /// The reference the body's controller tracks, for a rig whose body a controller
    /// positions (`closed_loop::ClosedLoop::of` measures the loop); `None` otherwise.
    pub reference: Option<Reference>,
    /// Whether that controller integrates its error (ki > 0): then the loop is at rest only
    /// where the error is zero, and a body stuck off the set point will move again.
    pub integral_action: bool,
    /// Whether the law at the contact has an internal state (the trajectory's `z`, also when
    /// no row was recorded).
    pub has_state: bool,
    /// The velocity of the surface under the contact, m/s (a belt's `v_belt`; 0 for the
    /// floor, a prescribed motion and the velocity sweep): the sliding velocity is
    /// `v − surface_velocity`.
    pub surface_velocity: f64,
}

impl Outcome {
    /// The last row.
    pub fn last(&self) -> Option<&Row> {
        self.rows.last()
    }
}

/// Checks the scenario parameters and the combination.
pub(crate) fn validate(spec: &RunSpec) -> Result<(), ScenarioError> {
    spec.params.validate()?;
    spec.scenario.rig().check(&spec.params)?;
    if !spec.scenario.has_body() && spec.scheme.is_time_stepping() {
        return Err(ScenarioError::Invalid(format!(
            "scheme `time-stepping` cannot run {}: the motion is prescribed, there is no body \
             to time-step; use the event-driven scheme (event, regularized or naive switching)",
            spec.scenario
        )));
    }
    if !spec.scenario.has_body() {
        let model = spec.law.build(&spec.friction)?;
        if model.stick_band() > 0.0 {
            return Err(ScenarioError::Invalid(format!(
                "model `{}` cannot run in {}: its stick band holds the body against the applied \
                 force, and here the motion is imposed (there is no applied force); use a body \
                 scenario such as belt or force-ramp",
                spec.law, spec.scenario
            )));
        }
    }
    if spec.output_points < 2 {
        return Err(ScenarioError::Invalid(format!(
            "option `points` = {} is out of range: allowed [2, inf)",
            spec.output_points
        )));
    }
    Ok(())
}

/// The integration options of a run: its step control, and `output_points` evenly spaced
/// output times on [0, t_end].
pub fn options(spec: &RunSpec, t_end: f64) -> Options {
    let n = spec.output_points;
    let grid = integrators::even_grid(0.0, t_end, n);
    Options {
        step: spec.step,
        output: Output::Grid(grid),
        max_steps: spec.limits.max_steps,
        time_limit: spec.limits.time_limit,
        time_limit_since: spec.limits.time_limit_since,
        ..Options::adaptive(0.0, t_end, 1e-8, 1e-10)
    }
}

/// The system of a body scenario: one body, its spring to a wall or its applied force, its
/// contact; `None` for a rig that imposes a motion.
pub fn body_system(spec: &RunSpec, model: Arc<dyn FrictionModel>) -> Option<System> {
    match spec
        .scenario
        .rig()
        .apparatus(&spec.params, &spec.friction, model)
    {
        Apparatus::Body(system) => Some(system),
        Apparatus::Motion(_) | Apparatus::SteadySweep(_) => None,
    }
}

fn finish(solution: Result<Solution, Failure>) -> (Solution, Option<SolverError>) {
    match solution {
        Ok(s) => (s, None),
        Err(f) => (*f.solution, Some(f.error)),
    }
}

fn run_body(
    spec: &RunSpec,
    system: &System,
    t_end: f64,
    measure_stiffness: bool,
    observe: &mut dyn FnMut(f64),
) -> Result<Outcome, ScenarioError> {
    let mut step_ends = Vec::new();
    let run = friction_systems::simulate(system, spec.scheme, options(spec, t_end), &mut |t| {
        if measure_stiffness {
            step_ends.push(t);
        }
        observe(t)
    })?;
    Ok(outcome_of(spec, system, &run, run.stiffness(&step_ends)))
}

/// The outcome of `run`, a run of `spec` on `system`, with the `stiffness` measured along it.
pub(crate) fn outcome_of(
    spec: &RunSpec,
    system: &System,
    run: &friction_systems::Run,
    stiffness: Vec<friction_systems::StiffnessPoint>,
) -> Outcome {
    let instability = run.instability(&spec.scheme, spec.step);
    let row = |b: friction_systems::BodyState| Row {
        t: b.t,
        x: b.x,
        v: b.v,
        friction: b.friction,
        mode: b.mode.unwrap_or(STICK),
        z: b.z,
    };
    let rows: Vec<Row> = run
        .body(0)
        .into_iter()
        .map(row)
        .take_while(Row::is_finite)
        .collect();
    let last = rows.last().map_or(f64::NEG_INFINITY, |r| r.t);
    Outcome {
        before_switches: run
            .before_switches(0)
            .into_iter()
            .map(row)
            .take_while(|r| r.is_finite() && r.t <= last)
            .collect(),
        rows,
        events: run
            .contact_events()
            .iter()
            .map(|e| EventEntry {
                t: e.t,
                from: e.from,
                to: e.to,
            })
            .collect(),
        stats: run.solution.stats,
        energy: run.energy(),
        error: run.error.clone(),
        friction_work: None,
        loop_area: None,
        wall_time_s: run.wall_time_s,
        stiffness_detected_at: run.solution.stiffness_detected_at,
        method_switches: run.solution.method_switches.clone(),
        stiffness,
        natural_period: system.shortest_period(true),
        instability,
        reference: (system.controllers.iter())
            .find(|c| c.body == 0)
            .map(|c| c.reference.clone()),
        integral_action: (system.controllers.iter()).any(|c| c.body == 0 && c.ki > 0.0),
        has_state: (system.contacts.iter()).any(|c| c.body == 0 && c.model.n_states() > 0),
        surface_velocity: (system.contacts.iter())
            .find(|c| c.body == 0)
            .map_or(0.0, |c| c.surface_velocity),
    }
}

/// Runs a prescribed motion from rest with zero internal state.
pub fn run_motion(
    spec: &RunSpec,
    model: &dyn FrictionModel,
    motion: Motion,
    t_end: f64,
    observe: &mut dyn FnMut(f64),
) -> Outcome {
    let k = Kinematic {
        model,
        motion,
        switching: spec.scheme.switching(),
    };
    let y0 = vec![0.0; k.dim()];
    let clock = Instant::now();
    let solver = (spec.scheme.solver()).expect("`validate` refuses a time-stepped motion");
    let (s, error) =
        finish(solver.solve_observed(&k, &y0, &[k.mode_at(0.0)], options(spec, t_end), observe));
    let wall_time_s = clock.elapsed().as_secs_f64();
    let w = k.work_index();
    let rows = (0..s.len())
        .map(|i| {
            let (x, v, _) = motion.at(s.t[i]);
            let y = s.y_at(i);
            Row {
                t: s.t[i],
                x,
                v,
                friction: k.friction(s.t[i], y, s.modes_at(i)[0]),
                mode: s.modes_at(i)[0],
                z: friction_models::reported_state(&y[..w]),
            }
        })
        .take_while(Row::is_finite)
        .collect();
    let last = s.last().map(|(_, y)| (y[w], y[w + 1]));
    Outcome {
        rows,
        before_switches: Vec::new(),
        events: s
            .events
            .iter()
            // The motion's reversal is its one event, and it always switches the one mode.
            .flat_map(|e| {
                e.switches.iter().map(|m| EventEntry {
                    t: e.t,
                    from: m.from,
                    to: m.to,
                })
            })
            .collect(),
        stats: s.stats,
        error,
        energy: None,
        friction_work: last.map(|l| l.0),
        loop_area: last.map(|l| l.1),
        wall_time_s,
        stiffness_detected_at: s.stiffness_detected_at,
        method_switches: s.method_switches.clone(),
        stiffness: Vec::new(),
        natural_period: None,
        instability: None,
        reference: None,
        integral_action: false,
        has_state: model.n_states() > 0,
        surface_velocity: 0.0,
    }
}

/// Steady friction at each of `velocities`: each point a constant-velocity run from z = 0
/// long enough for the state to settle (20 time constants 1/|∂ż/∂z| at the steady state;
/// stateless models need no settling).
fn run_sweep(
    spec: &RunSpec,
    model: &dyn FrictionModel,
    velocities: &[f64],
    observe: &mut dyn FnMut(f64),
) -> Outcome {
    let mut out = Outcome {
        rows: Vec::new(),
        before_switches: Vec::new(),
        events: Vec::new(),
        stats: Stats::default(),
        error: None,
        energy: None,
        friction_work: None,
        loop_area: None,
        wall_time_s: 0.0,
        stiffness_detected_at: None,
        method_switches: Vec::new(),
        stiffness: Vec::new(),
        natural_period: None,
        instability: None,
        reference: None,
        integral_action: false,
        has_state: model.n_states() > 0,
        surface_velocity: 0.0,
    };
    for &v in velocities {
        let settle = settling_time(model, v);
        let point = RunSpec {
            output_points: 2,
            limits: Limits::default(),
            ..spec.clone()
        };
        let o = run_motion(&point, model, Motion::Constant { v }, settle, observe);
        out.stats += o.stats;
        out.wall_time_s += o.wall_time_s;
        out.stiffness_detected_at = out.stiffness_detected_at.or(o.stiffness_detected_at);
        out.method_switches
            .extend(o.method_switches.iter().copied());
        if let Some(row) = o.last() {
            out.rows.push(*row);
        }
        if o.error.is_some() {
            out.error = o.error;
            break;
        }
    }
    out
}

/// Twenty time constants of the internal states on their way to steady sliding at velocity v
/// ([`friction_models::steady::time_constant`]; 1 ms for a stateless model).
pub fn settling_time(model: &dyn FrictionModel, v: f64) -> f64 {
    friction_models::steady::time_constant(model, v).map_or(1e-3, |tau| 20.0 * tau)
}

/// Runs `spec` on `system`, a one-body system of the caller's in place of the rig's
/// apparatus (the rig's own, changed: [`crate::tracking::run_tracking`]), checked as [`run`]
/// checks the spec.
pub fn run_system(
    spec: &RunSpec,
    system: &System,
    observe: &mut dyn FnMut(f64),
) -> Result<Outcome, ScenarioError> {
    validate(spec)?;
    run_body(spec, system, spec.end_time(), false, observe)
}

/// Runs the simulation `spec` describes; `observe` is told the time after each step.
pub fn run(spec: &RunSpec, observe: &mut dyn FnMut(f64)) -> Result<Outcome, ScenarioError> {
    run_as(spec, false, observe)
}

/// As [`run`], measuring besides the stiffness along the run ([`Outcome::stiffness`]: h·ρ at
/// every recorded point of a body scenario, an eigenvalue problem a point), as `simulate`
/// reports it; the studies and sweeps, which run many times, do not pay for it.
pub fn run_measuring_stiffness(
    spec: &RunSpec,
    observe: &mut dyn FnMut(f64),
) -> Result<Outcome, ScenarioError> {
    run_as(spec, true, observe)
}

fn run_as(
    spec: &RunSpec,
    stiffness: bool,
    observe: &mut dyn FnMut(f64),
) -> Result<Outcome, ScenarioError> {
    validate(spec)?;
    let model = spec.law.build(&spec.friction)?;
    let t_end = spec.end_time();
    let apparatus = (spec.scenario.rig()).apparatus(&spec.params, &spec.friction, model.clone());
    Ok(match apparatus {
        Apparatus::SteadySweep(velocities) => run_sweep(spec, model.as_ref(), &velocities, observe),
        Apparatus::Motion(motion) => run_motion(spec, model.as_ref(), motion, t_end, observe),
        Apparatus::Body(system) => run_body(spec, &system, t_end, stiffness, observe)?,
    })
}
