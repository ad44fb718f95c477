//! The Dormand–Prince 5(4) method as in E. Hairer's `dopri5.f` (version of 1996, subroutine
//! DOPCOR; Hairer, Nørsett, Wanner, *Solving ODEs I*, 2nd ed., sec. II.5 and II.6):
//! the same tableau, error estimate, PI ("Lund-stabilised") step control, step-growth limits,
//! initial-step heuristic (HINIT), FSAL, Shampine's order-4 dense output (CONTD5), and the
//! stiffness test. A fixed-step mode (no error control) exists for convergence studies.

use crate::error::SolverError;
use crate::method::OneStepMethod;
use crate::options::{Options, StepControl};
use crate::stats::Stats;
use crate::stepper::{
    check_finite, check_limits, next_grid_point, wrms, Ode, Stepper, StepperState,
};

// Runge–Kutta coefficients of Dormand and Prince (1980), subroutine CDOPRI of dopri5.f.
const C2: f64 = 0.2;
const C3: f64 = 0.3;
const C4: f64 = 0.8;
const C5: f64 = 8.0 / 9.0;
const A21: f64 = 0.2;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const A71: f64 = 35.0 / 384.0;
const A73: f64 = 500.0 / 1113.0;
const A74: f64 = 125.0 / 192.0;
const A75: f64 = -2187.0 / 6784.0;
const A76: f64 = 11.0 / 84.0;
// Error coefficients E_i = b_i − b̂_i (CDOPRI).
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;
// Dense output of Shampine (1986) (CDOPRI).
const D1: f64 = -12715105075.0 / 11282082432.0;
const D3: f64 = 87487479700.0 / 32700410799.0;
const D4: f64 = -10690763975.0 / 1880347072.0;
const D5: f64 = 701980252875.0 / 199316789632.0;
const D6: f64 = -1453857185.0 / 822651844.0;
const D7: f64 = 69997945.0 / 29380423.0;

// Step-size control: the defaults of dopri5.f (WORK(2)–WORK(5)).
/// Safety factor SAFE (WORK(2)).
const SAFE: f64 = 0.9;
/// FAC1: the new step is at least FAC1 times the old one (WORK(3)).
const FAC1: f64 = 0.2;
/// FAC2: the new step is at most FAC2 times the old one (WORK(4)).
const FAC2: f64 = 10.0;
/// BETA of the PI ("Lund") stabilisation (WORK(5)).
const BETA: f64 = 0.04;
/// EXPO1 = 1/5 − 0.75·BETA: the exponent of the current error (DOPCOR).
const EXPO1: f64 = 0.2 - BETA * 0.75;
/// FACOLD's starting value and floor (DOPCOR).
const FACOLD_MIN: f64 = 1e-4;
/// IORD, the order used by HINIT.
const HINIT_ORDER: f64 = 5.0;
// Stiffness detection (DOPCOR): test every NSTIFF accepted steps, or every step once
// suspicious; h·λ beyond 3.25 is "stiff"; 15 stiff verdicts in a row mean stiffness, and 6
// non-stiff ones clear the suspicion.
const NSTIFF: usize = 1000;
/// h·λ beyond which a step is "stiff" (DOPCOR: `IF (HLAMB.GT.3.25D0)`).
pub const STIFF_HLAMB: f64 = 3.25;
/// Stiff verdicts in a row that mean stiffness (DOPCOR: `IASTI.EQ.15`).
pub const STIFF_COUNT: usize = 15;
const NONSTIFF_COUNT: usize = 6;

/// `Σ_j a_j·k_j[i]`, summed left to right as `dopri5.f` writes its stage sums.
#[inline(always)]
fn weighted<const S: usize>(a: &[f64; S], k: &[&[f64]; S], i: usize) -> f64 {
    let mut sum = a[0] * k[0][i];
    for j in 1..S {
        sum += a[j] * k[j][i];
    }
    sum
}

