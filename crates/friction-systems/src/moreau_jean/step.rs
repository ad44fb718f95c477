//! One step of Moreau–Jean's θ-method (`TimeStepper`, the scheme's one-step integrator on the
//! driver of every method): the known part of each body's momentum equation at the start, the
//! step's contact problem ([`super::contact_problem`]) solved, and the end state, modes and
//! energy accumulators from its solution.

use super::contact_problem::{
    colour_order, BodyStep, ContactData, ContactProblem, Matrix, StepStart,
};
use super::{event_record, MoreauJean, CORRECT_AFTER, NAME};
use crate::hybrid::FrictionSystem;
use crate::local::{AffineLaw, Solved, StateStore, StepCache};
use crate::springs::Springs;
use crate::switching::{SLIP_NEGATIVE, SLIP_POSITIVE, STICK};
use friction_models::{Direction, SignLaw};
use integrators::{
    EventRecord, Mode, ModeSwitch, Ode, Options, SolverError, Stats, StepControl, Stepper,
    StepperState,
};

/// The scheme's working state between steps: its one-step integrator. The bodies of its
/// contact problem are in the sweep order ([`colour_order`]): body i is at place `at[i]`.
pub(super) struct TimeStepper<'p, 'a> {
    p: &'p FrictionSystem<'a>,
    theta: f64,
    /// The bodies and contacts of each step's contact problem.
    problem: ContactProblem<'p>,
    at: Vec<usize>,
    /// The state and modes at the end of the last step.
    state: StepperState,
    modes: Vec<Mode>,
    /// The state and modes at the start of the last step, kept only for a step the driver
    /// interpolates in.
    y_prev: Vec<f64>,
    modes_prev: Vec<Mode>,
    /// At the places of the internal states in y: their rates at the end of the last step.
    rate: Vec<f64>,
    /// Per contact: its friction force at the start of the step (written at the end of the
    /// step before).
    force_start: Vec<f64>,
    /// The springs by kind, their bodies by place, those to anchors sorted by place: place
    /// k's are `springs.anchored[anchored_start[k]..anchored_start[k + 1]]`.
    springs: Springs,
    anchored_start: Vec<usize>,
    /// Per pair: its force on end a and `v_b − v_a` at the start of the step (those at the
    /// end of the step before, kept from its energy accumulation).
    pair_force: Vec<(f64, f64)>,
    /// Per spring to an anchor: its force on the body and `v_anchor − v`, likewise.
    anchored_force: Vec<(f64, f64)>,
    /// Per controller: its force over the step, held at its value at the step's start (a
    /// sampled controller with a zero-order hold, the step its sampling period).
    control: Vec<f64>,
    /// The contacts whose model has an internal state.
    stateful: Vec<usize>,
    /// The contacts whose mode the last step switched.
    switches: Vec<ModeSwitch>,
    /// The run: its start, its end, its fixed step and how many steps it takes, the steps
    /// taken, and those that switched a mode (its events).
    t0: f64,
    t_end: f64,
    h: f64,
    n_steps: usize,
    taken: usize,
    switched_steps: usize,
    /// The output grid, if any, and the first of its points after the last step's end: a step
    /// with a point strictly inside keeps its start ([`TimeStepper::y_prev`]) for the driver's
    /// interpolation.
    grid: Option<Vec<f64>>,
    grid_next: usize,
}

