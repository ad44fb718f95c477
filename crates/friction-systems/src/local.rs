//! The one-contact problem of a Moreau–Jean step ([`crate::moreau_jean`]): one body, its
//! neighbours' velocities fixed, solved exactly.
//!
//! Unknowns: the relative velocity at the end of the step `u = v − v_s`, and the internal
//! states z of the contact's model (none, one as LuGre's, or one per slip block as GMS's, each
//! state's rate depending on itself only). With `Ŵ` the body's diagonal of the iteration
//! matrix and `b` everything else of its momentum equation,
//!
//! - `Ŵ·(u + v_s) = b − P`, P the friction impulse of the step;
//! - `x = x̂ + h·θ·(u + v_s)` (x̂ the part of the end position known before the step);
//! - `z = z_k + h·(1−θ)·g_k + h·θ·g(x, u, z)`.
//!
//! At rest (u = 0) the impulse is `P = h·λ*`, `λ* = (b − Ŵ·v_s)/h`, admissible when λ* lies in
//! the model's stick interval (a projection onto a closed interval: the relay problem of one
//! contact). Sliding in direction d, `P = h·[θ_f·F_d(x, u, z) + (1−θ_f)·F_k]` with the frozen
//! law of direction d, and `R(u) = Ŵ·(u + v_s) + P − b = 0` is solved for u on the side of d by
//! Newton's method safeguarded by bisection (Press et al., *Numerical Recipes*, `rtsafe`)
//! ([`Newton`]), or, for a law affine in v that ignores x and has no state, in closed form
//! ([`Affine`]). Which of rest and sliding holds is decided once for both, by [`solve`].
//!
//! Latency: a Gauss–Seidel visit is bound by the chain of dependent operations from b (its
//! neighbours' velocities) to its new velocity, not by its instruction count, and a division
//! on that chain costs about as much as the rest of it. A quotient by something that does
//! not depend on b (h, `R'(0±)` of an affine law) is therefore written as a product with its
//! reciprocal, one rounding more, far below the sweeps' tolerance: the processor divides
//! before b is known. Measured on the 1000-block Coulomb chain (the floor bench's general
//! scheme, criterion): 1.92 s → 1.78 s, where 12 % fewer instructions elsewhere in the step
//! had changed nothing.

use friction_models::{
    Direction, FrictionModel, SignLaw, StatePartials, StickInterval, MAX_STATES,
};
use std::fmt;
use std::ops::Range;

/// Most Newton iterations of the sliding equation, or of the internal state, before the
/// step is declared unsolved.
pub(crate) const MAX_LOCAL_ITERATIONS: usize = 200;

/// Newton's iteration has converged when the update is below this many units of roundoff
/// of the unknown.
const LOCAL_ROUNDOFF: f64 = 4.0 * f64::EPSILON;

/// A Newton update below this fraction of the unknown is taken without evaluating the law
/// again: the force and state at the new point are linearised, with an error
/// `½·|F''|·Δu²` ≤ `½·|F''|·u²·1e-16`, below rounding for every law whose force varies on the
/// scale of u (a Stribeck curve varies on v_s).
const LINEAR_UPDATE: f64 = 1e-8;

/// The rounding error of a sum of `terms`, to the same [`LOCAL_ROUNDOFF`]: a residual of that
/// size is zero to rounding, and a Newton update computed from it is noise. Near rest, where
/// the unknown is far smaller than the terms of its equation (a sliding velocity of 1e-17 m/s
/// against a belt at 0.1 m/s; a bristle deflection where the state equation cancels), an update
/// relative to the unknown never falls below rounding, and this is the test that ends the
/// iteration.
fn rounding(terms: &[f64]) -> f64 {
    LOCAL_ROUNDOFF * terms.iter().map(|t| t.abs()).sum::<f64>()
}

/// The momentum equation of one body in one sweep, `Ŵ·(u + v_s) = b − P`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Momentum {
    /// Step size h, s.
    pub h: f64,
    /// θ of the smooth forces (and of the internal state).
    pub theta: f64,
    /// Diagonal of the iteration matrix Ŵ = m + h·θ·Σ(c + h·θ·k), kg.
    pub w: f64,
    /// Right-hand side b of the momentum equation with the neighbours' velocities, N·s.
    pub b: f64,
    /// Surface velocity v_s, m/s.
    pub v_s: f64,
}

impl Momentum {
    /// The force that holds the body at rest, `λ* = (b − Ŵ·v_s)/h`.
    ///
    /// Multiplied by 1/h rather than divided by h (one rounding more, far below the sweeps'
    /// tolerance): the division does not wait for b, so the processor does it before b is
    /// known, off the visit's critical path (see the module's note on latency).
    fn holding_force(&self) -> f64 {
        (self.b - self.w * self.v_s) * (1.0 / self.h)
    }

    /// The rounding error of the holding force λ* compared with a force `bound` of the law
    /// ([`rounding`] of the terms of both tests: λ* against the stick interval, and the sliding
    /// residual at rest, `h·F(0±) + Ŵ·v_s − b`).
    fn holding_rounding(&self, bound: f64) -> f64 {
        let per_h = 1.0 / self.h;
        rounding(&[self.b * per_h, self.w * self.v_s * per_h, bound])
    }

