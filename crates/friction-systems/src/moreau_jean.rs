//! Moreau–Jean time-stepping (Moreau 1988; Jean 1999; Acary & Brogliato 2008, ch. 10;
//! Siconos's `MoreauJeanOSI`) for a friction [`crate::System`]: fixed steps, no event
//! located, every contact's friction impulse and mode found at the end of each step from its
//! set-valued law.
//!
//! One step from t_k to t_{k+1} = t_k + h, for every body i, with θ ∈ [1/2, 1]:
//!
//! ```text
//! m_i·(v_i' − v_i) = h·[θ·F_o,i(t_{k+1}, x', v') + (1−θ)·F_o,i(t_k, x, v)] − P_i
//! x_i'             = x_i + h·[θ·v_i' + (1−θ)·v_i]
//! z_i'             = z_i + h·[θ·g(x_i', u_i', z_i') + (1−θ)·g(x_i, u_i, z_i)]
//! ```
//!
//! with primes at t_{k+1}, `F_o` the springs, dampers and external forces, `u = v − v_s` and
//! `P_i` the friction impulse of the step. `F_o` is linear in (x, v), so eliminating x' leaves
//! one equation per body in the end velocities, `Ŵ·v' = b − P`, with
//! `Ŵ = M − h·θ·(C + h·θ·K)`: the pattern of the springs, symmetric, diagonally dominant.
//! Each contact's impulse obeys its set-valued law at the end of the step (the private module `local`):
//! at rest if the force that holds the body lies in the stick interval, otherwise sliding with
//! `P = h·F(u')`; a contact that slid the same way through the previous step and still does
//! has the θ-method on its friction too, `P = h·[θ·F(u') + (1−θ)·F(u)]` (identical for a
//! constant sliding force, as Coulomb's; second order at θ = 1/2 for a velocity-dependent one).
//!
//! The coupled problem is solved by nonsmooth Gauss–Seidel (Jean 1999; Acary & Brogliato
//! 2008, §13.4; Siconos's NSGS): each body's problem solved exactly with its neighbours'
//! velocities fixed, colour by colour (red–black on a chain: see `colour_order`), sweeping
//! until no velocity changes by more than
//! [`SWEEP_ATOL`]` + `[`SWEEP_RTOL`]`·|v|`; only the neighbours of a body that moved are
//! visited again. One sweep costs one pass over the springs and contacts: O(N) on a chain.
//! Where the coupling is stiff (h²θ²k ≳ m) Gauss–Seidel contracts slowly; after
//! [`CORRECT_AFTER`] sweeps each further sweep starts from Newton's correction of all the
//! velocities with the modes held (`correction`: a sparse symmetric solve, O(N) on a chain).
//!
//! The energy accumulators of [`crate::energy`] are the work of each step's impulses on the
//! mean velocity `(v + v')/2`; at θ = 1/2 the discrete balance then holds to rounding and to
//! the sweeps' tolerance (the scheme conserves what the system conserves; the sweeps leave
//! each body's momentum equation off by less than `Ŵ_i·(SWEEP_ATOL + SWEEP_RTOL·|v_i|)`), for
//! θ > 1/2 its residual is the scheme's own numerical dissipation. Points between step ends (a grid output) are linear interpolations.

use crate::correction::Correction;
use crate::hybrid::FrictionSystem;
use crate::local::{
    self, Affine, AffineLaw, Local, Momentum, Newton, Solved, StateStore, StepCache,
};
use crate::springs::Springs;
use crate::switching::{SLIP_NEGATIVE, SLIP_POSITIVE, STICK};
use crate::system::{System, SystemError};
use friction_models::params::show;
use friction_models::{Direction, FrictionModel, SignLaw};
use integrators::{
    EventRecord, Failure, Integrator, Mode, ModeSwitch, Ode, Options, Solution, SolverError, Stats,
    StepControl, Stepper, StepperState,
};

/// Relative change of a velocity in one sweep below which Gauss–Seidel has converged (the
/// momentum residual it leaves is a coupling, at most h²θ²k, times this: far below rounding
/// of the balance).
pub const SWEEP_RTOL: f64 = 1e-12;
/// Absolute change of a velocity in one sweep below which Gauss–Seidel has converged, m/s.
pub const SWEEP_ATOL: f64 = 1e-14;
/// Most Gauss–Seidel sweeps in one step.
pub const MAX_SWEEPS: usize = 10_000;
/// Sweeps of a step after which every further sweep starts from Newton's correction of the
/// velocities (the private module `correction`, docs/timestepping.md), as long as each
/// correction leaves the sweep after it a smaller largest change than the one before. Weakly
/// coupled bodies (h²θ²k ≪ m: the chain's defaults) converge in fewer sweeps and never pay
/// for a factorisation.
pub const CORRECT_AFTER: usize = 3;

