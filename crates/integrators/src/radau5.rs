//! Radau IIA of order 5 (three stages, stiffly accurate, L-stable) as in E. Hairer's
//! `radau5.f` (version of 2002; Hairer & Wanner, *Solving ODEs II*, 2nd ed., sec. IV.8):
//! the simplified Newton iteration on the transformed system, one real and one complex
//! linear system of order n per iteration (subroutines RADCOR, DECOMR, DECOMC, SLVRAD); the
//! tolerance transformation of RADAU5; the error estimate filtered through the real matrix
//! (ESTRAD); the predictive step-size controller of Gustafsson; the starting values from the
//! last step's collocation polynomial; and its dense output (CONTR5). Constants are named as
//! in the Fortran and traced to the statement that sets them; the dense linear algebra is
//! `decsol.f`'s ([`crate::decsol`]), so that a run matches `radau5.f`'s count for count, and
//! a sparse Jacobian goes to faer's sparse LU ([`crate::iteration_matrix`]).
//!
//! The mass matrix is diagonal ([`crate::OdeProblem::mass`]); zeros on it make an index-1
//! DAE, which the method integrates as it stands. Events are located by the driver on the
//! dense output, as for every method. A problem's quadratures
//! ([`crate::OdeProblem::quadratures`]: energy accumulators that no component of f reads)
//! are left out of the Newton norm, as implicit Euler leaves them out (their corrections are
//! the whole change of `h·A·f_q` between iterates), and set from the converged stages,
//! `M_q·Z_q = h·A·f_q(Y)`, at the price of one more evaluation of f at each stage; they stay
//! in the error estimate. A problem without quadratures runs exactly as `radau5.f`.

// T and T⁻¹ are Hairer's 20-digit literals, kept as he wrote them.
#![allow(clippy::excessive_precision)]

use crate::error::SolverError;
use crate::iteration_matrix::RadauSystems;
use crate::method::{adaptive_only, OneStepMethod};
use crate::newton;
use crate::options::Options;
use crate::problem::Entry;
use crate::stats::Stats;
use crate::stepper::{check_finite, Ode, Stepper, StepperState};

// The defaults of RADAU5 (its IWORK and WORK entries left at 0).
/// UROUND, the rounding unit (WORK(1)).
const UROUND: f64 = 1e-16;
/// SAFE, the safety factor of the step-size prediction (WORK(2)).
const SAFE: f64 = 0.9;
/// THET: the Jacobian is recomputed after a step whose Newton contraction exceeded it
/// (WORK(3)).
const THET: f64 = 0.001;
/// QUOT1 and QUOT2: a new step size within QUOT1·h..QUOT2·h keeps h and the factorisations
/// (WORK(5), WORK(6)).
const QUOT1: f64 = 1.0;
const QUOT2: f64 = 1.2;
/// FACL and FACR: the new step is at least h/FACL and at most h/FACR (FACL = 1/WORK(8) with
/// WORK(8) = 0.2, FACR = 1/WORK(9) with WORK(9) = 8).
const FACL: f64 = 5.0;
const FACR: f64 = 1.0 / 8.0;
/// NIT, the most Newton iterations a step (IWORK(3)).
const NIT: usize = 7;
/// The first step when none is given (RADCOR: `IF (ABS(H).LE.10.D0*UROUND) H=1.0D-6`).
const H_DEFAULT: f64 = 1e-6;
/// The exponent of RADAU5's tolerance transformation, `RTOL ← 0.1·RTOL^EXPM` (EXPM = 2/3).
const EXPM: f64 = 2.0 / 3.0;
/// Singular factorisations in a row before RADCOR gives up (label 78: `NSING.GE.5`).
const MAX_SINGULAR: usize = 5;

// The transformation matrices T and T⁻¹ of the Radau IIA(5) matrix (RADCOR, CONSTANTS).
const T11: f64 = 9.123_239_487_089_294_279_2e-02;
const T12: f64 = -0.141_255_295_020_954_208_43;
const T13: f64 = -3.002_919_410_514_742_449_2e-02;
const T21: f64 = 0.241_717_932_707_107_018_96;
const T22: f64 = 0.204_129_352_293_799_931_99;
const T23: f64 = 0.382_942_112_757_261_937_79;
const T31: f64 = 0.966_048_182_615_092_936_19;
const TI11: f64 = 4.325_579_890_063_155_351_0;
const TI12: f64 = 0.339_199_251_815_809_869_54;
const TI13: f64 = 0.541_770_539_935_874_871_19;
const TI21: f64 = -4.178_718_591_551_904_727_3;
const TI22: f64 = -0.327_682_820_761_062_387_08;
const TI23: f64 = 0.476_623_554_500_550_451_96;
const TI31: f64 = -0.502_872_634_945_786_875_95;
const TI32: f64 = 2.571_926_949_855_605_429_2;
const TI33: f64 = -0.596_039_204_828_224_924_97;

