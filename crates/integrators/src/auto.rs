//! `auto`: Dormand–Prince while the problem is not stiff, Radau IIA(5) while it is, switching
//! within one run, so that "explicit or implicit?" is answered interval by interval (as
//! LSODA answers it between Adams and BDF, and DifferentialEquations.jl's `AutoTsit5` between
//! its pair; Hairer & Wanner, *Solving ODEs II*, sec. IV.2, on detecting stiffness).
//!
//! - **To Radau IIA, by comparing step sizes** (LSODA's rule; L. Petzold, *SIAM J. Sci. Stat.
//!   Comput.* 4 (1983) 136–148, and ODEPACK's method switch: "the step size advantage must be
//!   at least RATIO = 5 to switch"). Where Dormand–Prince's step may be bounded by stability
//!   (Hairer's estimate `h·ρ̂ ≥` [`TRIAL_HLAMB`]), Radau IIA attempts one step [`RATIO`] times
//!   Dormand–Prince's next step from the current point. If it is accepted the run goes on
//!   with Radau IIA from that step's end. If not, Dormand–Prince goes on and the next trial
//!   waits twice as many steps ([`TRIAL_EVERY`], doubled up to dopri5.f's NSTIFF = 1000);
//!   the failed trial's work is counted. This catches stiffness that bounds the explicit step
//!   well below the stability boundary, where the estimate h·ρ̂ alone does not.
//! - **To Radau IIA, by Hairer's stiffness test** of `dopri5.f` (DOPCOR), taken at every
//!   accepted step here (dopri5.f takes it every 1000 steps until it is suspicious):
//!   `h·ρ̂ > 3.25` with `ρ̂ = ‖k7 − k6‖/‖y1 − ysti‖`, fifteen times in a row, where 3.25
//!   approximates the boundary of Dormand–Prince's stability region on the negative real
//!   axis (3.3).
//! - **Back to Dormand–Prince**: after each accepted Radau step, `h·‖J‖∞ ≤ 3.25` with the
//!   step just taken and the Jacobian Radau IIA holds (‖J‖∞, the largest row sum, bounds the
//!   spectral radius from above): Dormand–Prince could have taken that step stably. Fifteen
//!   such steps in a row, mirroring the count to the other side, switch back.
//!
//! Each switch is recorded ([`MethodSwitch`]: the time, the method switched to, the rule that
//! decided it and the estimate `h·ρ̂` there). The method switched to restarts at the current
//! point, as after an event: Radau IIA with the explicit method's last step size (or from its
//! accepted trial step), Dormand–Prince with its initial-step heuristic.

use crate::dopri5::{Dopri5, STIFF_COUNT, STIFF_HLAMB};
use crate::error::SolverError;
use crate::method::{adaptive_only, OneStepMethod};
use crate::options::Options;
use crate::radau5::Radau5;
use crate::solution::{MethodSwitch, SwitchRule};
use crate::stats::Stats;
use crate::stepper::{Ode, Stepper, StepperState};

/// LSODA's RATIO (ODEPACK, method switching): the stiff method must step at least this many
/// times further than the explicit one for the run to switch to it.
pub const RATIO: f64 = 5.0;

/// Dormand–Prince's `h·ρ̂` (Hairer's estimate) from which a trial step of Radau IIA is taken:
/// a step within a factor 3.25 of the stability boundary on the negative real axis may be
/// bounded by stability rather than accuracy. Below it the step is bounded by accuracy, and a
/// trial is mostly wasted or, worse, wins on a non-stiff stretch through Radau IIA's looser
/// transformed tolerance (measured with trials at any h·ρ̂: the paper's block with CVS and a
/// chain of 100 CVS blocks cost 1.27 and 1.10 times Dormand–Prince alone; with this
/// threshold, 1.00).
pub const TRIAL_HLAMB: f64 = 1.0;

/// Dormand–Prince steps before the first trial of Radau IIA (after its first step, so that a
/// problem stiff from the start, such as the test set's pollution, leaves the explicit method
/// at once), and after a switch back to it.
pub const TRIAL_EVERY: usize = 1;

/// The most steps between two trials: dopri5.f's NSTIFF, the interval of its own stiffness
/// test.
pub const TRIAL_EVERY_MAX: usize = 1000;

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
            since_trial: 0,
            trial_every: TRIAL_EVERY,
            switches: Vec::new(),
            end_read: false,
        }))
    }
}

