//! A [`System`] as a hybrid [`OdeProblem`]: one mode per contact, two event functions per
//! contact, the energy accumulators integrated with the state.
//!
//! Per body i with contact j (surface velocity `v_s`, relative velocity `v_rel = v_i − v_s`):
//!
//! - the force on the body from everything but friction, `F_o,i(t, y) = F_ext,i(t) +
//!   Σ_springs k·(x_other − x_i) + c·(v_other − v_i) + u_i`, is explicit in (t, y), because
//!   every coupling is a spring or a damper and a controller's force `u_i` reads the body's
//!   state and the integral of its error, which is in y ([`crate::control`]);
//! - `slip±`: `m_i·v̇_i = F_o,i − F(x_i, v_rel, z_i)` with the direction of sign(v_rel)
//!   frozen; event g_{2j} = v_rel, watched falling (slip+) or rising (slip−);
//! - `stick`: `ẋ_i = v_s`, `v̇_i = 0`, `ż_i = 0`, friction = `F_o,i` (the force that holds the
//!   body); events `g_{2j} = F_upper − F_o,i` and `g_{2j+1} = F_o,i − F_lower`, both watched
//!   falling, with `[F_lower, F_upper]` the model's stick interval;
//! - at v_rel = 0 the contact sticks if `F_o,i` lies inside a stick interval of positive
//!   width, and otherwise slides in the direction of `F_o,i`.
//!
//! Contacts whose events fire at one instant are switched in one call: first every arriving
//! body is put exactly on its surface velocity, then each contact's new mode is decided from
//! forces that already see all of them.

use crate::control::Actuation;
use crate::layout::Layout;
use crate::local;
use crate::springs::{Sorted, Springs};
use crate::switching::{mode_of_velocity, Switching, SLIP_NEGATIVE, SLIP_POSITIVE, STICK};
use crate::system::{End, System};
use friction_models::{
    Direction, FrictionModel, SignLaw, StatePartials, StickInterval, MAX_STATES,
};
use integrators::{Control, Crossing, Entry, EventSpec, Mode, OdeProblem};
use std::ops::Range;

const SLIP_POSITIVE_EVENT: EventSpec = EventSpec {
    name: "v_rel=0",
    crossing: Crossing::Falling,
};
const SLIP_NEGATIVE_EVENT: EventSpec = EventSpec {
    name: "v_rel=0",
    crossing: Crossing::Rising,
};
const BREAK_AWAY_POSITIVE: EventSpec = EventSpec {
    name: "break-away+",
    crossing: Crossing::Falling,
};
const BREAK_AWAY_NEGATIVE: EventSpec = EventSpec {
    name: "break-away-",
    crossing: Crossing::Falling,
};

/// How far ahead, in time scales of the problem ([`OdeProblem::time_scale`], its shortest
/// natural period; seconds without one), [`FrictionSystem::mode_at`] looks at the other forces
/// to break a tie: short against any change of a driver or profile, long against rounding of
/// t.
pub const TIE_LOOKAHEAD: f64 = 1e-6;

/// A system with a treatment of v_rel = 0, ready for any solver.
pub struct FrictionSystem<'a> {
    /// The system.
    pub system: &'a System,
    /// Where every unknown lives.
    pub layout: Layout,
    /// The treatment of v_rel = 0.
    pub switching: Switching,
    /// The springs sorted by their ends.
    pub(crate) springs: Springs,
    /// The springs at each body, in the declared order.
    springs_at: Vec<Vec<Sorted>>,
    /// The external forces on each body, by index.
    forces_at: Vec<Vec<usize>>,
    /// Each contact's stick interval, for a law whose law at rest is the same at every step
    /// (`local::invariant_at_rest`: no state, and x ignored), read once: a stuck contact's
    /// two event functions read it at every evaluation.
    rest: Vec<Option<StickInterval>>,
    /// What the right-hand side reads of each body, gathered once.
    bodies_at: Vec<BodyAt<'a>>,
    /// The place in y of each spring to an anchor's body (its x; v follows), in the order of
    /// `springs.anchored`.
    anchored_x: Vec<usize>,
    /// The places in y of each spring's two bodies, in the order of `springs.pairs`.
    pairs_x: Vec<(usize, usize)>,
    /// The controller of each body, by index.
    controller_at: Vec<Option<usize>>,
    /// The sign law a friction compensation reads: tanh(v/ε) where the contacts are
    /// regularised, sign(0) = 0 otherwise.
    compensation_law: SignLaw,
}

