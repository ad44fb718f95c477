//! The settings of a run as every front end gives them (the command line's options, Python's
//! keyword arguments, a Rust user's struct): the scheme and the treatment of v = 0, the
//! solver and its step control, the bounds of the run, and where the model's parameters come
//! from. Each is checked here, once, against the ranges of [`crate::ranges`].

use crate::error::AppError;
use crate::params::ParamSource;
use crate::ranges;
use crate::scheme::SchemeName;
use friction_models::Variant;
use integrators::{Solver, StepControl};
use scenarios::{Limits, SwitchingKind};
use std::time::Instant;

/// The paper's time step, s: RK4's and time-stepping's default.
pub const PAPER_DT: f64 = 1e-3;
/// The default relative tolerance of the adaptive solvers.
pub const DEFAULT_RTOL: f64 = 1e-8;
/// The default absolute tolerance of the adaptive solvers.
pub const DEFAULT_ATOL: f64 = 1e-10;
/// The default step cap of a run (accepted and rejected steps).
pub const DEFAULT_MAX_STEPS: i64 = 10_000_000;

/// The note given for `switching = timestepping`, the former spelling of the time-stepping
/// scheme, which is still taken.
pub const TIMESTEPPING_SPELLING: &str = "`--switching timestepping` is now spelt `--scheme \
     time-stepping` (time-stepping is a scheme, not a treatment of v = 0); the old spelling is \
     taken for now and will be refused in a later release";

/// The scheme, and the treatment of v = 0 under the event-driven one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SchemeChoice {
    /// Event-driven (a solver steps between located events) or time-stepping (Moreau–Jean).
    pub scheme: SchemeName,
    /// The treatment of v = 0 under event-driven integration (event, regularized, naive);
    /// `None`: event.
    pub switching: Option<SwitchingKind>,
}

impl Default for SchemeChoice {
    fn default() -> Self {
        SchemeChoice {
            scheme: SchemeName::EventDriven,
            switching: None,
        }
    }
}

impl SchemeChoice {
    /// The notes on their spelling: [`TIMESTEPPING_SPELLING`] for `switching = timestepping`.
    pub fn spelling_notes(&self) -> Vec<String> {
        let old = matches!(self.switching, Some(SwitchingKind::TimeStepping { .. }));
        old.then(|| TIMESTEPPING_SPELLING.to_string())
            .into_iter()
            .collect()
    }

    /// The treatment of v = 0 they ask for: time-stepping at `theta` (also from the former
    /// spelling `switching = timestepping`), or the switching under event-driven integration
    /// (event by default). Regularized or naive switching with the time-stepping scheme is
    /// refused: time-stepping treats v = 0 by the set-valued law.
    pub fn treatment(&self, theta: f64) -> Result<SwitchingKind, AppError> {
        match (self.scheme, self.switching) {
            (_, Some(SwitchingKind::TimeStepping { .. }))
            | (SchemeName::TimeStepping, None | Some(SwitchingKind::Event)) => {
                Ok(SwitchingKind::TimeStepping { theta })
            }
            (SchemeName::TimeStepping, Some(s)) => Err(AppError::Usage(format!(
                "option `--switching {}` applies to --scheme event-driven: time-stepping locates \
                 no event and treats v = 0 by the set-valued law at the end of each step",
                s.name()
            ))),
            (SchemeName::EventDriven, s) => Ok(s.unwrap_or(SwitchingKind::Event)),
        }
    }
}

/// The bounds of a run: a step cap and a wall-clock limit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunLimits {
    /// Most steps (accepted and rejected) before the run ends with an error, keeping what it
    /// computed.
    pub max_steps: i64,
    /// Wall-clock limit, s, counted from [`RunLimits::since`].
    pub time_limit: Option<f64>,
    /// When the limit started counting: set by a front end that checks these bounds once for
    /// each of many runs (a sweep), so that they bound the whole; `None` for the moment they
    /// are checked.
    pub since: Option<Instant>,
}

impl Default for RunLimits {
    fn default() -> Self {
        RunLimits {
            max_steps: DEFAULT_MAX_STEPS,
            time_limit: None,
            since: None,
        }
    }
}

impl RunLimits {
    /// The bounds, checked against their ranges.
    pub fn limits(&self) -> Result<Limits, AppError> {
        Ok(Limits {
            max_steps: ranges::MAX_STEPS.count(self.max_steps)?,
            time_limit: self
                .time_limit
                .map(|t| ranges::TIME_LIMIT.check(t))
                .transpose()?,
            time_limit_since: Some(self.since.unwrap_or_else(Instant::now)),
        })
    }
}

