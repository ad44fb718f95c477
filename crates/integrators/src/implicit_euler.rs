//! Implicit (backward) Euler, `M·(y1 − y0) = h·f(t1, y1)`, solved by Newton's method, with
//! fixed steps or with error control.
//!
//! Error estimate: the local error of implicit Euler is `−h²/2·y''`, estimated by
//! `e = h/2·(f(t1, y1) − f(t0, y0))` and filtered through the iteration matrix,
//! `err = (M − h·J)⁻¹·e`, as radau5.f does (Hairer & Wanner, *Solving ODEs II*, sec. IV.8),
//! so that stiff components do not overestimate it. Dense output is the linear interpolant.

use crate::error::SolverError;
use crate::linear::{self, LinearSolver};
use crate::method::OneStepMethod;
use crate::newton::{self, NewtonKind};
use crate::options::{Options, StepControl};
use crate::problem::Entry;
use crate::stats::Stats;
use crate::stepper::{
    check_finite, check_limits, linear_interpolation, next_grid_point, wrms, Ode, Stepper,
    StepperState,
};

// Step-size control: the defaults of radau5.f.
/// Safety factor SAFE (WORK(2)).
const SAFE: f64 = 0.9;
/// The step shrinks at most to FACMIN = 1/FACL, FACL = 5 (WORK(8)).
const FACMIN: f64 = 0.2;
/// The step grows at most to FACMAX = 1/FACR, FACR = 0.125 (WORK(9)).
const FACMAX: f64 = 8.0;
/// Step cut after a Newton failure (radau5.f: H = H·0.5 on an unexpected rejection).
const NEWTON_CUT: f64 = 0.5;
/// Most Newton iterations (NIT, WORK... IWORK(3) of radau5.f).
const MAX_NEWTON_ITERATIONS: usize = 7;
/// Newton converged when η·‖Δ‖ ≤ κ in the error norm (FNEWT of radau5.f is
/// max(10·UROUND/RTOL, min(0.03, RTOL^½)); 0.03 is its usual value).
const KAPPA: f64 = 0.03;
/// With fixed steps there is no error tolerance: Newton then converges to this relative
/// and absolute level (so that its error stays far below the discretisation error).
const FIXED_STEP_NEWTON_TOL: f64 = 1e-10;
/// A contraction factor θ above this asks for a fresh Jacobian at the next step (radau5.f:
/// THET = 0.001 recomputes the Jacobian whenever θ exceeds it; less eager here, because
/// the friction Jacobians change only at mode switches).
const THETA_REFRESH: f64 = 0.5;
/// Relative change of h below which the iteration matrix is not refactorised.
const REFACTOR_TOLERANCE: f64 = 1e-8;
/// Most step cuts after Newton failures within one step.
const MAX_NEWTON_CUTS: usize = 10;
/// First step of an adaptive run without a given one, as a fraction of the largest step.
const INITIAL_FRACTION: f64 = 1e-4;

/// Implicit Euler as a method (`implicit-euler`): order 1, modified Newton, adaptive or at a
/// fixed step.
#[derive(Clone, Copy, Debug)]
pub struct ImplicitEulerMethod;

impl OneStepMethod for ImplicitEulerMethod {
    fn name(&self) -> &'static str {
        "implicit-euler"
    }

    fn order(&self) -> usize {
        1
    }

    fn is_implicit(&self) -> bool {
        true
    }

    fn is_fixed_step(&self) -> bool {
        false
    }

    fn takes_fixed_steps(&self) -> bool {
        true
    }

    fn stepper(&self, options: &Options, dim: usize) -> Result<Box<dyn Stepper>, SolverError> {
        Ok(Box::new(ImplicitEuler::new(
            options.step,
            NewtonKind::Modified,
            options.h_max(),
            options.max_steps,
            dim,
        )))
    }
}

