//! RODAS, the Rosenbrock method of order 4(3) of Hairer and Wanner, as in E. Hairer's
//! `rodas.f` (version of 1996, subroutines RODAS, ROSCOR, ROCOE, SLVROD, CONTRO; Hairer &
//! Wanner, *Solving ODEs II*, 2nd ed., sec. VI.4): six stages with one LU factorisation of
//! `M/(h·γ) − J` a step and no Newton iteration, the coefficients of ROCOE's first set
//! (METH = 1, Hairer & Wanner's Table VI.4.x), the embedded third-order error estimate,
//! Gustafsson's predictive step-size controller, and the dense output of order 3 (CONTRO).
//! Stiffly accurate and L-stable; linearly implicit, so a Jacobian that jumps at v = 0 never
//! stalls an iteration. Constants are named as in the Fortran; dense matrices go through
//! `decsol.f`'s DEC/SOL, so runs match `rodas.f`'s count for count.
//!
//! A problem's explicit time dependence enters through `∂f/∂t`, taken by forward differences
//! as ROSCOR takes it when IFCN = 1 and no DFX is given: exactly zero for an autonomous
//! problem, so such a run equals rodas.f's with IFCN = 0. That evaluation of f, like those of
//! a finite-difference Jacobian, is not counted in `rhs_evals`. A problem's quadratures, whose
//! rows its Jacobian leaves out, get their part of each stage from one more (counted)
//! evaluation of f, a directional derivative (`Rodas::complete_quadratures`).

// ROCOE's coefficients are Hairer's 16-digit literals, kept as he wrote them.
#![allow(clippy::excessive_precision)]

use crate::error::SolverError;
use crate::iteration_matrix::RealSystem;
use crate::method::{adaptive_only, OneStepMethod};
use crate::newton;
use crate::options::Options;
use crate::problem::Entry;
use crate::stats::Stats;
use crate::stepper::{check_finite, Ode, Stepper, StepperState};

// The defaults of RODAS (its IWORK and WORK entries left at 0).
/// UROUND, the rounding unit (WORK(1)).
const UROUND: f64 = 1e-16;
/// FAC1 and FAC2: the new step is at least h/FAC1 and at most h/FAC2 (FAC1 = 1/WORK(3) with
/// WORK(3) = 0.2, FAC2 = 1/WORK(4) with WORK(4) = 6).
const FAC1: f64 = 5.0;
const FAC2: f64 = 1.0 / 6.0;
/// SAFE, the safety factor of the step-size prediction (WORK(5)).
const SAFE: f64 = 0.9;
/// The first step when none is given (ROSCOR: `IF (ABS(H).LE.10.D0*UROUND) H=1.0D-6`).
const H_DEFAULT: f64 = 1e-6;
/// Singular factorisations before ROSCOR gives up (label 80: `NSING.GE.5`).
const MAX_SINGULAR: usize = 5;

// ROCOE, METH = 1: the coefficients of RODAS.
const C2: f64 = 0.386;
const C3: f64 = 0.21;
const C4: f64 = 0.63;
const D1: f64 = 0.25;
const D2: f64 = -0.1043;
const D3: f64 = 0.1035;
const D4: f64 = -0.3620000000000023e-01;
const A21: f64 = 0.1544000000000000e+01;
const A31: f64 = 0.9466785280815826;
const A32: f64 = 0.2557011698983284;
const A41: f64 = 0.3314825187068521e+01;
const A42: f64 = 0.2896124015972201e+01;
const A43: f64 = 0.9986419139977817;
const A51: f64 = 0.1221224509226641e+01;
const A52: f64 = 0.6019134481288629e+01;
const A53: f64 = 0.1253708332932087e+02;
const A54: f64 = -0.6878860361058950;
const C21: f64 = -0.5668800000000000e+01;
const C31: f64 = -0.2430093356833875e+01;
const C32: f64 = -0.2063599157091915;
const C41: f64 = -0.1073529058151375;
const C42: f64 = -0.9594562251023355e+01;
const C43: f64 = -0.2047028614809616e+02;
const C51: f64 = 0.7496443313967647e+01;
const C52: f64 = -0.1024680431464352e+02;
const C53: f64 = -0.3399990352819905e+02;
const C54: f64 = 0.1170890893206160e+02;
const C61: f64 = 0.8083246795921522e+01;
const C62: f64 = -0.7981132988064893e+01;
const C63: f64 = -0.3152159432874371e+02;
const C64: f64 = 0.1631930543123136e+02;
const C65: f64 = -0.6058818238834054e+01;
const GAMMA: f64 = 0.25;
const D21: f64 = 0.1012623508344586e+02;
const D22: f64 = -0.7487995877610167e+01;
const D23: f64 = -0.3480091861555747e+02;
const D24: f64 = -0.7992771707568823e+01;
const D25: f64 = 0.1025137723295662e+01;
const D31: f64 = -0.6762803392801253;
const D32: f64 = 0.6087714651680015e+01;
const D33: f64 = 0.1643084320892478e+02;
const D34: f64 = 0.2476722511418386e+02;
const D35: f64 = -0.6594389125716872e+01;

