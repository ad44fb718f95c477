//! How far a system can move by its own scales, and the rule that a run beyond that has
//! diverged, whatever the method, the scheme or the front end.
//!
//! Every force on a body is bounded by the system's declaration: the external forces by their
//! constant and profile, friction by its stick interval and steady-sliding law, a controller
//! by its saturation or its gains on the reference. With `F` the sum of those bounds, `m` the
//! smallest mass and `T` the end time, a body starting from `x0, v0` can reach at most
//! `|x0| + |v0|·T + F·T²/(2m)` under them; springs to anchors only pull back, and springs
//! between bodies move energy, they do not make it. [`Reach`] takes the larger of that and
//! the motions the declaration prescribes (anchors, surfaces, references), and
//! [`RUNAWAY_FACTOR`] times it is a bound no true solution crosses. A run that crosses it
//! computed its motion from the integration, not the problem: a fixed step beyond the
//! stability limit, or a sampled control loop gone unstable. The energy balance cannot see
//! the second (the actuator's work ∫u·v dt books the runaway as a source, and the balance
//! closes to round-off); this bound can.

use crate::system::{Body, Profile, System};
use friction_models::{steady, SignLaw};

/// How many times its [`Reach`] a state may grow before the run is called diverged.
///
/// The reach is already an upper bound (the largest force applied for the whole run); the
/// factor leaves room for an integral controller winding up and for the bound's own
/// looseness, and still catches a runaway long before it overflows (the servo at a
/// zero-order-hold step of 1 s reached 7.4e84 m with status `ok`).
pub const RUNAWAY_FACTOR: f64 = 1e3;

/// Evenly spaced times at which a reference is sampled for its extent and speed.
const REFERENCE_SAMPLES: usize = 1001;

/// The largest displacement and speed a system can reach by its own scales over a run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reach {
    /// Displacement, m.
    pub length: f64,
    /// Speed, m/s.
    pub speed: f64,
}

impl Reach {
    /// The reach of `system` over `[0, t_end]`:
    ///
    /// - speed `V = max(|v0|, |v_anchor|, |v_surface|, |ṙ|, F·T/m, L·ω)`;
    /// - length `L = max(|x0|, |x_anchor| + |v_anchor|·T, |v_surface|·T, |v0|·T, |r|,
    ///   F·T²/(2m))`,
    ///
    /// with `F` the sum of every force's bound (external forces, friction, controllers), `m`
    /// the smallest mass, `T = t_end`, `r` the references sampled over the run and `ω` the
    /// fastest natural frequency `√((Σk + kp)/m)` of a body held by its springs and its
    /// controller's proportional gain.
    pub fn of(system: &System, t_end: f64) -> Reach {
        let t = t_end.max(0.0);
        let references = reference_extent(system, t);
        let prescribed_speed = (system.bodies.iter().map(|b| b.v0.abs()))
            .chain(system.anchors.iter().map(|a| a.v.abs()))
            .chain(system.contacts.iter().map(|c| c.surface_velocity.abs()))
            .chain([references.speed])
            .fold(0.0, f64::max);
        let force = force_bound(system, prescribed_speed, references, t);
        let m = (system.bodies.iter().map(|b| b.m)).fold(f64::INFINITY, f64::min);
        let by_force = |power: i32| match m.is_finite() && m > 0.0 {
            true => force * t.powi(power) / (m * f64::from(power)),
            false => 0.0,
        };
        let length = (system.bodies.iter())
            .map(|b| b.x0.abs() + b.v0.abs() * t)
            .chain(system.anchors.iter().map(|a| a.x0.abs() + a.v.abs() * t))
            .chain([prescribed_speed * t, references.length, by_force(2)])
            .fold(0.0, f64::max);
        let speed = [
            prescribed_speed,
            by_force(1),
            length * fastest_frequency(system),
        ]
        .into_iter()
        .fold(0.0, f64::max);
        Reach { length, speed }
    }