/// What the right-hand side reads of one body, gathered once instead of looked up through
/// the system and the layout at every evaluation: where its x is in y (v follows), its mass
/// and its contact.
struct BodyAt<'a> {
    x: usize,
    m: f64,
    contact: Option<ContactAt<'a>>,
}

/// What the right-hand side reads of one contact: its index, its law, the surface velocity
/// and the places of its internal states in y.
struct ContactAt<'a> {
    j: usize,
    model: &'a dyn FrictionModel,
    v_s: f64,
    z: Range<usize>,
}

impl<'a> FrictionSystem<'a> {
    /// The problem of `system` (which must be valid) under `switching`.
    pub fn new(system: &'a System, switching: Switching) -> Self {
        let mut forces_at = vec![Vec::new(); system.bodies.len()];
        for (f, force) in system.forces.iter().enumerate() {
            forces_at[force.body].push(f);
        }
        let (springs, springs_at) = Springs::of(system);
        let rest = system
            .contacts
            .iter()
            .map(|c| {
                let model = c.model.as_ref();
                local::invariant_at_rest(model).then(|| model.stick_interval(0.0, &[]))
            })
            .collect();
        let layout = Layout::of(system);
        let bodies_at = system
            .bodies
            .iter()
            .enumerate()
            .map(|(i, body)| BodyAt {
                x: layout.x[i],
                m: body.m,
                contact: layout.contact[i].map(|j| {
                    let c = &system.contacts[j];
                    ContactAt {
                        j,
                        model: c.model.as_ref(),
                        v_s: c.surface_velocity,
                        z: layout.z[i].clone(),
                    }
                }),
            })
            .collect();
        let anchored_x = springs.anchored.iter().map(|s| layout.x[s.body]).collect();
        let pairs_x = springs
            .pairs
            .iter()
            .map(|s| (layout.x[s.a], layout.x[s.b]))
            .collect();
        let mut controller_at = vec![None; system.bodies.len()];
        for (k, c) in system.controllers.iter().enumerate() {
            controller_at[c.body] = Some(k);
        }
        let compensation_law = match switching {
            Switching::Regularized { epsilon } => SignLaw::Smooth { epsilon },
            Switching::Event | Switching::Naive => SignLaw::Discontinuous,
        };
        FrictionSystem {
            system,
            layout,
            switching,
            springs,
            springs_at,
            forces_at,
            rest,
            bodies_at,
            anchored_x,
            pairs_x,
            controller_at,
            compensation_law,
        }
    }

    /// The force of body `i`'s controller at (t, y) with its partials, and the controller's
    /// index; `None` for a body without one. A compensation at the measured velocity reads
    /// sign(v_rel) as the body's contact does in `modes` (the direction of its slip mode,
    /// which holds at v_rel = 0 too); without modes, or sticking, sign(0) = 0.
    pub fn actuation(
        &self,
        i: usize,
        t: f64,
        y: &[f64],
        modes: Option<&[Mode]>,
    ) -> Option<(usize, Actuation)> {
        let k = self.controller_at[i]?;
        let b = &self.bodies_at[i];
        let law = match (modes, &b.contact) {
            (Some(modes), Some(c)) if self.switching.has_modes() && modes[c.j] != STICK => {
                self.switching.law(modes[c.j])
            }
            _ => self.compensation_law,
        };
        let v_s = b.contact.as_ref().map_or(0.0, |c| c.v_s);
        let (x, v) = (y[b.x], y[b.x + 1]);
        let integral = y[self.layout.integral[k]];
        let c = &self.system.controllers[k];
        Some((k, c.actuation(t, (x, v), integral, v - v_s, law)))
    }