/// The scheme, the solver and its step control, and the bounds of a run.
#[derive(Clone, Copy, Debug)]
pub struct SolverSettings {
    /// The scheme, and the treatment of v = 0 under the event-driven one.
    pub scheme: SchemeChoice,
    /// The solver of event-driven integration; `None`: Dormand–Prince.
    pub solver: Option<Solver>,
    /// θ of time-stepping, in [1/2, 1]; `None`: 1/2.
    pub theta: Option<f64>,
    /// The fixed step of RK4 and of time-stepping, or an adaptive solver's initial step, s.
    pub dt: Option<f64>,
    /// Integrate an adaptive solver that can with fixed steps of `dt`.
    pub fixed_step: bool,
    /// Relative tolerance of the adaptive solvers.
    pub rtol: f64,
    /// Absolute tolerance of the adaptive solvers.
    pub atol: f64,
    /// The bounds of the run.
    pub limits: RunLimits,
}

impl Default for SolverSettings {
    fn default() -> Self {
        SolverSettings {
            scheme: SchemeChoice::default(),
            solver: None,
            theta: None,
            dt: None,
            fixed_step: false,
            rtol: DEFAULT_RTOL,
            atol: DEFAULT_ATOL,
            limits: RunLimits::default(),
        }
    }
}

impl SolverSettings {
    /// The step control these settings ask for, every value checked against its range, also
    /// those the chosen solver does not use; `fixed_step` only with a solver that takes fixed
    /// steps, `theta` only under time-stepping, a solver only under the event-driven scheme.
    pub fn checked_step(&self) -> Result<StepControl, AppError> {
        ranges::RTOL.check(self.rtol)?;
        ranges::ATOL.check(self.atol)?;
        if let Some(theta) = self.theta {
            ranges::THETA.check(theta)?;
        }
        if let Some(dt) = self.dt {
            ranges::DT.check(dt)?;
        }
        let switching = self.checked_switching()?;
        if let (Some(theta), false) = (self.theta, switching.is_time_stepping()) {
            return Err(AppError::Usage(format!(
                "option `--theta {}` applies to --scheme time-stepping, the weight of its \
                 θ-method: the event-driven solvers have none; drop --theta, or choose \
                 --scheme time-stepping",
                ranges::show(theta)
            )));
        }
        if let (Some(solver), true) = (self.solver, switching.is_time_stepping()) {
            return Err(AppError::Usage(format!(
                "option `--solver {}` does not apply to --scheme time-stepping: Moreau–Jean's \
                 scheme takes no ODE solver (its step is --dt, its weight --theta); drop \
                 --solver, or choose --scheme event-driven",
                solver.name()
            )));
        }
        if self.fixed_step && !self.solver().takes_fixed_steps() && !switching.is_time_stepping() {
            let fixed: Vec<_> = Solver::ALL
                .iter()
                .filter(|s| s.takes_fixed_steps())
                .map(|s| s.name())
                .collect();
            return Err(AppError::Usage(format!(
                "option `fixed-step` does not apply to solver `{}`: it chooses its own steps \
                 from --rtol and --atol; allowed with {}",
                self.solver().name(),
                fixed.join(", ")
            )));
        }
        Ok(self.step())
    }

    /// The bounds of a run, checked.
    pub fn checked_limits(&self) -> Result<Limits, AppError> {
        self.limits.limits()
    }

    /// The treatment of v = 0 that the scheme and the switching ask for, θ from `theta`
    /// ([`SchemeChoice::treatment`]; checked by [`SolverSettings::checked_step`]).
    pub fn checked_switching(&self) -> Result<SwitchingKind, AppError> {
        self.scheme.treatment(self.theta())
    }

    /// θ of time-stepping: `theta`, or the trapezoidal rule's 1/2.
    pub fn theta(&self) -> f64 {
        self.theta.unwrap_or(scenarios::run::DEFAULT_THETA)
    }

    /// The treatment of v = 0, once [`SolverSettings::checked_step`] has passed.
    pub fn switching(&self) -> SwitchingKind {
        self.checked_switching()
            .unwrap_or(SwitchingKind::TimeStepping {
                theta: self.theta(),
            })
    }

    /// The solver of event-driven integration: `solver`, or Dormand–Prince.
    pub fn solver(&self) -> Solver {
        self.solver.unwrap_or(Solver::DOPRI5)
    }

    /// The step control these settings ask for.
    pub fn step(&self) -> StepControl {
        let fixed = self.solver().is_fixed_step() || self.fixed_step;
        if fixed || self.switching().is_time_stepping() {
            StepControl::Fixed {
                h: self.dt.unwrap_or(PAPER_DT),
            }
        } else {
            StepControl::Adaptive {
                rtol: self.rtol,
                atol: self.atol,
                h0: self.dt,
            }
        }
    }
}

/// Where a model's parameters come from, and the reading of its equations.
#[derive(Clone, Debug, Default)]
pub struct ModelSettings {
    /// The parameter set, file and assignments.
    pub params: ParamSource,
    /// `odd`: the static term carries sign(v) (default); `printed`: as printed.
    pub variant: Variant,
}
