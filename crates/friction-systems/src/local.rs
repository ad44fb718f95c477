//! The one-contact problem of a Moreau–Jean step ([`crate::moreau_jean`]): one body, its
//! neighbours' velocities fixed, solved exactly.
//!
//! Unknowns: the relative velocity at the end of the step `u = v − v_s`, and the internal
//! state z of the contact's model. With `Ŵ` the body's diagonal of the iteration matrix and
//! `b` everything else of its momentum equation,
//!
//! - `Ŵ·(u + v_s) = b − P`, P the friction impulse of the step;
//! - `x = x̂ + h·θ·(u + v_s)` (x̂ the part of the end position known before the step);
//! - `z = z_k + h·(1−θ)·g_k + h·θ·g(x, u, z)`.
//!
//! At rest (u = 0) the impulse is `P = h·λ*`, `λ* = (b − Ŵ·v_s)/h`, admissible when λ* lies in
//! the model's stick interval (a projection onto a closed interval: the relay problem of one
//! contact). Sliding in direction d, `P = h·[θ_f·F_d(x, u, z) + (1−θ_f)·F_k]` with the frozen
//! law of direction d, and `R(u) = Ŵ·(u + v_s) + P − b = 0` is solved for u on the side of d by
//! Newton's method safeguarded by bisection (Press et al., *Numerical Recipes*, `rtsafe`).

use friction_models::{Direction, FrictionModel, Partials, SignLaw, StatePartials, StickInterval};
use std::fmt;

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

/// One contact's problem in one sweep.
pub(crate) struct Local<'a> {
    /// The contact's law.
    pub model: &'a dyn FrictionModel,
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
    /// End position with the body's own end velocity left out, m.
    pub x_hat: f64,
    /// Internal state at the start of the step (0 without one).
    pub z0: f64,
    /// Its rate at the start of the step.
    pub rate0: f64,
    /// Whether the model has an internal state.
    pub has_state: bool,
    /// Whether the model is a static map that ignores x and is affine in v on each side of
    /// rest ([`FrictionModel::affine_in_velocity`]): R is then linear in u and its root is
    /// one Newton step from u = 0.
    pub affine: bool,
}

/// The solution of one contact's problem.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Solved {
    /// Relative velocity at the end of the step, m/s (exactly 0 at rest).
    pub u: f64,
    /// Internal state at the end of the step.
    pub z: f64,
    /// Friction force at the end of the step, N (the holding force λ* at rest).
    pub force: f64,
    /// Friction impulse of the step, N·s.
    pub impulse: f64,
    /// Direction of sliding at the end of the step; `None` at rest.
    pub direction: Option<Direction>,
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

/// The law at one relative velocity: the end state z(u), the force, and dF/du along z(u).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Point {
    z: f64,
    force: f64,
    /// dF/du along the solution z(u) of the state equation.
    dforce: f64,
    /// dz/du along it.
    dz: f64,
    iterations: usize,
}

