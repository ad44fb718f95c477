//! The classical fourth-order Runge–Kutta method with fixed steps, and its cubic Hermite
//! dense output (Hairer, Nørsett, Wanner, *Solving ODEs I*, sec. II.6, eq. (6.7)).
//!
//! The derivative at the end of a step is the first stage of the next one, so a step costs
//! four evaluations of f after the first.

use crate::error::SolverError;
use crate::method::OneStepMethod;
use crate::options::{Options, StepControl};
use crate::stats::Stats;
use crate::stepper::{check_finite, hermite_cubic, next_grid_point, Ode, Stepper, StepperState};

/// RK4 as a method (`rk4`): order 4, explicit, fixed steps only.
#[derive(Clone, Copy, Debug)]
pub struct Rk4Method;

impl OneStepMethod for Rk4Method {
    fn name(&self) -> &'static str {
        "rk4"
    }

    fn order(&self) -> usize {
        4
    }

    fn is_implicit(&self) -> bool {
        false
    }

    fn is_fixed_step(&self) -> bool {
        true
    }

    fn stability_polynomial(&self) -> Option<&'static [f64]> {
        Some(&crate::stability::RK4_POLYNOMIAL)
    }

    /// RK4 at the fixed step of `options`; tolerances are refused (it has no error estimate).
    fn stepper(&self, options: &Options, dim: usize) -> Result<Box<dyn Stepper>, SolverError> {
        match options.step {
            StepControl::Fixed { h } => Ok(Box::new(Rk4::new(h, dim))),
            StepControl::Adaptive { .. } => Err(SolverError::Unsupported {
                solver: "rk4",
                why: "RK4 has no error estimate: give a fixed step h (dt)".into(),
            }),
        }
    }
}

/// RK4 with constant step `h`.
#[derive(Clone, Debug)]
pub struct Rk4 {
    t_start: f64,
    /// Where the method stands (`h` is the constant step).
    state: StepperState,
    y_prev: Vec<f64>,
    /// f at the start of the last step.
    f_prev: Vec<f64>,
    /// f at the current point (the next step's first stage).
    f: Vec<f64>,
    k: [Vec<f64>; 3],
    stage: Vec<f64>,
    stats: Stats,
}

impl Rk4 {
    /// RK4 with step `h` for a system of `dim` unknowns.
    pub fn new(h: f64, dim: usize) -> Self {
        let v = || vec![0.0; dim];
        Rk4 {
            t_start: 0.0,
            state: StepperState {
                h,
                ..StepperState::new(dim)
            },
            y_prev: v(),
            f_prev: v(),
            f: v(),
            k: [v(), v(), v()],
            stage: v(),
            stats: Stats::default(),
        }
    }
}

impl Stepper for Rk4 {
    fn name(&self) -> &'static str {
        "rk4"
    }

    fn start(&mut self, ode: &Ode, t: f64, y: &[f64]) -> Result<(), SolverError> {
        ode.require_regular_mass("rk4")?;
        self.t_start = t;
        self.state.t_prev = t;
        self.state.t = t;
        self.state.y.copy_from_slice(y);
        ode.explicit_rhs(t, y, &mut self.f, &mut self.stats);
        Ok(())
    }

    fn step(&mut self, ode: &Ode, t_stop: f64) -> Result<(), SolverError> {
        let t0 = self.state.t;
        let t1 = next_grid_point(self.t_start, self.state.h, t0, t_stop);
        let h = t1 - t0;
        let n = self.state.y.len();
        let [k2, k3, k4] = &mut self.k;
        let (y, k1, s) = (&self.state.y, &self.f, &mut self.stage);
        for i in 0..n {
            s[i] = y[i] + 0.5 * h * k1[i];
        }
        ode.explicit_rhs(t0 + 0.5 * h, s, k2, &mut self.stats);
        for i in 0..n {
            s[i] = y[i] + 0.5 * h * k2[i];
        }
        ode.explicit_rhs(t0 + 0.5 * h, s, k3, &mut self.stats);
        for i in 0..n {
            s[i] = y[i] + h * k3[i];
        }
        ode.explicit_rhs(t1, s, k4, &mut self.stats);
        self.y_prev.copy_from_slice(&self.state.y);
        for i in 0..n {
            self.state.y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        check_finite(&self.state.y, t0, h, "RK4 step result")?;
        std::mem::swap(&mut self.f_prev, &mut self.f);
        ode.explicit_rhs(t1, &self.state.y, &mut self.f, &mut self.stats);
        // f at the step's end enters the dense output and starts the next step.
        check_finite(&self.f, t0, h, "RK4 f at the step's end")?;
        self.state.t_prev = t0;
        self.state.t = t1;
        self.stats.steps += 1;
        Ok(())
    }

    fn state(&self) -> &StepperState {
        &self.state
    }

    /// The cubic Hermite interpolant of the step's ends ([`hermite_cubic`]).
    fn dense_output(&self, t: f64, out: &mut [f64]) {
        hermite_cubic(
            (self.state.t_prev, &self.y_prev, &self.f_prev),
            (self.state.t, &self.state.y, &self.f),
            t,
            out,
        );
    }

    fn stats(&self) -> Stats {
        self.stats
    }
}