/// RODAS as a method (`rodas`): Rosenbrock, order 4, adaptive.
#[derive(Clone, Copy, Debug)]
pub struct RodasMethod;

impl OneStepMethod for RodasMethod {
    fn name(&self) -> &'static str {
        "rodas"
    }

    fn order(&self) -> usize {
        4
    }

    fn is_implicit(&self) -> bool {
        true
    }

    fn is_fixed_step(&self) -> bool {
        false
    }

    fn stepper(&self, options: &Options, dim: usize) -> Result<Box<dyn Stepper>, SolverError> {
        let (rtol, atol, h0) = adaptive_only("rodas", options.step)?;
        let (h_max, max_steps) = (options.h_max(), options.max_steps);
        Ok(Box::new(Rodas::new(rtol, atol, h0, h_max, max_steps, dim)?))
    }
}

/// Hairer's RODAS (ROSCOR) for `n` unknowns.
pub struct Rodas {
    rtol: f64,
    atol: f64,
    h0: Option<f64>,
    h_max: f64,
    max_steps: usize,
    state: StepperState,
    /// DY1 (f at the step's start), FX (∂f/∂t), DY (f at a stage), YNEW, and AK1..AK6.
    dy1: Vec<f64>,
    fx: Vec<f64>,
    dy: Vec<f64>,
    ynew: Vec<f64>,
    /// Scratch for the quadratures' directional derivative: its argument and f there.
    arg: Vec<f64>,
    jq: Vec<f64>,
    /// The step size of the stages being computed.
    h_stage: f64,
    ak: [Vec<f64>; 6],
    /// CONT of the last accepted step: y at its start, at its end, and the two corrections.
    cont: [Vec<f64>; 4],
    jac: Vec<Entry>,
    /// Whether the problem has quadratures and the Jacobian left their rows out (then each
    /// stage completes them: `complete_quadratures`), decided once per Jacobian.
    quadrature_rows_missing: bool,
    system: RealSystem,
    /// HOUT: the size of the last accepted step, which CONTRO divides by.
    hout: f64,
    fresh: bool,
    hmaxn: f64,
    reject: bool,
    hacc: f64,
    erracc: f64,
    nsing: usize,
    attempts: usize,
    stats: Stats,
}

impl Rodas {
    /// RODAS for `dim` unknowns at tolerances `rtol`, `atol`, with first step `h0` (1e-6 when
    /// absent), largest step `h_max` and at most `max_steps` attempts (NMAX).
    pub fn new(
        rtol: f64,
        atol: f64,
        h0: Option<f64>,
        h_max: f64,
        max_steps: usize,
        dim: usize,
    ) -> Result<Self, SolverError> {
        // RODAS, "CHECK IF TOLERANCES ARE O.K.".
        if rtol <= 10.0 * UROUND {
            return Err(SolverError::InvalidOption {
                name: "rtol",
                value: rtol,
                allowed: "(1e-15, inf) for rodas (10·UROUND)",
            });
        }
        let v = || vec![0.0; dim];
        Ok(Rodas {
            rtol,
            atol,
            h0,
            h_max,
            max_steps,
            state: StepperState::new(dim),
            dy1: v(),
            fx: v(),
            dy: v(),
            ynew: v(),
            arg: v(),
            jq: v(),
            h_stage: 0.0,
            ak: [v(), v(), v(), v(), v(), v()],
            cont: [v(), v(), v(), v()],
            jac: Vec::new(),
            quadrature_rows_missing: false,
            system: RealSystem::for_size(dim, dim * dim),
            hout: 0.0,
            fresh: true,
            hmaxn: h_max,
            reject: false,
            hacc: 0.0,
            erracc: 0.0,
            nsing: 0,
            attempts: 0,
            stats: Stats::default(),
        })
    }

