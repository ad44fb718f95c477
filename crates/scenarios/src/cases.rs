//! What a study runs: any problem that can be integrated again and again with different
//! solvers and steps and measured the same way. A rig ([`Case`]), a system of many bodies
//! ([`SystemCase`]), or a user's own problem through the public [`StudyCase`] trait.

use crate::chain::ChainSource;
use crate::error::ScenarioError;
use crate::method::Method;
use crate::motion::Kinematic;
use crate::quantity::Quantity;
use crate::run::Limits;
use crate::run::{body_system, run, Law, Outcome, Row, RunSpec};
use crate::scenario::Scenario;
use crate::ScenarioParams;
use friction_models::{FrictionParams, ModelId, Parameters};
use friction_systems::{simulate, EnergyBalance, Layout, Run, Scheme, System, STICK};
use integrators::stability::Instability;
use integrators::{Options, Output, Solver, SolverError, Stats, StepControl};
use serde::Serialize;

/// Points of the common time grid on which trajectories are compared.
pub const GRID_POINTS: usize = 201;

/// What a run is judged by.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Measures {
    /// Every body's state at the end, body after body: x, v and, for a law with internal
    /// states, z.
    pub final_state: Vec<f64>,
    /// The quantity of each entry of `final_state`.
    pub final_quantities: Vec<Quantity>,
    /// The measured bodies' states on the common grid (x, v and z, body after body), one row
    /// per grid point.
    pub grid: Vec<Vec<f64>>,
    /// The quantity of each column of `grid`.
    pub quantities: Vec<Quantity>,
    /// Times of the measured bodies' events, body after body.
    pub event_times: Vec<f64>,
    /// Durations of the measured bodies' completed stick phases, body after body.
    pub stick_durations: Vec<f64>,
    /// Largest |friction| of the measured bodies on the grid.
    pub peak_friction: f64,
    /// The run's energy balance, where it keeps one (not the prescribed motions).
    pub energy: Option<EnergyBalance>,
}

/// The state of one body as the measures hold it, with the quantity of each entry: x, v,
/// and z where the law has an internal state.
fn body_state(x: f64, v: f64, z: Option<f64>) -> (Vec<f64>, Vec<Quantity>) {
    let mut state = vec![x, v];
    let mut quantities = vec![Quantity::Position, Quantity::Velocity];
    if let Some(z) = z {
        state.push(z);
        quantities.push(Quantity::InternalState);
    }
    (state, quantities)
}

/// One run of a case, measured.
#[derive(Clone, Debug, PartialEq)]
pub struct Measured {
    /// The measures.
    pub measures: Measures,
    /// Work done.
    pub stats: Stats,
    /// The solver's error, if it failed (the measures are of what it computed before).
    pub error: Option<SolverError>,
    /// Wall time of the integration, s.
    pub wall_time_s: f64,
    /// Where Hairer's stiffness test (Dormand–Prince's) first judged the problem stiff;
    /// `None` for another solver or a run it did not judge stiff.
    pub stiffness_detected_at: Option<f64>,
    /// The decaying mode at the start that an explicit method's fixed step amplifies, if any
    /// ([`integrators::stability`]): the run is `inaccurate` for it.
    pub instability: Option<Instability>,
}

/// A problem a study integrates with many schemes and steps: the declared problem only, as
/// Siconos declares a nonsmooth system once; each run's [`Scheme`] says how it is integrated.
pub trait StudyCase: Sync + Send {
    /// What it is, for titles: "belt with CS" ([`describe`] adds the studied treatment).
    fn describe(&self) -> String;

    /// End time, s.
    fn t_end(&self) -> f64;

    /// Number of unknowns the solvers integrate (the `dim` of [`Stats::work`]).
    fn dim(&self) -> Result<usize, ScenarioError>;

    /// The same problem with parameter `name` set to `value` (for a stiffness sweep).
    fn with_parameter(&self, name: &str, value: f64) -> Result<Box<dyn StudyCase>, ScenarioError>;

    /// One run under `scheme` with `step`, measured on the common grid.
    fn measure(&self, scheme: Scheme, step: StepControl) -> Result<Measured, ScenarioError>;

    /// The declared system, where the case integrates bodies (a rig with a body, a system
    /// file, the chain); `None` for a rig that imposes a motion, and for a case that is no
    /// system.
    fn system(&self) -> Result<Option<System>, ScenarioError> {
        Ok(None)
    }

