//! The contact problem of one Moreau–Jean step: every body's momentum equation
//! `Ŵ·v' = b − P` with each contact's impulse `P` on its set-valued law (`crate::local`),
//! coupled through the iteration matrix `Ŵ`, and solved by nonsmooth Gauss–Seidel in a
//! colouring order, with Newton's correction where the coupling is stiff
//! (`crate::correction`). The step that poses it and reads its solution is
//! [`super::step`].

use super::{MAX_SWEEPS, SWEEP_ATOL, SWEEP_RTOL};
use crate::correction::Correction;
use crate::hybrid::FrictionSystem;
use crate::local::{
    self, Affine, AffineLaw, Local, Momentum, Newton, Solved, StateStore, StepCache,
};
use crate::springs::Springs;
use crate::switching::{SLIP_NEGATIVE, SLIP_POSITIVE};
use friction_models::{Direction, FrictionModel};
use integrators::{Mode, SolverError};

/// The iteration matrix `Ŵ = M − h·θ·(C + h·θ·K)` of one step size, row by row in the
/// sweep order (the bodies numbered by their place in it: see [`colour_order`]): the
/// couplings `h·θ·(c + h·θ·k)` to other bodies (its diagonal is kept with each body,
/// [`BodyStep::w`]).
pub(super) struct Matrix {
    pub(super) h: f64,
    start: Vec<usize>,
    coupling: Vec<(usize, f64)>,
}

impl Matrix {
    /// The matrix of `bodies` joined by `springs`, numbered alike; writes its diagonal into
    /// the bodies.
    pub(super) fn new(bodies: &mut [BodyStep], springs: &Springs, h: f64, theta: f64) -> Matrix {
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

    pub(super) fn row(&self, k: usize) -> &[(usize, f64)] {
        &self.coupling[self.start[k]..self.start[k + 1]]
    }
    /// Its stored entries: the diagonal and the couplings.
    pub(super) fn entries(&self) -> usize {
        self.start.len() - 1 + self.coupling.len()
    }
}

/// The order in which Gauss–Seidel visits `n` bodies coupled by `edges`: a greedy colouring
/// of the coupling graph (each body takes the smallest colour none of its earlier-indexed
/// neighbours has), colour after colour, ascending within a colour. The visits of one
/// colour read only velocities of other colours, so they do not wait on each other and the
/// processor overlaps them; on a chain this is the red–black order, whose Gauss–Seidel
/// converges as fast as the lexicographic one (Young 1971, consistently ordered matrices).
pub(super) fn colour_order(n: usize, edges: &[(usize, usize)]) -> Vec<usize> {
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
pub(super) struct ContactData<'p> {
    pub(super) body: usize,
    /// The body's place in the sweep order.
    pub(super) at: usize,
    /// Surface velocity v_s.
    pub(super) v_s: f64,
    pub(super) model: &'p dyn FrictionModel,
    /// The places of the internal states in y (empty for a model without any).
    pub(super) states: std::ops::Range<usize>,
    /// Whether the law at rest is the same at every step ([`local::invariant_at_rest`]): its
    /// problem then keeps the law at v_rel = 0± and the stick interval from step to step.
    pub(super) invariant: bool,
    /// The law read once, if it is also affine in v on each side of rest
    /// ([`FrictionModel::affine_in_velocity`]): its sliding equation is then linear.
    pub(super) affine: Option<AffineLaw>,
}

/// What a step reads and writes of one body, kept together: Gauss–Seidel's visit of a body
/// touches it and its neighbours' only.
#[derive(Clone, Debug, Default)]
pub(super) struct BodyStep {
    /// Mass m, and the diagonal Ŵ of the body's row of the iteration matrix, kg.
    pub(super) m: f64,
    pub(super) w: f64,
    /// Position at the end of the last step, m.
    pub(super) x: f64,
    /// Velocity at the end of the last step, then Gauss–Seidel's iterate, m/s.
    pub(super) v: f64,
    /// Velocity at the start of the step (the extrapolation's older point), m/s.
    pub(super) v_last: f64,
    /// End position with the body's own end velocity left out, `x + h·(1−θ)·v`, m.
    pub(super) x_hat: f64,
    /// Forces but friction at the start of the step, then the known part of b.
    pub(super) known: f64,
    /// The change of b since the body's last visit, and whether it waits for a visit.
    pub(super) drift: f64,
    pub(super) dirty: bool,
    /// Index of x in y (v follows), and the body's contact.
    pub(super) x_index: usize,
    pub(super) contact: Option<usize>,
}

/// What the contact problem of a step reads of the step's start.
pub(super) struct StepStart<'s> {
    /// θ of the scheme.
    pub(super) theta: f64,
    /// The state at the start of the step (the contacts' internal states in it).
    pub(super) y: &'s [f64],
    /// The modes at the start of the step.
    pub(super) modes: &'s [Mode],
    /// Per contact: its friction force at the start of the step.
    pub(super) force_start: &'s [f64],
    /// At the places of the internal states in y: their rates at the start of the step.
    pub(super) rate: &'s [f64],
}

/// The bodies and contacts of the coupled problem, in the sweep order ([`colour_order`]:
/// body `body_of[k]` is at place k), with what the sweeps keep between steps and their counts.
pub(super) struct ContactProblem<'p> {
    pub(super) body_of: Vec<usize>,
    pub(super) bodies: Vec<BodyStep>,
    pub(super) matrix: Matrix,
    /// Per contact: the last local solution.
    pub(super) solved: Vec<Solved>,
    /// Per contact: what its problem keeps through the sweeps of the step, and its internal
    /// states.
    pub(super) cache: Vec<StepCache>,
    pub(super) states: StateStore,
    /// Per contact: what the run does not change.
    pub(super) contacts: Vec<ContactData<'p>>,
    /// Newton's correction for stiff coupling, built at its first use, and the sweeps of a
    /// step before it is first tried ([`super::CORRECT_AFTER`]).
    pub(super) correction: Option<Correction>,
    pub(super) correct_after: usize,
    /// Gauss–Seidel sweeps, local Newton iterations and corrections, over the run.
    pub(super) sweeps: usize,
    pub(super) iterations: usize,
    pub(super) corrections: usize,
}

impl ContactProblem<'_> {
    /// Nonsmooth Gauss–Seidel over the bodies until no velocity changes.
    ///
    /// Kept out of line, as are the step's other phases (`step`, `finish_step`, `accumulate`;
    /// then also a pass that listed the switches): inlined into one function they took 12 %
    /// more instructions (callgrind,
    /// 100-block chain over 50 s: 3.92e9 against 3.46e9) and about 13 % more time (paired
    /// runs on 1000 blocks), and out of line a profile names each phase.
    #[inline(never)]
    pub(super) fn sweep_to_convergence(
        &mut self,
        p: &FrictionSystem,
        start: &StepStart,
        t0: f64,
        h: f64,
    ) -> Result<(), SolverError> {
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
                            theta: start.theta,
                            w,
                            b,
                            v_s: c.v_s,
                        };
                        // The mode the step started in (`finish_step` writes the new one).
                        let previous = match start.modes[j] {
                            SLIP_POSITIVE => Some((Direction::Positive, start.force_start[j])),
                            SLIP_NEGATIVE => Some((Direction::Negative, start.force_start[j])),
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
                                    z0: &start.y[c.states.clone()],
                                    rate0: &start.rate[c.states.clone()],
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
    pub(super) fn correct(&mut self) -> bool {
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
}