/// A stage's argument `out = y + h·Σ_j a_j·k_j`, component by component.
#[inline(always)]
fn stage<const S: usize>(out: &mut [f64], y: &[f64], h: f64, a: [f64; S], k: [&Vec<f64>; S]) {
    let n = out.len();
    let (y, k) = (&y[..n], k.map(|k| &k[..n]));
    for (i, o) in out.iter_mut().enumerate() {
        *o = y[i] + h * weighted(&a, &k, i);
    }
}

/// Dormand–Prince as a method (`dopri5`): order 5, explicit, adaptive or at a fixed step.
#[derive(Clone, Copy, Debug)]
pub struct Dopri5Method;

impl OneStepMethod for Dopri5Method {
    fn name(&self) -> &'static str {
        "dopri5"
    }

    fn order(&self) -> usize {
        5
    }

    fn is_implicit(&self) -> bool {
        false
    }

    fn is_fixed_step(&self) -> bool {
        false
    }

    fn takes_fixed_steps(&self) -> bool {
        true
    }

    fn stability_polynomial(&self) -> Option<&'static [f64]> {
        Some(&crate::stability::DOPRI5_POLYNOMIAL)
    }

    fn stepper(&self, options: &Options, dim: usize) -> Result<Box<dyn Stepper>, SolverError> {
        Ok(Box::new(Dopri5::new(
            options.step,
            options.h_max(),
            options.max_steps,
            dim,
        )))
    }
}

/// Hairer's Dormand–Prince 5(4), adaptive or with fixed steps.
#[derive(Clone, Debug)]
pub struct Dopri5 {
    control: StepControl,
    h_max: f64,
    max_steps: usize,
    t_start: f64,
    /// Where the method stands.
    state: StepperState,
    y1: Vec<f64>,
    ysti: Vec<f64>,
    /// k[0] = f(t, y) (FSAL), k[1..6] stages 2..6, k[6] = f(t + h, y1).
    k: [Vec<f64>; 7],
    err: Vec<f64>,
    /// Dense output coefficients CONT of the last accepted step.
    cont: [Vec<f64>; 5],
    facold: f64,
    reject: bool,
    attempts: usize,
    iasti: usize,
    nonsti: usize,
    stiff_at: Option<f64>,
    /// Accepted steps between stiffness tests until one is suspicious (NSTIFF).
    nstiff: usize,
    /// The last stiffness test's h·ρ̂ (HLAMB).
    hlamb: f64,
    /// Whether a step so far read where the run ends: shortened to land on it, or sized by
    /// the largest step (the span by default) or by the distance to it ([`Stepper::resume`]).
    end_read: bool,
    stats: Stats,
}

impl Dopri5 {
    /// Dormand–Prince for `dim` unknowns with the given step control, largest step and
    /// step limit (NMAX).
    pub fn new(control: StepControl, h_max: f64, max_steps: usize, dim: usize) -> Self {
        let v = || vec![0.0; dim];
        Dopri5 {
            control,
            h_max,
            max_steps,
            t_start: 0.0,
            state: StepperState::new(dim),
            y1: v(),
            ysti: v(),
            k: [v(), v(), v(), v(), v(), v(), v()],
            err: v(),
            cont: [v(), v(), v(), v(), v()],
            facold: FACOLD_MIN,
            reject: false,
            attempts: 0,
            iasti: 0,
            nonsti: 0,
            stiff_at: None,
            nstiff: NSTIFF,
            hlamb: 0.0,
            end_read: false,
            stats: Stats::default(),
        }
    }

    /// The stiffness test taken every `n` accepted steps until one is suspicious (dopri5.f's
    /// NSTIFF, IWORK(4), 1000 by default).
    pub fn with_stiffness_test_every(mut self, n: usize) -> Self {
        self.nstiff = n.max(1);
        self
    }

    /// Stiff verdicts in a row since the last non-stiff ones (IASTI): [`STIFF_COUNT`] means
    /// the problem is stiff.
    pub fn stiffness_verdicts(&self) -> usize {
        self.iasti
    }

