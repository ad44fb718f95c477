//! The describing-function prediction of a hunting cycle: first-harmonic balance of a PID loop
//! around a mass with Coulomb friction, stiction and viscous friction.
//!
//! **The plant** ([`StictionMass`]): sliding in direction s = ±1, `m·v̇ = u − s·F_c − F_v·v`;
//! at rest it sticks while |u| ≤ F_s and breaks away in the direction of u once |u| > F_s.
//! **Its describing function** N(U, ω): driven by u = U·sin ωt it settles on a periodic
//! velocity v(t) (it depends on t mod T alone, not on x); the position x = ∫v has the first
//! harmonic X₁ = (2/T)∫x·e^{−jωt}dt = V₁/(jω), and the force's is −jU, so
//! `N = X₁/(−jU) = V₁/(ω·U)`. A frictionless mass has N = −1/(mω²). The mass and its
//! friction are taken together, as Olsson (1996) does: the friction element alone, with the
//! velocity as its input, has a real positive describing function, which under integral
//! action predicts no hunting at all.
//! **The loop**: the PID `C(jω) = kp + ki/(jω) + kd·jω` acts on e = r − x, so around the set
//! point u = −C·x and a symmetric cycle of first harmonic (U, ω) satisfies the harmonic
//! balance `1 + C(jω)·N(U, ω) = 0` ([`predict_hunting`]).
//!
//! The prediction assumes a sinusoidal control force; the simulated hunting cycle's force
//! ramps while the body sticks (the integral winds up), which is why Armstrong-Hélouvry &
//! Amin (1996, *Automatica* 32(5)) find the describing function unreliable for this problem
//! (docs/closed-loop.md gives the numbers).

use crate::run::Law;
use friction_models::{FrictionModel, FrictionParams};
use num_complex::Complex64;
use serde::Serialize;
use std::f64::consts::PI;

/// A mass on the floor with Coulomb friction, stiction and viscous friction (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct StictionMass {
    /// Mass m, kg (> 0).
    pub m: f64,
    /// Coulomb level F_c, N (≥ 0).
    pub f_c: f64,
    /// Static level F_s, N (≥ F_c).
    pub f_s: f64,
    /// Viscous coefficient F_v, N·s/m (≥ 0).
    pub f_v: f64,
}

impl StictionMass {
    /// The mass `m` with the friction of `law` at `p` idealised as Coulomb friction, stiction
    /// and viscous friction ([`StictionMass::of`]); `None` for a law of another form, or one
    /// whose parameters do not build it.
    pub fn idealising(law: &Law, p: &FrictionParams, m: f64) -> Option<Self> {
        Self::of(law.build(p).ok()?.as_ref(), m)
    }

    /// The mass `m` with the friction `model`'s steady levels
    /// ([`FrictionModel::stiction_levels`]): `static` (F_c, F_s), `coulomb` (F_c, F_c),
    /// `viscous` (μ_v), `karnopp` (F_c, F_s, μ_v), LuGre in the limit of a vanishing Stribeck
    /// speed and presliding displacement (F_c, F_s, σ2), and any law of one's own that gives
    /// them. `None` for the others.
    pub fn of(model: &dyn FrictionModel, m: f64) -> Option<Self> {
        let l = model.stiction_levels()?;
        Some(StictionMass {
            m,
            f_c: l.f_c,
            f_s: l.f_s,
            f_v: l.f_v,
        })
    }
}

/// A PID on the position error: `u = kp·e + ki·∫e dt + kd·ė`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Pid {
    /// Proportional gain, N/m.
    pub kp: f64,
    /// Integral gain, N/(m·s).
    pub ki: f64,
    /// Derivative gain, N·s/m.
    pub kd: f64,
}

impl Pid {
    /// Its frequency response `C(jω) = kp + ki/(jω) + kd·jω`.
    pub fn at(&self, omega: f64) -> Complex64 {
        Complex64::new(self.kp, self.kd * omega - self.ki / omega)
    }
}

/// The periodic response of a [`StictionMass`] to u = U·sin ωt over one period.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Response {
    /// The describing function N(U, ω) = X₁/(−jU), m/N.
    pub n: Complex64,
    /// Half the range of x over the period, m.
    pub half_range: f64,
    /// The time at rest in the period, s.
    pub stick_time: f64,
}