    /// The impulse `P = h·[θ_f·F + (1−θ_f)·F_k]` of a step that ends sliding with `force`.
    fn impulse(&self, sliding: Sliding, force: f64) -> f64 {
        self.h * (sliding.theta_f * force + (1.0 - sliding.theta_f) * sliding.f_k)
    }

    /// The rounding error of R at w with the law's `force` there ([`rounding`] of its terms).
    fn residual_rounding(&self, sliding: Sliding, w: f64, force: f64) -> f64 {
        let s = sliding.d.sign();
        rounding(&[
            self.w * (s * w + self.v_s),
            self.impulse(sliding, force),
            self.b,
        ])
    }

    /// R along the side of sliding as a function of w = s·u ≥ 0 (increasing through its
    /// root), and dR/dw, with the law's force and dF/du there.
    fn residual(&self, sliding: Sliding, w: f64, force: f64, dforce: f64) -> (f64, f64) {
        let s = sliding.d.sign();
        let r = self.w * (s * w + self.v_s) + self.impulse(sliding, force) - self.b;
        (s * r, self.w + self.h * sliding.theta_f * dforce)
    }
}

/// One side's sliding equation: direction d, weight θ_f of the force at the end of the step
/// and the force F_k at its start.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Sliding {
    d: Direction,
    theta_f: f64,
    f_k: f64,
}

/// One contact's problem in one sweep, for any law: the law called through
/// [`FrictionModel::evaluate`], its internal states solved with the velocity.
pub(crate) struct Local<'a> {
    /// The contact's law.
    pub model: &'a dyn FrictionModel,
    /// The body's momentum equation.
    pub eq: Momentum,
    /// End position with the body's own end velocity left out, m.
    pub x_hat: f64,
    /// Internal states at the start of the step (empty without any).
    pub z0: &'a [f64],
    /// Their rates at the start of the step.
    pub rate0: &'a [f64],
}

/// The solution of one contact's problem.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Solved {
    /// Relative velocity at the end of the step, m/s (exactly 0 at rest). (The internal
    /// states there are kept by the problem: [`StateStore`].)
    pub u: f64,
    /// Friction force at the end of the step, N (the holding force λ* at rest).
    pub force: f64,
    /// Friction impulse of the step, N·s.
    pub impulse: f64,
    /// Direction of sliding at the end of the step; `None` at rest.
    pub direction: Option<Direction>,
    /// The slope of the sliding residual at the solution, `∂R/∂u = Ŵ + h·θ_f·dF/du`: how the
    /// solution follows b, `∂u/∂b = 1/(∂R/∂u)` (0 at rest, where u does not follow b).
    pub dr_du: f64,
    /// Newton iterations spent.
    pub iterations: usize,
}

/// Why one contact's problem has no solution (formatted only when a step fails).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Unsolved {
    /// The internal state's equation did not converge at this relative velocity.
    State { u: f64, update: f64 },
    /// The sliding force at rest lies outside the stick interval, so neither rest nor
    /// sliding in direction `d` solves the problem.
    OutsideInterval {
        d: Direction,
        lower: f64,
        upper: f64,
    },
    /// The sliding residual does not change sign at any speed in direction `d`.
    NoSpeed { d: Direction },
    /// Newton's iteration in direction `d` did not converge in the bracket `[lo, hi]`.
    NoConvergence { d: Direction, lo: f64, hi: f64 },
}

impl fmt::Display for Unsolved {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Unsolved::State { u, update } => write!(
                f,
                "the internal state did not converge at v_rel = {u:e} (last update {update:e})"
            ),
            Unsolved::OutsideInterval { d, lower, upper } => write!(
                f,
                "no sliding solution in direction {d:?}: the model's sliding force at v_rel = 0 \
                 lies outside its stick interval [{lower}, {upper}]"
            ),
            Unsolved::NoSpeed { d } => {
                write!(f, "no sliding solution in direction {d:?} at any speed")
            }
            Unsolved::NoConvergence { d, lo, hi } => write!(
                f,
                "the sliding equation in direction {d:?} did not converge in \
                 {MAX_LOCAL_ITERATIONS} iterations (bracket [{lo:e}, {hi:e}] m/s)"
            ),
        }
    }
}

/// The law at one relative velocity: the force and dF/du along the solution z(u) of the
/// state equations (z(u) and dz/du themselves are written into [`StateWork`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Point {
    force: f64,
    /// dF/du along z(u).
    dforce: f64,
    iterations: usize,
}

/// Working storage of the state equations at one relative velocity, of room for
/// [`MAX_STATES`] states, the first n of them used: z(u) and dz/du, the law's rates and state
/// partials there, and each state's bracket `(lo, hi)` of its root.
pub(crate) struct StateWork {
    z: Vec<f64>,
    dz: Vec<f64>,
    rate: Vec<f64>,
    partials: Vec<StatePartials>,
    bracket: Vec<(f64, f64)>,
}