    /// Label 1's work at (t, y): DY1 = f(t, y), the Jacobian, and FX = ∂f/∂t by forward
    /// differences.
    fn linearise(&mut self, ode: &Ode) {
        let (t, y) = (self.state.t, &self.state.y);
        ode.rhs(t, y, &mut self.dy1, &mut self.stats);
        newton::jacobian(ode, t, y, &self.dy1, &mut self.jac, &mut self.stats);
        let q = y.len() - ode.problem.quadratures();
        self.quadrature_rows_missing = q < y.len() && self.jac.iter().all(|&(i, _, _)| i < q);
        if !self.system.suits(y.len(), self.jac.len()) {
            self.system = RealSystem::for_size(y.len(), self.jac.len());
        }
        let delt = (UROUND * t.abs().max(1e-5)).sqrt();
        ode.problem.rhs(t + delt, y, ode.modes, &mut self.dy);
        for (fx, (a, b)) in self.fx.iter_mut().zip(self.dy.iter().zip(&self.dy1)) {
            *fx = (a - b) / delt;
        }
    }

    /// SLVROD: `AK_s = E⁻¹·(f + HD·FX + M·YNEW)`, with `f` the stage's value of f (DY1 for
    /// the first stage, which adds no YNEW).
    fn solve_stage(&mut self, ode: &Ode, s: usize, hd: f64) {
        let mass = ode.problem.mass();
        let f = if s == 0 { &self.dy1 } else { &self.dy };
        let ak = &mut self.ak[s];
        for i in 0..ak.len() {
            ak[i] = if hd == 0.0 {
                f[i]
            } else {
                f[i] + hd * self.fx[i]
            };
            if s > 0 {
                ak[i] += mass.map_or(1.0, |m| m[i]) * self.ynew[i];
            }
        }
        self.system.solve(ak);
        self.complete_quadratures(ode, s);
    }

    /// The quadratures' part of stage `s` where the Jacobian leaves out their rows
    /// ([`crate::OdeProblem::quadratures`]): no other unknown reads them, so E is block
    /// lower-triangular and their increments are `AK_q += (J_q·AK)/(m_q·fac)`, with `J_q·AK`
    /// by one forward difference of f along AK at the step's start (one more evaluation of f,
    /// counted). Without it a Rosenbrock method, whose order conditions assume the exact
    /// Jacobian, integrates them to first order only.
    fn complete_quadratures(&mut self, ode: &Ode, s: usize) {
        let n = self.state.y.len();
        let q = n - ode.problem.quadratures();
        if !self.quadrature_rows_missing {
            return;
        }
        let ak = &self.ak[s];
        let size = ak[..q].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if size == 0.0 {
            return;
        }
        let scale = self.state.y[..q].iter().fold(1.0f64, |m, v| m.max(v.abs()));
        let delta = UROUND.sqrt() * scale / size;
        for (i, (a, y)) in self.arg.iter_mut().zip(&self.state.y).enumerate() {
            *a = y + if i < q { delta * ak[i] } else { 0.0 };
        }
        ode.rhs(self.state.t, &self.arg, &mut self.jq, &mut self.stats);
        let mass = ode.problem.mass();
        let fac = 1.0 / (self.h_stage * GAMMA);
        let ak = &mut self.ak[s];
        for i in q..n {
            let derivative = (self.jq[i] - self.dy1[i]) / delta;
            ak[i] += derivative / (mass.map_or(1.0, |m| m[i]) * fac);
        }
    }

