//! One integration of a system by any solver, and what it produced, read per body and per
//! contact: trajectories, final states, the switching log, the energy balance. A solver
//! failure keeps what was computed before it, with its typed error.

use crate::energy::EnergyBalance;
use crate::hybrid::FrictionSystem;
use crate::moreau_jean::{self, MoreauJean};
use crate::reach::Reach;
use crate::scheme::Scheme;
use crate::system::{System, SystemError};
use integrators::stability::Instability;
use integrators::{
    EventRecord, Failure, Integrator, Mode, OdeProblem, Options, Solution, SolverError, StepControl,
};
use std::time::Instant;

/// The most recorded states at which [`Run::instability`] takes a time-stepped run's one-step
/// map (each costs n + 1 steps and two eigenvalue problems of order n).
pub const SAMPLED_LOOP_STATES: usize = 200;

/// A switch (or a touch of v_rel = 0 that kept the mode) of one contact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactEvent {
    /// Time, s.
    pub t: f64,
    /// The contact, by index.
    pub contact: usize,
    /// Its body, by index.
    pub body: usize,
    /// Mode before.
    pub from: Mode,
    /// Mode after (equal to `from` where v_rel touched zero and the contact slid on).
    pub to: Mode,
}

/// The state of one body at one recorded time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyState {
    /// Time, s.
    pub t: f64,
    /// Displacement, m.
    pub x: f64,
    /// Velocity, m/s.
    pub v: f64,
    /// Friction force at its contact, N (0 without one).
    pub friction: f64,
    /// Contact mode (`None` without a contact).
    pub mode: Option<Mode>,
    /// Internal state of its contact model (the mean of its states when it has several), if
    /// any.
    pub z: Option<f64>,
}

/// A finished (or failed) integration of a system.
pub struct Run<'a> {
    /// The problem that was integrated.
    pub problem: FrictionSystem<'a>,
    /// Start time and state.
    pub t0: f64,
    /// Initial state (accumulators included).
    pub y0: Vec<f64>,
    /// Initial modes.
    pub modes0: Vec<Mode>,
    /// What was computed (up to the failure, if any).
    pub solution: Solution,
    /// The solver's error, if it failed.
    pub error: Option<SolverError>,
    /// Wall time of the integration, s.
    pub wall_time_s: f64,
}

/// The stiffness at one recorded point of a run ([`Run::stiffness`]).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct StiffnessPoint {
    /// Time, s.
    pub t: f64,
    /// The step that reached it, s.
    pub h: f64,
    /// The spectral radius of the Jacobian there, 1/s.
    pub rho: f64,
    /// `h·ρ`: beyond about 3.3 an explicit Runge–Kutta step of that size would be unstable on
    /// the stiffest mode (Dormand–Prince's boundary on the negative real axis).
    pub h_rho: f64,
}

/// Integrates `system` by `scheme` with `options` from the bodies' initial states; `observe`
/// is told the time after every step.
pub fn simulate<'a>(
    system: &'a System,
    scheme: Scheme,
    options: Options,
    observe: &mut dyn FnMut(f64),
) -> Result<Run<'a>, SystemError> {
    system.validate()?;
    if let Scheme::TimeStepping { .. } = scheme {
        moreau_jean::check_contacts(system)?;
    }
    let problem = FrictionSystem::new(system, scheme.switching());
    let (t0, t_end) = (options.t0, options.t_end);
    let y0 = problem.initial_state();
    let modes0 = problem.initial_modes(t0, &y0);
    let clock = Instant::now();
    let result = match scheme {
        Scheme::TimeStepping { theta } => {
            MoreauJean { theta }.solve(&problem, &y0, &modes0, &options, observe)
        }
        Scheme::EventDriven { solver, .. } => {
            solver.solve_observed(&problem, &y0, &modes0, options, observe)
        }
    };
    let (solution, error) = match result {
        Ok(s) => (s, None),
        Err(Failure { error, solution }) => (*solution, Some(error)),
    };
    let (solution, error) = judged(&problem, solution, error, t_end);
    Ok(Run {
        problem,
        t0,
        y0,
        modes0,
        solution,
        error,
        wall_time_s: clock.elapsed().as_secs_f64(),
    })
}