/// The contacts' internal states kept through the sweeps of a step, at their places in y:
/// at rest, and at the last sliding solution with dz/du there (from which a later visit
/// starts, and the states at the end of the step are read); and the working storage of the
/// one contact being solved.
pub(crate) struct StateStore {
    rest: Vec<f64>,
    last: Vec<f64>,
    last_dz: Vec<f64>,
    work: StateWork,
}

impl StateStore {
    /// Storage for a state vector of `dim` unknowns.
    pub fn new(dim: usize) -> StateStore {
        StateStore {
            rest: vec![0.0; dim],
            last: vec![0.0; dim],
            last_dz: vec![0.0; dim],
            work: StateWork {
                z: vec![0.0; MAX_STATES],
                dz: vec![0.0; MAX_STATES],
                rate: vec![0.0; MAX_STATES],
                partials: vec![StatePartials::default(); MAX_STATES],
                bracket: vec![(0.0, 0.0); MAX_STATES],
            },
        }
    }

    /// The states at the end of the step of the contact whose states are `at` in y, solved
    /// sliding (`sliding`) or at rest.
    pub fn end(&self, at: Range<usize>, sliding: bool) -> &[f64] {
        if sliding {
            &self.last[at]
        } else {
            &self.rest[at]
        }
    }
}

/// What a contact's problem keeps through the sweeps of one step: everything that does not
/// depend on b (on the neighbours' velocities), computed at the first visit; for a static map
/// that ignores x, the law at rest is kept through the whole run ([`StepCache::next_step`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct StepCache {
    /// The law at u = 0+ (index 0) and u = 0− (index 1), under the frozen sign.
    edge: [Option<Point>; 2],
    /// The stick interval at rest (the internal states there in [`StateStore`]).
    rest: Option<StickInterval>,
    /// Whether each side (index as `edge`) has been visited in this step: the first visit
    /// starts Newton's iteration from the edge, a later one from the last solution.
    visited: [bool; 2],
    /// The last sliding solution: direction, weight θ_f, w = |u|, and the law there (after a
    /// linearised update, the linearised law; the states in [`StateStore`]), from
    /// which a later visit starts Newton's iteration without evaluating the law again.
    last: Option<(Direction, f64, f64, Point)>,
}

impl StepCache {
    /// Forgets what belongs to the step just ended. A contact whose law is `invariant` (a
    /// static map that does not depend on x: see
    /// [`FrictionModel::depends_on_position`]) keeps its law at v_rel = 0± and its stick
    /// interval, which are then the same at every step.
    pub fn next_step(&mut self, invariant: bool) {
        self.visited = [false; 2];
        self.last = None;
        if !invariant {
            self.edge = [None; 2];
            self.rest = None;
        }
    }
}

fn side(d: Direction) -> usize {
    match d {
        Direction::Positive => 0,
        Direction::Negative => 1,
    }
}

impl Local<'_> {
    /// The end position for relative velocity u.
    fn x(&self, u: f64) -> f64 {
        self.x_hat + self.eq.h * self.eq.theta * (u + self.eq.v_s)
    }

    /// z(u) from the state equations (into `work.z`, with dz/du into `work.dz`) and
    /// F(x(u), u, z(u)) with dF/du, under `law`.
    fn point(&self, u: f64, law: SignLaw, work: &mut StateWork) -> Result<Point, Unsolved> {
        let x = self.x(u);
        let (h, theta) = (self.eq.h, self.eq.theta);
        let ht = h * theta;
        let n = self.z0.len();
        if n == 0 {
            let (force, p) = self.model.evaluate(x, u, &[], law, &mut [], &mut []);
            return Ok(Point {
                force,
                dforce: p.force_dv + p.force_dx * ht,
                iterations: 0,
            });
        }
        let (z, dz) = (&mut work.z[..n], &mut work.dz[..n]);
        let (rate, partials) = (&mut work.rate[..n], &mut work.partials[..n]);
        let bracket = &mut work.bracket[..n];
        z.copy_from_slice(self.z0);
        // The state equations G_i(z_i) = z_i − known_i − h·θ·ż_i(z_i) = 0 first, each state's
        // rate depending on itself only, all iterated together by Newton's method safeguarded
        // by bisection (`rtsafe`, as the sliding equation), each in its own bracket: a step
        // that leaves the bracket of the root, or a slope that is not positive, bisects (or,
        // with one side of the bracket still open, steps twice the residual towards it:
        // G' = 1 − h·θ·∂ż/∂z ≥ 1 for a dissipative state). An elasto-plastic law's ż has a
        // kink in z (its α), where Newton's method alone cycled (the belt at v_belt = 1 m/s
        // failed at t = 1e-3). The known parts wait in dz.
        for ((k, z0), rate0) in dz.iter_mut().zip(self.z0).zip(self.rate0) {
            *k = z0 + h * (1.0 - theta) * rate0;
        }
        bracket.fill((f64::NEG_INFINITY, f64::INFINITY));
        let mut iterations = 0;
        loop {
            self.model.evaluate(x, u, z, law, rate, partials);
            let (mut converged, mut largest) = (true, 0.0_f64);
            let rows = z.iter_mut().zip(dz.iter()).zip(rate.iter());
            for (((z, &known), &rate), (d, (lo, hi))) in
                rows.zip(partials.iter().zip(bracket.iter_mut()))
            {
                let (terms, slope) = ([*z, known, ht * rate], 1.0 - ht * d.rate_dz);
                let r = terms[0] - terms[1] - terms[2];
                if r > 0.0 {
                    *hi = *z;
                } else if r < 0.0 {
                    *lo = *z;
                }
                let mut step = r / slope;
                let newton = *z - step;
                if !(slope > 0.0 && newton > *lo && newton < *hi) && r != 0.0 {
                    let next = if lo.is_finite() && hi.is_finite() {
                        0.5 * (*lo + *hi)
                    } else {
                        *z - 2.0 * r
                    };
                    step = *z - next;
                }
                *z -= step;
                converged &= step.abs() <= LOCAL_ROUNDOFF * z.abs()
                    || step.abs() <= rounding(&terms) / slope.abs();
                if !step.is_finite() {
                    return Err(Unsolved::State { u, update: step });
                }
                largest = largest.max(step.abs());
            }
            iterations += 1;
            if converged {
                break;
            }
            if iterations == MAX_LOCAL_ITERATIONS {
                return Err(Unsolved::State { u, update: largest });
            }
        }
        let (force, p) = self.model.evaluate(x, u, z, law, rate, partials);
        let mut dforce = p.force_dv + p.force_dx * ht;
        for (dz, d) in dz.iter_mut().zip(partials.iter()) {
            *dz = ht * (d.rate_dv + d.rate_dx * ht) / (1.0 - ht * d.rate_dz);
            dforce += d.force_dz * *dz;
        }
        Ok(Point {
            force,
            dforce,
            iterations,
        })
    }
}