impl<'p, 'a> TimeStepper<'p, 'a> {
    /// The scheme at θ = `theta` for the run of `options` from `y0` in `modes0`: θ in
    /// [`MoreauJean::THETA_RANGE`], a fixed step that divides the span into fewer than 2^64
    /// steps.
    pub(super) fn new(
        p: &'p FrictionSystem<'a>,
        theta: f64,
        options: &Options,
        y0: &[f64],
        modes0: &[Mode],
    ) -> Result<Self, SolverError> {
        options.validate()?;
        if !(0.5..=1.0).contains(&theta) {
            return Err(SolverError::InvalidOption {
                name: "theta",
                value: theta,
                allowed: MoreauJean::THETA_RANGE,
            });
        }
        let StepControl::Fixed { h } = options.step else {
            return Err(SolverError::Unsupported {
                solver: NAME,
                why: "time-stepping takes a fixed step h (dt), not tolerances".into(),
            });
        };
        let (t0, t_end) = (options.t0, options.t_end);
        let n_steps = ((t_end - t0) / h - 1e-9).ceil().max(1.0);
        if n_steps >= usize::MAX as f64 {
            return Err(SolverError::InvalidOption {
                name: "dt",
                value: h,
                allowed: "a step that divides the span into fewer than 2^64 steps",
            });
        }
        let grid = options.output.grid().map(<[f64]>::to_vec);
        let grid_next = grid.as_ref().map_or(0, |g| g.partition_point(|&t| t <= t0));
        Ok(TimeStepper {
            t_end,
            n_steps: n_steps as usize,
            grid,
            grid_next,
            ..TimeStepper::build(p, theta, (t0, h), y0, modes0)
        })
    }

    /// The scheme's state at (t0, y0) in `modes0` with step h, for a run of one step.
    pub(super) fn build(
        p: &'p FrictionSystem<'a>,
        theta: f64,
        (t0, h): (f64, f64),
        y0: &[f64],
        modes0: &[Mode],
    ) -> Self {
        let n = p.system.bodies.len();
        let l = &p.layout;
        let solved: Vec<Solved> = p
            .system
            .contacts
            .iter()
            .enumerate()
            .map(|(j, c)| Solved {
                u: y0[l.v(c.body)] - c.surface_velocity,
                force: p.friction(j, 0.0, y0, modes0),
                impulse: 0.0,
                direction: None,
                dr_du: 0.0,
                iterations: 0,
            })
            .collect();
        let edges: Vec<(usize, usize)> = p.springs.pairs.iter().map(|s| (s.a, s.b)).collect();
        let body_of = colour_order(n, &edges);
        let mut at = vec![0; n];
        for (k, &i) in body_of.iter().enumerate() {
            at[i] = k;
        }
        let mut springs = p.springs.renumbered(&at);
        let anchored_start = springs.sort_anchored_by_body(n);
        let mut bodies: Vec<BodyStep> = body_of
            .iter()
            .map(|&i| {
                let x = l.x[i];
                BodyStep {
                    m: p.system.bodies[i].m,
                    x: y0[x],
                    v: y0[x + 1],
                    v_last: y0[x + 1],
                    x_index: x,
                    contact: l.contact[i],
                    ..BodyStep::default()
                }
            })
            .collect();
        let state = |k: usize| (bodies[k].x, bodies[k].v);
        let pair_force: Vec<(f64, f64)> = springs
            .pairs
            .iter()
            .map(|s| s.force(state(s.a), state(s.b)))
            .collect();
        let anchored_force: Vec<(f64, f64)> = springs
            .anchored
            .iter()
            .map(|s| s.force(t0, state(s.body)))
            .collect();
        // The first step's spring forces at t0, as `accumulate` adds them for the others.
        for (s, &(f, _)) in springs.anchored.iter().zip(&anchored_force) {
            bodies[s.body].known += f;
        }
        for (s, &(f, _)) in springs.pairs.iter().zip(&pair_force) {
            bodies[s.a].known += f;
            bodies[s.b].known -= f;
        }
        let force_start = solved.iter().map(|s| s.force).collect();
        let contacts = p
            .system
            .contacts
            .iter()
            .enumerate()
            .map(|(j, c)| ContactData {
                body: c.body,
                at: at[c.body],
                v_s: c.surface_velocity,
                model: c.model.as_ref(),
                states: l.z[c.body].clone(),
                invariant: p.invariant_at_rest(j),
                affine: AffineLaw::new(c.model.as_ref()),
            })
            .collect();
        let mut s = TimeStepper {
            p,
            theta,
            problem: ContactProblem {
                body_of,
                matrix: Matrix::new(&mut bodies, &springs, h, theta),
                bodies,
                solved,
                cache: vec![StepCache::default(); p.system.contacts.len()],
                states: StateStore::new(y0.len()),
                contacts,
                correction: None,
                correct_after: CORRECT_AFTER,
                sweeps: 0,
                iterations: 0,
                corrections: 0,
            },
            state: StepperState {
                t_prev: t0,
                t: t0,
                y: y0.to_vec(),
                h,
            },
            y_prev: y0.to_vec(),
            modes: modes0.to_vec(),
            modes_prev: modes0.to_vec(),
            pair_force,
            anchored_force,
            springs,
            anchored_start,
            rate: vec![0.0; y0.len()],
            control: vec![0.0; p.system.controllers.len()],
            force_start,
            stateful: (0..l.z.len())
                .filter(|&i| !l.z[i].is_empty())
                .filter_map(|i| l.contact[i])
                .collect(),
            switches: Vec::new(),
            at,
            t0,
            t_end: t0 + h,
            h,
            n_steps: 1,
            taken: 0,
            switched_steps: 0,
            grid: None,
            grid_next: 0,
        };
        for j in 0..p.system.contacts.len() {
            s.state_rates(j);
        }
        s
    }