/// Implicit Euler with Newton's method.
pub struct ImplicitEuler {
    control: StepControl,
    newton: NewtonKind,
    h_max: f64,
    max_steps: usize,
    t_start: f64,
    /// Where the method stands.
    state: StepperState,
    y_prev: Vec<f64>,
    /// f(t, y) at the current point, valid when `f_known`.
    f: Vec<f64>,
    f_known: bool,
    /// Newton's iterate Y and f(t1, Y), the correction, and the error estimate: scratch kept
    /// between steps so that a step allocates nothing.
    y_new: Vec<f64>,
    f_new: Vec<f64>,
    delta: Vec<f64>,
    err: Vec<f64>,
    jac: Vec<Entry>,
    jac_valid: bool,
    jac_fresh: bool,
    matrix: Vec<Entry>,
    lu: Box<dyn LinearSolver>,
    /// The step size of the current factorisation (0 for none).
    lu_h: f64,
    eta: f64,
    reject: bool,
    attempts: usize,
    stats: Stats,
}

impl ImplicitEuler {
    /// Implicit Euler for `dim` unknowns.
    pub fn new(
        control: StepControl,
        newton: NewtonKind,
        h_max: f64,
        max_steps: usize,
        dim: usize,
    ) -> Self {
        ImplicitEuler {
            control,
            newton,
            h_max,
            max_steps,
            t_start: 0.0,
            state: StepperState::new(dim),
            y_prev: vec![0.0; dim],
            f: vec![0.0; dim],
            f_known: false,
            y_new: vec![0.0; dim],
            f_new: vec![0.0; dim],
            delta: vec![0.0; dim],
            err: vec![0.0; dim],
            jac: Vec::new(),
            jac_valid: false,
            jac_fresh: false,
            matrix: Vec::new(),
            lu: linear::for_size(dim, dim * dim),
            lu_h: 0.0,
            eta: 1.0,
            reject: false,
            attempts: 0,
            stats: Stats::default(),
        }
    }

    /// Newton's tolerances: the step's (rtol, atol), or the fixed-step level.
    fn tolerances(&self) -> (f64, f64, f64) {
        match self.control {
            StepControl::Adaptive { rtol, atol, .. } => (rtol, atol, KAPPA),
            StepControl::Fixed { .. } => (FIXED_STEP_NEWTON_TOL, FIXED_STEP_NEWTON_TOL, 1.0),
        }
    }

    /// Makes f at the current point known, evaluating it if needed.
    fn f_here(&mut self, ode: &Ode) {
        if !self.f_known {
            ode.rhs(self.state.t, &self.state.y, &mut self.f, &mut self.stats);
            self.f_known = true;
        }
    }

    /// Evaluates J at the current point (`at_iterate`: at Newton's iterate instead).
    fn evaluate_jacobian(&mut self, ode: &Ode, t: f64, at_iterate: bool) {
        let (y, f) = if at_iterate {
            (&self.y_new, &self.f_new)
        } else {
            (&self.state.y, &self.f)
        };
        newton::jacobian(ode, t, y, f, &mut self.jac, &mut self.stats);
        self.jac_valid = true;
        self.jac_fresh = true;
        self.lu_h = 0.0;
    }

    /// Factorises `M − h·J` unless the current factorisation was made for nearly the same h
    /// (within [`REFACTOR_TOLERANCE`]: fixed steps `t_(k+1) − t_k` differ in their last bits,
    /// and Newton's iteration needs only an approximate matrix).
    fn factor(&mut self, ode: &Ode, h: f64) -> Result<(), SolverError> {
        if (self.lu_h - h).abs() <= REFACTOR_TOLERANCE * h {
            return Ok(());
        }
        let n = self.state.y.len();
        newton::iteration_matrix(ode.problem.mass(), n, h, &self.jac, &mut self.matrix);
        if self.lu.name() != linear::choice(n, self.matrix.len()) {
            self.lu = linear::for_size(n, self.matrix.len());
        }
        self.stats.lu_factorizations += 1;
        if !self.lu.factor(n, &self.matrix) {
            self.lu_h = 0.0;
            return Err(SolverError::SingularMatrix { t: self.state.t, h });
        }
        self.lu_h = h;
        Ok(())
    }