    /// The force on body `i` from everything but friction, `F_o,i(t, y)`.
    pub fn other_force(&self, i: usize, t: f64, y: &[f64]) -> f64 {
        let mut f: f64 = self.forces_at[i]
            .iter()
            .map(|&g| {
                let g = &self.system.forces[g];
                g.constant + g.profile.at(t)
            })
            .sum();
        if let Some((_, a)) = self.actuation(i, t, y, None) {
            f += a.force;
        }
        let state = |x: usize| (y[x], y[x + 1]);
        for &s in &self.springs_at[i] {
            f += match s {
                Sorted::Anchored(s) => {
                    self.springs.anchored[s]
                        .force(t, state(self.anchored_x[s]))
                        .0
                }
                Sorted::Pair(k) => {
                    let (s, (xa, xb)) = (&self.springs.pairs[k], self.pairs_x[k]);
                    let force = s.force(state(xa), state(xb)).0;
                    if s.a == i {
                        force
                    } else {
                        -force
                    }
                }
            };
        }
        f
    }

    /// Every force but friction at (t, y) in `modes`, handed to `add(v, force)` term by term
    /// with `v` the place in y of the body's velocity (the external forces, the controllers',
    /// then each spring and damper on each of its body ends); returns the power of those forces
    /// that is not stored in the springs, `Σ F_ext,i·v_i + Σ u_i·v_i + Σ anchor power −
    /// Σ c·Δv²`.
    pub(crate) fn applied_forces(
        &self,
        t: f64,
        y: &[f64],
        modes: &[Mode],
        mut add: impl FnMut(usize, f64),
    ) -> f64 {
        let mut external = 0.0;
        for f in &self.system.forces {
            let force = f.constant + f.profile.at(t);
            let v = self.bodies_at[f.body].x + 1;
            add(v, force);
            external += force * y[v];
        }
        for c in &self.system.controllers {
            let (_, a) =
                (self.actuation(c.body, t, y, Some(modes))).expect("a controller's body has it");
            let v = self.bodies_at[c.body].x + 1;
            add(v, a.force);
            external += a.force * y[v];
        }
        // The springs to anchors, then the pairs (at a body whose springs to anchors are
        // declared before its pairs, as in the chain, in the declared order); an anchor's
        // power `−F_anchor·v_anchor` is `F_body·v_anchor`.
        let state = |x: usize| (y[x], y[x + 1]);
        for (s, &x) in self.springs.anchored.iter().zip(&self.anchored_x) {
            let (force, dv) = s.force(t, state(x));
            external -= s.c * dv * dv;
            add(x + 1, force);
            external += force * s.v;
        }
        for (s, &(xa, xb)) in self.springs.pairs.iter().zip(&self.pairs_x) {
            let (force, dv) = s.force(state(xa), state(xb));
            external -= s.c * dv * dv;
            add(xa + 1, force);
            add(xb + 1, -force);
        }
        external
    }

    /// Whether contact `j`'s law at rest is the same at every step
    /// (`local::invariant_at_rest`), as read once when the problem was made.
    pub(crate) fn invariant_at_rest(&self, j: usize) -> bool {
        self.rest[j].is_some()
    }

    /// The admissible friction forces of contact `j` at rest, in state y.
    pub fn stick_interval(&self, j: usize, y: &[f64]) -> StickInterval {
        if let Some(interval) = self.rest[j] {
            return interval;
        }
        let c = &self.system.contacts[j];
        c.model
            .stick_interval(y[self.layout.x[c.body]], self.layout.states(c.body, y))
    }