    /// The first of `bodies` whose displacement `x(i)` or speed `|v(i)|` exceeds
    /// [`RUNAWAY_FACTOR`] times the reach, said in words with its value and the bound; `None`
    /// where every body is within it. A zero length or speed bounds nothing (a system with
    /// nothing to move it).
    pub fn exceeded(
        &self,
        bodies: &[Body],
        x: impl Fn(usize) -> f64,
        v: impl Fn(usize) -> f64,
    ) -> Option<String> {
        let checks: [Check; 2] = [
            ("displacement", "m", self.length, &x),
            ("velocity", "m/s", self.speed, &v),
        ];
        for (what, unit, scale, value_of) in checks {
            if scale <= 0.0 || !scale.is_finite() {
                continue;
            }
            let bound = RUNAWAY_FACTOR * scale;
            let beyond = (0..bodies.len()).find(|&i| value_of(i).abs() > bound);
            if let Some(i) = beyond {
                return Some(format!(
                    "the {what} of body \"{}\", {:.3e} {unit}, is beyond {RUNAWAY_FACTOR:e} \
                     times the largest the system's forces and prescribed motions can give it \
                     ({scale:.3e} {unit}): the integration, not the problem, made the motion \
                     (a step beyond the stability limit, or a sampled loop gone unstable)",
                    bodies[i].name,
                    value_of(i)
                ));
            }
        }
        None
    }
}

/// A quantity checked against the reach: its name, unit, scale and value per body.
type Check<'a> = (&'a str, &'a str, f64, &'a dyn Fn(usize) -> f64);

/// The largest |r| and |ṙ| of the system's controller references over `[0, t]`.
fn reference_extent(system: &System, t: f64) -> Reach {
    let mut extent = Reach {
        length: 0.0,
        speed: 0.0,
    };
    for c in &system.controllers {
        for k in 0..REFERENCE_SAMPLES {
            let (r, rdot) = c
                .reference
                .at(t * k as f64 / (REFERENCE_SAMPLES - 1) as f64);
            extent.length = extent.length.max(r.abs());
            extent.speed = extent.speed.max(rdot.abs());
        }
    }
    extent
}

/// The sum of the bounds of every force of `system` over a run of `t` s: external forces by
/// their constant and profile; friction by its stick interval and its steady sliding at ±`v`
/// (the fastest prescribed speed); a controller by its saturation, or by
/// `(kp + ki·t)·|r| + kd·|ṙ|` on its reference's extent.
fn force_bound(system: &System, v: f64, references: Reach, t: f64) -> f64 {
    let external = system.forces.iter().map(|f| {
        f.constant.abs()
            + match f.profile {
                Profile::None => 0.0,
                Profile::Ramp { rate } => rate.abs() * t,
                Profile::Trapezoid { peak, .. } => peak.abs(),
                Profile::Sine { amplitude, .. } => amplitude.abs(),
            }
    });
    let friction = system.contacts.iter().map(|c| {
        let model = c.model.as_ref();
        let stick = model.stick_interval(0.0, &vec![0.0; model.n_states()]);
        let sliding = [v, -v].map(|v| steady::force(model, v, SignLaw::Discontinuous).abs());
        [stick.lower.abs(), stick.upper.abs(), sliding[0], sliding[1]]
            .into_iter()
            .filter(|f| f.is_finite())
            .fold(0.0, f64::max)
    });
    let control = system.controllers.iter().map(|c| {
        c.saturation.map_or_else(
            || (c.kp.abs() + c.ki.abs() * t) * references.length + c.kd.abs() * references.speed,
            f64::abs,
        )
    });
    external.chain(friction).chain(control).sum()
}

/// The fastest natural frequency `√((Σk + kp)/m)` of a body held by its springs and by its
/// controller's proportional gain, rad/s ([`System::shortest_period`]; 0 for a system with
/// neither).
fn fastest_frequency(system: &System) -> f64 {
    system
        .shortest_period(true)
        .map_or(0.0, |period| 2.0 * std::f64::consts::PI / period)
}