    /// Newton's iteration for `G(Y) = M(Y − y) − h·f(t1, Y) = 0` from `Y = y` (a new
    /// Jacobian at every iterate when `full`). Leaves the solution in `y_new` and `f(t1, Y)`
    /// in `f_new`, or says why it failed.
    fn newton(&mut self, ode: &Ode, t1: f64, h: f64, full: bool) -> Result<(), String> {
        let n = self.state.y.len();
        let (rtol, atol, kappa) = self.tolerances();
        let mass = ode.problem.mass();
        self.y_new.copy_from_slice(&self.state.y);
        // Converged or not by the unknowns that are not quadratures.
        let q = n - ode.problem.quadratures();
        let mut norm_prev = 0.0;
        for k in 0..MAX_NEWTON_ITERATIONS {
            ode.rhs(t1, &self.y_new, &mut self.f_new, &mut self.stats);
            if full && k > 0 {
                self.evaluate_jacobian(ode, t1, true);
                self.factor(ode, h).map_err(|e| e.to_string())?;
            }
            for i in 0..n {
                let m = mass.map_or(1.0, |m| m[i]);
                self.delta[i] = -(m * (self.y_new[i] - self.state.y[i]) - h * self.f_new[i]);
            }
            self.stats.newton_iterations += 1;
            self.stats.linear_solves += 1;
            if !self.lu.solve(&mut self.delta) {
                return Err("the linear solve gave a non-finite correction".into());
            }
            for i in 0..n {
                self.y_new[i] += self.delta[i];
            }
            let norm = wrms(
                &self.delta[..q],
                &self.y_new[..q],
                &self.state.y[..q],
                rtol,
                atol,
            );
            let eta = if k == 0 {
                self.eta.max(crate::stepper::UROUND).powf(0.8)
            } else {
                let theta = norm / norm_prev;
                if theta >= 1.0 || !theta.is_finite() {
                    return Err(format!(
                        "contraction factor {theta:.3} >= 1 at iteration {}",
                        k + 1
                    ));
                }
                if theta > THETA_REFRESH {
                    self.jac_valid = false;
                }
                theta / (1.0 - theta)
            };
            if eta * norm <= kappa {
                self.eta = eta;
                ode.rhs(t1, &self.y_new, &mut self.f_new, &mut self.stats);
                // The quadratures from the converged state: `M_q·(Y_q − y_q) = h·f_q(t1, Y)`.
                for i in q..n {
                    let m = mass.map_or(1.0, |m| m[i]);
                    self.y_new[i] = self.state.y[i] + h * self.f_new[i] / m;
                }
                return Ok(());
            }
            norm_prev = norm;
        }
        Err(format!(
            "no convergence in {MAX_NEWTON_ITERATIONS} iterations"
        ))
    }
}