/// `solution`, computed for `problem` and ended with `error`, judged: cut at the first recorded
/// point beyond the system's reach over `[t0, t_end]` ([`runaway`]), a solver that failed on a
/// non-finite value left as it said.
fn judged(
    problem: &FrictionSystem,
    mut solution: Solution,
    mut error: Option<SolverError>,
    t_end: f64,
) -> (Solution, Option<SolverError>) {
    if !matches!(error, Some(SolverError::NonFinite { .. })) {
        if let Some((k, what)) = runaway(problem, &solution, t_end) {
            let t = solution.t[k];
            solution.truncate(k);
            error = Some(SolverError::Runaway { t, what });
        }
    }
    (solution, error)
}

/// Integrates `system` by `scheme` over the spans `next` asks for: first with `options`, then,
/// while `next` returns the options of a longer run (these options but for the end time, the
/// largest step and the output grid), with those. Each run is the one [`simulate`] gives for
/// its options. An event-driven run of a method that can be copied continues the run before it
/// from before its last step ([`Integrator::extend`]), so that no span is integrated twice;
/// any other is run again from the start. `next` sees every run, its wall time that of the
/// spans so far; the last is returned.
pub fn simulate_spans<'a>(
    system: &'a System,
    scheme: Scheme,
    options: Options,
    next: &mut dyn FnMut(&Run<'a>) -> Option<Options>,
) -> Result<Run<'a>, SystemError> {
    system.validate()?;
    let problem = FrictionSystem::new(system, scheme.switching());
    let (t0, y0) = (options.t0, problem.initial_state());
    let modes0 = problem.initial_modes(t0, &y0);
    // The integration to continue: an event-driven scheme whose method makes a stepper.
    let resumable = |options: &Options| match scheme {
        Scheme::EventDriven { solver, .. } => {
            let stepper = solver.method().stepper(options, problem.dim()).ok()?;
            let integrator = Integrator::new(&problem, stepper, &y0, &modes0, options.clone());
            Some((integrator.ok()?.resumable(), solver.method().name()))
        }
        Scheme::TimeStepping { .. } => None,
    };
    let clock = Instant::now();
    let mut options = options;
    let mut integration = resumable(&options);
    loop {
        let run = match integration.as_mut() {
            Some((integrator, name)) => {
                let error = integrator.advance(&mut |_| {}).err();
                let mut solution = integrator.solution();
                solution.solver = name;
                let (solution, error) = judged(&problem, solution, error, options.t_end);
                Run {
                    problem: FrictionSystem::new(system, scheme.switching()),
                    t0,
                    y0: y0.clone(),
                    modes0: modes0.clone(),
                    solution,
                    error,
                    wall_time_s: clock.elapsed().as_secs_f64(),
                }
            }
            // Its wall time counts the spans before it too.
            None => Run {
                wall_time_s: clock.elapsed().as_secs_f64(),
                ..simulate(system, scheme, options.clone(), &mut |_| {})?
            },
        };
        let Some(longer) = next(&run) else {
            return Ok(run);
        };
        let extended = integration
            .as_mut()
            .is_some_and(|(i, _)| run.error.is_none() && i.extend(longer.clone()));
        if !extended {
            integration = resumable(&longer);
        }
        options = longer;
    }
}

/// The first recorded point of `solution` at which a body is beyond the system's
/// [`Reach`] over `[t0, t_end]` times [`crate::RUNAWAY_FACTOR`], with what is beyond it.
fn runaway(problem: &FrictionSystem, solution: &Solution, t_end: f64) -> Option<(usize, String)> {
    let (system, layout) = (problem.system, &problem.layout);
    let reach = Reach::of(system, t_end);
    (0..solution.len()).find_map(|k| {
        let y = solution.y_at(k);
        let beyond = reach.exceeded(&system.bodies, |i| y[layout.x[i]], |i| y[layout.v(i)]);
        beyond.map(|what| (k, what))
    })
}