    /// ż of contact j's model at the state y in its mode, written into `rate` at the states'
    /// places (nothing for a model without internal states).
    fn state_rates(&mut self, j: usize) {
        let c = &self.problem.contacts[j];
        if c.states.is_empty() {
            return;
        }
        let law = match self.modes[j] {
            STICK => SignLaw::Discontinuous,
            m => self.p.switching.law(m),
        };
        let (x, y) = (self.p.layout.x[c.body], &self.state.y);
        let states = c.states.clone();
        c.model.response(
            y[x],
            y[x + 1] - c.v_s,
            &y[states.clone()],
            law,
            &mut self.rate[states],
        );
    }

    /// The state one step h after (t0, y0) in `modes0`, the scheme started afresh there.
    pub(super) fn one_step(
        p: &'p FrictionSystem<'a>,
        theta: f64,
        (t0, h): (f64, f64),
        y0: &[f64],
        modes0: &[Mode],
    ) -> Result<Vec<f64>, SolverError> {
        let mut s = TimeStepper::build(p, theta, (t0, h), y0, modes0);
        s.advance(t0, h, false)?;
        Ok(s.state.y)
    }

    /// One step from t0 to t0 + h, keeping its start in `y_prev` and `modes_prev` if
    /// `keep_start` (the driver interpolates in it).
    #[inline(never)]
    fn advance(&mut self, t0: f64, h: f64, keep_start: bool) -> Result<(), SolverError> {
        self.begin_step(t0, h, keep_start);
        self.sweep(t0, h)?;
        self.finish_step(t0, h);
        Ok(())
    }

    /// The step's contact problem solved, from what it reads of the step's start.
    fn sweep(&mut self, t0: f64, h: f64) -> Result<(), SolverError> {
        let start = StepStart {
            theta: self.theta,
            y: &self.state.y,
            modes: &self.modes,
            force_start: &self.force_start,
            rate: &self.rate,
        };
        self.problem.sweep_to_convergence(self.p, &start, t0, h)
    }