    /// The exact solution's measures, where one is known, with its formula.
    fn closed_form(&self) -> Option<(String, Measures)> {
        None
    }
}

/// `case` as a study of `methods` titles it: "belt with CS (event switching)", with the
/// treatment of v = 0 of the studied methods (`timestepping` for Moreau–Jean's).
pub fn describe(case: &dyn StudyCase, methods: &[Method]) -> String {
    format!(
        "{} ({} switching)",
        case.describe(),
        Method::treatment_name(methods)
    )
}

/// Stick durations from a sequence of (time, mode after) of one contact.
fn stick_durations(events: impl Iterator<Item = (f64, bool)>, out: &mut Vec<f64>) {
    let mut start = None;
    for (t, sticks) in events {
        match (sticks, start) {
            (true, _) => start = Some(t),
            (false, Some(s)) => {
                out.push(t - s);
                start = None;
            }
            _ => {}
        }
    }
}

impl Measures {
    /// The measures of a rig's outcome on the output grid `grid`: one row per grid time (the
    /// last at that time, the state after a switch there: time-stepping switches at its step
    /// ends, which the grid's times can be), the rows at events between them skipped.
    pub fn of(o: &Outcome, grid: &[f64]) -> Measures {
        let event_times: Vec<f64> = o.events.iter().map(|e| e.t).collect();
        let mut sticks = Vec::new();
        stick_durations(o.events.iter().map(|e| (e.t, e.to == STICK)), &mut sticks);
        let state = |r: &Row| body_state(r.x, r.v, r.z);
        let (final_state, final_quantities) = match o.last() {
            Some(r) => state(r),
            None => (
                vec![f64::NAN; 2],
                vec![Quantity::Position, Quantity::Velocity],
            ),
        };
        let mut times = grid.iter().peekable();
        let mut grid = Vec::with_capacity(o.rows.len());
        for (i, r) in o.rows.iter().enumerate() {
            while times.next_if(|&&g| g < r.t).is_some() {}
            let last_at_t = o.rows.get(i + 1).is_none_or(|next| next.t != r.t);
            if last_at_t && times.next_if(|&&g| g == r.t).is_some() {
                grid.push(state(r).0);
            }
        }
        Measures {
            final_state,
            quantities: final_quantities.clone(),
            final_quantities,
            grid,
            event_times,
            stick_durations: sticks,
            peak_friction: o.rows.iter().map(|r| r.friction.abs()).fold(0.0, f64::max),
            energy: o.energy,
        }
    }

    /// The measures of a system's run: every body's final state, and the grid, events and
    /// stick phases of `bodies`.
    pub fn of_run(run: &Run, bodies: &[usize]) -> Measures {
        let n = run.problem.system.bodies.len();
        let state = |i: usize, k: usize| {
            let b = run.body_at(i, k);
            body_state(b.x, b.v, b.z)
        };
        let (mut final_state, mut final_quantities) = (Vec::new(), Vec::new());
        match run.solution.len().checked_sub(1) {
            Some(k) => {
                for i in 0..n {
                    let (s, q) = state(i, k);
                    final_state.extend(s);
                    final_quantities.extend(q);
                }
            }
            None => {
                final_state = vec![f64::NAN; 2 * n];
                final_quantities = [Quantity::Position, Quantity::Velocity].repeat(n);
            }
        }
        let mut quantities = Vec::new();
        if !run.solution.is_empty() {
            for &i in bodies {
                quantities.extend(state(i, 0).1);
            }
        }
        let mut peak: f64 = 0.0;
        let grid = (0..run.solution.len())
            .map(|k| {
                bodies
                    .iter()
                    .flat_map(|&i| {
                        let b = run.body_at(i, k);
                        peak = peak.max(b.friction.abs());
                        body_state(b.x, b.v, b.z).0
                    })
                    .collect()
            })
            .collect();
        let events = run.contact_events();
        let mut event_times = Vec::new();
        let mut sticks = Vec::new();
        for &i in bodies {
            let mine = || events.iter().filter(move |e| e.body == i);
            event_times.extend(mine().map(|e| e.t));
            stick_durations(mine().map(|e| (e.t, e.to == STICK)), &mut sticks);
        }
        Measures {
            final_state,
            final_quantities,
            grid,
            quantities,
            event_times,
            stick_durations: sticks,
            peak_friction: peak,
            energy: run.energy(),
        }
    }
}