/// What distinguishes one law's contact problem from another's: its law at rest and the
/// solution of its sliding equation on one side. Which of them holds is decided by
/// [`solve`], the same for every law.
pub(crate) trait ContactProblem {
    /// The body's momentum equation.
    fn eq(&self) -> &Momentum;

    /// The stick interval at rest (with the internal states there, for a problem that has
    /// them), adding the Newton iterations spent to `out.iterations`.
    fn rest(&mut self, out: &mut Solved) -> Result<StickInterval, Unsolved>;

    /// The sliding solution on `sliding`'s side written into `out`, if one exists there
    /// (`false` when R does not change sign on that side); the iterations spent are added to
    /// `out.iterations` either way.
    fn slide(&mut self, sliding: Sliding, out: &mut Solved) -> Result<bool, Unsolved>;
}

/// Solves `problem` into `out`, adding the Newton iterations spent to `out.iterations`:
/// first, if the contact slid in `previous` (direction, force F_k) through the step before,
/// with the θ-method on friction if it still slides that way (or either way, for a law
/// continuous at rest: a stick interval of zero width, as LuGre's); otherwise at rest if λ*
/// is admissible, else sliding with the impulse implicit.
#[inline]
pub(crate) fn solve<P: ContactProblem>(
    problem: &mut P,
    previous: Option<(Direction, f64)>,
    out: &mut Solved,
) -> Result<(), Unsolved> {
    let theta = problem.eq().theta;
    if let Some((d, f_k)) = previous.filter(|_| theta < 1.0) {
        let sliding = Sliding {
            d,
            theta_f: theta,
            f_k,
        };
        if problem.slide(sliding, out)? {
            return Ok(());
        }
        let interval = problem.rest(out)?;
        if interval.upper == interval.lower {
            let reversed = match d {
                Direction::Positive => Direction::Negative,
                Direction::Negative => Direction::Positive,
            };
            if problem.slide(
                Sliding {
                    d: reversed,
                    ..sliding
                },
                out,
            )? {
                return Ok(());
            }
        }
    }
    let interval = problem.rest(out)?;
    let eq = *problem.eq();
    let held = eq.holding_force();
    // At rest on the surface, held there by λ*.
    let rest = |out: &mut Solved| {
        *out = Solved {
            u: 0.0,
            force: held,
            impulse: eq.h * held,
            direction: None,
            dr_du: 0.0,
            iterations: out.iterations,
        }
    };
    if interval.contains(held) {
        rest(out);
        return Ok(());
    }
    let d = if held > interval.upper {
        Direction::Positive
    } else {
        Direction::Negative
    };
    let sliding = Sliding {
        d,
        theta_f: 1.0,
        f_k: 0.0,
    };
    if problem.slide(sliding, out)? {
        return Ok(());
    }
    // No sliding solution: the sliding force at rest would hold the body. A holding force
    // outside the stick interval by no more than rounding (a law whose sliding force at rest
    // is the interval's bound, as AV's F_s + C1) leaves the body at rest on that bound.
    let bound = match d {
        Direction::Positive => interval.upper,
        Direction::Negative => interval.lower,
    };
    if (held - bound).abs() <= eq.holding_rounding(bound) {
        rest(out);
        return Ok(());
    }
    Err(Unsolved::OutsideInterval {
        d,
        lower: interval.lower,
        upper: interval.upper,
    })
}