    /// The start of a step: the known part of each body's momentum equation and the first
    /// guess of its velocity, every body waiting for the first sweep.
    #[inline]
    fn begin_step(&mut self, t0: f64, h: f64, keep_start: bool) {
        let (p, theta) = (self.p, self.theta);
        let t1 = t0 + h;
        if h != self.problem.matrix.h {
            self.problem.matrix = Matrix::new(&mut self.problem.bodies, &self.springs, h, theta);
        }
        if keep_start {
            self.y_prev.copy_from_slice(&self.state.y);
            self.modes_prev.copy_from_slice(&self.modes);
        }
        // Each controller's force, held over the step.
        for (c, u) in p.system.controllers.iter().zip(&mut self.control) {
            *u = (p.actuation(c.body, t0, &self.state.y, Some(&self.modes)))
                .expect("a controller's body has it")
                .1
                .force;
        }
        // The known part of b: m·v + h·(1−θ)·F_o(t_k) + h·θ·F_o(t_{k+1}) at zero end velocities.
        // Each body's `known` holds its springs' forces at t0 here (`finish_step` cleared it,
        // then `accumulate` added them at the end of the step before, or `TimeStepper::new`).
        let bodies = &mut self.problem.bodies;
        for f in &p.system.forces {
            bodies[self.at[f.body]].known += f.constant + f.profile.at(t0);
        }
        for (c, &u) in p.system.controllers.iter().zip(&self.control) {
            bodies[self.at[c.body]].known += u;
        }
        let (springs, ht) = (&self.springs, h * theta);
        let anchored_at = self.anchored_start.windows(2).map(|w| w[0]..w[1]);
        for (b, anchored) in bodies.iter_mut().zip(anchored_at) {
            let (x, v) = (b.x, b.v);
            b.x_hat = x + h * (1.0 - theta) * v;
            b.known = b.m * v + h * (1.0 - theta) * b.known;
            // The body's springs to anchors at its predicted position, at t1.
            for s in &springs.anchored[anchored] {
                b.known += ht * s.force(t1, (b.x_hat, 0.0)).0;
            }
            // The first guess of v': extrapolated from the last two step ends (a body that
            // was at rest at both stays there).
            b.v = 2.0 * v - b.v_last;
            b.v_last = v;
            // Every body waits for the first sweep, with no change of b yet.
            b.dirty = true;
            b.drift = 0.0;
        }
        for f in &p.system.forces {
            bodies[self.at[f.body]].known += ht * (f.constant + f.profile.at(t1));
        }
        for (c, &u) in p.system.controllers.iter().zip(&self.control) {
            bodies[self.at[c.body]].known += ht * u;
        }
        for s in &springs.pairs {
            let f = ht
                * s.force((bodies[s.a].x_hat, 0.0), (bodies[s.b].x_hat, 0.0))
                    .0;
            bodies[s.a].known += f;
            bodies[s.b].known -= f;
        }
    }

    /// Writes the end state, the modes and the energy accumulators.
    #[inline(never)]
    fn finish_step(&mut self, t0: f64, h: f64) {
        let theta = self.theta;
        for b in self.problem.bodies.iter_mut() {
            b.x = b.x_hat + h * theta * b.v;
            self.state.y[b.x_index] = b.x;
            self.state.y[b.x_index + 1] = b.v;
            // The next step's sums start from zero.
            b.known = 0.0;
        }
        // Each contact's end force and mode.
        self.switches.clear();
        let modes = self.modes.iter_mut().zip(&mut self.force_start);
        for (component, (s, (mode, force))) in self.problem.solved.iter().zip(modes).enumerate() {
            *force = s.force;
            let to = match s.direction {
                Some(Direction::Positive) => SLIP_POSITIVE,
                Some(Direction::Negative) => SLIP_NEGATIVE,
                None => STICK,
            };
            if to != *mode {
                self.switches.push(ModeSwitch {
                    component,
                    from: *mode,
                    to,
                });
                *mode = to;
            }
        }
        // Each contact's impulse's work on the mean velocity: dissipated `P·(v̄ − v_s)` and done
        // by the belt `−P·v_s`. Summed in a loop of its own: in the loop above, which may call
        // the allocator (a switch), the two sums lived on the stack, and their chain of
        // additions through memory bound the whole pass (half its samples, `perf annotate`).
        let (mut dissipated, mut belt) = (0.0, 0.0);
        let bodies = &self.problem.bodies;
        for (c, s) in self.problem.contacts.iter().zip(&self.problem.solved) {
            let mean = 0.5 * (bodies[c.at].v_last + bodies[c.at].v);
            dissipated += s.impulse * (mean - c.v_s);
            belt -= s.impulse * c.v_s;
        }
        // The internal states at the end of the step, and their rates there.
        for k in 0..self.stateful.len() {
            let j = self.stateful[k];
            let at = self.problem.contacts[j].states.clone();
            let end = self
                .problem
                .states
                .end(at.clone(), self.problem.solved[j].direction.is_some());
            self.state.y[at].copy_from_slice(end);
            self.state_rates(j);
        }
        self.accumulate(t0, h, dissipated, belt);
    }