/// A rig to study: everything of a run but its scheme and step control.
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    /// The rig.
    pub scenario: Scenario,
    /// The friction law at its contact.
    pub law: Law,
    /// Friction parameters (the width ε of a regularised run is its scheme's).
    pub friction: FrictionParams,
    /// Scenario parameters.
    pub params: ScenarioParams,
    /// End time.
    pub t_end: f64,
    /// Bounds of every run.
    pub limits: Limits,
}

impl Case {
    /// The run of this case under `scheme` with `step`.
    pub fn spec(&self, scheme: Scheme, step: StepControl) -> RunSpec {
        RunSpec {
            scenario: self.scenario,
            law: self.law.clone(),
            friction: self.friction,
            params: self.params,
            scheme,
            step,
            t_end: Some(self.t_end),
            output_points: GRID_POINTS,
            limits: self.limits,
        }
    }
}

/// An exact motion t ↦ (x, v).
type ExactMotion = Box<dyn Fn(f64) -> (f64, f64)>;

impl StudyCase for Case {
    fn describe(&self) -> String {
        format!("{} with {}", self.scenario, self.law)
    }

    fn t_end(&self) -> f64 {
        self.t_end
    }

    /// A body rig's: the unknowns of its one-body system (x, v, the internal states, the
    /// energy accumulators); a prescribed motion's: those of its kinematic problem.
    fn dim(&self) -> Result<usize, ScenarioError> {
        let model = self.law.build(&self.friction)?;
        // The scheme and step do not change the system.
        let spec = self.spec(
            Scheme::events(Solver::DOPRI5),
            StepControl::Fixed { h: self.t_end },
        );
        Ok(match body_system(&spec, model.clone()) {
            Some(system) => Layout::of(&system).dim(),
            None => Kinematic::dim_of(model.as_ref()),
        })
    }

    fn with_parameter(&self, name: &str, value: f64) -> Result<Box<dyn StudyCase>, ScenarioError> {
        let mut c = self.clone();
        if FrictionParams::spec(name).is_some() {
            c.friction.set(name, value)?;
        } else {
            c.params.set(name, value)?;
        }
        Ok(Box::new(c))
    }

    /// The rig's system with the case's law, for a rig with a body.
    fn system(&self) -> Result<Option<System>, ScenarioError> {
        let law = self.law.build(&self.friction)?;
        // The system does not depend on how it is integrated.
        let step = StepControl::Adaptive {
            rtol: 1e-8,
            atol: 1e-10,
            h0: None,
        };
        Ok(body_system(
            &self.spec(Scheme::events(Solver::DOPRI5), step),
            law,
        ))
    }

    fn measure(&self, scheme: Scheme, step: StepControl) -> Result<Measured, ScenarioError> {
        let o = run(&self.spec(scheme, step), &mut |_| {})?;
        let grid = integrators::even_grid(0.0, self.t_end, GRID_POINTS);
        Ok(Measured {
            measures: Measures::of(&o, &grid),
            stats: o.stats,
            error: o.error,
            wall_time_s: o.wall_time_s,
            stiffness_detected_at: o.stiffness_detected_at,
            instability: o.instability,
        })
    }

    /// The block pushed from rest against viscous friction (v = F/μ_v·(1 − e^(−μ_v t/m))) or
    /// against a constant Coulomb level (v = (F − F_c)·t/m once it slides).
    fn closed_form(&self) -> Option<(String, Measures)> {
        if self.scenario != Scenario::PAPER_BLOCK || self.params.x0 != 0.0 || self.params.v0 != 0.0
        {
            return None;
        }
        let (m, f, p) = (self.params.m, self.params.f_ex, &self.friction);
        let (name, motion): (&str, ExactMotion) = match self.law.catalog() {
            Some(ModelId::Viscous) => {
                let tau = m / p.mu_v;
                let vt = f / p.mu_v;
                (
                    "x = v_t(t - tau(1 - e^(-t/tau))), v = v_t(1 - e^(-t/tau))",
                    Box::new(move |t| {
                        (
                            vt * (t - tau * (1.0 - (-t / tau).exp())),
                            vt * (1.0 - (-t / tau).exp()),
                        )
                    }),
                )
            }
            Some(ModelId::Coulomb | ModelId::Static) if f > p.f_s.max(p.f_c) => {
                let a = (f - p.f_c) / m;
                (
                    "x = a t^2/2, v = a t, a = (F_ex - F_c)/m",
                    Box::new(move |t| (0.5 * a * t * t, a * t)),
                )
            }
            _ => return None,
        };
        let grid = integrators::even_grid(0.0, self.t_end, GRID_POINTS)
            .into_iter()
            .map(|t| {
                let (x, v) = motion(t);
                vec![x, v]
            })
            .collect();
        let (x, v) = motion(self.t_end);
        let peak = match self.law.catalog() {
            Some(ModelId::Viscous) => f * (1.0 - (-self.t_end * p.mu_v / m).exp()),
            _ => p.f_c,
        };
        Some((
            name.to_string(),
            Measures {
                final_state: vec![x, v],
                final_quantities: vec![Quantity::Position, Quantity::Velocity],
                grid,
                quantities: vec![Quantity::Position, Quantity::Velocity],
                event_times: vec![],
                stick_durations: vec![],
                peak_friction: peak,
                energy: None,
            },
        ))
    }
}