/// Dormand–Prince and Radau IIA(5), one of them stepping.
#[derive(Clone)]
pub struct Auto {
    explicit: Dopri5,
    implicit: Radau5,
    /// Whether Radau IIA takes the next step.
    stiff: bool,
    /// Whether Radau IIA took the last step (its dense output and state are the run's).
    last_stiff: bool,
    /// Radau steps in a row that Dormand–Prince could have taken stably.
    nonstiff_steps: usize,
    /// Dormand–Prince steps since the last trial of Radau IIA, and how many the next waits.
    since_trial: usize,
    trial_every: usize,
    switches: Vec<MethodSwitch>,
    /// Whether a trial was left out because it would have reached the end.
    end_read: bool,
}

impl Auto {
    /// The method that took the last step.
    fn last(&self) -> &dyn Stepper {
        if self.last_stiff {
            &self.implicit
        } else {
            &self.explicit
        }
    }

    /// LSODA's comparison of step sizes, when one is due: Radau IIA attempts a step
    /// [`RATIO`] times Dormand–Prince's next one from where the run stands, and takes the
    /// run over if it is accepted (`true`: the step is the run's).
    fn trial(&mut self, ode: &Ode, t_stop: f64) -> Result<bool, SolverError> {
        let state = self.explicit.state();
        let h = RATIO * state.h;
        let due = self.since_trial >= self.trial_every
            && self.explicit.stiffness_estimate() >= TRIAL_HLAMB;
        self.end_read |= due && state.t + h >= t_stop;
        if !due || state.t + h >= t_stop {
            return Ok(false);
        }
        self.since_trial = 0;
        let (t, y) = (state.t, state.y.clone());
        if self.implicit.trial(ode, (t, &y), h, t_stop)? {
            self.switch_to_radau(SwitchRule::StepRatio);
            self.last_stiff = true;
            return Ok(true);
        }
        self.trial_every = (2 * self.trial_every).min(TRIAL_EVERY_MAX);
        Ok(false)
    }

    /// Records a switch to Radau IIA where Dormand–Prince stands.
    fn switch_to_radau(&mut self, rule: SwitchRule) {
        self.switches.push(MethodSwitch {
            t: self.explicit.state().t,
            to: "radau5",
            rule,
            estimate: self.explicit.stiffness_estimate(),
        });
        self.stiff = true;
        self.nonstiff_steps = 0;
    }

    /// A step of Radau IIA, and the switch back to Dormand–Prince after [`STIFF_COUNT`]
    /// steps in a row that it could have taken stably.
    fn implicit_step(&mut self, ode: &Ode, t_stop: f64) -> Result<(), SolverError> {
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
                rule: SwitchRule::StabilityBound,
                estimate,
            });
            self.stiff = false;
            self.since_trial = 0;
            self.trial_every = TRIAL_EVERY;
            let y = state.y.clone();
            self.explicit.start(ode, t, &y)?;
        }
        Ok(())
    }
}

impl Stepper for Auto {
    fn name(&self) -> &'static str {
        "auto"
    }

    /// (Re)starts the method that steps now; a run starts explicit. A trial waits for a step
    /// of the restarted Dormand–Prince: its step size and h·ρ̂ before it are the last
    /// interval's.
    fn start(&mut self, ode: &Ode, t: f64, y: &[f64]) -> Result<(), SolverError> {
        self.nonstiff_steps = 0;
        self.since_trial = 0;
        self.last_stiff = self.stiff;
        if self.stiff {
            self.implicit.start(ode, t, y)
        } else {
            self.explicit.start(ode, t, y)
        }
    }

    fn step(&mut self, ode: &Ode, t_stop: f64) -> Result<(), SolverError> {
        self.last_stiff = self.stiff;
        if self.stiff {
            return self.implicit_step(ode, t_stop);
        }
        if self.trial(ode, t_stop)? {
            return Ok(());
        }
        self.explicit.step(ode, t_stop)?;
        self.since_trial += 1;
        if self.explicit.stiffness_verdicts() >= STIFF_COUNT {
            let h = self.explicit.state().h;
            self.switch_to_radau(SwitchRule::StiffnessTest);
            self.implicit.set_next_step(h);
            let (t, y) = (self.explicit.state().t, self.explicit.state().y.clone());
            self.implicit.start(ode, t, &y)?;
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

    fn copy(&self) -> Option<Box<dyn Stepper>> {
        Some(Box::new(self.clone()))
    }

    /// As the method stepping says, and for Dormand–Prince also when a trial of Radau IIA,
    /// [`RATIO`] times its step, would reach the end.
    fn may_read_end(&self, t_stop: f64) -> bool {
        if self.stiff {
            return self.implicit.may_read_end(t_stop);
        }
        let state = self.explicit.state();
        self.explicit.may_read_end(t_stop) || state.t + RATIO * state.h >= t_stop
    }

    fn resume(&mut self, options: &Options) -> bool {
        let explicit = self.explicit.resume(options);
        let implicit = self.implicit.resume(options);
        explicit && implicit && !self.end_read
    }
}