    /// The energy accumulators: each impulse of the step from t0 to t0 + h times the mean
    /// velocity it acts on; the contacts' work, `dissipated` and `belt`, summed by the caller.
    #[inline(never)]
    fn accumulate(&mut self, t0: f64, h: f64, dissipated: f64, belt: f64) {
        let (p, theta) = (self.p, self.theta);
        let t1 = t0 + h;
        let impulse = |f0: f64, f1: f64| h * (theta * f1 + (1.0 - theta) * f0);
        let bodies = &mut self.problem.bodies;
        let mut external = 0.0;
        for f in &p.system.forces {
            let i = impulse(f.constant + f.profile.at(t0), f.constant + f.profile.at(t1));
            let b = &bodies[self.at[f.body]];
            external += i * (0.5 * (b.v_last + b.v));
        }
        for (c, &u) in p.system.controllers.iter().zip(&self.control) {
            let b = &bodies[self.at[c.body]];
            external += h * u * (0.5 * (b.v_last + b.v));
        }
        // Each spring's force at t1 is also the next step's start force: added to the
        // bodies' `known` (which `finish_step` cleared) and kept for the next accumulation.
        let damper = |c: f64, dv0: f64, dv1: f64| c * impulse(dv0, dv1) * 0.5 * (dv0 + dv1);
        for (s, start) in self.springs.anchored.iter().zip(&mut self.anchored_force) {
            let b = &mut bodies[s.body];
            let ((f0, dv0), (f1, dv1)) = (*start, s.force(t1, (b.x, b.v)));
            *start = (f1, dv1);
            b.known += f1;
            if s.c != 0.0 {
                external -= damper(s.c, dv0, dv1);
            }
            external += impulse(f0, f1) * s.v;
        }
        for (s, start) in self.springs.pairs.iter().zip(&mut self.pair_force) {
            let end = |k: usize| (bodies[k].x, bodies[k].v);
            let (dv0, (f1, dv1)) = (start.1, s.force(end(s.a), end(s.b)));
            *start = (f1, dv1);
            bodies[s.a].known += f1;
            bodies[s.b].known -= f1;
            // A spring between two bodies without a damper does no work that is not stored.
            if s.c != 0.0 {
                external -= damper(s.c, dv0, dv1);
            }
        }
        // Each controller's integral of the error, to the step's end (backward Euler).
        for (c, &k) in p.system.controllers.iter().zip(&p.layout.integral) {
            self.state.y[k] += h * c.error(t1, bodies[self.at[c.body]].x);
        }
        let a = p.layout.accumulators;
        self.state.y[a] += external;
        self.state.y[a + 1] += dissipated;
        self.state.y[a + 2] += belt;
    }
}