    /// The six stages of a step of size h from (t, y), the new solution in YNEW, its error
    /// estimate in AK6, and the dense output's corrections; then the error norm.
    fn stages(&mut self, ode: &Ode, h: f64) -> f64 {
        let (t, n) = (self.state.t, self.state.y.len());
        self.h_stage = h;
        let hd = [D1, D2, D3, D4].map(|d| h * d);
        let hc = |c: f64| c / h;
        self.solve_stage(ode, 0, hd[0]);
        // Stage 2.
        for i in 0..n {
            self.ynew[i] = self.state.y[i] + A21 * self.ak[0][i];
        }
        ode.rhs(t + C2 * h, &self.ynew, &mut self.dy, &mut self.stats);
        for i in 0..n {
            self.ynew[i] = hc(C21) * self.ak[0][i];
        }
        self.solve_stage(ode, 1, hd[1]);
        // Stage 3.
        let [a1, a2, ..] = &self.ak;
        for i in 0..n {
            self.ynew[i] = self.state.y[i] + A31 * a1[i] + A32 * a2[i];
        }
        ode.rhs(t + C3 * h, &self.ynew, &mut self.dy, &mut self.stats);
        let [a1, a2, ..] = &self.ak;
        for i in 0..n {
            self.ynew[i] = hc(C31) * a1[i] + hc(C32) * a2[i];
        }
        self.solve_stage(ode, 2, hd[2]);
        // Stage 4.
        let [a1, a2, a3, ..] = &self.ak;
        for i in 0..n {
            self.ynew[i] = self.state.y[i] + A41 * a1[i] + A42 * a2[i] + A43 * a3[i];
        }
        ode.rhs(t + C4 * h, &self.ynew, &mut self.dy, &mut self.stats);
        let [a1, a2, a3, ..] = &self.ak;
        for i in 0..n {
            self.ynew[i] = hc(C41) * a1[i] + hc(C42) * a2[i] + hc(C43) * a3[i];
        }
        self.solve_stage(ode, 3, hd[3]);
        // Stage 5: YNEW is the fourth-order solution's first part; AK6 holds the combination.
        let [a1, a2, a3, a4, ..] = &self.ak;
        for i in 0..n {
            self.ynew[i] = self.state.y[i] + A51 * a1[i] + A52 * a2[i] + A53 * a3[i] + A54 * a4[i];
        }
        ode.rhs(t + h, &self.ynew, &mut self.dy, &mut self.stats);
        let mass = ode.problem.mass();
        let [a1, a2, a3, a4, a5, a6] = &mut self.ak;
        for i in 0..n {
            a6[i] = hc(C52) * a2[i] + hc(C54) * a4[i] + hc(C51) * a1[i] + hc(C53) * a3[i];
        }
        for i in 0..n {
            a5[i] = self.dy[i] + mass.map_or(1.0, |m| m[i]) * a6[i];
        }
        self.system.solve(a5);
        self.complete_quadratures(ode, 4);
        // Stage 6: the embedded estimate.
        for i in 0..n {
            self.ynew[i] += self.ak[4][i];
        }
        ode.rhs(t + h, &self.ynew, &mut self.dy, &mut self.stats);
        let [a1, a2, a3, a4, a5, _] = &self.ak;
        let c = &mut self.cont[0];
        for i in 0..n {
            c[i] = hc(C61) * a1[i]
                + hc(C62) * a2[i]
                + hc(C65) * a5[i]
                + hc(C64) * a4[i]
                + hc(C63) * a3[i];
        }
        let a6 = &mut self.ak[5];
        for i in 0..n {
            a6[i] = self.dy[i] + mass.map_or(1.0, |m| m[i]) * self.cont[0][i];
        }
        self.system.solve(a6);
        self.complete_quadratures(ode, 5);
        for i in 0..n {
            self.ynew[i] += self.ak[5][i];
        }
        self.stats.linear_solves += 6;
        // The dense output's corrections (IOUT ≠ 0).
        let [a1, a2, a3, a4, a5, _] = &self.ak;
        let [c0, _, c2, c3] = &mut self.cont;
        for i in 0..n {
            c0[i] = self.state.y[i];
            c2[i] = D21 * a1[i] + D22 * a2[i] + D23 * a3[i] + D24 * a4[i] + D25 * a5[i];
            c3[i] = D31 * a1[i] + D32 * a2[i] + D33 * a3[i] + D34 * a4[i] + D35 * a5[i];
        }
        let mut err = 0.0;
        for i in 0..n {
            let sk = self.atol + self.rtol * self.state.y[i].abs().max(self.ynew[i].abs());
            err += (self.ak[5][i] / sk).powi(2);
        }
        (err / n as f64).sqrt()
    }
}