/// The nodes, error-estimate weights and eigenvalues of Radau IIA(5), computed as RADCOR
/// computes them (CONSTANTS), so that every rounding is the Fortran's.
#[derive(Clone, Copy, Debug)]
struct Coefficients {
    /// C1 = (4 − √6)/10 and C2 = (4 + √6)/10, the first two nodes (the third is 1).
    c1: f64,
    c2: f64,
    c1m1: f64,
    c2m1: f64,
    c1mc2: f64,
    /// DD1..DD3: the weights of the embedded error estimate.
    dd1: f64,
    dd2: f64,
    dd3: f64,
    /// U1: the real eigenvalue γ̂ of A⁻¹; ALPH ± i·BETA its complex pair.
    u1: f64,
    alph: f64,
    beta: f64,
    /// The Radau IIA(5) matrix A (Hairer & Wanner, *Solving ODEs II*, Table IV.5.6), for the
    /// quadratures' stages.
    a: [[f64; 3]; 3],
}

impl Coefficients {
    fn new() -> Self {
        let sq6 = 6f64.sqrt();
        let (c1, c2) = ((4.0 - sq6) / 10.0, (4.0 + sq6) / 10.0);
        let (cbrt81, cbrt9) = (81f64.powf(1.0 / 3.0), 9f64.powf(1.0 / 3.0));
        let u1 = (6.0 + cbrt81 - cbrt9) / 30.0;
        let alph = (12.0 - cbrt81 + cbrt9) / 60.0;
        let beta = (cbrt81 + cbrt9) * 3f64.sqrt() / 60.0;
        let cno = alph * alph + beta * beta;
        Coefficients {
            c1,
            c2,
            c1m1: c1 - 1.0,
            c2m1: c2 - 1.0,
            c1mc2: c1 - c2,
            dd1: -(13.0 + 7.0 * sq6) / 3.0,
            dd2: (-13.0 + 7.0 * sq6) / 3.0,
            dd3: -1.0 / 3.0,
            u1: 1.0 / u1,
            alph: alph / cno,
            beta: beta / cno,
            a: [
                [
                    (88.0 - 7.0 * sq6) / 360.0,
                    (296.0 - 169.0 * sq6) / 1800.0,
                    (-2.0 + 3.0 * sq6) / 225.0,
                ],
                [
                    (296.0 + 169.0 * sq6) / 1800.0,
                    (88.0 + 7.0 * sq6) / 360.0,
                    (-2.0 - 3.0 * sq6) / 225.0,
                ],
                [(16.0 - sq6) / 36.0, (16.0 + sq6) / 36.0, 1.0 / 9.0],
            ],
        }
    }
}

/// Radau IIA of order 5 as a method (`radau5`): implicit, adaptive.
#[derive(Clone, Copy, Debug)]
pub struct Radau5Method;

impl OneStepMethod for Radau5Method {
    fn name(&self) -> &'static str {
        "radau5"
    }

    fn order(&self) -> usize {
        5
    }

    fn is_implicit(&self) -> bool {
        true
    }

    fn is_fixed_step(&self) -> bool {
        false
    }

    fn stepper(&self, options: &Options, dim: usize) -> Result<Box<dyn Stepper>, SolverError> {
        let (rtol, atol, h0) = adaptive_only("radau5", options.step)?;
        let (h_max, max_steps) = (options.h_max(), options.max_steps);
        Ok(Box::new(Radau5::new(
            rtol, atol, h0, h_max, max_steps, dim,
        )?))
    }
}

/// Where RADCOR goes next: a new Jacobian (label 10), new factorisations (20), or a step
/// with the current ones (30).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Next {
    Jacobian,
    Factorize,
    Step,
}

/// Where [`Radau5::stage_rhs`] writes.
#[derive(Clone, Copy)]
enum Stages {
    Z,
    W,
}

/// What an attempt at a step ended in.
enum Attempt {
    Accepted,
    Retry,
}