/// One slide of the mass: from `t0` at velocity `v0` in direction `s`, until `t1`.
#[derive(Clone, Copy, Debug)]
struct Slide {
    t0: f64,
    t1: f64,
    v0: f64,
    s: f64,
}

/// The number of sample intervals per period at which the end of a slide is bracketed before
/// bisection (a velocity that touches zero and turns back within 1/512 of a period, 0.7° of
/// the force's phase, is not seen to stop).
const BRACKET_STEPS: f64 = 512.0;
/// The pieces per period over which the harmonic is integrated, each by [`GAUSS_8`].
const QUADRATURE_PIECES: f64 = 64.0;
/// The symmetric response's velocity at the force's peak is found to this fraction of its
/// bound.
const SYMMETRY_TOLERANCE: f64 = 1e-14;
/// Steps of the Illinois method at most.
const ILLINOIS_STEPS: usize = 200;

/// Gauss–Legendre nodes and weights on [−1, 1], eight points (exact for degree 15).
const GAUSS_8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_48),
    (-0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_48),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
];

impl StictionMass {
    /// The velocity at `t` of a slide started at `t0` with `v0` in direction `s` under
    /// u = U·sin ωt: `v0 + (U/ω·(cos ωt0 − cos ωt) − s·F_c·(t − t0))/m` without viscous
    /// friction, else the particular solution `A·sin ωt + B·cos ωt − s·F_c/F_v` (a = F_v/m,
    /// A = (U/m)·a/(a² + ω²), B = −(U/m)·ω/(a² + ω²)) plus `(v0 − v_p(t0))·e^{−a(t − t0)}`.
    fn velocity(&self, slide: &Slide, t: f64, u: f64, omega: f64) -> f64 {
        let Slide { t0, v0, s, .. } = *slide;
        if self.f_v == 0.0 {
            return v0
                + (u / omega * ((omega * t0).cos() - (omega * t).cos()) - s * self.f_c * (t - t0))
                    / self.m;
        }
        let a = self.f_v / self.m;
        let den = a * a + omega * omega;
        let (amp_s, amp_c) = (u / self.m * a / den, -u / self.m * omega / den);
        let particular = |t: f64| {
            amp_s * (omega * t).sin() + amp_c * (omega * t).cos() - s * self.f_c / self.f_v
        };
        particular(t) + (v0 - particular(t0)) * (-a * (t - t0)).exp()
    }

    /// The end of a slide started at `slide.t0`: the first time its velocity reaches zero,
    /// or `None` if it slides past `limit`.
    fn slide_end(&self, slide: &Slide, u: f64, omega: f64, limit: f64) -> Option<f64> {
        let h = 2.0 * PI / omega / BRACKET_STEPS;
        let moving = |t: f64| slide.s * self.velocity(slide, t, u, omega) > 0.0;
        let mut lo = slide.t0;
        loop {
            let hi = lo + h;
            if !moving(hi) {
                let (mut a, mut b) = (lo, hi);
                while b - a > 1e-15 * b.abs().max(h) {
                    let mid = 0.5 * (a + b);
                    if moving(mid) {
                        a = mid;
                    } else {
                        b = mid;
                    }
                }
                return Some(b);
            }
            if hi > limit {
                return None;
            }
            lo = hi;
        }
    }

    /// The motion from `t0` at velocity `v0` (at rest if 0) to `t_end` under u = U·sin ωt: its
    /// slides, and the velocity at `t_end` (0 at rest).
    fn drive(&self, u: f64, omega: f64, t0: f64, v0: f64, t_end: f64) -> (Vec<Slide>, f64) {
        let force = |t: f64| u * (omega * t).sin();
        let break_angle = (self.f_s / u).asin();
        let mut slides = Vec::new();
        let mut t = t0;
        let mut moving = (v0 != 0.0).then(|| (v0, v0.signum()));
        while t < t_end {
            let (v0, s) = match moving {
                Some(state) => state,
                None if force(t).abs() > self.f_s => (0.0, force(t).signum()),
                None => {
                    // The next break-away: |u| rises past F_s at ωt = θ_b + iπ.
                    let i = ((omega * t - break_angle) / PI).floor() + 1.0;
                    t = (break_angle + i * PI) / omega;
                    moving = (t < t_end).then(|| (0.0, force(t).signum()));
                    continue;
                }
            };
            let slide = Slide {
                t0: t,
                t1: t_end,
                v0,
                s,
            };
            match self.slide_end(&slide, u, omega, t_end) {
                Some(t1) => {
                    slides.push(Slide { t1, ..slide });
                    t = t1;
                    moving = (force(t1).abs() > self.f_s).then(|| (0.0, force(t1).signum()));
                }
                None => {
                    slides.push(slide);
                    return (slides, self.velocity(&slide, t_end, u, omega));
                }
            }
        }
        (slides, 0.0)
    }