/// A contact's problem for any law: the sliding equation by Newton's method safeguarded by
/// bisection, with what the sweeps of the step keep in `cache`; `u_guess` (the last
/// solution) starts Newton's iteration on a visit after the first.
pub(crate) struct Newton<'l, 'c> {
    /// The contact's problem.
    pub local: &'l Local<'l>,
    /// What the sweeps of the step keep.
    pub cache: &'c mut StepCache,
    /// The contact's last relative velocity.
    pub u_guess: f64,
    /// The contacts' internal states.
    pub store: &'c mut StateStore,
    /// The places of this contact's internal states in y (and in `store`).
    pub at: Range<usize>,
}

impl ContactProblem for Newton<'_, '_> {
    fn eq(&self) -> &Momentum {
        &self.local.eq
    }

    /// Computed once per step (once per run for a static map that ignores x).
    #[inline]
    fn rest(&mut self, out: &mut Solved) -> Result<StickInterval, Unsolved> {
        if let Some(interval) = self.cache.rest {
            return Ok(interval);
        }
        let (local, store, n) = (self.local, &mut *self.store, self.at.len());
        if n > 0 {
            let rest = local.point(0.0, SignLaw::Discontinuous, &mut store.work)?;
            out.iterations += rest.iterations;
            store.rest[self.at.clone()].copy_from_slice(&store.work.z[..n]);
        }
        let interval = local
            .model
            .stick_interval(local.x(0.0), &store.rest[self.at.clone()]);
        self.cache.rest = Some(interval);
        Ok(interval)
    }

    /// Newton's iteration starts from u = 0 at the first visit of the step, from `u_guess`
    /// after it; a start at the last solution of the step takes the law kept there instead
    /// of evaluating it.
    fn slide(&mut self, sliding: Sliding, out: &mut Solved) -> Result<bool, Unsolved> {
        let (local, eq) = (self.local, &self.local.eq);
        let Sliding { d, theta_f, .. } = sliding;
        let (law, s) = (SignLaw::Frozen(d), d.sign());
        let first_visit = !std::mem::replace(&mut self.cache.visited[side(d)], true);
        let edge = match self.cache.edge[side(d)] {
            Some(p) => p,
            None => {
                let p = local.point(0.0, law, &mut self.store.work)?;
                out.iterations += p.iterations;
                self.cache.edge[side(d)] = Some(p);
                p
            }
        };
        let (r0, dr0) = eq.residual(sliding, 0.0, edge.force, edge.dforce);
        if r0 >= 0.0 {
            return Ok(false);
        }
        let guess = s * self.u_guess;
        let mut w = if !first_visit && guess > 0.0 {
            guess
        } else if dr0 > 0.0 {
            -r0 / dr0
        } else {
            (eq.b / eq.w - eq.v_s).abs().max(f64::MIN_POSITIVE)
        };
        let mut iterations = out.iterations;
        let (mut lo, mut hi) = (0.0, f64::INFINITY);
        let mut known = self
            .cache
            .last
            .filter(|&(dl, tl, wl, _)| dl == d && tl == theta_f && wl == w)
            .map(|(.., p)| p);
        for _ in 0..MAX_LOCAL_ITERATIONS {
            // The law at w, and whether its states are the kept ones (else in `work`).
            let (p, kept) = match known.take() {
                Some(p) => (p, true),
                None => {
                    let p = local.point(s * w, law, &mut self.store.work)?;
                    iterations += p.iterations + 1;
                    (p, false)
                }
            };
            let (r, dr) = eq.residual(sliding, w, p.force, p.dforce);
            if r < 0.0 {
                lo = w;
            } else {
                hi = w;
            }
            let newton = w - r / dr;
            let step = newton - w;
            // The bracket closed to rounding: the root lies between neighbouring floats, where
            // R, its states solved to rounding, need not fall below its rounding estimate
            // (GMS in the presliding rig at t = 3.115 s, w = 6.4e-13 m/s).
            let closed = hi.is_finite() && hi - lo <= LOCAL_ROUNDOFF * hi;
            if r == 0.0
                || step.abs() <= LINEAR_UPDATE * w
                || r.abs() <= eq.residual_rounding(sliding, w, p.force)
                || closed
            {
                // At w itself to rounding, or one linearised Newton step from it.
                let du = if closed || step.abs() <= LOCAL_ROUNDOFF * w {
                    0.0
                } else {
                    s * step
                };
                let at = Point {
                    force: p.force + p.dforce * du,
                    ..p
                };
                if !self.at.is_empty() {
                    let (store, places) = (&mut *self.store, self.at.clone());
                    let last = &mut store.last[places.clone()];
                    let last_dz = &mut store.last_dz[places];
                    if !kept {
                        last.copy_from_slice(&store.work.z[..last.len()]);
                        last_dz.copy_from_slice(&store.work.dz[..last.len()]);
                    }
                    for (z, dz) in last.iter_mut().zip(last_dz.iter()) {
                        *z += dz * du;
                    }
                }
                *out = Solved {
                    u: s * w + du,
                    force: at.force,
                    impulse: eq.impulse(sliding, at.force),
                    direction: Some(d),
                    dr_du: dr,
                    iterations,
                };
                self.cache.last = Some((d, theta_f, s * out.u, at));
                return Ok(true);
            }
            w = if dr > 0.0 && newton > lo && newton < hi {
                newton
            } else if hi.is_finite() {
                0.5 * (lo + hi)
            } else {
                2.0 * w
            };
            if !w.is_finite() {
                return Err(Unsolved::NoSpeed { d });
            }
        }
        Err(Unsolved::NoConvergence { d, lo, hi })
    }
}