impl Stepper for Rodas {
    fn name(&self) -> &'static str {
        "rodas"
    }

    /// ROSCOR's initialisation at (t, y): the given first step, or 1e-6; a restart (after an
    /// event) keeps the step size reached.
    fn start(&mut self, _ode: &Ode, t: f64, y: &[f64]) -> Result<(), SolverError> {
        self.state.t_prev = t;
        self.state.t = t;
        self.state.y.copy_from_slice(y);
        if self.state.h == 0.0 {
            self.state.h = self.h0.unwrap_or(H_DEFAULT);
        }
        if self.state.h.abs() <= 10.0 * UROUND {
            self.state.h = H_DEFAULT;
        }
        self.reject = false;
        self.fresh = true;
        self.nsing = 0;
        Ok(())
    }

    fn step(&mut self, ode: &Ode, t_stop: f64) -> Result<(), SolverError> {
        let t = self.state.t;
        if self.fresh {
            self.hmaxn = self.h_max.abs().min((t_stop - t).abs());
            self.state.h = self.state.h.abs().min(self.hmaxn);
            self.fresh = false;
        }
        // Label 1.
        let hopt = self.state.h;
        let mut last = false;
        if t + self.state.h * 1.0001 - t_stop >= 0.0 {
            self.state.h = t_stop - t;
            last = true;
        }
        self.linearise(ode);
        loop {
            let h = self.state.h;
            self.attempts += 1;
            if self.attempts > self.max_steps {
                return Err(SolverError::TooManySteps {
                    t,
                    h,
                    max: self.max_steps,
                });
            }
            if 0.1 * h.abs() <= t.abs() * UROUND {
                return Err(SolverError::StepSizeUnderflow { t, h });
            }
            // Label 2: E = M/(h·γ) − J.
            let fac = 1.0 / (h * GAMMA);
            if !self
                .system
                .factor(self.state.y.len(), &self.jac, ode.problem.mass(), fac)
            {
                // Label 80.
                self.nsing += 1;
                if self.nsing >= MAX_SINGULAR {
                    return Err(SolverError::SingularMatrix { t, h });
                }
                self.state.h *= 0.5;
                self.reject = true;
                last = false;
                continue;
            }
            self.stats.lu_factorizations += 1;
            let err = self.stages(ode, h);
            if !err.is_finite() {
                // No estimate to steer by: cut as a singular matrix would be cut.
                self.stats.rejected_error += 1;
                self.state.h *= 0.5;
                self.reject = true;
                last = false;
                continue;
            }
            let mut fac = FAC2.max(FAC1.min(err.powf(0.25) / SAFE));
            let mut hnew = h / fac;
            if err > 1.0 {
                self.reject = true;
                last = false;
                self.state.h = hnew;
                self.stats.rejected_error += 1;
                continue;
            }
            // Accepted, with Gustafsson's predictive controller.
            self.stats.steps += 1;
            if self.stats.steps > 1 {
                let facgus = (self.hacc / h) * (err * err / self.erracc).powf(0.25) / SAFE;
                fac = fac.max(FAC2.max(FAC1.min(facgus)));
                hnew = h / fac;
            }
            self.hacc = h;
            self.erracc = err.max(1e-2);
            check_finite(&self.ynew, t, h, "Rosenbrock step result")?;
            std::mem::swap(&mut self.state.y, &mut self.ynew);
            self.cont[1].copy_from_slice(&self.state.y);
            self.hout = h;
            self.state.t_prev = t;
            self.state.t = if last { t_stop } else { t + h };
            if hnew.abs() > self.hmaxn {
                hnew = self.hmaxn;
            }
            if self.reject {
                hnew = hnew.min(h);
            }
            self.reject = false;
            // ROSCOR returns H = HOPT after its last step.
            self.state.h = if last { hopt } else { hnew };
            return Ok(());
        }
    }

    fn state(&self) -> &StepperState {
        &self.state
    }

    /// CONTRO: `y0·(1 − s) + s·(y1 + (1 − s)·(c2 + s·c3))`, s = (t − t_prev)/HOUT.
    fn dense_output(&self, t: f64, out: &mut [f64]) {
        if self.hout == 0.0 || self.state.t == self.state.t_prev {
            out.copy_from_slice(&self.state.y);
            return;
        }
        let s = (t - self.state.t_prev) / self.hout;
        let [c0, c1, c2, c3] = &self.cont;
        for (i, o) in out.iter_mut().enumerate() {
            *o = c0[i] * (1.0 - s) + s * (c1[i] + (1.0 - s) * (c2[i] + s * c3[i]));
        }
    }

    fn stats(&self) -> Stats {
        self.stats
    }
}
