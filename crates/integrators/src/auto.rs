//! `auto`: Dormand–Prince while the problem is not stiff, Radau IIA(5) while it is, switching
//! within one run, so that "explicit or implicit?" is answered interval by interval (as
//! LSODA answers it between Adams and BDF, and DifferentialEquations.jl's `AutoTsit5` between
//! its pair; Hairer & Wanner, *Solving ODEs II*, sec. IV.2, on detecting stiffness).
//!
//! - **To Radau IIA**: Hairer's stiffness test of `dopri5.f` (DOPCOR), taken at every accepted
//!   step here (dopri5.f takes it every 1000 steps until it is suspicious): `h·ρ̂ > 3.25` with
//!   `ρ̂ = ‖k7 − k6‖/‖y1 − ysti‖`, fifteen times in a row, where 3.25 approximates the
//!   boundary of Dormand–Prince's stability region on the negative real axis (3.3).
//! - **Back to Dormand–Prince**: after each accepted Radau step, `h·‖J‖∞ ≤ 3.25` with the
//!   step just taken and the Jacobian Radau IIA holds (‖J‖∞, the largest row sum, bounds the
//!   spectral radius from above): Dormand–Prince could have taken that step stably. Fifteen
//!   such steps in a row, mirroring the count to the other side, switch back.
//!
//! Each switch is recorded ([`MethodSwitch`]: the time, the method switched to, and the
//! estimate `h·ρ̂` that decided it). The method switched to restarts at the current point, as
//! after an event: Radau IIA with the explicit method's last step size, Dormand–Prince with
//! its initial-step heuristic.

use crate::dopri5::{Dopri5, STIFF_COUNT, STIFF_HLAMB};
use crate::error::SolverError;
use crate::method::{adaptive_only, OneStepMethod};
use crate::options::Options;
use crate::radau5::Radau5;
use crate::solution::MethodSwitch;
use crate::stats::Stats;
use crate::stepper::{Ode, Stepper, StepperState};

/// `auto` as a method: Dormand–Prince and Radau IIA(5), switched by stiffness.
#[derive(Clone, Copy, Debug)]
pub struct AutoMethod;

impl OneStepMethod for AutoMethod {
    fn name(&self) -> &'static str {
        "auto"
    }

    fn order(&self) -> usize {
        5
    }

    /// Implicit where the problem is stiff: its runs may factorise matrices.
    fn is_implicit(&self) -> bool {
        true
    }

    fn is_fixed_step(&self) -> bool {
        false
    }

    fn stepper(&self, options: &Options, dim: usize) -> Result<Box<dyn Stepper>, SolverError> {
        let (rtol, atol, h0) = adaptive_only("auto", options.step)?;
        let (h_max, max_steps) = (options.h_max(), options.max_steps);
        Ok(Box::new(Auto {
            explicit: Dopri5::new(options.step, h_max, max_steps, dim).with_stiffness_test_every(1),
            implicit: Radau5::new(rtol, atol, h0, h_max, max_steps, dim)?,
            stiff: false,
            last_stiff: false,
            nonstiff_steps: 0,
            switches: Vec::new(),
        }))
    }
}

/// Dormand–Prince and Radau IIA(5), one of them stepping.
pub struct Auto {
    explicit: Dopri5,
    implicit: Radau5,
    /// Whether Radau IIA takes the next step.
    stiff: bool,
    /// Whether Radau IIA took the last step (its dense output and state are the run's).
    last_stiff: bool,
    /// Radau steps in a row that Dormand–Prince could have taken stably.
    nonstiff_steps: usize,
    switches: Vec<MethodSwitch>,
}

impl Auto {
    fn last(&self) -> &dyn Stepper {
        if self.last_stiff {
            &self.implicit
        } else {
            &self.explicit
        }
    }
}

impl Stepper for Auto {
    fn name(&self) -> &'static str {
        "auto"
    }

    /// (Re)starts the method that steps now; a run starts explicit.
    fn start(&mut self, ode: &Ode, t: f64, y: &[f64]) -> Result<(), SolverError> {
        self.nonstiff_steps = 0;
        self.last_stiff = self.stiff;
        if self.stiff {
            self.implicit.start(ode, t, y)
        } else {
            self.explicit.start(ode, t, y)
        }
    }

    fn step(&mut self, ode: &Ode, t_stop: f64) -> Result<(), SolverError> {
        self.last_stiff = self.stiff;
        if !self.stiff {
            self.explicit.step(ode, t_stop)?;
            if self.explicit.stiffness_verdicts() >= STIFF_COUNT {
                let (t, h) = (self.explicit.state().t, self.explicit.state().h);
                let estimate = self.explicit.stiffness_estimate();
                self.switches.push(MethodSwitch {
                    t,
                    to: "radau5",
                    estimate,
                });
                self.stiff = true;
                self.nonstiff_steps = 0;
                self.implicit.set_next_step(h);
                let y = self.explicit.state().y.clone();
                self.implicit.start(ode, t, &y)?;
            }
            return Ok(());
        }
        self.implicit.step(ode, t_stop)?;
        let state = self.implicit.state();
        let estimate = (state.t - state.t_prev) * self.implicit.jacobian_norm();
        self.nonstiff_steps = if estimate <= STIFF_HLAMB {
            self.nonstiff_steps + 1
        } else {
            0
        };
        if self.nonstiff_steps >= STIFF_COUNT && state.t < t_stop {
            let t = state.t;
            self.switches.push(MethodSwitch {
                t,
                to: "dopri5",
                estimate,
            });
            self.stiff = false;
            let y = state.y.clone();
            self.explicit.start(ode, t, &y)?;
        }
        Ok(())
    }

    fn state(&self) -> &StepperState {
        self.last().state()
    }

    fn dense_output(&self, t: f64, y: &mut [f64]) {
        self.last().dense_output(t, y);
    }

    /// The work of both methods.
    fn stats(&self) -> Stats {
        let mut stats = self.explicit.stats();
        stats += self.implicit.stats();
        stats
    }

    /// Where it first switched to Radau IIA.
    fn stiffness_detected_at(&self) -> Option<f64> {
        self.switches.first().map(|s| s.t)
    }

    fn method_switches(&self) -> &[MethodSwitch] {
        &self.switches
    }
}