impl Stepper for TimeStepper<'_, '_> {
    fn name(&self) -> &'static str {
        NAME
    }

    /// Built at the run's start, where the driver starts it; it locates no event, so it is
    /// never restarted.
    fn start(&mut self, _ode: &Ode, _t: f64, _y: &[f64]) -> Result<(), SolverError> {
        Ok(())
    }

    /// Step k from t_k = t0 + k·h to t0 + (k+1)·h, the last one shortened to end at t_end (the
    /// times computed from t0, not accumulated).
    fn step(&mut self, _ode: &Ode, _t_stop: f64) -> Result<(), SolverError> {
        let k = self.taken;
        let t_k = self.t0 + k as f64 * self.h;
        let last = k + 1 >= self.n_steps;
        let (t_next, step) = match last {
            true => (self.t_end, self.t_end - t_k),
            false => (self.t0 + (k + 1) as f64 * self.h, self.h),
        };
        let inside = |g: &[f64], next: usize| next < g.len() && g[next] < t_next;
        let keep_start = self
            .grid
            .as_ref()
            .is_some_and(|g| inside(g, self.grid_next));
        self.advance(t_k, step, keep_start)?;
        if let Some(g) = &self.grid {
            self.grid_next += g[self.grid_next..].partition_point(|&t| t <= t_next);
        }
        self.state.t_prev = t_k;
        self.state.t = t_next;
        self.taken += 1;
        if !self.switches.is_empty() {
            self.switched_steps += 1;
        }
        Ok(())
    }

    fn state(&self) -> &StepperState {
        &self.state
    }

    /// The linear interpolant of the step's ends (kept for a step with an output point inside).
    fn dense_output(&self, t: f64, y: &mut [f64]) {
        let (t0, t1) = (self.state.t_prev, self.state.t);
        let s = (t - t0) / (t1 - t0);
        for ((y, a), b) in y.iter_mut().zip(&self.y_prev).zip(&self.state.y) {
            *y = a + s * (b - a);
        }
    }

    /// Gauss–Seidel sweeps as evaluations, their Newton iterations, their corrections (each a
    /// factorisation and a solve of Ŵ's pattern over the bodies, whose order and entries weigh
    /// them in the counted work), and the steps that switched a mode as events.
    fn stats(&self) -> Stats {
        let corrected = self.problem.corrections > 0;
        Stats {
            matrix_order: if corrected {
                self.problem.bodies.len()
            } else {
                0
            },
            matrix_entries: if corrected {
                self.problem.matrix.entries()
            } else {
                0
            },
            steps: self.taken,
            rhs_evals: self.problem.sweeps,
            newton_iterations: self.problem.iterations,
            lu_factorizations: self.problem.corrections,
            linear_solves: self.problem.corrections,
            events: self.switched_steps,
            ..Stats::default()
        }
    }

    fn locates_events(&self) -> bool {
        false
    }

    fn take_switches(&mut self) -> Option<EventRecord> {
        (!self.switches.is_empty()).then(|| event_record(self.state.t, self.switches.clone()))
    }

    /// Inside a step a contact is reported stuck only if it is stuck at both ends, so that a
    /// stuck contact moves with its surface exactly.
    fn modes_inside(&self, before: &[Mode], after: &[Mode], out: &mut [Mode]) {
        for ((m, &a), &b) in out.iter_mut().zip(before).zip(after) {
            *m = if b == STICK && a != STICK { a } else { b };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::contact_problem::colour_order;
    use super::super::{SWEEP_ATOL, SWEEP_RTOL};
    use super::TimeStepper;
    use crate::chain::ChainParams;
    use crate::{FrictionSystem, Switching};
    use friction_models::{FrictionParams, ModelId, Variant};
    use std::sync::Arc;

    /// Steps h = 1e-3 at θ = 1/2 from the start of `problem`, Newton's correction first tried
    /// after `correct_after` sweeps. At the end of each step Gauss–Seidel alone sweeps again
    /// every body to convergence; returns the largest change that made, in units of the
    /// sweeps' tolerance (below 1: the step ended at Gauss–Seidel's fixed point), and the
    /// sweeps and corrections spent.
    fn fixed_points(
        problem: &FrictionSystem,
        steps: usize,
        correct_after: usize,
    ) -> (f64, usize, usize) {
        let y0 = problem.initial_state();
        let modes0 = problem.initial_modes(0.0, &y0);
        let h = 1e-3;
        let mut s = TimeStepper::build(problem, 0.5, (0.0, h), &y0, &modes0);
        let mut worst = 0.0_f64;
        for k in 0..steps {
            let t = k as f64 * h;
            s.problem.correct_after = correct_after;
            s.begin_step(t, h, false);
            s.sweep(t, h).expect("the step converges");
            let (sweeps, end) = (
                s.problem.sweeps,
                s.problem.bodies.iter().map(|b| b.v).collect::<Vec<_>>(),
            );
            s.problem.correct_after = usize::MAX;
            s.problem.bodies.iter_mut().for_each(|b| b.dirty = true);
            s.sweep(t, h).expect("the step converges");
            for (b, v) in s.problem.bodies.iter().zip(end) {
                let r = (b.v - v).abs() / (SWEEP_ATOL + SWEEP_RTOL * v.abs());
                worst = worst.max(r);
            }
            s.problem.sweeps = sweeps;
            s.finish_step(t, h);
        }
        (worst, s.problem.sweeps, s.problem.corrections)
    }

    #[test]
    fn newtons_correction_takes_a_stiff_chain_to_a_fixed_point_of_gauss_seidel_in_few_sweeps() {
        // 30 Coulomb blocks joined by k_chain = 1e8 N/m: h²θ²k/m = 25, each coupling 0.49 of
        // the diagonal, over 10 s: at rest until each driver spring reaches F_c (6 s), then
        // stick–slip.
        let system = ChainParams {
            n_bodies: 30,
            k_chain: 1e8,
            ..ChainParams::default()
        }
        .build(&FrictionParams::paper(), |p| {
            ModelId::Coulomb.build(Variant::Odd, p).map(Arc::from)
        })
        .expect("a valid chain");
        let problem = FrictionSystem::new(&system, Switching::Event);
        let steps = 10_000;
        let (off, sweeps, corrections) = fixed_points(&problem, steps, super::CORRECT_AFTER);
        let (plain_off, plain, none) = fixed_points(&problem, steps, usize::MAX);
        assert_eq!(none, 0);
        // Corrected, every step ends at the fixed point to the tolerance (observed: 5e-4 of
        // it). Gauss–Seidel alone stops once a sweep changes little, which under slow
        // contraction is still far from its fixed point (observed: 21 tolerances).
        assert!(off < 1.0, "{off} tolerances from the fixed point");
        assert!(
            plain_off > 1.0,
            "{plain_off} tolerances from the fixed point alone"
        );
        // Gauss–Seidel alone: over a hundred sweeps a step once the chain slides; corrected:
        // at most one factorisation a step, under three sweeps a step on average.
        assert!(plain > 100 * steps, "{plain} sweeps alone");
        assert!(
            corrections > 0 && corrections <= steps,
            "{corrections} corrections"
        );
        assert!(sweeps < 3 * steps, "{sweeps} sweeps with corrections");
    }

    #[test]
    fn a_chain_is_visited_red_black() {
        let chain: Vec<(usize, usize)> = (0..6).map(|i| (i, i + 1)).collect();
        assert_eq!(colour_order(7, &chain), [0, 2, 4, 6, 1, 3, 5]);
    }

    #[test]
    fn no_two_coupled_bodies_share_a_colour_and_every_body_is_visited_once() {
        // A triangle, a star and a free body: three colours, then the order by colour.
        let edges = [(0, 1), (1, 2), (2, 0), (3, 4), (3, 5), (3, 6)];
        let order = colour_order(8, &edges);
        assert_eq!(order, [0, 3, 7, 1, 4, 5, 6, 2]);
        let mut sorted = order.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..8).collect::<Vec<_>>());
    }
}