    /// Friction force of contact `c` of a body at `(x, v)` with internal states `z`, in
    /// `mode`, given the other forces `other` on the body; writes the rates of its internal
    /// states into `rate` (zero while it sticks).
    fn contact_force(
        &self,
        c: &ContactAt,
        (x, v): (f64, f64),
        z: &[f64],
        mode: Mode,
        other: f64,
        rate: &mut [f64],
    ) -> f64 {
        let v_rel = v - c.v_s;
        match self.switching {
            s if s.has_modes() && mode == STICK => {
                rate.fill(0.0);
                return other;
            }
            Switching::Naive if v_rel == 0.0 || v_rel.abs() < c.model.stick_band() => {
                rate.fill(0.0);
                return c.model.stick_interval(x, z).clamp(other);
            }
            _ => {}
        }
        c.model
            .response(x, v_rel, z, self.switching.law(mode), rate)
    }

    /// The friction force of contact `j` at (t, y) in `modes`, as the right-hand side uses it.
    pub fn friction(&self, j: usize, t: f64, y: &[f64], modes: &[Mode]) -> f64 {
        let body = self.system.contacts[j].body;
        let b = &self.bodies_at[body];
        let c = b.contact.as_ref().expect("a contact's body has it");
        let other = self.other_force(body, t, y);
        let rate = &mut [0.0; MAX_STATES][..c.z.len()];
        self.contact_force(
            c,
            (y[b.x], y[b.x + 1]),
            &y[c.z.clone()],
            modes[j],
            other,
            rate,
        )
    }

    /// The mode contact `j` is in at (t, y): by the sign of v_rel, and at v_rel = 0 by the
    /// stick law. At a tie (the other forces exactly on the bound of a stick interval of zero
    /// width), the direction they are heading decides, read [`TIE_LOOKAHEAD`] time scales
    /// later with the state held, or where that still ties, with the whole system integrated
    /// over that time (docs/solvers.md, "A tie at rest").
    pub fn mode_at(&self, j: usize, t: f64, y: &[f64]) -> Mode {
        self.first_mode(j, t, y).unwrap_or_else(|| {
            let modes = self.first_modes(t, y);
            self.ties_by_motion(&[j], t, y, &modes)[0]
        })
    }

    /// The mode contact `j` is in at (t, y) by the forces there: by the sign of v_rel, and at
    /// v_rel = 0 by the stick law. At a tie, the other forces exactly on the bound of a stick
    /// interval of zero width (a law continuous at rest, as LuGre's, with no force on the body:
    /// every block of a chain at t = 0), the direction they are heading decides: the other
    /// forces [`TIE_LOOKAHEAD`] time scales later, the state held (an anchor driven at a speed,
    /// a force profile). `None` where the tie holds even then: the force reaches the body
    /// only through other bodies, which have yet to move.
    fn first_mode(&self, j: usize, t: f64, y: &[f64]) -> Option<Mode> {
        let c = &self.system.contacts[j];
        let v_rel = y[self.layout.v(c.body)] - c.surface_velocity;
        match Direction::of(v_rel) {
            Some(Direction::Positive) => Some(SLIP_POSITIVE),
            Some(Direction::Negative) => Some(SLIP_NEGATIVE),
            None => {
                let s = self.stick_interval(j, y);
                let mut f = self.other_force(c.body, t, y);
                if s.upper == s.lower && f == s.upper {
                    f = self.other_force(c.body, self.tie_horizon(t), y);
                    if f == s.upper {
                        return None;
                    }
                }
                Some(if s.upper > s.lower && s.contains(f) {
                    STICK
                } else if f > s.upper {
                    SLIP_POSITIVE
                } else {
                    SLIP_NEGATIVE
                })
            }
        }
    }

    /// Every contact's [`FrictionSystem::first_mode`] at (t, y), a tie held at rest (stick).
    fn first_modes(&self, t: f64, y: &[f64]) -> Vec<Mode> {
        (0..self.system.contacts.len())
            .map(|k| self.first_mode(k, t, y).unwrap_or(STICK))
            .collect()
    }

    /// The time [`TIE_LOOKAHEAD`] time scales after t (seconds without a time scale).
    fn tie_horizon(&self, t: f64) -> f64 {
        t + TIE_LOOKAHEAD * self.time_scale().unwrap_or(1.0)
    }