/// Hairer's RADAU5 (RADCOR) for `n` unknowns.
#[derive(Clone)]
pub struct Radau5 {
    k: Coefficients,
    /// RTOL and ATOL after RADAU5's transformation.
    rtol: f64,
    atol: f64,
    /// FNEWT, Newton's stopping criterion.
    fnewt: f64,
    h0: Option<f64>,
    h_max: f64,
    max_steps: usize,
    /// Where the method stands; `state.h` is RADCOR's H, the step to try next.
    state: StepperState,
    /// Y0 of RADCOR: f(x, y) at the current point.
    f0: Vec<f64>,
    f0_known: bool,
    /// Z1..Z3 (the stage increments) and F1..F3 (their transforms W = (T⁻¹ ⊗ I)·Z).
    z: [Vec<f64>; 3],
    w: [Vec<f64>; 3],
    /// CONT(N+1..4N): the collocation polynomial of the last accepted step.
    cont: [Vec<f64>; 3],
    /// Scratch: a stage's argument, and the error estimate's two vectors.
    arg: Vec<f64>,
    est: Vec<f64>,
    scal: Vec<f64>,
    jac: Vec<Entry>,
    /// ‖J‖∞ of `jac`, and the row sums it is taken from (scratch).
    jac_norm: f64,
    row_sums: Vec<f64>,
    /// E1 and E2, factorised.
    systems: RadauSystems,
    next: Next,
    /// RADCOR's logical flags.
    first: bool,
    reject: bool,
    last: bool,
    caljac: bool,
    /// Whether the next step() must first set HMAXN and LAST against the end (RADCOR's
    /// initialisation, which needs XEND).
    fresh: bool,
    hmaxn: f64,
    /// Where HMAXN was last set against the end.
    hmaxn_at: f64,
    /// Whether a step so far read where the run ends: shortened to land on it, or sized by
    /// HMAXN, the distance to it or the largest step ([`Stepper::resume`]).
    end_read: bool,
    hold: f64,
    hopt: f64,
    faccon: f64,
    theta: f64,
    hacc: f64,
    erracc: f64,
    nsing: usize,
    attempts: usize,
    stats: Stats,
}

impl Radau5 {
    /// RADAU5 for `dim` unknowns at tolerances `rtol`, `atol` (transformed as RADAU5 does),
    /// with first step `h0` (1e-6 when absent), largest step `h_max` and at most `max_steps`
    /// attempts (NMAX).
    pub fn new(
        rtol: f64,
        atol: f64,
        h0: Option<f64>,
        h_max: f64,
        max_steps: usize,
        dim: usize,
    ) -> Result<Self, SolverError> {
        // RADAU5, "CHECK AND CHANGE THE TOLERANCES".
        if rtol <= 10.0 * UROUND {
            return Err(SolverError::InvalidOption {
                name: "rtol",
                value: rtol,
                allowed: "(1e-15, inf) for radau5 (10·UROUND)",
            });
        }
        let quot = atol / rtol;
        let rtol = 0.1 * rtol.powf(EXPM);
        let atol = rtol * quot;
        // RADAU5, "FNEWT": Newton stops when FACCON·‖ΔZ‖ ≤ FNEWT.
        let fnewt = (10.0 * UROUND / rtol).max(0.03f64.min(rtol.sqrt()));
        let v = || vec![0.0; dim];
        Ok(Radau5 {
            k: Coefficients::new(),
            rtol,
            atol,
            fnewt,
            h0,
            h_max,
            max_steps,
            state: StepperState::new(dim),
            f0: v(),
            f0_known: false,
            z: [v(), v(), v()],
            w: [v(), v(), v()],
            cont: [v(), v(), v()],
            arg: v(),
            est: v(),
            scal: v(),
            jac: Vec::new(),
            jac_norm: 0.0,
            row_sums: Vec::new(),
            systems: RadauSystems::for_size(dim, dim * dim),
            next: Next::Jacobian,
            first: true,
            reject: false,
            last: false,
            caljac: false,
            fresh: true,
            hmaxn: h_max,
            hmaxn_at: 0.0,
            end_read: false,
            hold: 0.0,
            hopt: 0.0,
            faccon: 1.0,
            theta: THET,
            hacc: 0.0,
            erracc: 0.0,
            nsing: 0,
            attempts: 0,
            stats: Stats::default(),
        })
    }

    /// The step size the next start takes (RADCOR's H on entry).
    pub fn set_next_step(&mut self, h: f64) {
        self.state.h = h;
    }

    /// ‖J‖∞, the largest absolute row sum of the Jacobian held (0 before the first): an upper
    /// bound of its spectral radius, taken once per Jacobian.
    pub fn jacobian_norm(&self) -> f64 {
        self.jac_norm
    }