/// A law affine in v on each side of rest that ignores x and has no internal state
/// ([`FrictionModel::affine_in_velocity`], [`FrictionModel::depends_on_position`]), read
/// once per run: `F(u) = F(0±) + F'(0±)·u` in each direction, and its stick interval.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct AffineLaw {
    /// F and dF/du at u = 0+ (index 0) and u = 0− (index 1), under the frozen sign.
    edge: [(f64, f64); 2],
    interval: StickInterval,
}

/// Speeds, m/s, at which [`AffineLaw::new`] holds a law's promise to be affine against the
/// law itself, in each direction.
const AFFINE_CHECK_SPEEDS: [f64; 3] = [1e-3, 1.0, 1e3];

/// The relative distance from the line through the law at rest within which a force at
/// [`AFFINE_CHECK_SPEEDS`] keeps the promise: rounding of a few operations.
const AFFINE_CHECK_RTOL: f64 = 1e-12;

/// Positions, m, at which [`invariant_at_rest`] holds a law's promise to ignore x against
/// the law at x = 0.
const INVARIANT_CHECK_POSITIONS: [f64; 2] = [-1e3, 1e3];

/// Whether `model` is a static map whose law at rest is the same at every step: it has no
/// internal state, says it ignores x ([`FrictionModel::depends_on_position`]), and its
/// stick interval and its force and slope at v_rel = 0± are the same to the bit at x = 0 and
/// at [`INVARIANT_CHECK_POSITIONS`]. A law that breaks its promise there has its law at rest
/// evaluated at every step instead: a wrong promise costs speed, not the solution.
pub(crate) fn invariant_at_rest(model: &dyn FrictionModel) -> bool {
    if model.n_states() > 0 || model.depends_on_position() {
        return false;
    }
    let at_rest = |x| {
        let edge = [Direction::Positive, Direction::Negative]
            .map(|d| model.evaluate(x, 0.0, &[], SignLaw::Frozen(d), &mut [], &mut []));
        (model.stick_interval(x, &[]), edge)
    };
    let origin = at_rest(0.0);
    INVARIANT_CHECK_POSITIONS
        .into_iter()
        .all(|x| at_rest(x) == origin)
}

impl AffineLaw {
    /// The law of `model`, if it is one: a law whose law at rest is the same at every step
    /// ([`invariant_at_rest`]) and that says it is affine in v, whose forces at
    /// ±[`AFFINE_CHECK_SPEEDS`] lie on the line through its force and slope at rest. A law
    /// that breaks its promise there is solved by Newton's method instead: a wrong promise
    /// costs speed, not the solution.
    pub fn new(model: &dyn FrictionModel) -> Option<AffineLaw> {
        if !model.affine_in_velocity() || !invariant_at_rest(model) {
            return None;
        }
        let at = |d, u| {
            let (force, p) = model.evaluate(0.0, u, &[], SignLaw::Frozen(d), &mut [], &mut []);
            (force, p.force_dv)
        };
        let sides = [Direction::Positive, Direction::Negative];
        let edge = sides.map(|d| at(d, 0.0));
        for (d, (force0, slope)) in sides.into_iter().zip(edge) {
            for speed in AFFINE_CHECK_SPEEDS {
                let u = d.sign() * speed;
                let (line, force) = (force0 + slope * u, at(d, u).0);
                if (force - line).abs() > AFFINE_CHECK_RTOL * force.abs().max(force0.abs()) {
                    return None;
                }
            }
        }
        Some(AffineLaw {
            edge,
            interval: model.stick_interval(0.0, &[]),
        })
    }
}

/// A contact's problem for an [`AffineLaw`]: its sliding residual is linear in u,
/// `R(u) = R(0±) + R'(0±)·u`, and its root is taken in closed form, with no call of the law.
pub(crate) struct Affine<'a> {
    /// The contact's law.
    pub law: &'a AffineLaw,
    /// The body's momentum equation.
    pub eq: Momentum,
}

impl ContactProblem for Affine<'_> {
    fn eq(&self) -> &Momentum {
        &self.eq
    }

    fn rest(&mut self, _: &mut Solved) -> Result<StickInterval, Unsolved> {
        Ok(self.law.interval)
    }

    fn slide(&mut self, sliding: Sliding, out: &mut Solved) -> Result<bool, Unsolved> {
        let (force0, slope) = self.law.edge[side(sliding.d)];
        let (r0, dr0) = self.eq.residual(sliding, 0.0, force0, slope);
        if r0 >= 0.0 {
            return Ok(false);
        }
        if dr0 <= 0.0 {
            // A slope that cancels Ŵ: R stays negative on the whole side.
            return Err(Unsolved::NoSpeed { d: sliding.d });
        }
        // Times 1/R', whose division does not wait for b (the module's note on latency).
        let u = sliding.d.sign() * (-r0 * (1.0 / dr0));
        let force = force0 + slope * u;
        *out = Solved {
            u,
            force,
            impulse: self.eq.impulse(sliding, force),
            direction: Some(sliding.d),
            dr_du: dr0,
            iterations: out.iterations,
        };
        Ok(true)
    }
}