    /// The modes of the tied contacts `tied` at (t, y), decided by the motion: the whole system
    /// integrated over [`TIE_LOOKAHEAD`] time scales in `modes` (four RK4 steps), every tied
    /// contact held at rest, and each decided by the other forces on its body then. So a body
    /// pushed only through a neighbour that has yet to move (the far one of two masses, the
    /// near one pulled by a driver) slides the way it will be pushed; it once started sliding
    /// backwards, and an implicit solver that located the arrival at v = 0 with t ≈ 1e-18 kept
    /// it so for the whole run. A tie that holds even then slides backwards, as before.
    fn ties_by_motion(&self, tied: &[usize], t: f64, y: &[f64], modes: &[Mode]) -> Vec<Mode> {
        let mut held = modes.to_vec();
        for &j in tied {
            held[j] = STICK;
        }
        let later = self.tie_horizon(t);
        let ahead = self.advanced(t, y, later - t, &held);
        tied.iter()
            .map(|&j| {
                let s = self.stick_interval(j, &ahead);
                let f = self.other_force(self.system.contacts[j].body, later, &ahead);
                if f > s.upper {
                    SLIP_POSITIVE
                } else {
                    SLIP_NEGATIVE
                }
            })
            .collect()
    }

    /// `y` at `t` integrated over `span` in `modes` by four classical Runge–Kutta steps.
    fn advanced(&self, t: f64, y: &[f64], span: f64, modes: &[Mode]) -> Vec<f64> {
        const STEPS: usize = 4;
        let (n, h) = (y.len(), span / STEPS as f64);
        let mut y = y.to_vec();
        let (mut k, mut stage, mut sum) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        for i in 0..STEPS {
            let t = t + i as f64 * h;
            sum.fill(0.0);
            for (c, w) in [(0.0, 1.0), (0.5, 2.0), (0.5, 2.0), (1.0, 1.0)] {
                for m in 0..n {
                    stage[m] = y[m] + c * h * k[m];
                }
                if c == 0.0 {
                    stage.copy_from_slice(&y);
                }
                self.rhs(t + c * h, &stage, modes, &mut k);
                for m in 0..n {
                    sum[m] += w * k[m];
                }
            }
            for m in 0..n {
                y[m] += h / 6.0 * sum[m];
            }
        }
        y
    }

    /// The initial state: every body's x0 and v0, internal states and accumulators zero.
    pub fn initial_state(&self) -> Vec<f64> {
        let mut y = vec![0.0; self.layout.dim()];
        for (i, b) in self.system.bodies.iter().enumerate() {
            y[self.layout.x[i]] = b.x0;
            y[self.layout.v(i)] = b.v0;
        }
        y
    }

    /// The modes of every contact at (t0, y0): by the forces, and the ties by the motion (one
    /// lookahead for them all).
    pub fn initial_modes(&self, t0: f64, y0: &[f64]) -> Vec<Mode> {
        let first: Vec<Option<Mode>> = (0..self.system.contacts.len())
            .map(|j| self.first_mode(j, t0, y0))
            .collect();
        let tied: Vec<usize> = (0..first.len()).filter(|&j| first[j].is_none()).collect();
        let mut modes: Vec<Mode> = first.iter().map(|m| m.unwrap_or(STICK)).collect();
        if !tied.is_empty() {
            let decided = self.ties_by_motion(&tied, t0, y0, &modes);
            for (&j, m) in tied.iter().zip(decided) {
                modes[j] = m;
            }
        }
        modes
    }

    /// The mode of contact `j` to report: the integrated mode under event switching,
    /// otherwise the sign of v_rel.
    pub fn reported_mode(&self, j: usize, y: &[f64], modes: &[Mode]) -> Mode {
        if self.switching.has_modes() {
            return modes[j];
        }
        let c = &self.system.contacts[j];
        mode_of_velocity(y[self.layout.v(c.body)] - c.surface_velocity)
    }