    /// The periodic response to u = U·sin ωt; `None` where U ≤ F_s (the mass never moves,
    /// N = 0). The response is symmetric, v(t + T/2) = −v(t): its velocity v₀ at the force's
    /// peak t₀ = T/4 is the root of `v(t₀ + T/2; v₀) + v₀`, found by the Illinois method
    /// between ±(U/(mω) + F_c·T/m) (the first term alone is a frictionless mass's range, and
    /// friction changes the velocity by at most F_c·T/m in a period).
    pub fn response(&self, u: f64, omega: f64) -> Option<Response> {
        if u <= self.f_s {
            return None;
        }
        let period = 2.0 * PI / omega;
        let t0 = period / 4.0;
        let bound = u / (self.m * omega) + self.f_c * period / self.m;
        let half = |v0: f64| self.drive(u, omega, t0, v0, t0 + period / 2.0).1 + v0;
        let v0 = illinois(half, -bound, bound, SYMMETRY_TOLERANCE * bound)?;
        let (slides, _) = self.drive(u, omega, t0, v0, t0 + period);
        Some(self.harmonic(&slides, u, omega, t0))
    }

    /// The describing function, the half range of x and the time at rest over the period
    /// from `start`, of the slides in `slides`.
    fn harmonic(&self, slides: &[Slide], u: f64, omega: f64, start: f64) -> Response {
        let period = 2.0 * PI / omega;
        let end = start + period;
        let (mut v1, mut x, mut x_min, mut x_max, mut sliding) =
            (Complex64::new(0.0, 0.0), 0.0f64, 0.0f64, 0.0f64, 0.0);
        for slide in slides {
            let (a, b) = (slide.t0.max(start), slide.t1.min(end));
            if b <= a {
                continue;
            }
            sliding += b - a;
            let pieces = ((b - a) / period * QUADRATURE_PIECES).ceil().max(1.0);
            let h = (b - a) / pieces;
            for i in 0..pieces as usize {
                let mid = a + (i as f64 + 0.5) * h;
                for (node, weight) in GAUSS_8 {
                    let t = mid + 0.5 * h * node;
                    let v = self.velocity(slide, t, u, omega);
                    let w = 0.5 * h * weight;
                    v1 += w * v * Complex64::from_polar(1.0, -omega * t);
                    x += w * v;
                }
            }
            // x is monotone along a slide and holds still at rest.
            (x_min, x_max) = (x_min.min(x), x_max.max(x));
        }
        Response {
            n: v1 * (2.0 / period) / (omega * u),
            half_range: 0.5 * (x_max - x_min),
            stick_time: (period - sliding).max(0.0),
        }
    }
}

/// A cycle the harmonic balance predicts.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct HuntingPrediction {
    /// Its angular frequency ω, rad/s.
    pub omega: f64,
    /// Its period 2π/ω, s.
    pub period: f64,
    /// The amplitude U of the control force's first harmonic, N.
    pub force_amplitude: f64,
    /// The amplitude |N|·U of the position's first harmonic, m.
    pub amplitude: f64,
    /// Half the range of x in the periodic response to U·sin ωt, m (comparable with the
    /// simulated cycle's amplitude, half the range of the error).
    pub half_range: f64,
    /// The time at rest per period in that response, s.
    pub stick_time: f64,
    /// |1 + C(jω)·N(U, ω)| at the solution.
    pub residual: f64,
}