    /// One attempt at a step of size `h` from (t, y), from a fresh start with a new Jacobian:
    /// `auto`'s test of whether Radau IIA steps further than the explicit method (LSODA
    /// compares the two methods' step sizes in the same way, from estimates its shared
    /// history gives; here a trial step gives it). `true` when the step is accepted: the
    /// method stands at its end, ready to go on. `false` when Newton's iteration fails, a
    /// matrix is singular or the error test rejects the step: the method must be started
    /// again before it steps. Its work is counted either way.
    pub fn trial(
        &mut self,
        ode: &Ode,
        (t, y): (f64, &[f64]),
        h: f64,
        t_stop: f64,
    ) -> Result<bool, SolverError> {
        self.set_next_step(h);
        self.start(ode, t, y)?;
        self.prepare(ode, t_stop);
        self.new_jacobian(ode);
        if !self.new_factorization(ode) {
            return Ok(false);
        }
        Ok(matches!(self.attempt(ode, t_stop)?, Attempt::Accepted))
    }

    /// What RADCOR does before its first step (HMAXN, H within it, LAST if it reaches XEND)
    /// and after a restart moved the end (f at the current point).
    fn prepare(&mut self, ode: &Ode, t_stop: f64) {
        let t = self.state.t;
        if self.fresh {
            // RADCOR: HMAXN = min(|HMAX|, |XEND − X|), H within it, LAST if it reaches XEND.
            self.hmaxn = self.h_max.abs().min((t_stop - t).abs());
            self.hmaxn_at = t;
            self.end_read |= self.state.h.abs() > self.hmaxn;
            self.state.h = self.state.h.abs().min(self.hmaxn);
            self.hold = self.state.h;
            if t + self.state.h * 1.0001 - t_stop >= 0.0 {
                self.state.h = t_stop - t;
                self.last = true;
                self.end_read = true;
            }
            self.hopt = self.state.h;
            self.fresh = false;
        }
        if !self.f0_known {
            ode.rhs(t, &self.state.y, &mut self.f0, &mut self.stats);
            self.f0_known = true;
            self.last = t + self.state.h - t_stop >= 0.0;
            if self.last {
                self.state.h = t_stop - t;
                self.end_read = true;
            }
        }
    }

    /// Label 10: the Jacobian at the current point, and its norm ‖J‖∞.
    fn new_jacobian(&mut self, ode: &Ode) {
        let (t, y) = (self.state.t, &self.state.y);
        newton::jacobian(ode, t, y, &self.f0, &mut self.jac, &mut self.stats);
        self.row_sums.clear();
        self.row_sums.resize(y.len(), 0.0);
        for &(i, _, v) in &self.jac {
            self.row_sums[i] += v.abs();
        }
        self.jac_norm = self.row_sums.iter().fold(0.0, |m, r| r.max(m));
        self.caljac = true;
        self.next = Next::Factorize;
    }

    /// Label 20 with its count: `false` when a matrix is singular.
    fn new_factorization(&mut self, ode: &Ode) -> bool {
        let regular = self.factorize(ode.problem.mass());
        if regular {
            self.stats.lu_factorizations += 1;
            self.stats.complex_lu_factorizations += 1;
        }
        regular
    }

    /// SCAL(I) = ATOL + RTOL·|Y(I)|.
    fn scale(&mut self) {
        for (s, y) in self.scal.iter_mut().zip(&self.state.y) {
            *s = self.atol + self.rtol * y.abs();
        }
    }

    /// Label 20: E1 = FAC1·M − J and E2 = (ALPHN + i·BETAN)·M − J, factorised (DECOMR,
    /// DECOMC); `false` when either is singular.
    fn factorize(&mut self, mass: Option<&[f64]>) -> bool {
        let (n, h) = (self.state.y.len(), self.state.h);
        let k = &self.k;
        let coefficients = (k.u1 / h, k.alph / h, k.beta / h);
        self.systems.factor(n, &self.jac, mass, coefficients)
    }

    /// Label 78, an unexpected rejection (Newton failed, or a factorisation was singular):
    /// the step is halved; the fifth singular matrix in a row ends the run.
    fn unexpected_rejection(&mut self, singular: bool) -> Result<(), SolverError> {
        if singular {
            self.nsing += 1;
            if self.nsing >= MAX_SINGULAR {
                return Err(SolverError::SingularMatrix {
                    t: self.state.t,
                    h: self.state.h,
                });
            }
        } else {
            self.stats.rejected_newton += 1;
        }
        self.state.h *= 0.5;
        self.reject = true;
        self.last = false;
        self.next = if self.caljac {
            Next::Factorize
        } else {
            Next::Jacobian
        };
        Ok(())
    }