    /// The last stiffness test's h·ρ̂ (HLAMB; 0 before the first).
    pub fn stiffness_estimate(&self) -> f64 {
        self.hlamb
    }

    /// HINIT of dopri5.f: an explicit Euler step of size 0.01·‖y0‖/‖f0‖ estimates the second
    /// derivative; h is chosen so that h⁵·max(‖f0‖, ‖y''‖) = 0.01.
    fn hinit(&mut self, ode: &Ode, rtol: f64, atol: f64, t_stop: f64) -> f64 {
        let (y, f0) = (&self.state.y, &self.k[0]);
        let sk = |i: usize| atol + rtol * y[i].abs();
        let dnf: f64 = (0..y.len()).map(|i| (f0[i] / sk(i)).powi(2)).sum();
        let dny: f64 = (0..y.len()).map(|i| (y[i] / sk(i)).powi(2)).sum();
        let mut h = if dnf <= 1e-10 || dny <= 1e-10 {
            1e-6
        } else {
            (dny / dnf).sqrt() * 0.01
        };
        self.end_read |= h > self.h_max.min(t_stop - self.state.t);
        h = h.min(self.h_max).min(t_stop - self.state.t);
        for i in 0..y.len() {
            self.y1[i] = y[i] + h * f0[i];
        }
        let (y1, f1) = (&self.y1, &mut self.k[1]);
        ode.explicit_rhs(self.state.t + h, y1, f1, &mut self.stats);
        let der2: f64 = (0..y.len())
            .map(|i| ((self.k[1][i] - self.k[0][i]) / sk(i)).powi(2))
            .sum::<f64>()
            .sqrt()
            / h;
        let der12 = der2.abs().max(dnf.sqrt());
        let h1 = if der12 <= 1e-15 {
            (h * 1e-3).max(1e-6)
        } else {
            (0.01 / der12).powf(1.0 / HINIT_ORDER)
        };
        self.end_read |= (100.0 * h).min(h1) > self.h_max;
        (100.0 * h).min(h1).min(self.h_max)
    }

    /// The six stages, the fifth-order solution `y1`, f at its end (`k[6]`, FSAL) and the
    /// error estimate `err = h·Σ E_i k_i`, each sum taken in `dopri5.f`'s order.
    fn stages(&mut self, ode: &Ode, h: f64) {
        let t = self.state.t;
        let y = &self.state.y[..];
        let [k1, k2, k3, k4, k5, k6, k7] = &mut self.k;
        let k1 = &*k1;
        let y1 = &mut self.y1[..];
        // Y1 = Y + H*A21*K1: (H*A21) first, as the Fortran multiplies.
        let (ha21, k1s, ys) = (h * A21, &k1[..y1.len()], &y[..y1.len()]);
        for (i, out) in y1.iter_mut().enumerate() {
            *out = ys[i] + ha21 * k1s[i];
        }
        ode.explicit_rhs(t + C2 * h, y1, k2, &mut self.stats);
        let k2 = &*k2;
        stage(y1, y, h, [A31, A32], [k1, k2]);
        ode.explicit_rhs(t + C3 * h, y1, k3, &mut self.stats);
        let k3 = &*k3;
        stage(y1, y, h, [A41, A42, A43], [k1, k2, k3]);
        ode.explicit_rhs(t + C4 * h, y1, k4, &mut self.stats);
        let k4 = &*k4;
        stage(y1, y, h, [A51, A52, A53, A54], [k1, k2, k3, k4]);
        ode.explicit_rhs(t + C5 * h, y1, k5, &mut self.stats);
        let k5 = &*k5;
        let ysti = &mut self.ysti[..];
        stage(ysti, y, h, [A61, A62, A63, A64, A65], [k1, k2, k3, k4, k5]);
        ode.explicit_rhs(t + h, ysti, k6, &mut self.stats);
        let k6 = &*k6;
        stage(y1, y, h, [A71, A73, A74, A75, A76], [k1, k3, k4, k5, k6]);
        ode.explicit_rhs(t + h, y1, k7, &mut self.stats);
        let k = [k1, k3, k4, k5, k6, &*k7].map(|k| &k[..]);
        for (i, e) in self.err.iter_mut().enumerate() {
            *e = h * weighted(&[E1, E3, E4, E5, E6, E7], &k, i);
        }
    }