/// The frequencies searched, from [`OMEGA_RANGE`]`.0` to `.1` rad/s at [`OMEGA_PER_DECADE`]
/// points a decade, and the force amplitudes, U/F_s − 1 from [`FORCE_RANGE`]`.0` to `.1` at
/// [`FORCE_PER_DECADE`] a decade (U/F_c − 1 for a mass without stiction).
pub const OMEGA_RANGE: (f64, f64) = (1e-3, 1e2);
/// Points per decade of ω.
pub const OMEGA_PER_DECADE: f64 = 12.0;
/// The range of U/F_s − 1 searched.
pub const FORCE_RANGE: (f64, f64) = (1e-6, 1e2);
/// Points per decade of U/F_s − 1.
pub const FORCE_PER_DECADE: f64 = 4.0;
/// Bisection steps of each one-dimensional solve.
const BISECTIONS: usize = 50;

/// The root of `f` between `a` and `b`, where its signs differ, by the Illinois variant of
/// regula falsi, to within `tolerance`; `None` where the signs do not differ.
fn illinois(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64, tolerance: f64) -> Option<f64> {
    let (mut fa, mut fb) = (f(a), f(b));
    if fa == 0.0 {
        return Some(a);
    }
    if (fa > 0.0) == (fb > 0.0) {
        return None;
    }
    let mut side = 0;
    for _ in 0..ILLINOIS_STEPS {
        let c = (a * fb - b * fa) / (fb - fa);
        let fc = f(c);
        if fc == 0.0 || (b - a).abs() <= tolerance {
            return Some(c);
        }
        if (fc > 0.0) == (fb > 0.0) {
            (b, fb) = (c, fc);
            if side == -1 {
                fa /= 2.0;
            }
            side = -1;
        } else {
            (a, fa) = (c, fc);
            if side == 1 {
                fb /= 2.0;
            }
            side = 1;
        }
    }
    Some((a * fb - b * fa) / (fb - fa))
}

/// A geometric grid from `a` to `b` with `per_decade` points a decade.
fn geometric(a: f64, b: f64, per_decade: f64) -> Vec<f64> {
    let n = ((b / a).log10() * per_decade).round() as usize;
    (0..=n)
        .map(|i| a * (b / a).powf(i as f64 / n as f64))
        .collect()
}

/// Bisects `f` between `a` and `b` (where its signs differ) in log space.
fn bisect_log(mut a: f64, mut b: f64, f: impl Fn(f64) -> Option<f64>) -> Option<f64> {
    let fa = f(a)?;
    for _ in 0..BISECTIONS {
        let mid = (a * b).sqrt();
        let fm = f(mid)?;
        if (fm > 0.0) == (fa > 0.0) {
            a = mid;
        } else {
            b = mid;
        }
    }
    Some((a * b).sqrt())
}

/// The loop gain L = C(jω)·N(U, ω), `None` where the response is undefined.
fn loop_gain(mass: &StictionMass, pid: &Pid, u: f64, omega: f64) -> Option<Complex64> {
    mass.response(u, omega).map(|r| pid.at(omega) * r.n)
}

/// The phase crossovers at force amplitude U: the ω where L is real and negative.
fn crossovers(mass: &StictionMass, pid: &Pid, u: f64) -> Vec<f64> {
    let grid = geometric(OMEGA_RANGE.0, OMEGA_RANGE.1, OMEGA_PER_DECADE);
    let im = |w: f64| loop_gain(mass, pid, u, w).map(|l| l.im);
    let values: Vec<Option<f64>> = grid.iter().map(|&w| im(w)).collect();
    let mut out = Vec::new();
    for i in 1..grid.len() {
        if let (Some(a), Some(b)) = (values[i - 1], values[i]) {
            if (a > 0.0) != (b > 0.0) {
                if let Some(w) = bisect_log(grid[i - 1], grid[i], im) {
                    if loop_gain(mass, pid, u, w).is_some_and(|l| l.re < 0.0) {
                        out.push(w);
                    }
                }
            }
        }
    }
    out
}

/// The phase crossover at force amplitude U nearest to `guess`: bisected within
/// [`NEAR`] of it where Im L changes sign there, else the nearest of [`crossovers`].
fn crossover_near(mass: &StictionMass, pid: &Pid, u: f64, guess: f64) -> Option<f64> {
    let im = |w: f64| loop_gain(mass, pid, u, w).map(|l| l.im);
    let (a, b) = (guess / NEAR, guess * NEAR);
    if let (Some(fa), Some(fb)) = (im(a), im(b)) {
        if (fa > 0.0) != (fb > 0.0) {
            if let Some(w) = bisect_log(a, b, im) {
                if loop_gain(mass, pid, u, w).is_some_and(|l| l.re < 0.0) {
                    return Some(w);
                }
            }
        }
    }
    crossovers(mass, pid, u)
        .into_iter()
        .min_by(|x, y| (*x / guess).ln().abs().total_cmp(&(*y / guess).ln().abs()))
}