#[cfg(test)]
mod tests {
    use super::{
        invariant_at_rest, solve, Affine, AffineLaw, Local, Momentum, Newton, Solved, StateStore,
        StepCache, Unsolved,
    };
    use friction_models::{Direction, FrictionModel, FrictionParams, ModelId, SignLaw, Variant};

    /// Karnopp's law with F_c = 1 N, μ_v = 0.4 N·s/m and break-away at F_s = 7.5 N: Coulomb
    /// plus viscous friction, affine in v on each side of rest.
    fn law() -> Box<dyn FrictionModel> {
        let p = FrictionParams {
            f_c: 1.0,
            mu_v: 0.4,
            ..FrictionParams::paper()
        };
        ModelId::Karnopp.build(Variant::Odd, &p).expect("valid")
    }

    fn eq(b: f64) -> Momentum {
        Momentum {
            h: 1e-2,
            theta: 0.5,
            w: 2.0,
            b,
            v_s: 0.3,
        }
    }

    fn empty() -> Solved {
        Solved {
            u: 0.0,
            force: 0.0,
            impulse: 0.0,
            direction: None,
            dr_du: 0.0,
            iterations: 0,
        }
    }

    /// The problem of `eq` solved by Newton's method, as for any law without a state.
    fn newton(
        model: &dyn FrictionModel,
        eq: Momentum,
        previous: Option<(Direction, f64)>,
    ) -> Result<Solved, Unsolved> {
        let local = Local {
            model,
            eq,
            x_hat: 0.0,
            z0: &[],
            rate0: &[],
        };
        let mut problem = Newton {
            local: &local,
            cache: &mut StepCache::default(),
            u_guess: 0.0,
            store: &mut StateStore::new(0),
            at: 0..0,
        };
        let mut out = empty();
        solve(&mut problem, previous, &mut out).map(|()| out)
    }

    /// The problem solved by Newton's method, as for any law.
    fn by_newton(model: &dyn FrictionModel, b: f64, previous: Option<(Direction, f64)>) -> Solved {
        newton(model, eq(b), previous).expect("solvable")
    }

    /// The problem solved in closed form.
    fn closed(model: &dyn FrictionModel, b: f64, previous: Option<(Direction, f64)>) -> Solved {
        let law = AffineLaw::new(model).expect("an affine law");
        let mut out = empty();
        solve(
            &mut Affine {
                law: &law,
                eq: eq(b),
            },
            previous,
            &mut out,
        )
        .expect("solvable");
        out
    }

    /// The closed form of an affine law solves `Ŵ·(u + v_s) + P − b = 0` with the impulse
    /// of the law evaluated at its u, to rounding, and agrees with Newton's iteration (the
    /// path every other law takes) to rounding: sliding either way from rest, and keeping a
    /// direction under the θ-method on friction.
    #[test]
    fn an_affine_law_slides_in_closed_form_at_newtons_root() {
        let model = law();
        for (b, previous) in [
            (1.5, None),
            (-1.0, None),
            (1.5, Some((Direction::Positive, 1.1))),
            (-2.0, Some((Direction::Negative, -1.2))),
        ] {
            let closed = closed(model.as_ref(), b, previous);
            let newton = by_newton(model.as_ref(), b, previous);
            let d = closed.direction.expect("slides");
            let theta_f = if previous.is_some() { 0.5 } else { 1.0 };
            let f_k = previous.map_or(0.0, |p| p.1);
            let force = model.force(0.0, closed.u, &[], SignLaw::Frozen(d));
            let residual =
                2.0 * (closed.u + 0.3) + 1e-2 * (theta_f * force + (1.0 - theta_f) * f_k) - b;
            assert!(
                residual.abs() <= 4.0 * f64::EPSILON * b.abs(),
                "{b}: R = {residual:e}"
            );
            assert!((closed.force - force).abs() <= 4.0 * f64::EPSILON, "{b}");
            assert_eq!(closed.iterations, 0, "{b}: no Newton iteration");
            assert!(newton.iterations > 0, "{b}");
            assert_eq!(newton.direction, closed.direction, "{b}");
            assert!(
                (newton.u - closed.u).abs() <= 4.0 * f64::EPSILON * closed.u.abs(),
                "{b}: {} against {}",
                newton.u,
                closed.u
            );
        }
    }

    /// A holding force inside the stick interval sticks, in closed form as by Newton.
    #[test]
    fn an_affine_law_at_rest_sticks() {
        let model = law();
        let b = 2.0 * 0.3 + 1e-2 * 0.5;
        for s in [
            closed(model.as_ref(), b, None),
            by_newton(model.as_ref(), b, None),
        ] {
            assert_eq!((s.u, s.direction), (0.0, None));
            assert!((s.force - 0.5).abs() < 1e-12);
        }
    }