impl Stepper for ImplicitEuler {
    fn name(&self) -> &'static str {
        "implicit-euler"
    }

    fn start(&mut self, _ode: &Ode, t: f64, y: &[f64]) -> Result<(), SolverError> {
        self.t_start = t;
        self.state.t_prev = t;
        self.state.t = t;
        self.state.y.copy_from_slice(y);
        self.y_prev.copy_from_slice(y);
        self.f_known = false;
        self.jac_valid = false;
        self.lu_h = 0.0;
        self.eta = 1.0;
        self.reject = false;
        if self.state.h == 0.0 || matches!(self.control, StepControl::Fixed { .. }) {
            // Without a given step: INITIAL_FRACTION of the largest step (the whole interval
            // by default); the controller grows it by up to FACMAX per step.
            self.state.h = self
                .control
                .given_step()
                .unwrap_or(INITIAL_FRACTION * self.h_max);
        }
        Ok(())
    }

    fn step(&mut self, ode: &Ode, t_stop: f64) -> Result<(), SolverError> {
        let adaptive = matches!(self.control, StepControl::Adaptive { .. });
        let mut cuts = 0;
        let mut full_fallback = false;
        loop {
            self.attempts += 1;
            let (t1, h) = match self.control {
                StepControl::Fixed { h } => {
                    let t1 = next_grid_point(self.t_start, h, self.state.t, t_stop);
                    (t1, t1 - self.state.t)
                }
                StepControl::Adaptive { .. } => {
                    let h = if self.state.t + 1.01 * self.state.h - t_stop > 0.0 {
                        t_stop - self.state.t
                    } else {
                        self.state.h
                    };
                    (self.state.t + h, h)
                }
            };
            check_limits(self.attempts, self.max_steps, self.state.t, h)?;
            if !self.jac_valid || self.newton == NewtonKind::Full {
                self.f_here(ode);
                self.evaluate_jacobian(ode, self.state.t, false);
            }
            if let Err(e) = self.factor(ode, h) {
                if !adaptive || cuts >= MAX_NEWTON_CUTS {
                    return Err(e);
                }
                cuts += 1;
                self.stats.rejected_newton += 1;
                self.state.h = h * NEWTON_CUT;
                continue;
            }
            let full = self.newton == NewtonKind::Full || full_fallback;
            match self.newton(ode, t1, h, full) {
                Ok(()) => {}
                Err(why) => {
                    self.stats.rejected_newton += 1;
                    // Modified Newton: first a fresh Jacobian, then full Newton, and only
                    // then a smaller step.
                    if !full {
                        if self.jac_fresh {
                            full_fallback = true;
                        } else {
                            self.jac_valid = false;
                        }
                        continue;
                    }
                    if !adaptive || cuts >= MAX_NEWTON_CUTS {
                        return Err(SolverError::NewtonDivergence {
                            t: self.state.t,
                            h,
                            cuts,
                            why,
                        });
                    }
                    cuts += 1;
                    self.state.h = h * NEWTON_CUT;
                    continue;
                }
            };
            check_finite(&self.y_new, self.state.t, h, "implicit Euler step result")?;
            let mut h_new = h;
            if let StepControl::Adaptive { rtol, atol, .. } = self.control {
                self.f_here(ode);
                for i in 0..self.err.len() {
                    self.err[i] = 0.5 * h * (self.f_new[i] - self.f[i]);
                }
                if !self.lu.solve(&mut self.err) {
                    return Err(SolverError::SingularMatrix { t: self.state.t, h });
                }
                let err = wrms(&self.err, &self.state.y, &self.y_new, rtol, atol);
                let fac = (SAFE / err.sqrt()).clamp(FACMIN, FACMAX);
                if err > 1.0 {
                    self.stats.rejected_error += 1;
                    self.reject = true;
                    self.state.h = h * fac.min(1.0);
                    continue;
                }
                h_new = (h * fac).min(self.h_max);
                if self.reject {
                    h_new = h_new.min(h);
                }
                self.reject = false;
            }
            std::mem::swap(&mut self.y_prev, &mut self.state.y);
            std::mem::swap(&mut self.state.y, &mut self.y_new);
            std::mem::swap(&mut self.f, &mut self.f_new);
            self.f_known = true;
            self.state.t_prev = self.state.t;
            self.state.t = t1;
            self.jac_fresh = false;
            self.stats.steps += 1;
            if adaptive {
                self.state.h = h_new;
            }
            return Ok(());
        }
    }

    fn state(&self) -> &StepperState {
        &self.state
    }

    fn dense_output(&self, t: f64, out: &mut [f64]) {
        linear_interpolation(
            self.state.t_prev,
            &self.y_prev,
            self.state.t,
            &self.state.y,
            t,
            out,
        );
    }

    fn stats(&self) -> Stats {
        self.stats
    }
}