    /// Stiffness test of DOPCOR, run as the step is accepted (NACCPT already counting it):
    /// h·λ ≈ h·‖k7 − k6‖/‖y1 − ysti‖.
    fn stiffness_test(&mut self, h: f64) {
        let accepted = self.stats.steps + 1;
        if !accepted.is_multiple_of(self.nstiff) && self.iasti == 0 {
            return;
        }
        let num: f64 = self.k[6]
            .iter()
            .zip(&self.k[5])
            .map(|(a, b)| (a - b).powi(2))
            .sum();
        let den: f64 = self
            .y1
            .iter()
            .zip(&self.ysti)
            .map(|(a, b)| (a - b).powi(2))
            .sum();
        let hlamb = if den > 0.0 {
            h * (num / den).sqrt()
        } else {
            0.0
        };
        self.hlamb = hlamb;
        if hlamb > STIFF_HLAMB {
            self.nonsti = 0;
            self.iasti += 1;
            if self.iasti == STIFF_COUNT && self.stiff_at.is_none() {
                self.stiff_at = Some(self.state.t);
            }
        } else {
            self.nonsti += 1;
            if self.nonsti == NONSTIFF_COUNT {
                self.iasti = 0;
            }
        }
    }

    /// Accepts the step just computed: dense output coefficients, FSAL, new time.
    fn accept(&mut self, h: f64, t_new: f64) -> Result<(), SolverError> {
        check_finite(&self.y1, self.state.t, h, "Dormand-Prince step result")?;
        // f at the step's end enters the dense output and is the next step's first stage
        // (FSAL): a finite end whose derivative is not would hand NaN to the event location.
        check_finite(
            &self.k[6],
            self.state.t,
            h,
            "Dormand-Prince f at the step's end",
        )?;
        let [c0, c1, c2, c3, c4] = &mut self.cont;
        let k = &self.k;
        for i in 0..self.state.y.len() {
            let ydiff = self.y1[i] - self.state.y[i];
            let bspl = h * k[0][i] - ydiff;
            c0[i] = self.state.y[i];
            c1[i] = ydiff;
            c2[i] = bspl;
            c3[i] = -h * k[6][i] + ydiff - bspl;
            c4[i] = h
                * (D1 * k[0][i]
                    + D3 * k[2][i]
                    + D4 * k[3][i]
                    + D5 * k[4][i]
                    + D6 * k[5][i]
                    + D7 * k[6][i]);
        }
        let [k1, .., k7] = &mut self.k;
        std::mem::swap(k1, k7);
        std::mem::swap(&mut self.state.y, &mut self.y1);
        self.state.t_prev = self.state.t;
        self.state.t = t_new;
        self.stats.steps += 1;
        Ok(())
    }
}