/// A system of many bodies to study: every body's final state is compared, and the grid,
/// the events and the stick phases of the chosen `bodies`.
#[derive(Clone, Debug)]
pub struct SystemCase {
    /// What it is, for titles.
    pub name: String,
    /// The system.
    pub system: System,
    /// End time, s.
    pub t_end: f64,
    /// The bodies whose trajectories, events and stick phases are measured.
    pub bodies: Vec<usize>,
    /// Bounds of every run.
    pub limits: Limits,
    /// What the system was built from, when it is the chain: a stiffness study can then sweep
    /// the chain's parameters and its law's (`None`: a system file, or a chain changed after
    /// it was built).
    pub chain: Option<ChainSource>,
}

impl SystemCase {
    /// A study of `system` over `t_end` seconds: its first body measured, the default limits,
    /// no chain to build again (change any field with
    /// `SystemCase { bodies: …, ..SystemCase::new(…) }`).
    pub fn new(name: impl Into<String>, system: System, t_end: f64) -> SystemCase {
        SystemCase {
            name: name.into(),
            system,
            t_end,
            bodies: vec![0],
            limits: Limits::default(),
            chain: None,
        }
    }
}

impl StudyCase for SystemCase {
    fn describe(&self) -> String {
        self.name.clone()
    }

    fn t_end(&self) -> f64 {
        self.t_end
    }

    fn dim(&self) -> Result<usize, ScenarioError> {
        self.system.validate()?;
        Ok(friction_systems::Layout::of(&self.system).dim())
    }

    /// On the chain, its parameters and those its law reads can be swept, each value building
    /// the chain again ([`ChainSource::with`]); on a system file none (each contact has its
    /// own parameters). (The regularisation width `epsilon`, a parameter of the scheme, is
    /// swept by the study on its methods: [`crate::studies::stiffness`].)
    fn with_parameter(&self, name: &str, value: f64) -> Result<Box<dyn StudyCase>, ScenarioError> {
        let Some(source) = &self.chain else {
            return Err(ScenarioError::Invalid(format!(
                "parameter `{name}` cannot be swept on a system file (each contact has its \
                 own parameters): allowed epsilon"
            )));
        };
        let source = source.with(name, value)?;
        let system = source.build()?;
        if let Some(&b) = self.bodies.iter().find(|&&b| b >= system.bodies.len()) {
            return Err(ScenarioError::Invalid(format!(
                "parameter `{name}` = {value} leaves {} bodies: the measured body {} is not \
                 among them",
                system.bodies.len(),
                b + 1
            )));
        }
        Ok(Box::new(SystemCase {
            name: source.name(),
            system,
            chain: Some(source),
            ..self.clone()
        }))
    }

    fn system(&self) -> Result<Option<System>, ScenarioError> {
        Ok(Some(self.system.clone()))
    }

    fn measure(&self, scheme: Scheme, step: StepControl) -> Result<Measured, ScenarioError> {
        let grid = integrators::even_grid(0.0, self.t_end, GRID_POINTS);
        let options = Options {
            step,
            output: Output::GridOnly(grid),
            max_steps: self.limits.max_steps,
            time_limit: self.limits.time_limit,
            time_limit_since: self.limits.time_limit_since,
            ..Options::adaptive(0.0, self.t_end, 1e-8, 1e-10)
        };
        let run = simulate(&self.system, scheme, options, &mut |_| {})?;
        Ok(Measured {
            measures: Measures::of_run(&run, &self.bodies),
            stats: run.solution.stats,
            stiffness_detected_at: run.solution.stiffness_detected_at,
            instability: run.instability(&scheme, step),
            error: run.error,
            wall_time_s: run.wall_time_s,
        })
    }
}
