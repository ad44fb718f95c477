//! Test problems shared by the integrator tests.
#![allow(dead_code)]

use integrators::testset::Robertson;
use integrators::{Control, Crossing, Entry, EventSpec, Mode, OdeProblem};

/// The Arenstorf orbit (Hairer, Nørsett, Wanner, *Solving ODEs I*, sec. II.0, eq. (0.1)).
pub struct Arenstorf;

/// Initial state of the Arenstorf orbit, digits as printed in Hairer's driver dr_dopri5.f.
#[allow(clippy::excessive_precision)]
pub const ARENSTORF_Y0: [f64; 4] = [0.994, 0.0, 0.0, -2.00158510637908252240537862224];
/// Period of the Arenstorf orbit, digits as printed in dr_dopri5.f.
#[allow(clippy::excessive_precision)]
pub const ARENSTORF_T_END: f64 = 17.0652165601579625588917206249;

impl OdeProblem for Arenstorf {
    fn dim(&self) -> usize {
        4
    }
    fn rhs(&self, _t: f64, y: &[f64], _m: &[Mode], f: &mut [f64]) {
        let amu = 0.012277471;
        let amup = 1.0 - amu;
        let r1 = (y[0] + amu).powi(2) + y[1] * y[1];
        let r1 = r1 * r1.sqrt();
        let r2 = (y[0] - amup).powi(2) + y[1] * y[1];
        let r2 = r2 * r2.sqrt();
        f[0] = y[2];
        f[1] = y[3];
        f[2] = y[0] + 2.0 * y[3] - amup * (y[0] + amu) / r1 - amu * (y[0] - amup) / r2;
        f[3] = y[1] - 2.0 * y[2] - amup * y[1] / r1 - amu * y[1] / r2;
    }
}

/// x'' = −x: x = cos t, v = −sin t from (1, 0); events: x = 0 in the given direction,
/// handled with the given control.
pub struct Oscillator {
    /// The event functions (all x = 0).
    pub events: Vec<EventSpec>,
    /// What every event does.
    pub control: Control,
}

impl Oscillator {
    /// Without events.
    pub fn plain() -> Self {
        Oscillator {
            events: vec![],
            control: Control::Continue,
        }
    }
    /// Watching x = 0 in `crossing` direction.
    pub fn watching(crossing: Crossing, control: Control) -> Self {
        Oscillator {
            events: vec![EventSpec {
                name: "x=0",
                crossing,
            }],
            control,
        }
    }
}

impl OdeProblem for Oscillator {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], _m: &[Mode], f: &mut [f64]) {
        f[0] = y[1];
        f[1] = -y[0];
    }
    fn jacobian(
        &self,
        _t: f64,
        _y: &[f64],
        _m: &[Mode],
        jac: &mut Vec<(usize, usize, f64)>,
    ) -> bool {
        jac.extend([(0, 1, 1.0), (1, 0, -1.0)]);
        true
    }
    fn n_events(&self) -> usize {
        self.events.len()
    }
    fn event_spec(&self, i: usize, _m: &[Mode]) -> Option<EventSpec> {
        Some(self.events[i])
    }
    fn event(&self, _i: usize, _t: f64, y: &[f64], _m: &[Mode]) -> f64 {
        y[0]
    }
    fn on_events(&self, _i: &[usize], _t: f64, _y: &mut [f64], _m: &mut [Mode]) -> Control {
        self.control
    }
}

/// A ball bouncing with restitution 1/2 from height 1: its bounces accumulate at a finite
/// time (a Zeno point).
pub struct BouncingBall;

/// The bouncing ball with its clock stretched by `scale` (gravity 9.81/scale²), declaring
/// `scale` as its time scale: its Zeno point is at `scale` times the ball's.
pub struct ScaledBall {
    /// The time scale, s.
    pub scale: f64,
}