    /// RADCOR's starting values for Newton's iteration: zero on the first step, else the
    /// last step's collocation polynomial extrapolated to the new stages.
    fn starting_values(&mut self) {
        let [z1, z2, z3] = &mut self.z;
        let [f1, f2, f3] = &mut self.w;
        if self.first {
            for v in [z1, z2, z3, f1, f2, f3] {
                v.fill(0.0);
            }
            return;
        }
        let k = &self.k;
        let c3q = self.state.h / self.hold;
        let (c1q, c2q) = (k.c1 * c3q, k.c2 * c3q);
        let [ak1, ak2, ak3] = &self.cont;
        for i in 0..z1.len() {
            let p = |q: f64| q * (ak1[i] + (q - k.c2m1) * (ak2[i] + (q - k.c1m1) * ak3[i]));
            let (z1i, z2i, z3i) = (p(c1q), p(c2q), p(c3q));
            z1[i] = z1i;
            z2[i] = z2i;
            z3[i] = z3i;
            f1[i] = TI11 * z1i + TI12 * z2i + TI13 * z3i;
            f2[i] = TI21 * z1i + TI22 * z2i + TI23 * z3i;
            f3[i] = TI31 * z1i + TI32 * z2i + TI33 * z3i;
        }
    }

    /// f at the three stages, `f(t + c_i·h, y + Z_i)`, into Z itself (the Newton iteration,
    /// as RADCOR overwrites Z1..Z3) or into F1..F3.
    fn stage_rhs(&mut self, ode: &Ode, into: Stages) {
        let (t, h, k) = (self.state.t, self.state.h, self.k);
        for (stage, c) in [k.c1, k.c2, 1.0].into_iter().enumerate() {
            for (a, (y, z)) in self
                .arg
                .iter_mut()
                .zip(self.state.y.iter().zip(&self.z[stage]))
            {
                *a = y + z;
            }
            // The third node is the step's end, x + h as RADCOR writes it (XPH).
            let tc = if stage == 2 { t + h } else { t + c * h };
            let out = match into {
                Stages::Z => &mut self.z[stage],
                Stages::W => &mut self.w[stage],
            };
            ode.rhs(tc, &self.arg, out, &mut self.stats);
        }
    }

    /// One simplified Newton iteration (label 40 to the convergence test): the three stage
    /// values of f, transformed by T⁻¹, the real and complex solves (SLVRAD), and the
    /// increments' norm DYNO.
    fn newton_iteration(&mut self, ode: &Ode) -> f64 {
        let (h, n) = (self.state.h, self.state.y.len());
        let k = self.k;
        self.stage_rhs(ode, Stages::Z);
        let [z1, z2, z3] = &mut self.z;
        let [f1, f2, f3] = &self.w;
        let (fac1, alphn, betan) = (k.u1 / h, k.alph / h, k.beta / h);
        let mass = ode.problem.mass();
        for i in 0..n {
            let (a1, a2, a3) = (z1[i], z2[i], z3[i]);
            let m = mass.map_or(1.0, |m| m[i]);
            // SLVRAD: the right-hand sides of the real and the complex system.
            let (s1, s2, s3) = (-(m * f1[i]), -(m * f2[i]), -(m * f3[i]));
            z1[i] = TI11 * a1 + TI12 * a2 + TI13 * a3 + s1 * fac1;
            z2[i] = TI21 * a1 + TI22 * a2 + TI23 * a3 + s2 * alphn - s3 * betan;
            z3[i] = TI31 * a1 + TI32 * a2 + TI33 * a3 + s3 * alphn + s2 * betan;
        }
        self.systems.real.solve(z1);
        self.systems.complex.solve(z2, z3);
        self.stats.newton_iterations += 1;
        self.stats.linear_solves += 1;
        self.stats.complex_linear_solves += 1;
        // DYNO over the unknowns that are not quadratures.
        let q = (n - ode.problem.quadratures()).max(1);
        let mut dyno = 0.0;
        for i in 0..q {
            let denom = self.scal[i];
            dyno =
                dyno + (z1[i] / denom).powi(2) + (z2[i] / denom).powi(2) + (z3[i] / denom).powi(2);
        }
        (dyno / (3 * q) as f64).sqrt()
    }