    /// AV's sliding force at rest is its stick interval's bound, F_s + C1 = 9 N: a holding
    /// force on that bound to rounding either way leaves the body at rest there or sliding
    /// off at a speed of rounding, never without a solution (a free body of 1 kg on a force
    /// ramp time-stepped at h = 1e-3, θ = 1 found none at t = 8.999 s until 2026-11-24).
    #[test]
    fn a_holding_force_on_the_bound_to_rounding_has_a_solution() {
        let av = ModelId::Av
            .build(Variant::Odd, &FrictionParams::paper())
            .expect("valid");
        assert_eq!(av.stick_interval(0.0, &[]).upper, 9.0);
        let h = 1e-3;
        // λ* = b/h = 9 N at b = 9·h; 64 floats either side of it.
        let mut b = 9.0 * h - 64.0 * f64::EPSILON * 9.0 * h;
        let mut at_rest = 0;
        for _ in 0..129 {
            let eq = Momentum {
                h,
                theta: 1.0,
                w: 1.0,
                b,
                v_s: 0.0,
            };
            let solved = newton(av.as_ref(), eq, None);
            assert!(solved.is_ok(), "b = {b:e}: {solved:?}");
            let s = solved.unwrap();
            match s.direction {
                None => {
                    at_rest += 1;
                    assert!((s.force - 9.0).abs() <= 1e-12, "{b:e}: {s:?}");
                }
                Some(d) => {
                    assert_eq!(d, Direction::Positive, "{b:e}");
                    assert!(s.u > 0.0 && s.u <= 1e-12, "{b:e}: {s:?}");
                }
            }
            b = b.next_up();
        }
        assert!(at_rest > 0, "some of them rest on the bound");
    }

    /// Only a law that says it is affine, ignores x and has no state is read as one.
    #[test]
    fn only_an_affine_static_map_is_an_affine_law() {
        let p = FrictionParams::paper();
        let is =
            |id: ModelId| AffineLaw::new(id.build(Variant::Odd, &p).unwrap().as_ref()).is_some();
        assert!(is(ModelId::Coulomb) && is(ModelId::Viscous) && is(ModelId::Karnopp));
        assert!(!is(ModelId::Cvs) && !is(ModelId::Dv) && !is(ModelId::LuGre));
    }

    /// Coulomb's law of 1 N plus `q·v·|v|`, with the stick interval `±(1 + creep·|x|)` N,
    /// which says it is affine in v and ignores x: each promise is broken when its
    /// coefficient is not zero.
    #[derive(Debug)]
    struct Promising {
        q: f64,
        creep: f64,
    }

    impl FrictionModel for Promising {
        fn name(&self) -> &str {
            "promising"
        }
        fn n_states(&self) -> usize {
            0
        }
        fn evaluate(
            &self,
            _x: f64,
            v: f64,
            _z: &[f64],
            law: SignLaw,
            _rate: &mut [f64],
            _states: &mut [friction_models::StatePartials],
        ) -> (f64, friction_models::Partials) {
            let partials = friction_models::Partials {
                force_dx: 0.0,
                force_dv: 2.0 * self.q * v.abs(),
            };
            (law.branches(v).sign() + self.q * v * v.abs(), partials)
        }
        fn stick_interval(&self, x: f64, _z: &[f64]) -> friction_models::StickInterval {
            let level = 1.0 + self.creep * x.abs();
            friction_models::StickInterval {
                lower: -level,
                upper: level,
            }
        }
        fn depends_on_position(&self) -> bool {
            false
        }
        fn affine_in_velocity(&self) -> bool {
            true
        }
    }

    /// A law that breaks its promise to ignore x has its law at rest evaluated at every step
    /// and is not read as an affine law; the catalog's static maps keep theirs.
    #[test]
    fn a_law_that_breaks_its_promise_to_ignore_x_is_evaluated_at_every_step() {
        let creeping = Promising {
            q: 0.0,
            creep: 1e-6,
        };
        assert!(!invariant_at_rest(&creeping));
        assert!(AffineLaw::new(&creeping).is_none());
        let p = FrictionParams::paper();
        for id in [ModelId::Coulomb, ModelId::Cvs, ModelId::Av] {
            assert!(
                invariant_at_rest(id.build(Variant::Odd, &p).unwrap().as_ref()),
                "{id:?}"
            );
        }
        assert!(!invariant_at_rest(
            ModelId::Dv.build(Variant::Odd, &p).unwrap().as_ref()
        ));
    }

    /// A law that breaks its promise to be affine is not read as one (it is then solved by
    /// Newton's method), even when its quadratic term is 1e-9 of the force at 1 m/s; without
    /// the term it is.
    #[test]
    fn a_law_that_breaks_its_affine_promise_is_not_read_as_one() {
        let law = |q| Promising { q, creep: 0.0 };
        assert!(AffineLaw::new(&law(0.0)).is_some());
        assert!(AffineLaw::new(&law(1e-9)).is_none());
        assert!(AffineLaw::new(&law(0.3)).is_none());
    }
}