impl Run<'_> {
    /// Body `i` at recorded point `k`.
    pub fn body_at(&self, i: usize, k: usize) -> BodyState {
        let p = &self.problem;
        let s = &self.solution;
        let (t, y, modes) = (s.t[k], s.y_at(k), s.modes_at(k));
        let contact = p.layout.contact[i];
        BodyState {
            t,
            x: y[p.layout.x[i]],
            v: y[p.layout.v(i)],
            friction: contact.map_or(0.0, |j| p.friction(j, t, y, modes)),
            mode: contact.map(|j| p.reported_mode(j, y, modes)),
            z: friction_models::reported_state(p.layout.states(i, y)),
        }
    }

    /// Body `i` at every recorded point.
    pub fn body(&self, i: usize) -> Vec<BodyState> {
        (0..self.solution.len())
            .map(|k| self.body_at(i, k))
            .collect()
    }

    /// Every body at the last recorded point (none if nothing was recorded).
    pub fn final_states(&self) -> Vec<BodyState> {
        match self.solution.len() {
            0 => Vec::new(),
            n => (0..self.problem.system.bodies.len())
                .map(|i| self.body_at(i, n - 1))
                .collect(),
        }
    }

    /// Each event in time order, with the modes before it and after it.
    fn events_with_modes(&self) -> impl Iterator<Item = (&EventRecord, Vec<Mode>, Vec<Mode>)> {
        let mut modes = self.modes0.clone();
        self.solution.events.iter().map(move |e| {
            let before = modes.clone();
            for s in &e.switches {
                modes[s.component] = s.to;
            }
            (e, before, modes.clone())
        })
    }

    /// The switching log: every contact whose event fired, in time order.
    pub fn contact_events(&self) -> Vec<ContactEvent> {
        let mut out = Vec::new();
        for (e, before, after) in self.events_with_modes() {
            let mut contacts: Vec<usize> = e.fired.iter().map(|&k| k / 2).collect();
            contacts.dedup();
            out.extend(contacts.into_iter().map(|j| ContactEvent {
                t: e.t,
                contact: j,
                body: self.problem.system.contacts[j].body,
                from: before[j],
                to: after[j],
            }));
        }
        out
    }

    /// Body `i` at each switch of its contact's mode that has a recorded point, with the mode
    /// it leaves: the one-sided limit `F(t_e⁻)` of its friction, where the recorded point holds
    /// the mode it enters and `F(t_e⁺)`. The state (x, v, z) is continuous at a switch; the
    /// friction jumps, as at a re-stick from the sliding force to the holding force. (The
    /// event-driven solvers record a point at each switch; time-stepping at the end of the
    /// step that switched, where this is the law of the mode left at the step's end state.)
    pub fn before_switches(&self, i: usize) -> Vec<BodyState> {
        let p = &self.problem;
        let Some(j) = p.layout.contact[i] else {
            return Vec::new();
        };
        let s = &self.solution;
        let mut out = Vec::new();
        for (e, before, after) in self.events_with_modes() {
            if before[j] == after[j] {
                continue;
            }
            // The recorded point at the switch, if any.
            let k = s.t.partition_point(|&t| t < e.t);
            if k < s.len() && s.t[k] == e.t {
                let y = s.y_at(k);
                out.push(BodyState {
                    friction: p.friction(j, e.t, y, &before),
                    mode: Some(p.reported_mode(j, y, &before)),
                    ..self.body_at(i, k)
                });
            }
        }
        out
    }

    /// The mode that the fixed step amplifies most over the recorded states (each with its
    /// modes), if any; `None` for an adaptive step, for an implicit method and for a method
    /// whose stability polynomial is not known.
    /// - An explicit method: the decaying mode of the Jacobian its step amplifies
    ///   ([`integrators::stability::unstable_mode`]), at
    ///   [`integrators::stability::CHECK_BUDGET`]` / n³` states, evenly spread, the first
    ///   included.
    /// - Time-stepping of a system with controllers: the growing mode of the scheme's one-step
    ///   map where the continuous system has none ([`integrators::stability::sampled_loop_mode`]:
    ///   the controllers' forces, held over each step, close a sampled loop), at
    ///   [`SAMPLED_LOOP_STATES`] states at most. Without a controller the scheme holds no
    ///   feedback over a step and is not checked.
    pub fn instability(&self, scheme: &Scheme, step: StepControl) -> Option<Instability> {
        use integrators::stability::{sampled_loop_mode, unstable_mode, CHECK_BUDGET};
        let StepControl::Fixed { h } = step else {
            return None;
        };
        let s = &self.solution;
        let n = integrators::OdeProblem::dim(&self.problem).max(1);
        let budget = (CHECK_BUDGET / n.pow(3)).max(1);
        // The state at the k-th of `states` points evenly spread over the run's record.
        let at = |k: usize, states: usize| match s.len() {
            0 => (self.t0, self.y0.as_slice(), self.modes0.as_slice()),
            len => {
                let i = k * (len - 1) / (states - 1).max(1);
                (s.t[i], s.y_at(i), s.modes_at(i))
            }
        };
        let worst = |found: &mut dyn Iterator<Item = Instability>| {
            found.max_by(|a, b| a.amplification().total_cmp(&b.amplification()))
        };
        match scheme {
            Scheme::EventDriven { solver, .. } => {
                let r = solver.stability_polynomial()?;
                let states = budget.min(s.len().max(1));
                worst(&mut (0..states).filter_map(|k| {
                    let (t, y, modes) = at(k, states);
                    unstable_mode(&self.problem, t, y, modes, h, r)
                }))
            }
            Scheme::TimeStepping { theta } => {
                if self.problem.system.controllers.is_empty() {
                    return None;
                }
                let scheme = MoreauJean { theta: *theta };
                let states = budget.min(SAMPLED_LOOP_STATES).min(s.len().max(1));
                worst(&mut (0..states).filter_map(|k| {
                    let (t, y, modes) = at(k, states);
                    let mut map = |y: &[f64]| scheme.step_map(&self.problem, (t, h), y, modes);
                    sampled_loop_mode(&self.problem, (t, h), y, modes, &mut map)
                }))
            }
        }
    }

    /// The stiffness along the run: at recorded points evenly spread (as many as
    /// [`CHECK_BUDGET`] over [`radius_cost`] allows, at least [`MIN_STIFFNESS_POINTS`], at most
    /// all), the step size h of the step that reached it, the spectral radius ρ of the Jacobian
    /// there ([`spectral_radius`]: exact on small systems, by power iteration on large ones) and
    /// `h·ρ`. `step_ends` are the times the driver reached after each step, in order (what
    /// `simulate`'s observer is told). Empty for a differential–algebraic problem.
    ///
    /// [`CHECK_BUDGET`]: integrators::stability::CHECK_BUDGET
    /// [`radius_cost`]: integrators::stability::radius_cost
    /// [`MIN_STIFFNESS_POINTS`]: integrators::stability::MIN_STIFFNESS_POINTS
    /// [`spectral_radius`]: integrators::stability::spectral_radius
    pub fn stiffness(&self, step_ends: &[f64]) -> Vec<StiffnessPoint> {
        use integrators::stability::{
            radius_cost, spectral_radius, CHECK_BUDGET, MIN_STIFFNESS_POINTS,
        };
        let s = &self.solution;
        let n = integrators::OdeProblem::dim(&self.problem).max(1);
        if s.is_empty() || step_ends.is_empty() {
            return Vec::new();
        }
        let points = (CHECK_BUDGET / radius_cost(n))
            .max(MIN_STIFFNESS_POINTS)
            .min(s.len());
        let mut out = Vec::with_capacity(points);
        for k in 0..points {
            let i = k * (s.len() - 1) / (points - 1).max(1);
            let t = s.t[i];
            // The step (step_ends[j − 1], step_ends[j]] that reached t; the first from t0.
            let j = step_ends
                .partition_point(|&e| e < t)
                .min(step_ends.len() - 1);
            let start = if j == 0 { self.t0 } else { step_ends[j - 1] };
            let h = step_ends[j] - start;
            if let Some(rho) = spectral_radius(&self.problem, t, s.y_at(i), s.modes_at(i)) {
                out.push(StiffnessPoint {
                    t,
                    h,
                    rho,
                    h_rho: h * rho,
                });
            }
        }
        out
    }

    /// The energy balance from the start to the last recorded point.
    pub fn energy(&self) -> Option<EnergyBalance> {
        self.solution
            .last()
            .map(|(t1, y1)| self.problem.balance(self.t0, &self.y0, t1, y1))
    }
}