impl Stepper for Dopri5 {
    fn name(&self) -> &'static str {
        "dopri5"
    }

    fn start(&mut self, ode: &Ode, t: f64, y: &[f64]) -> Result<(), SolverError> {
        ode.require_regular_mass("dopri5")?;
        self.t_start = t;
        self.state.t_prev = t;
        self.state.t = t;
        self.state.y.copy_from_slice(y);
        self.facold = FACOLD_MIN;
        self.reject = false;
        self.iasti = 0;
        self.nonsti = 0;
        ode.explicit_rhs(t, y, &mut self.k[0], &mut self.stats);
        // Zero: HINIT chooses the first step.
        self.state.h = self.control.given_step().unwrap_or(0.0);
        Ok(())
    }

    fn step(&mut self, ode: &Ode, t_stop: f64) -> Result<(), SolverError> {
        let (rtol, atol) = match self.control {
            StepControl::Fixed { h } => {
                let t_new = next_grid_point(self.t_start, h, self.state.t, t_stop);
                self.end_read |= t_new == t_stop;
                let step = t_new - self.state.t;
                self.attempts += 1;
                check_limits(self.attempts, self.max_steps, self.state.t, step)?;
                self.stages(ode, step);
                return self.accept(step, t_new);
            }
            StepControl::Adaptive { rtol, atol, .. } => (rtol, atol),
        };
        if self.state.h == 0.0 {
            self.state.h = self.hinit(ode, rtol, atol, t_stop);
        }
        loop {
            let mut h = self.state.h;
            self.attempts += 1;
            check_limits(self.attempts, self.max_steps, self.state.t, h)?;
            let last = self.state.t + 1.01 * h - t_stop > 0.0;
            if last {
                h = t_stop - self.state.t;
                self.end_read = true;
            }
            self.stages(ode, h);
            let err = wrms(&self.err, &self.state.y, &self.y1, rtol, atol);
            if !err.is_finite() {
                // A NaN error estimate cannot steer the step: cut it as FAC1 would.
                self.stats.rejected_error += 1;
                self.reject = true;
                self.state.h = h * FAC1;
                continue;
            }
            let fac11 = err.powf(EXPO1);
            // Lund stabilisation, limited so that FAC1 <= hnew/h <= FAC2.
            let fac = (fac11 / self.facold.powf(BETA) / SAFE).clamp(1.0 / FAC2, 1.0 / FAC1);
            let h_new = h / fac;
            if err <= 1.0 {
                self.facold = err.max(FACOLD_MIN);
                self.stiffness_test(h);
                self.accept(h, if last { t_stop } else { self.state.t + h })?;
                // On the last step DOPCOR returns H = HNEW before the HMAX and REJECT limits.
                self.state.h = if last {
                    h_new
                } else {
                    self.end_read |= h_new > self.h_max;
                    match self.reject {
                        true => h_new.min(self.h_max).min(h),
                        false => h_new.min(self.h_max),
                    }
                };
                self.reject = false;
                return Ok(());
            }
            self.reject = true;
            self.stats.rejected_error += 1;
            self.state.h = h / (1.0 / FAC1).min(fac11 / SAFE);
        }
    }

    fn state(&self) -> &StepperState {
        &self.state
    }

    /// CONTD5: `u(θ) = c0 + θ(c1 + (1−θ)(c2 + θ(c3 + (1−θ)c4)))`, θ = (t − t_old)/h.
    fn dense_output(&self, t: f64, out: &mut [f64]) {
        let h = self.state.t - self.state.t_prev;
        if h == 0.0 {
            out.copy_from_slice(&self.state.y);
            return;
        }
        let th = (t - self.state.t_prev) / h;
        let th1 = 1.0 - th;
        let [c0, c1, c2, c3, c4] = &self.cont;
        for (i, o) in out.iter_mut().enumerate() {
            *o = c0[i] + th * (c1[i] + th1 * (c2[i] + th * (c3[i] + th1 * c4[i])));
        }
    }

    fn stats(&self) -> Stats {
        self.stats
    }

    fn stiffness_detected_at(&self) -> Option<f64> {
        self.stiff_at
    }

    fn copy(&self) -> Option<Box<dyn Stepper>> {
        Some(Box::new(self.clone()))
    }

    /// The next step reads the end when it is the first after a (re)start (HINIT sizes it
    /// by the distance to the end), when it would come within 1 % of a step of the end
    /// (DOPCOR's `X+1.01D0*H-XEND`), or, at a fixed step, when it lands on the end.
    fn may_read_end(&self, t_stop: f64) -> bool {
        let (t, h) = (self.state.t, self.state.h);
        match self.control {
            StepControl::Fixed { h } => next_grid_point(self.t_start, h, t, t_stop) == t_stop,
            StepControl::Adaptive { .. } => h == 0.0 || t + 1.01 * h - t_stop > 0.0,
        }
    }

    fn resume(&mut self, options: &Options) -> bool {
        self.h_max = options.h_max();
        self.max_steps = options.max_steps;
        !self.end_read
    }
}