/// The scheme's name in solutions and summaries.
pub const NAME: &str = "moreau-jean";

/// Refuses, with a clear error, a contact the scheme cannot solve: a static map that ignores
/// x (`local::invariant_at_rest`) whose sliding force at v_rel = 0± lies outside its stick
/// interval beyond rounding (CS or CVS with F_s below F_c + C1; static or Karnopp with F_s
/// below F_c): a holding force between the interval's bound and that sliding force has
/// neither rest nor sliding as a solution, and the step that meets one could only fail.
pub fn check_contacts(system: &System) -> Result<(), SystemError> {
    for (j, c) in system.contacts.iter().enumerate() {
        let model = c.model.as_ref();
        let refuse = |why: String| SystemError::Invalid {
            what: format!("[[contact]] {}", j + 1),
            why,
        };
        if !local::invariant_at_rest(model) {
            continue;
        }
        let interval = model.stick_interval(0.0, &[]);
        for d in [Direction::Positive, Direction::Negative] {
            let (force, _) = model.evaluate(0.0, 0.0, &[], SignLaw::Frozen(d), &mut [], &mut []);
            let (bound, beyond) = match d {
                Direction::Positive => (interval.upper, force > interval.upper),
                Direction::Negative => (interval.lower, force < interval.lower),
            };
            let rounding = 4.0 * f64::EPSILON * (force.abs() + bound.abs());
            if beyond && (force - bound).abs() > rounding {
                let side = if d == Direction::Positive { "0+" } else { "0-" };
                return Err(refuse(format!(
                    "model `{}`: its sliding force at v_rel = {side}, {} N, lies outside \
                     its stick interval [{}, {}] N; a holding force between them has neither \
                     rest nor sliding, so time-stepping (Moreau-Jean) needs the sliding force at \
                     rest within the stick interval: widen it (for the catalog's laws, \
                     F_s >= {}), or use --switching event or regularized",
                    model.name(),
                    show(force),
                    show(interval.lower),
                    show(interval.upper),
                    show(force.abs())
                )));
            }
        }
    }
    Ok(())
}

/// Moreau–Jean time-stepping with weight θ of the end of the step on the smooth forces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MoreauJean {
    /// θ ∈ [1/2, 1]: 1/2 the trapezoidal rule (second order, energy-conserving), 1 implicit
    /// Euler (first order, dissipative).
    pub theta: f64,
}

/// The iteration matrix `Ŵ = M − h·θ·(C + h·θ·K)` of one step size, row by row in the
/// sweep order (the bodies numbered by their place in it: see [`colour_order`]): the
/// couplings `h·θ·(c + h·θ·k)` to other bodies (its diagonal is kept with each body,
/// [`BodyStep::w`]).
struct Matrix {
    h: f64,
    start: Vec<usize>,
    coupling: Vec<(usize, f64)>,
}

impl Matrix {
    /// The matrix of `bodies` joined by `springs`, numbered alike; writes its diagonal into
    /// the bodies.
    fn new(bodies: &mut [BodyStep], springs: &Springs, h: f64, theta: f64) -> Matrix {
        for b in bodies.iter_mut() {
            b.w = b.m;
        }
        let weight = |k: f64, c: f64| h * theta * (c + h * theta * k);
        for s in &springs.anchored {
            bodies[s.body].w += weight(s.k, s.c);
        }
        let mut rows = vec![Vec::new(); bodies.len()];
        for s in &springs.pairs {
            let w = weight(s.k, s.c);
            for (me, other) in [(s.a, s.b), (s.b, s.a)] {
                bodies[me].w += w;
                rows[me].push((other, w));
            }
        }
        let mut start = vec![0];
        let mut coupling = Vec::new();
        for row in rows {
            coupling.extend(row);
            start.push(coupling.len());
        }
        Matrix { h, start, coupling }
    }

    fn row(&self, k: usize) -> &[(usize, f64)] {
        &self.coupling[self.start[k]..self.start[k + 1]]
    }
}