    /// F ← F + ΔZ and Z = (T ⊗ I)·F, after an iteration that goes on or converged.
    fn update_iterates(&mut self) {
        let [z1, z2, z3] = &mut self.z;
        let [f1, f2, f3] = &mut self.w;
        for i in 0..z1.len() {
            let (f1i, f2i, f3i) = (f1[i] + z1[i], f2[i] + z2[i], f3[i] + z3[i]);
            f1[i] = f1i;
            f2[i] = f2i;
            f3[i] = f3i;
            z1[i] = T11 * f1i + T12 * f2i + T13 * f3i;
            z2[i] = T21 * f1i + T22 * f2i + T23 * f3i;
            z3[i] = T31 * f1i + f2i;
        }
    }

    /// The quadratures' stage increments from the converged stages, `M_q·Z_q = h·A·f_q(Y)`,
    /// with A the Radau IIA(5) matrix (Hairer & Wanner, *Solving ODEs II*, Table IV.5.6).
    fn quadrature_stages(&mut self, ode: &Ode) {
        let (h, n) = (self.state.h, self.state.y.len());
        let q = n - ode.problem.quadratures();
        // f at the three stages, into F1..F3 (spent once Newton has converged).
        self.stage_rhs(ode, Stages::W);
        let mass = ode.problem.mass();
        let a = &self.k.a;
        for i in q..n {
            let m = mass.map_or(1.0, |m| m[i]);
            for (row, z) in a.iter().zip(&mut self.z) {
                let sum: f64 = row.iter().zip(&self.w).map(|(a, f)| a * f[i]).sum();
                z[i] = h * sum / m;
            }
        }
    }

    /// ESTRAD: err = ‖E1⁻¹·(f0 + M·(DD1·Z1 + DD2·Z2 + DD3·Z3)/h)‖, and, on a first or
    /// rejected step whose estimate fails, once more with f evaluated at y + that estimate
    /// (Hairer & Wanner, sec. IV.8, eq. (8.20)).
    fn error_estimate(&mut self, ode: &Ode) -> f64 {
        let (t, h, n) = (self.state.t, self.state.h, self.state.y.len());
        let (hee1, hee2, hee3) = (self.k.dd1 / h, self.k.dd2 / h, self.k.dd3 / h);
        let mass = ode.problem.mass();
        let [z1, z2, z3] = &self.z;
        // F2 of ESTRAD (M·the weighted sum) in `est`, CONT in `arg`.
        for i in 0..n {
            let f1 = hee1 * z1[i] + hee2 * z2[i] + hee3 * z3[i];
            self.est[i] = mass.map_or(1.0, |m| m[i]) * f1;
            self.arg[i] = self.est[i] + self.f0[i];
        }
        self.systems.real.solve(&mut self.arg);
        self.stats.linear_solves += 1;
        let mut err = self.scaled_norm();
        if err >= 1.0 && (self.first || self.reject) {
            for i in 0..n {
                self.arg[i] += self.state.y[i];
            }
            // f at y + the estimate, into the first W vector (scratch here, as in ESTRAD).
            ode.rhs(t, &self.arg, &mut self.w[0], &mut self.stats);
            for i in 0..n {
                self.arg[i] = self.w[0][i] + self.est[i];
            }
            self.systems.real.solve(&mut self.arg);
            self.stats.linear_solves += 1;
            err = self.scaled_norm();
        }
        err
    }

    /// ESTRAD's norm of the estimate: `max(√(Σ (CONT_i/SCAL_i)²/n), 1e-10)`.
    fn scaled_norm(&self) -> f64 {
        let mut sum = 0.0;
        for (e, s) in self.arg.iter().zip(&self.scal) {
            sum += (e / s).powi(2);
        }
        (sum / self.arg.len() as f64).sqrt().max(1e-10)
    }