impl OdeProblem for ScaledBall {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], _m: &[Mode], f: &mut [f64]) {
        f[0] = y[1];
        f[1] = -9.81 / (self.scale * self.scale);
    }
    fn n_events(&self) -> usize {
        BouncingBall.n_events()
    }
    fn event_spec(&self, i: usize, m: &[Mode]) -> Option<EventSpec> {
        BouncingBall.event_spec(i, m)
    }
    fn event(&self, i: usize, t: f64, y: &[f64], m: &[Mode]) -> f64 {
        BouncingBall.event(i, t, y, m)
    }
    fn on_events(&self, i: &[usize], t: f64, y: &mut [f64], m: &mut [Mode]) -> Control {
        BouncingBall.on_events(i, t, y, m)
    }
    fn time_scale(&self) -> Option<f64> {
        Some(self.scale)
    }
}

impl OdeProblem for BouncingBall {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], _m: &[Mode], f: &mut [f64]) {
        f[0] = y[1];
        f[1] = -9.81;
    }
    fn n_events(&self) -> usize {
        1
    }
    fn event_spec(&self, _i: usize, _m: &[Mode]) -> Option<EventSpec> {
        Some(EventSpec {
            name: "bounce",
            crossing: Crossing::Falling,
        })
    }
    fn event(&self, _i: usize, _t: f64, y: &[f64], _m: &[Mode]) -> f64 {
        y[0]
    }
    fn on_events(&self, _i: &[usize], _t: f64, y: &mut [f64], _m: &mut [Mode]) -> Control {
        y[0] = 0.0;
        y[1] *= -0.5;
        Control::Continue
    }
}

/// y' = y², y(0) = 1: y = 1/(1 − t) blows up at t = 1.
pub struct BlowUp;

impl OdeProblem for BlowUp {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&self, _t: f64, y: &[f64], _m: &[Mode], f: &mut [f64]) {
        f[0] = y[0] * y[0];
    }
}

/// Robertson as an index-1 DAE: the third equation replaced by the conservation law
/// `0 = y1 + y2 + y3 − 1`, with mass matrix diag(1, 1, 0).
pub struct RobertsonDae;

impl OdeProblem for RobertsonDae {
    fn dim(&self) -> usize {
        3
    }
    fn rhs(&self, t: f64, y: &[f64], m: &[Mode], f: &mut [f64]) {
        Robertson.rhs(t, y, m, f);
        f[2] = y[0] + y[1] + y[2] - 1.0;
    }
    fn mass(&self) -> Option<&[f64]> {
        Some(&[1.0, 1.0, 0.0])
    }
}

/// Prothero and Robinson's stiff problem `y' = λ·(y − sin t) + cos t`, λ = −1e6, whose
/// solution from y(0) = 0 is sin t; a second component integrates `sin t` as a quadrature
/// (`q' = y`, read by nothing), so `q(t) = 1 − cos t`.
pub struct ProtheroRobinson;

impl OdeProblem for ProtheroRobinson {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, t: f64, y: &[f64], _m: &[Mode], f: &mut [f64]) {
        f[0] = -1e6 * (y[0] - t.sin()) + t.cos();
        f[1] = y[0];
    }
    fn jacobian(&self, _t: f64, _y: &[f64], _m: &[Mode], jac: &mut Vec<Entry>) -> bool {
        jac.push((0, 0, -1e6));
        true
    }
    fn quadratures(&self) -> usize {
        1
    }
}

/// The heat equation on n interior points, `u' = k·(u_{i−1} − 2u_i + u_{i+1})`, stiff (its
/// eigenvalues reach −4k) and sparse (a tridiagonal Jacobian).
pub struct Heat {
    /// Interior points.
    pub n: usize,
    /// The diffusion coefficient over the squared spacing.
    pub k: f64,
}

impl OdeProblem for Heat {
    fn dim(&self) -> usize {
        self.n
    }
    fn rhs(&self, _t: f64, u: &[f64], _m: &[Mode], f: &mut [f64]) {
        for i in 0..self.n {
            let left = if i > 0 { u[i - 1] } else { 0.0 };
            let right = if i + 1 < self.n { u[i + 1] } else { 0.0 };
            f[i] = self.k * (left - 2.0 * u[i] + right);
        }
    }
    fn jacobian(&self, _t: f64, _u: &[f64], _m: &[Mode], jac: &mut Vec<Entry>) -> bool {
        for i in 0..self.n {
            jac.push((i, i, -2.0 * self.k));
            if i > 0 {
                jac.push((i, i - 1, self.k));
            }
            if i + 1 < self.n {
                jac.push((i, i + 1, self.k));
            }
        }
        true
    }
}