/// The order in which Gauss–Seidel visits `n` bodies coupled by `edges`: a greedy colouring
/// of the coupling graph (each body takes the smallest colour none of its earlier-indexed
/// neighbours has), colour after colour, ascending within a colour. The visits of one
/// colour read only velocities of other colours, so they do not wait on each other and the
/// processor overlaps them; on a chain this is the red–black order, whose Gauss–Seidel
/// converges as fast as the lexicographic one (Young 1971, consistently ordered matrices).
fn colour_order(n: usize, edges: &[(usize, usize)]) -> Vec<usize> {
    let mut neighbours = vec![Vec::new(); n];
    for &(a, b) in edges {
        neighbours[a].push(b);
        neighbours[b].push(a);
    }
    let mut colour = vec![usize::MAX; n];
    for (i, row) in neighbours.iter().enumerate() {
        let taken: Vec<usize> = row.iter().map(|&o| colour[o]).collect();
        colour[i] = (0..).find(|c| !taken.contains(c)).expect("a free colour");
    }
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by_key(|&i| colour[i]);
    order
}

/// What a contact's problem needs that does not change through the run.
struct ContactData<'p> {
    body: usize,
    /// The body's place in the sweep order.
    at: usize,
    /// Surface velocity v_s.
    v_s: f64,
    model: &'p dyn FrictionModel,
    /// The places of the internal states in y (empty for a model without any).
    states: std::ops::Range<usize>,
    /// Whether the law at rest is the same at every step ([`local::invariant_at_rest`]): its
    /// problem then keeps the law at v_rel = 0± and the stick interval from step to step.
    invariant: bool,
    /// The law read once, if it is also affine in v on each side of rest
    /// ([`FrictionModel::affine_in_velocity`]): its sliding equation is then linear.
    affine: Option<AffineLaw>,
}

/// What a step reads and writes of one body, kept together: Gauss–Seidel's visit of a body
/// touches it and its neighbours' only.
#[derive(Clone, Debug, Default)]
struct BodyStep {
    /// Mass m, and the diagonal Ŵ of the body's row of the iteration matrix, kg.
    m: f64,
    w: f64,
    /// Position at the end of the last step, m.
    x: f64,
    /// Velocity at the end of the last step, then Gauss–Seidel's iterate, m/s.
    v: f64,
    /// Velocity at the start of the step (the extrapolation's older point), m/s.
    v_last: f64,
    /// End position with the body's own end velocity left out, `x + h·(1−θ)·v`, m.
    x_hat: f64,
    /// Forces but friction at the start of the step, then the known part of b.
    known: f64,
    /// The change of b since the body's last visit, and whether it waits for a visit.
    drift: f64,
    dirty: bool,
    /// Index of x in y (v follows), and the body's contact.
    x_index: usize,
    contact: Option<usize>,
}