    /// Label 30 onwards: one attempt at the step of size `state.h`.
    fn attempt(&mut self, ode: &Ode, t_stop: f64) -> Result<Attempt, SolverError> {
        let (t, h) = (self.state.t, self.state.h);
        self.attempts += 1;
        if self.attempts > self.max_steps {
            return Err(SolverError::TooManySteps {
                t,
                h,
                max: self.max_steps,
            });
        }
        // Label 30: `IF (0.1D0*ABS(H).LE.ABS(X)*UROUND) GOTO 177`.
        if 0.1 * h.abs() <= t.abs() * UROUND {
            return Err(SolverError::StepSizeUnderflow { t, h });
        }
        self.starting_values();
        let mut newt = 0;
        self.faccon = self.faccon.max(UROUND).powf(0.8);
        self.theta = THET.abs();
        let (mut dynold, mut thqold) = (0.0, 0.0);
        loop {
            if newt >= NIT {
                self.unexpected_rejection(false)?;
                return Ok(Attempt::Retry);
            }
            let dyno = self.newton_iteration(ode);
            newt += 1;
            if !dyno.is_finite() {
                self.unexpected_rejection(false)?;
                return Ok(Attempt::Retry);
            }
            // Bad convergence or too many iterations to come.
            if newt > 1 && newt < NIT {
                let thq = dyno / dynold;
                self.theta = if newt == 2 {
                    thq
                } else {
                    (thq * thqold).sqrt()
                };
                thqold = thq;
                if self.theta < 0.99 {
                    self.faccon = self.theta / (1.0 - self.theta);
                    let dyth =
                        self.faccon * dyno * self.theta.powi((NIT - 1 - newt) as i32) / self.fnewt;
                    if dyth >= 1.0 {
                        // Convergence predicted too slow: a smaller step, same Jacobian.
                        let qnewt = dyth.clamp(1e-4, 20.0);
                        let hhfac = 0.8 * qnewt.powf(-1.0 / (4.0 + (NIT - 1 - newt) as f64));
                        self.state.h *= hhfac;
                        self.reject = true;
                        self.last = false;
                        self.stats.rejected_newton += 1;
                        self.next = if self.caljac {
                            Next::Factorize
                        } else {
                            Next::Jacobian
                        };
                        return Ok(Attempt::Retry);
                    }
                } else {
                    self.unexpected_rejection(false)?;
                    return Ok(Attempt::Retry);
                }
            }
            dynold = dyno.max(UROUND);
            self.update_iterates();
            if self.faccon * dyno <= self.fnewt {
                break;
            }
        }
        if ode.problem.quadratures() > 0 {
            self.quadrature_stages(ode);
        }
        let err = self.error_estimate(ode);
        if !err.is_finite() {
            self.unexpected_rejection(false)?;
            return Ok(Attempt::Retry);
        }
        // "COMPUTATION OF HNEW ... WE REQUIRE .2<=HNEW/H<=8."
        let cfac = SAFE * (1 + 2 * NIT) as f64;
        let fac = SAFE.min(cfac / (newt + 2 * NIT) as f64);
        let mut quot = FACR.max(FACL.min(err.powf(0.25) / fac));
        let mut hnew = h / quot;
        if err >= 1.0 {
            // "STEP IS REJECTED".
            self.reject = true;
            self.last = false;
            if self.first {
                self.state.h = h * 0.1;
            } else {
                self.state.h = hnew;
            }
            self.stats.rejected_error += 1;
            self.next = if self.caljac {
                Next::Factorize
            } else {
                Next::Jacobian
            };
            return Ok(Attempt::Retry);
        }
        // "STEP IS ACCEPTED", with the predictive controller of Gustafsson.
        self.first = false;
        self.stats.steps += 1;
        if self.stats.steps > 1 {
            let facgus = (self.hacc / h) * (err * err / self.erracc).powf(0.25) / SAFE;
            quot = quot.max(FACR.max(FACL.min(facgus)));
            hnew = h / quot;
        }
        self.hacc = h;
        self.erracc = err.max(1e-2);
        self.accept(h)?;
        if self.last {
            // The end exactly, whatever the rounding of t + (t_stop − t).
            self.state.t = t_stop;
            // RADCOR returns with H = HOPT; f at the end is evaluated only if stepping on
            // (an end moved later), and then with a new Jacobian and factorisations for it.
            self.state.h = self.hopt;
            self.f0_known = false;
            self.next = Next::Jacobian;
            return Ok(Attempt::Accepted);
        }
        ode.rhs(self.state.t, &self.state.y, &mut self.f0, &mut self.stats);
        self.end_read |= hnew.abs() > self.hmaxn;
        hnew = hnew.abs().min(self.hmaxn);
        self.hopt = h.min(hnew);
        if self.reject {
            hnew = hnew.min(h);
        }
        self.reject = false;
        let theta_small = self.theta <= THET;
        if self.state.t + hnew / QUOT1 - t_stop >= 0.0 {
            self.state.h = t_stop - self.state.t;
            self.last = true;
            self.end_read = true;
        } else {
            let qt = hnew / h;
            if theta_small && (QUOT1..=QUOT2).contains(&qt) {
                self.next = Next::Step;
                return Ok(Attempt::Accepted);
            }
            self.state.h = hnew;
        }
        self.next = if theta_small {
            Next::Factorize
        } else {
            Next::Jacobian
        };
        Ok(Attempt::Accepted)
    }