/// What a contact's problem keeps through the sweeps of one step: everything that does not
/// depend on b (on the neighbours' velocities), computed at the first visit; for a static map
/// that ignores x, the law at rest is kept through the whole run ([`StepCache::next_step`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct StepCache {
    /// The law at u = 0+ (index 0) and u = 0− (index 1), under the frozen sign.
    edge: [Option<Point>; 2],
    /// The stick interval and the internal state at rest.
    rest: Option<(StickInterval, f64)>,
    /// Whether each side (index as `edge`) has been visited in this step: the first visit
    /// starts Newton's iteration from the edge, a later one from the last solution.
    visited: [bool; 2],
    /// The last sliding solution: direction, weight θ_f, w = |u|, and the law there (after a
    /// linearised update, the linearised law), from which a later visit starts Newton's
    /// iteration without evaluating the law again.
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
        self.x_hat + self.h * self.theta * (u + self.v_s)
    }

    /// F, ż, the partials in x and v and those in z at (x, u, z), for a model with one
    /// internal state (the scheme takes at most one, checked by [`crate::simulate`]).
    fn law_at(&self, x: f64, u: f64, z: f64, law: SignLaw) -> (f64, f64, Partials, StatePartials) {
        let (mut rate, mut states) = ([0.0], [StatePartials::default()]);
        let (force, p) = self.model.evaluate(x, u, &[z], law, &mut rate, &mut states);
        (force, rate[0], p, states[0])
    }

    /// z(u) from the state equation and F(x(u), u, z(u)) with dF/du, under `law`.
    fn point(&self, u: f64, law: SignLaw) -> Result<Point, Unsolved> {
        let x = self.x(u);
        let ht = self.h * self.theta;
        if !self.has_state {
            let (force, p) = self.model.evaluate(x, u, &[], law, &mut [], &mut []);
            return Ok(Point {
                z: self.z0,
                force,
                dforce: p.force_dv + p.force_dx * ht,
                dz: 0.0,
                iterations: 0,
            });
        }
        // With an internal state: z(u) from the state equation by Newton's method first.
        let known = self.z0 + self.h * (1.0 - self.theta) * self.rate0;
        let (mut z, mut iterations) = (self.z0, 0);
        loop {
            let (_, rate, _, d) = self.law_at(x, u, z, law);
            let dz = (z - known - ht * rate) / (1.0 - ht * d.rate_dz);
            z -= dz;
            iterations += 1;
            if dz.abs() <= LOCAL_ROUNDOFF * z.abs() {
                break;
            }
            if !dz.is_finite() || iterations == MAX_LOCAL_ITERATIONS {
                return Err(Unsolved::State { u, update: dz });
            }
        }
        let (force, _, p, d) = self.law_at(x, u, z, law);
        let dz_du = ht * (d.rate_dv + d.rate_dx * ht) / (1.0 - ht * d.rate_dz);
        Ok(Point {
            z,
            force,
            dforce: p.force_dv + p.force_dx * ht + d.force_dz * dz_du,
            dz: dz_du,
            iterations,
        })
    }

    /// The force that holds the body at rest, λ*.
    fn holding_force(&self) -> f64 {
        (self.b - self.w * self.v_s) / self.h
    }

    /// The stick interval and the internal state at rest, computed once per step (once per
    /// run for a static map that ignores x).
    fn rest(&self, cache: &mut StepCache) -> Result<((StickInterval, f64), usize), Unsolved> {
        if let Some(rest) = cache.rest {
            return Ok((rest, 0));
        }
        let (z, iterations) = if self.has_state {
            let rest = self.point(0.0, SignLaw::Discontinuous)?;
            (rest.z, rest.iterations)
        } else {
            (self.z0, 0)
        };
        let n = usize::from(self.has_state);
        let rest = (self.model.stick_interval(self.x(0.0), &[z][..n]), z);
        cache.rest = Some(rest);
        Ok((rest, iterations))
    }

    /// Solves the problem into `out`, adding the Newton iterations spent to
    /// `out.iterations`: first, if the contact slid in `previous` (direction, force F_k)
    /// through the step before, with the θ-method on friction if it still slides that way (or
    /// either way, for a law continuous at rest: a stick interval of zero width, as LuGre's);
    /// otherwise at rest if λ* is admissible, else sliding with the impulse implicit.
    /// `u_guess` starts Newton's iteration on a visit after the first (`cache` filled).
    pub fn solve(
        &self,
        cache: &mut StepCache,
        previous: Option<(Direction, f64)>,
        u_guess: f64,
        out: &mut Solved,
    ) -> Result<(), Unsolved> {
        if let Some((d, f_k)) = previous.filter(|_| self.theta < 1.0) {
            if self.slide(cache, d, self.theta, f_k, u_guess, out)? {
                return Ok(());
            }
            let ((interval, _), n) = self.rest(cache)?;
            out.iterations += n;
            if interval.upper == interval.lower {
                let reversed = match d {
                    Direction::Positive => Direction::Negative,
                    Direction::Negative => Direction::Positive,
                };
                if self.slide(cache, reversed, self.theta, f_k, u_guess, out)? {
                    return Ok(());
                }
            }
        }
        let ((interval, z_rest), n) = self.rest(cache)?;
        out.iterations += n;
        let held = self.holding_force();
        if interval.contains(held) {
            *out = Solved {
                u: 0.0,
                z: z_rest,
                force: held,
                impulse: self.h * held,
                direction: None,
                iterations: out.iterations,
            };
            return Ok(());
        }
        let d = if held > interval.upper {
            Direction::Positive
        } else {
            Direction::Negative
        };
        if self.slide(cache, d, 1.0, 0.0, u_guess, out)? {
            Ok(())
        } else {
            Err(Unsolved::OutsideInterval {
                d,
                lower: interval.lower,
                upper: interval.upper,
            })
        }
    }

    /// The impulse of a step that ends sliding with `force` on `side`.
    fn impulse(&self, side: Sliding, force: f64) -> f64 {
        self.h * (side.theta_f * force + (1.0 - side.theta_f) * side.f_k)
    }

    /// R along `side` as a function of w = s·u ≥ 0 (increasing through its root), and dR/dw,
    /// with the law at w given by `p`.
    fn residual(&self, side: Sliding, w: f64, p: &Point) -> (f64, f64) {
        let s = side.d.sign();
        let r = self.w * (s * w + self.v_s) + self.impulse(side, p.force) - self.b;
        (s * r, self.w + self.h * side.theta_f * p.dforce)
    }

    /// The sliding solution in direction `d` with weight `theta_f` on the end force and
    /// `f_k` at the start, written into `out` if one exists on that side (`false` when R
    /// does not change sign there); the iterations spent are added to `out.iterations`
    /// either way. In closed form for an affine law, else by [`Local::newton`].
    #[inline]
    fn slide(
        &self,
        cache: &mut StepCache,
        d: Direction,
        theta_f: f64,
        f_k: f64,
        u_guess: f64,
        out: &mut Solved,
    ) -> Result<bool, Unsolved> {
        let sliding = Sliding { d, theta_f, f_k };
        let first_visit = !std::mem::replace(&mut cache.visited[side(d)], true);
        let edge = match cache.edge[side(d)] {
            Some(p) => p,
            None => {
                let p = self.point(0.0, SignLaw::Frozen(d))?;
                out.iterations += p.iterations;
                cache.edge[side(d)] = Some(p);
                p
            }
        };
        let (r0, dr0) = self.residual(sliding, 0.0, &edge);
        if r0 >= 0.0 {
            return Ok(false);
        }
        if self.affine && dr0 > 0.0 {
            // R(w) = r0 + dr0·w exactly: its root in closed form, the force on the line.
            let u = d.sign() * (-r0 / dr0);
            let force = edge.force + edge.dforce * u;
            *out = Solved {
                u,
                z: edge.z,
                force,
                impulse: self.impulse(sliding, force),
                direction: Some(d),
                iterations: out.iterations,
            };
            return Ok(true);
        }
        let guess = d.sign() * u_guess;
        let w = if !first_visit && guess > 0.0 {
            guess
        } else if dr0 > 0.0 {
            -r0 / dr0
        } else {
            (self.b / self.w - self.v_s).abs().max(f64::MIN_POSITIVE)
        };
        self.newton(cache, sliding, w, out)
    }

    /// Newton's iteration on `sliding`'s equation from w = s·u > 0 (the root lies on that
    /// side), safeguarded by bisection; a start at the last solution of the step takes the
    /// law kept there instead of evaluating it.
    fn newton(
        &self,
        cache: &mut StepCache,
        sliding: Sliding,
        mut w: f64,
        out: &mut Solved,
    ) -> Result<bool, Unsolved> {
        let Sliding { d, theta_f, .. } = sliding;
        let (law, s) = (SignLaw::Frozen(d), d.sign());
        let mut iterations = out.iterations;
        let (mut lo, mut hi) = (0.0, f64::INFINITY);
        let mut known = cache
            .last
            .filter(|&(dl, tl, wl, _)| dl == d && tl == theta_f && wl == w)
            .map(|(.., p)| p);
        for _ in 0..MAX_LOCAL_ITERATIONS {
            let p = match known.take() {
                Some(p) => p,
                None => {
                    let p = self.point(s * w, law)?;
                    iterations += p.iterations + 1;
                    p
                }
            };
            let (r, dr) = self.residual(sliding, w, &p);
            if r < 0.0 {
                lo = w;
            } else {
                hi = w;
            }
            let newton = w - r / dr;
            let step = newton - w;
            if r == 0.0 || step.abs() <= LINEAR_UPDATE * w {
                // At w itself to rounding, or one linearised Newton step from it.
                let du = if step.abs() <= LOCAL_ROUNDOFF * w {
                    0.0
                } else {
                    s * step
                };
                let at = Point {
                    z: p.z + p.dz * du,
                    force: p.force + p.dforce * du,
                    ..p
                };
                *out = Solved {
                    u: s * w + du,
                    z: at.z,
                    force: at.force,
                    impulse: self.impulse(sliding, at.force),
                    direction: Some(d),
                    iterations,
                };
                cache.last = Some((d, theta_f, s * out.u, at));
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

/// One side's sliding equation: direction d, weight θ_f of the force at the end of the step
/// and the force F_k at its start.
#[derive(Clone, Copy)]
struct Sliding {
    d: Direction,
    theta_f: f64,
    f_k: f64,
}

#[cfg(test)]
mod tests {
    use super::{Local, Solved, StepCache};
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

    fn problem(model: &dyn FrictionModel, b: f64, affine: bool) -> Local<'_> {
        Local {
            model,
            h: 1e-2,
            theta: 0.5,
            w: 2.0,
            b,
            v_s: 0.3,
            x_hat: 0.0,
            z0: 0.0,
            rate0: 0.0,
            has_state: false,
            affine,
        }
    }

    fn solve(local: &Local, previous: Option<(Direction, f64)>) -> Solved {
        let mut out = Solved {
            u: 0.0,
            z: 0.0,
            force: 0.0,
            impulse: 0.0,
            direction: None,
            iterations: 0,
        };
        local
            .solve(&mut StepCache::default(), previous, 0.0, &mut out)
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
            let closed = solve(&problem(model.as_ref(), b, true), previous);
            let newton = solve(&problem(model.as_ref(), b, false), previous);
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

    /// A holding force inside the stick interval still sticks: the closed form only replaces
    /// the sliding equation.
    #[test]
    fn an_affine_law_at_rest_sticks() {
        let model = law();
        let b = 2.0 * 0.3 + 1e-2 * 0.5;
        let s = solve(&problem(model.as_ref(), b, true), None);
        assert_eq!((s.u, s.direction), (0.0, None));
        assert!((s.force - 0.5).abs() < 1e-12);
    }
}