/// The scheme's working state between steps. The bodies are in the sweep order
/// ([`colour_order`]): body `body_of[k]` is at place k, body i at place `at[i]`.
struct TimeStepper<'p, 'a> {
    p: &'p FrictionSystem<'a>,
    theta: f64,
    body_of: Vec<usize>,
    at: Vec<usize>,
    bodies: Vec<BodyStep>,
    matrix: Matrix,
    /// The state and modes at the end of the last step.
    state: StepperState,
    modes: Vec<Mode>,
    /// The state and modes at the start of the last step, kept only for a step the driver
    /// interpolates in.
    y_prev: Vec<f64>,
    modes_prev: Vec<Mode>,
    /// Per contact: the last local solution. At the places of the internal states in y:
    /// their rates at the end of the last step.
    solved: Vec<Solved>,
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
    /// Per contact: what its problem keeps through the sweeps of the step, and its internal
    /// states.
    cache: Vec<StepCache>,
    states: StateStore,
    /// Per contact: what the run does not change.
    contacts: Vec<ContactData<'p>>,
    /// The contacts whose model has an internal state.
    stateful: Vec<usize>,
    /// The contacts whose mode the last step switched.
    switches: Vec<ModeSwitch>,
    /// Newton's correction for stiff coupling, built at its first use, and the sweeps of a
    /// step before it is first tried ([`CORRECT_AFTER`]).
    correction: Option<Correction>,
    correct_after: usize,
    sweeps: usize,
    iterations: usize,
    corrections: usize,
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
    fn new(
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
                why: "time-stepping takes a fixed step (--dt), not tolerances".into(),
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
    fn build(
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
        let mut s = TimeStepper {
            p,
            theta,
            matrix: Matrix::new(&mut bodies, &springs, h, theta),
            bodies,
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
            force_start: solved.iter().map(|s| s.force).collect(),
            cache: vec![StepCache::default(); p.system.contacts.len()],
            states: StateStore::new(y0.len()),
            contacts: p
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
                .collect(),
            solved,
            stateful: (0..l.z.len())
                .filter(|&i| !l.z[i].is_empty())
                .filter_map(|i| l.contact[i])
                .collect(),
            switches: Vec::new(),
            correction: None,
            correct_after: CORRECT_AFTER,
            body_of,
            at,
            sweeps: 0,
            iterations: 0,
            corrections: 0,
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
        let c = &self.contacts[j];
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

    /// One step from t0 to t0 + h, keeping its start in `y_prev` and `modes_prev` if
    /// `keep_start` (the driver interpolates in it).
    #[inline(never)]
    fn advance(&mut self, t0: f64, h: f64, keep_start: bool) -> Result<(), SolverError> {
        self.begin_step(t0, h, keep_start);
        self.sweep_to_convergence(t0, h)?;
        self.finish_step(t0, h);
        Ok(())
    }

    /// The start of a step: the known part of each body's momentum equation and the first
    /// guess of its velocity, every body waiting for the first sweep.
    #[inline]
    fn begin_step(&mut self, t0: f64, h: f64, keep_start: bool) {
        let (p, theta) = (self.p, self.theta);
        let t1 = t0 + h;
        if h != self.matrix.h {
            self.matrix = Matrix::new(&mut self.bodies, &self.springs, h, theta);
        }
        if keep_start {
            self.y_prev.copy_from_slice(&self.state.y);
            self.modes_prev.copy_from_slice(&self.modes);
        }
        // The known part of b: m·v + h·(1−θ)·F_o(t_k) + h·θ·F_o(t_{k+1}) at zero end velocities.
        // Each body's `known` holds its springs' forces at t0 here (`finish_step` cleared it,
        // then `accumulate` added them at the end of the step before, or `TimeStepper::new`).
        let bodies = &mut self.bodies;
        for f in &p.system.forces {
            bodies[self.at[f.body]].known += f.constant + f.profile.at(t0);
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
        for s in &springs.pairs {
            let f = ht
                * s.force((bodies[s.a].x_hat, 0.0), (bodies[s.b].x_hat, 0.0))
                    .0;
            bodies[s.a].known += f;
            bodies[s.b].known -= f;
        }
    }

    /// Nonsmooth Gauss–Seidel over the bodies until no velocity changes.
    ///
    /// Kept out of line, as are the step's other phases (`step`, `finish_step`, `accumulate`;
    /// then also a pass that listed the switches): inlined into one function they took 12 %
    /// more instructions (callgrind,
    /// 100-block chain over 50 s: 3.92e9 against 3.46e9) and about 13 % more time (paired
    /// runs on 1000 blocks), and out of line a profile names each phase.
    #[inline(never)]
    fn sweep_to_convergence(&mut self, t0: f64, h: f64) -> Result<(), SolverError> {
        let p = self.p;
        let mut pending = true;
        let mut sweeps = 0;
        // The largest change of the sweep after the last correction, and whether to go on
        // correcting.
        let (mut correcting, mut after_correction) = (true, f64::INFINITY);
        let mut largest = 0.0_f64;
        while pending {
            if sweeps == MAX_SWEEPS {
                return Err(SolverError::ContactProblem {
                    t: t0,
                    h,
                    why: format!("Gauss–Seidel did not converge in {MAX_SWEEPS} sweeps"),
                });
            }
            if correcting && sweeps > self.correct_after {
                // A correction that left a larger change than the one before ends them for the
                // step: with a law whose force drops at break-away the modes it holds can
                // cycle (Karnopp's, CVS's chain), where Gauss–Seidel alone converges.
                correcting = largest < after_correction;
                after_correction = largest;
            }
            if correcting && sweeps >= self.correct_after {
                correcting = self.correct();
            }
            // The largest change is needed only in the sweeps after a correction; not kept
            // before, it does not lengthen the visits' chain of dependent operations.
            let track = correcting && sweeps >= self.correct_after;
            sweeps += 1;
            self.sweeps += 1;
            pending = false;
            largest = 0.0;
            for i in 0..self.bodies.len() {
                let body = &mut self.bodies[i];
                if !body.dirty {
                    continue;
                }
                body.dirty = false;
                let (known, w, x_hat, contact) = (body.known, body.w, body.x_hat, body.contact);
                let row = self.matrix.row(i);
                let b = row
                    .iter()
                    .fold(known, |b, &(o, w)| b + w * self.bodies[o].v);
                let v = match contact {
                    // Times 1/Ŵ, whose division does not wait for b (as in `local`).
                    None => b * (1.0 / w),
                    Some(j) => {
                        let c = &self.contacts[j];
                        let eq = Momentum {
                            h,
                            theta: self.theta,
                            w,
                            b,
                            v_s: c.v_s,
                        };
                        // The mode the step started in (`finish_step` writes the new one).
                        let previous = match self.modes[j] {
                            SLIP_POSITIVE => Some((Direction::Positive, self.force_start[j])),
                            SLIP_NEGATIVE => Some((Direction::Negative, self.force_start[j])),
                            _ => None,
                        };
                        let solved = &mut self.solved[j];
                        solved.iterations = 0;
                        let result = match &c.affine {
                            Some(law) => local::solve(&mut Affine { law, eq }, previous, solved),
                            None => {
                                let cache = &mut self.cache[j];
                                if sweeps == 1 {
                                    // The first visit of the step (sweep 1 visits every body).
                                    cache.next_step(c.invariant);
                                }
                                let local = Local {
                                    model: c.model,
                                    eq,
                                    x_hat,
                                    z0: &self.state.y[c.states.clone()],
                                    rate0: &self.rate[c.states.clone()],
                                };
                                // The last solution is Newton's starting point.
                                let u_guess = solved.u;
                                let mut problem = Newton {
                                    local: &local,
                                    cache,
                                    u_guess,
                                    store: &mut self.states,
                                    at: c.states.clone(),
                                };
                                local::solve(&mut problem, previous, solved)
                            }
                        };
                        if let Err(why) = result {
                            return Err(SolverError::ContactProblem {
                                t: t0,
                                h,
                                why: format!(
                                    "contact {} (body \"{}\"): {why}",
                                    j + 1,
                                    p.system.bodies[self.body_of[i]].name
                                ),
                            });
                        }
                        self.iterations += solved.iterations;
                        solved.u + c.v_s
                    }
                };
                if !v.is_finite() {
                    return Err(SolverError::NonFinite {
                        t: t0,
                        h,
                        what: format!(
                            "velocity of body \"{}\"",
                            p.system.bodies[self.body_of[i]].name
                        ),
                    });
                }
                // The change reaches each neighbour's b through its coupling; the neighbour is
                // visited again once the changes since its last visit could move its own
                // velocity by more than the tolerance.
                let body = &mut self.bodies[i];
                let dv = v - body.v;
                body.v = v;
                body.drift = 0.0;
                if track {
                    largest = largest.max(dv.abs());
                }
                if dv != 0.0 {
                    for &(o, w) in row {
                        let other = &mut self.bodies[o];
                        other.drift += w * dv;
                        let tolerance = SWEEP_ATOL + SWEEP_RTOL * other.v.abs();
                        if other.drift.abs() > other.w * tolerance {
                            other.dirty = true;
                            pending = true;
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// Newton's correction of every velocity ([`crate::correction`]) from the last solution
    /// of each body's problem, with every body then waiting for a visit; `false` when there is
    /// none (a singular matrix: Gauss–Seidel goes on alone).
    #[inline(never)]
    fn correct(&mut self) -> bool {
        let matrix = &self.matrix;
        if self.correction.is_none() {
            self.correction = Correction::new(self.bodies.len(), |k| matrix.row(k)).ok();
        }
        let Some(correction) = self.correction.as_mut() else {
            return false;
        };
        let (bodies, solved) = (&self.bodies, &self.solved);
        let slope = |k: usize| match bodies[k].contact {
            None => Some(bodies[k].w),
            Some(j) => {
                let s = &solved[j];
                (s.direction.is_some() && s.dr_du > 0.0).then_some(s.dr_du)
            }
        };
        let Some(delta) = correction.solve(|k| matrix.row(k), slope, |k| bodies[k].drift) else {
            return false;
        };
        for (b, d) in self.bodies.iter_mut().zip(delta) {
            b.v += d;
            b.dirty = true;
            b.drift = 0.0;
        }
        self.corrections += 1;
        true
    }

    /// Writes the end state, the modes and the energy accumulators.
    #[inline(never)]
    fn finish_step(&mut self, t0: f64, h: f64) {
        let theta = self.theta;
        for b in self.bodies.iter_mut() {
            b.x = b.x_hat + h * theta * b.v;
            self.state.y[b.x_index] = b.x;
            self.state.y[b.x_index + 1] = b.v;
            // The next step's sums start from zero.
            b.known = 0.0;
        }
        // Each contact's end force and mode.
        self.switches.clear();
        let modes = self.modes.iter_mut().zip(&mut self.force_start);
        for (component, (s, (mode, force))) in self.solved.iter().zip(modes).enumerate() {
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
        let bodies = &self.bodies;
        for (c, s) in self.contacts.iter().zip(&self.solved) {
            let mean = 0.5 * (bodies[c.at].v_last + bodies[c.at].v);
            dissipated += s.impulse * (mean - c.v_s);
            belt -= s.impulse * c.v_s;
        }
        // The internal states at the end of the step, and their rates there.
        for k in 0..self.stateful.len() {
            let j = self.stateful[k];
            let at = self.contacts[j].states.clone();
            let end = self
                .states
                .end(at.clone(), self.solved[j].direction.is_some());
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
        let bodies = &mut self.bodies;
        let mut external = 0.0;
        for f in &p.system.forces {
            let i = impulse(f.constant + f.profile.at(t0), f.constant + f.profile.at(t1));
            let b = &bodies[self.at[f.body]];
            external += i * (0.5 * (b.v_last + b.v));
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

    /// Gauss–Seidel sweeps as evaluations, their Newton iterations and corrections, and the
    /// steps that switched a mode as events.
    fn stats(&self) -> Stats {
        Stats {
            steps: self.taken,
            rhs_evals: self.sweeps,
            newton_iterations: self.iterations,
            lu_factorizations: self.corrections,
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

impl MoreauJean {
    /// The allowed range of θ, as messages print it.
    pub const THETA_RANGE: &'static str = "[0.5, 1]";

    /// Integrates `problem` (built with [`Switching::Event`](crate::Switching)'s modes, as
    /// [`crate::Scheme::TimeStepping`] builds it) from `y0` in `modes0` with the fixed step
    /// of `options`, telling `observe` the time after every step but the last. The steps run on
    /// the driver of every method ([`Integrator`]: its step cap, time limit, interrupt and
    /// output), which locates no event for this method: it settles each contact's mode at the
    /// end of every step (`TimeStepper`). A failure keeps everything recorded before it.
    pub fn solve(
        &self,
        problem: &FrictionSystem,
        y0: &[f64],
        modes0: &[Mode],
        options: &Options,
        observe: &mut dyn FnMut(f64),
    ) -> Result<Solution, Failure> {
        let failed = |error| Failure {
            error,
            solution: Box::new(Solution::new(NAME, y0.len(), modes0.len())),
        };
        let stepper = TimeStepper::new(problem, self.theta, options, y0, modes0).map_err(failed)?;
        Integrator::new(problem, Box::new(stepper), y0, modes0, options.clone())
            .map_err(failed)?
            .solve_observed(observe)
    }
}

/// A step's switches as an event record with the names of event switching: `v_rel=0` for a
/// contact that came to rest or reversed, `break-away±` for one that left rest.
fn event_record(t: f64, switches: Vec<ModeSwitch>) -> EventRecord {
    let (fired, names) = switches
        .iter()
        .map(|s| match (s.from, s.to) {
            (STICK, SLIP_NEGATIVE) => (2 * s.component + 1, "break-away-"),
            (STICK, _) => (2 * s.component, "break-away+"),
            _ => (2 * s.component, "v_rel=0"),
        })
        .unzip();
    EventRecord {
        t,
        fired,
        names,
        switches,
    }
}

#[cfg(test)]
mod tests {
    use super::{colour_order, TimeStepper, SWEEP_ATOL, SWEEP_RTOL};
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
            s.correct_after = correct_after;
            s.begin_step(t, h, false);
            s.sweep_to_convergence(t, h).expect("the step converges");
            let (sweeps, end) = (s.sweeps, s.bodies.iter().map(|b| b.v).collect::<Vec<_>>());
            s.correct_after = usize::MAX;
            s.bodies.iter_mut().for_each(|b| b.dirty = true);
            s.sweep_to_convergence(t, h).expect("the step converges");
            for (b, v) in s.bodies.iter().zip(end) {
                let r = (b.v - v).abs() / (SWEEP_ATOL + SWEEP_RTOL * v.abs());
                worst = worst.max(r);
            }
            s.sweeps = sweeps;
            s.finish_step(t, h);
        }
        (worst, s.sweeps, s.corrections)
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