/// The factor either side of a guess within which [`crossover_near`] first looks.
const NEAR: f64 = 1.1;

/// |C(jω)·N(U, ω)| at the phase crossover of the smallest force amplitude searched, U =
/// F_s·(1 + [`FORCE_RANGE`]`.0`): the loop gain the break-away starts from. Below 1 a cycle
/// may balance at a larger U; above 1 the balance jumps over −1 as U passes F_s (N = 0
/// below). `None` without a crossover there.
pub fn break_away_gain(mass: &StictionMass, pid: &Pid) -> Option<f64> {
    let u = break_level(mass) * (1.0 + FORCE_RANGE.0);
    let w = *crossovers(mass, pid, u).first()?;
    loop_gain(mass, pid, u, w).map(|l| l.norm())
}

/// The force at which the mass breaks away: F_s, or F_c without stiction.
fn break_level(mass: &StictionMass) -> f64 {
    if mass.f_s > 0.0 {
        mass.f_s
    } else {
        mass.f_c
    }
}

/// The cycles of the harmonic balance `1 + C(jω)·N(U, ω) = 0` within the searched ranges,
/// by increasing force amplitude: along each branch of phase crossovers ω(U) the force
/// amplitude where |L| = 1, bisected in U between grid points where |L| − 1 changes sign.
/// Empty where the balance has no solution there (no cycle predicted), and for a mass
/// without a Coulomb level, whose N does not depend on U (a linear loop, which has a cycle
/// only where it is marginally stable).
pub fn predict_hunting(mass: &StictionMass, pid: &Pid) -> Vec<HuntingPrediction> {
    let level = break_level(mass);
    if level <= 0.0 {
        return Vec::new();
    }
    let forces: Vec<f64> = geometric(FORCE_RANGE.0, FORCE_RANGE.1, FORCE_PER_DECADE)
        .into_iter()
        .map(|r| level * (1.0 + r))
        .collect();
    let gain = |u: f64, w: f64| loop_gain(mass, pid, u, w).map(|l| l.norm() - 1.0);
    let branches: Vec<Vec<f64>> = forces.iter().map(|&u| crossovers(mass, pid, u)).collect();
    let mut out = Vec::new();
    for i in 1..forces.len() {
        for &wa in &branches[i - 1] {
            // The crossover of the next force on the same branch: the nearest within 50 %.
            let Some(&wb) = branches[i]
                .iter()
                .filter(|&&w| (w / wa).ln().abs() < 1.5f64.ln())
                .min_by(|x, y| (*x / wa).ln().abs().total_cmp(&(*y / wa).ln().abs()))
            else {
                continue;
            };
            let (Some(ga), Some(gb)) = (gain(forces[i - 1], wa), gain(forces[i], wb)) else {
                continue;
            };
            if (ga > 0.0) == (gb > 0.0) {
                continue;
            }
            // The branch's crossover at U, near the ω interpolated between its ends.
            let branch = |u: f64| {
                let t = (u / forces[i - 1]).ln() / (forces[i] / forces[i - 1]).ln();
                crossover_near(mass, pid, u, wa * (wb / wa).powf(t))
            };
            let (lo, hi) = (forces[i - 1] - level, forces[i] - level);
            let Some(excess) = bisect_log(lo, hi, |e| gain(level + e, branch(level + e)?)) else {
                continue;
            };
            let u = level + excess;
            let Some(omega) = branch(u) else { continue };
            let Some(r) = mass.response(u, omega) else {
                continue;
            };
            out.push(HuntingPrediction {
                omega,
                period: 2.0 * PI / omega,
                force_amplitude: u,
                amplitude: r.n.norm() * u,
                half_range: r.half_range,
                stick_time: r.stick_time,
                residual: (1.0 + pid.at(omega) * r.n).norm(),
            });
        }
    }
    out
}