    fn stuck(&self, i: usize, modes: &[Mode]) -> bool {
        self.switching.has_modes() && self.layout.contact[i].is_some_and(|j| modes[j] == STICK)
    }
}

impl OdeProblem for FrictionSystem<'_> {
    fn dim(&self) -> usize {
        self.layout.dim()
    }

    /// `ẋ_i = v_i`, `m_i·v̇_i = F_o,i − F_f,i`, `ż_i = g_i`, and the accumulators
    /// `İ_k = r_k(t) − x_i` for each controller, and the accumulators
    /// `Ẇ_ext = Σ F_ext,i·v_i + Σ u_i·v_i + Σ anchor power − Σ c·Δv²`,
    /// `Ḋ = Σ F_f,j·v_rel,j`, `Ẇ_belt = −Σ F_f,j·v_s,j`.
    fn rhs(&self, t: f64, y: &[f64], modes: &[Mode], dy: &mut [f64]) {
        for b in &self.bodies_at {
            dy[b.x] = y[b.x + 1];
            dy[b.x + 1] = 0.0;
        }
        let external = self.applied_forces(t, y, modes, |v, f| dy[v] += f);
        let (mut dissipated, mut belt) = (0.0, 0.0);
        for b in &self.bodies_at {
            let v = b.x + 1;
            let Some(c) = &b.contact else {
                dy[v] /= b.m;
                continue;
            };
            let other = dy[v];
            let state = (y[b.x], y[v]);
            let force = self.contact_force(
                c,
                state,
                &y[c.z.clone()],
                modes[c.j],
                other,
                &mut dy[c.z.clone()],
            );
            dissipated += force * (y[v] - c.v_s);
            belt -= force * c.v_s;
            if self.switching.has_modes() && modes[c.j] == STICK {
                dy[b.x] = c.v_s;
                dy[v] = 0.0;
            } else {
                dy[v] = (other - force) / b.m;
            }
        }
        for (c, &k) in self.system.controllers.iter().zip(&self.layout.integral) {
            dy[k] = c.error(t, y[self.bodies_at[c.body].x]);
        }
        let a = self.layout.accumulators;
        dy[a] = external;
        dy[a + 1] = dissipated;
        dy[a + 2] = belt;
    }

    /// The three energy accumulators, last in y: nothing reads them.
    fn quadratures(&self) -> usize {
        self.layout.dim() - self.layout.accumulators
    }

    /// The analytic Jacobian of the bodies' unknowns, sparse. Its pattern does not depend on
    /// the modes: the rows of a stuck body are listed with the value zero (a sparse LU that
    /// analyses the pattern once stays valid through every switch). The accumulators, which do
    /// not act back, are left out: they are the problem's quadratures
    /// ([`OdeProblem::quadratures`]).
    fn jacobian(&self, t: f64, y: &[f64], modes: &[Mode], jac: &mut Vec<Entry>) -> bool {
        let l = &self.layout;
        // 1 for a body that moves with the forces, 0 for one held by its contact.
        let moving = |i: usize| if self.stuck(i, modes) { 0.0 } else { 1.0 };
        let live = |i: usize| moving(i) / self.system.bodies[i].m;
        for i in 0..self.system.bodies.len() {
            jac.push((l.x[i], l.v(i), moving(i)));
        }
        for spring in &self.system.springs {
            for (me, other) in [(spring.a, spring.b), (spring.b, spring.a)] {
                let End::Body(i) = me else { continue };
                let (k, c) = (spring.k * live(i), spring.c * live(i));
                jac.push((l.v(i), l.x[i], -k));
                jac.push((l.v(i), l.v(i), -c));
                if let End::Body(o) = other {
                    jac.push((l.v(i), l.x[o], k));
                    jac.push((l.v(i), l.v(o), c));
                }
            }
        }
        for (j, contact) in self.system.contacts.iter().enumerate() {
            let i = contact.body;
            let (x, v) = (l.x[i], l.v(i));
            let states = &mut [StatePartials::default(); MAX_STATES][..l.z[i].len()];
            let p = contact.model.partials(
                y[x],
                y[v] - contact.surface_velocity,
                l.states(i, y),
                self.switching.law(modes[j]),
                states,
            );
            let (w, state) = (live(i), moving(i));
            jac.push((v, x, -p.force_dx * w));
            jac.push((v, v, -p.force_dv * w));
            for (z, d) in l.z[i].clone().zip(states.iter()) {
                jac.push((v, z, -d.force_dz * w));
                jac.push((z, x, d.rate_dx * state));
                jac.push((z, v, d.rate_dv * state));
                jac.push((z, z, d.rate_dz * state));
            }
        }
        // Each controller: u on its body's velocity row (zero where saturated), and the
        // integral's row, İ = r(t) − x.
        for c in &self.system.controllers {
            let i = c.body;
            let (k, a) =
                (self.actuation(i, t, y, Some(modes))).expect("a controller's body has it");
            let (du_dx, du_dv, du_di) = a.partials;
            let (v, w, integral) = (l.v(i), live(i), l.integral[k]);
            jac.push((v, l.x[i], du_dx * w));
            jac.push((v, v, du_dv * w));
            jac.push((v, integral, du_di * w));
            jac.push((integral, l.x[i], -1.0));
        }
        true
    }

    fn n_events(&self) -> usize {
        match self.switching {
            Switching::Event => 2 * self.system.contacts.len(),
            _ => 0,
        }
    }

    fn event_spec(&self, index: usize, modes: &[Mode]) -> Option<EventSpec> {
        match (modes[index / 2], index % 2) {
            (SLIP_POSITIVE, 0) => Some(SLIP_POSITIVE_EVENT),
            (SLIP_NEGATIVE, 0) => Some(SLIP_NEGATIVE_EVENT),
            (STICK, 0) => Some(BREAK_AWAY_POSITIVE),
            (STICK, _) => Some(BREAK_AWAY_NEGATIVE),
            _ => None,
        }
    }

    fn event(&self, index: usize, t: f64, y: &[f64], modes: &[Mode]) -> f64 {
        let j = index / 2;
        let c = &self.system.contacts[j];
        if modes[j] != STICK {
            return y[self.layout.v(c.body)] - c.surface_velocity;
        }
        let s = self.stick_interval(j, y);
        let f = self.other_force(c.body, t, y);
        if index.is_multiple_of(2) {
            s.upper - f
        } else {
            f - s.lower
        }
    }

    fn on_events(&self, fired: &[usize], t: f64, y: &mut [f64], modes: &mut [Mode]) -> Control {
        // Every arriving body onto its surface first (removing the location residual), so
        // that each new mode is decided from forces that see all of them.
        for &index in fired {
            let j = index / 2;
            if modes[j] != STICK {
                let c = &self.system.contacts[j];
                y[self.layout.v(c.body)] = c.surface_velocity;
            }
        }
        let mut tied = Vec::new();
        for &index in fired {
            let j = index / 2;
            if modes[j] == STICK {
                // The needed force has left the stick interval through one of its bounds.
                modes[j] = if index % 2 == 0 {
                    SLIP_POSITIVE
                } else {
                    SLIP_NEGATIVE
                };
            } else {
                match self.first_mode(j, t, y) {
                    Some(m) => modes[j] = m,
                    None => tied.push(j),
                }
            }
        }
        // The ties by the motion, the other contacts in their modes (one lookahead for all).
        if !tied.is_empty() {
            let decided = self.ties_by_motion(&tied, t, y, modes);
            for (&j, m) in tied.iter().zip(decided) {
                modes[j] = m;
            }
        }
        Control::Continue
    }

    /// The shortest natural period `2π·√(m_i / Σ k)` over the bodies held by springs
    /// ([`System::shortest_period`] without controllers): the scale of the Zeno guard's
    /// window and of a tie's lookahead.
    fn time_scale(&self) -> Option<f64> {
        self.system.shortest_period(false)
    }
}