    /// The accepted step of size `h`: y ← y + Z3 and the collocation polynomial's
    /// coefficients for the dense output and the next starting values.
    fn accept(&mut self, h: f64) -> Result<(), SolverError> {
        let k = self.k;
        let [z1, z2, z3] = &self.z;
        let [c1, c2, c3] = &mut self.cont;
        for i in 0..z1.len() {
            self.arg[i] = self.state.y[i] + z3[i];
            let (z1i, z2i) = (z1[i], z2[i]);
            c1[i] = (z2i - z3[i]) / k.c2m1;
            let ak = (z1i - z2i) / k.c1mc2;
            let acont3 = (ak - z1i / k.c1) / k.c2;
            c2[i] = (ak - c1[i]) / k.c1m1;
            c3[i] = c2[i] - acont3;
        }
        check_finite(&self.arg, self.state.t, h, "Radau IIA step result")?;
        std::mem::swap(&mut self.state.y, &mut self.arg);
        self.hold = h;
        self.state.t_prev = self.state.t;
        self.state.t += h;
        self.caljac = false;
        self.scale();
        Ok(())
    }
}

impl Stepper for Radau5 {
    fn name(&self) -> &'static str {
        "radau5"
    }

    /// RADCOR's initialisation at (t, y): f there, the scale, a fresh start (zero starting
    /// values, the first-step rules) with a new Jacobian. The first step is the given one, or
    /// 1e-6; a restart (after an event) keeps the step size reached.
    fn start(&mut self, ode: &Ode, t: f64, y: &[f64]) -> Result<(), SolverError> {
        self.state.t_prev = t;
        self.state.t = t;
        self.state.y.copy_from_slice(y);
        if self.state.h == 0.0 {
            self.state.h = self.h0.unwrap_or(H_DEFAULT);
        }
        if self.state.h.abs() <= 10.0 * UROUND {
            self.state.h = H_DEFAULT;
        }
        self.hold = self.state.h;
        self.first = true;
        self.reject = false;
        self.last = false;
        self.fresh = true;
        self.faccon = 1.0;
        self.nsing = 0;
        self.next = Next::Jacobian;
        self.scale();
        ode.rhs(t, y, &mut self.f0, &mut self.stats);
        self.f0_known = true;
        Ok(())
    }

    fn step(&mut self, ode: &Ode, t_stop: f64) -> Result<(), SolverError> {
        self.prepare(ode, t_stop);
        loop {
            match self.next {
                Next::Jacobian => self.new_jacobian(ode),
                Next::Factorize => {
                    if self.new_factorization(ode) {
                        self.next = Next::Step;
                    } else {
                        self.unexpected_rejection(true)?;
                    }
                }
                Next::Step => {
                    if let Attempt::Accepted = self.attempt(ode, t_stop)? {
                        return Ok(());
                    }
                }
            }
        }
    }

    fn state(&self) -> &StepperState {
        &self.state
    }

    /// CONTR5: `y + s·(C1 + (s − C2M1)·(C2 + (s − C1M1)·C3))`, s = (t − t_new)/h ∈ [−1, 0].
    fn dense_output(&self, t: f64, out: &mut [f64]) {
        if self.hold == 0.0 || self.state.t == self.state.t_prev {
            out.copy_from_slice(&self.state.y);
            return;
        }
        let s = (t - self.state.t) / self.hold;
        let [c1, c2, c3] = &self.cont;
        let k = &self.k;
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.state.y[i] + s * (c1[i] + (s - k.c2m1) * (c2[i] + (s - k.c1m1) * c3[i]));
        }
    }

    fn stats(&self) -> Stats {
        self.stats
    }

    fn copy(&self) -> Option<Box<dyn Stepper>> {
        Some(Box::new(self.clone()))
    }

    /// The next step reads the end when it is the first after a (re)start (HMAXN, LAST), or
    /// when it or the step after it may reach the end: the step grows at most 1/FACR = 8
    /// times, and RADCOR aims the next step at XEND once `X + HNEW/QUOT1` passes it.
    fn may_read_end(&self, t_stop: f64) -> bool {
        let (t, h) = (self.state.t, self.state.h.abs());
        self.fresh || !self.f0_known || t + h + h / (FACR * QUOT1) - t_stop >= 0.0
    }

    /// HMAXN as a run to the later end would have set it where it was last set.
    fn resume(&mut self, options: &Options) -> bool {
        self.h_max = options.h_max();
        self.max_steps = options.max_steps;
        self.hmaxn = self.h_max.abs().min((options.t_end - self.hmaxn_at).abs());
        !self.end_read
    }
}
