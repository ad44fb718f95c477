//! The settings of a run as every front end gives them (the command line's options, Python's
//! keyword arguments, a Rust user's struct): the scheme and the treatment of v = 0, the
//! solver and its step control, the bounds of the run, and where the model's parameters come
//! from. Each is declared here once, with its help, default and unit, as clap arguments: the
//! command line flattens them into its commands, the other front ends fill the same structs
//! (whose `Default` is the declared defaults: [`declared_defaults`]). Each is checked here,
//! once, against the ranges of [`crate::ranges`].

use crate::error::{field, setting, AppError};
use crate::params::ParamSource;
use crate::ranges;
use crate::scheme::{SchemeName, SwitchingName};
use friction_models::Variant;
use friction_systems::Scheme;
use integrators::{Solver, StepControl};
use scenarios::Limits;
use std::time::Instant;

/// The paper's time step, s: RK4's and time-stepping's default.
pub const PAPER_DT: f64 = 1e-3;

/// The request `T` with every option at its declared default and no argument given: what a
/// front end that sets no option gets. The defaults are written once, in `T`'s declaration.
pub fn declared_defaults<T: clap::Args + clap::FromArgMatches>() -> T {
    let command = T::augment_args(clap::Command::new("defaults"));
    let matches = command
        .try_get_matches_from(["defaults"])
        .expect("every option of a request is optional or has a default");
    T::from_arg_matches(&matches).expect("a request's defaults parse as its fields")
}

/// [`Default`] as the declared defaults ([`declared_defaults`]) of each request type.
macro_rules! default_as_declared {
    ($($request:ty),*) => {$(
        impl Default for $request {
            fn default() -> Self {
                $crate::settings::declared_defaults()
            }
        }
    )*};
}

pub(crate) use default_as_declared;

default_as_declared!(SchemeChoice, RunLimits, SolverSettings, ModelSettings);

/// The note given for `switching = timestepping`, the former spelling of the time-stepping
/// scheme, which is still taken.
pub fn timestepping_spelling() -> String {
    format!(
        "`{}` is now spelt `{}` (time-stepping is a scheme, not a treatment of v = 0); the old \
         spelling is taken for now and will be refused in a later release",
        setting("switching", "timestepping"),
        setting("scheme", "time-stepping")
    )
}

/// `--scheme` and `--switching`: how a run or a study is integrated, and how v = 0 is treated
/// under the event-driven scheme.
#[derive(clap::Args, Clone, Copy, Debug, PartialEq)]
pub struct SchemeChoice {
    /// event-driven (a solver steps between located events; v = 0 treated by --switching) or
    /// time-stepping (Moreau–Jean: fixed steps, no event located, no solver; a study's one
    /// method, over its step sizes, against an event-driven reference).
    #[arg(
        long,
        value_name = "event-driven|time-stepping",
        default_value = "event-driven"
    )]
    pub scheme: SchemeName,
    /// The treatment of v = 0 under event-driven integration: event (stick/slip switching),
    /// regularized (tanh, width epsilon) or naive [default: event]. (`timestepping`, the
    /// former spelling of --scheme time-stepping, is still taken, with a note.)
    #[arg(long, value_name = "event|regularized|naive")]
    pub switching: Option<SwitchingName>,
}

impl SchemeChoice {
    /// The notes on their spelling: [`timestepping_spelling`] for `switching = timestepping`.
    pub fn spelling_notes(&self) -> Vec<String> {
        let old = self.switching == Some(SwitchingName::TimeStepping);
        old.then(timestepping_spelling).into_iter().collect()
    }

    /// Whether they ask for time-stepping (also by the former spelling
    /// `switching = timestepping`).
    pub fn is_time_stepping(&self) -> bool {
        self.scheme == SchemeName::TimeStepping
            || self.switching == Some(SwitchingName::TimeStepping)
    }

    /// The treatment of v = 0 they ask for when it does not read the friction parameter
    /// `epsilon` (`event`, `naive`, `timestepping`); `None` under regularized switching, which
    /// does.
    pub fn unread_epsilon(&self) -> Option<&'static str> {
        match (self.is_time_stepping(), self.switching) {
            (true, _) => Some(SwitchingName::TimeStepping.name()),
            (false, Some(SwitchingName::Regularized)) => None,
            (false, s) => Some(s.unwrap_or(SwitchingName::Event).name()),
        }
    }

    /// The combination checked: regularized or naive switching with the time-stepping scheme
    /// is refused (time-stepping treats v = 0 by the set-valued law).
    pub fn check(&self) -> Result<(), AppError> {
        match (self.scheme, self.switching) {
            (
                SchemeName::TimeStepping,
                Some(s @ (SwitchingName::Regularized | SwitchingName::Naive)),
            ) => {
                let (switching, scheme) = (field("switching"), field("scheme"));
                Err(AppError::Usage(format!(
                    "option `{switching} {}` applies to {scheme} event-driven: time-stepping \
                     locates no event and treats v = 0 by the set-valued law at the end of each \
                     step",
                    s.name()
                )))
            }
            _ => Ok(()),
        }
    }

    /// The schemes they ask for, checked ([`SchemeChoice::check`]): each of `solvers` under
    /// the treatment of v = 0 (event by default; regularised at width `epsilon`), or
    /// time-stepping at `theta`, the one scheme whatever the solvers.
    pub fn schemes(
        &self,
        solvers: &[Solver],
        epsilon: f64,
        theta: f64,
    ) -> Result<Vec<Scheme>, AppError> {
        self.check()?;
        if self.is_time_stepping() {
            return Ok(vec![Scheme::TimeStepping { theta }]);
        }
        let name = self.switching.unwrap_or(SwitchingName::Event);
        let switching = name.switching(epsilon).expect("not time-stepping");
        Ok(solvers
            .iter()
            .map(|&solver| Scheme::EventDriven { solver, switching })
            .collect())
    }
}

/// The bounds of a run: a step cap and a wall-clock limit.
#[derive(clap::Args, Clone, Copy, Debug, PartialEq)]
pub struct RunLimits {
    /// Most steps (accepted and rejected) of a run before it ends with an error, keeping what
    /// it computed.
    #[arg(
        long,
        value_name = "N",
        allow_hyphen_values = true,
        default_value = "10000000"
    )]
    pub max_steps: i64,
    /// Wall-clock limit of the command, s, counted from its start: a run in progress when it
    /// passes ends with an error, keeping what it computed, and a run not started yet ends at
    /// its first step (a study or a sweep of many runs is bounded as a whole).
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    pub time_limit: Option<f64>,
    /// When the limit started counting: set by a front end that checks these bounds once for
    /// each of many runs (a sweep), so that they bound the whole; `None` for the moment they
    /// are checked.
    #[arg(skip)]
    pub since: Option<Instant>,
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

/// The help of a solver option: `what`, the names in [`integrators::SOLVERS`] (the list the
/// option takes, from the one registry of solvers), then `then` (its default and when it is
/// refused).
pub fn solver_help(what: &str, then: &str) -> String {
    let names = integrators::SOLVERS.names();
    format!("{what}: {} {then}", names.join(", "))
}

/// The scheme, the solver and its step control, and the bounds of a run: the options every
/// command that integrates shares.
#[derive(clap::Args, Clone, Copy, Debug)]
pub struct SolverSettings {
    /// The scheme, and the treatment of v = 0 under the event-driven one.
    #[command(flatten)]
    pub scheme: SchemeChoice,
    /// The solver of event-driven integration; `None`: `auto` (Dormand–Prince, switched to
    /// Radau IIA where the problem turns stiff), or Dormand–Prince with `fixed_step`.
    #[arg(
        long,
        value_name = "SOLVER",
        help = solver_help(
            "The solver of event-driven integration",
            "[default: auto, Dormand-Prince switched to Radau IIA where the problem turns \
             stiff (a run that never does is Dormand-Prince's, value for value); dopri5 with \
             --fixed-step; refused under time-stepping]"
        )
    )]
    pub solver: Option<Solver>,
    /// θ of --scheme time-stepping: the weight of the step's end on the smooth forces,
    /// 0.5 (trapezoidal, second order) to 1 (implicit Euler, first order) [default: 0.5;
    /// refused under the event-driven scheme, which has no θ].
    #[arg(long, value_name = "THETA", allow_hyphen_values = true)]
    pub theta: Option<f64>,
    /// Fixed step of rk4 and of time-stepping (default 1e-3 s, the paper's), or the initial
    /// step of the adaptive solvers (the fixed step with --fixed-step).
    #[arg(long, value_name = "H", allow_hyphen_values = true)]
    pub dt: Option<f64>,
    /// Integrate dopri5 or implicit-euler with fixed steps of --dt.
    #[arg(long)]
    pub fixed_step: bool,
    /// Relative tolerance of the adaptive solvers.
    #[arg(
        long,
        value_name = "R",
        allow_hyphen_values = true,
        default_value = "1e-8"
    )]
    pub rtol: f64,
    /// Absolute tolerance of the adaptive solvers.
    #[arg(
        long,
        value_name = "A",
        allow_hyphen_values = true,
        default_value = "1e-10"
    )]
    pub atol: f64,
    /// The bounds of the run.
    #[command(flatten)]
    pub limits: RunLimits,
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
        self.scheme.check()?;
        let time_stepping = self.scheme.is_time_stepping();
        let [scheme, theta_, solver_, dt] = ["scheme", "theta", "solver", "dt"].map(field);
        if let (Some(theta), false) = (self.theta, time_stepping) {
            return Err(AppError::Usage(format!(
                "option `{}` applies to {scheme} time-stepping, the weight of its θ-method: the \
                 event-driven solvers have none; drop {theta_}, or choose {scheme} time-stepping",
                setting("theta", &ranges::show(theta))
            )));
        }
        if let (Some(solver), true) = (self.solver, time_stepping) {
            return Err(AppError::Usage(format!(
                "option `{}` does not apply to {scheme} time-stepping: Moreau–Jean's scheme takes \
                 no ODE solver (its step is {dt}, its weight {theta_}); drop {solver_}, or choose \
                 {scheme} event-driven",
                setting("solver", solver.name())
            )));
        }
        if self.fixed_step && !self.solver().takes_fixed_steps() && !time_stepping {
            let fixed: Vec<_> = Solver::ALL
                .iter()
                .filter(|s| s.takes_fixed_steps())
                .map(|s| s.name())
                .collect();
            let [fixed_step, rtol, atol] = ["fixed_step", "rtol", "atol"].map(field);
            return Err(AppError::Usage(format!(
                "option `{fixed_step}` does not apply to solver `{}`: it chooses its own steps \
                 from {rtol} and {atol}; allowed with {}",
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

    /// θ of time-stepping: `theta`, or the trapezoidal rule's 1/2.
    pub fn theta(&self) -> f64 {
        self.theta.unwrap_or(scenarios::run::DEFAULT_THETA)
    }

    /// The scheme they ask for, regularised at width `epsilon` under regularized switching
    /// (the other settings are checked by [`SolverSettings::checked_step`], which every run
    /// calls first).
    pub fn scheme(&self, epsilon: f64) -> Result<Scheme, AppError> {
        let schemes = self
            .scheme
            .schemes(&[self.solver()], epsilon, self.theta())?;
        Ok(schemes[0])
    }

    /// The solver of event-driven integration: `solver`; by default `auto`, which is
    /// Dormand–Prince until Hairer's stiffness test fires and Radau IIA while the problem is
    /// stiff (the servo, the bristle models), or Dormand–Prince with `fixed_step` (a fixed
    /// step has no stiffness test to switch on).
    pub fn solver(&self) -> Solver {
        let default = match self.fixed_step {
            true => Solver::DOPRI5,
            false => Solver::AUTO,
        };
        self.solver.unwrap_or(default)
    }

    /// The step control these settings ask for.
    pub fn step(&self) -> StepControl {
        let fixed = self.solver().is_fixed_step() || self.fixed_step;
        if fixed || self.scheme.is_time_stepping() {
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
#[derive(clap::Args, Clone, Debug)]
pub struct ModelSettings {
    /// The parameter set, file and assignments.
    #[command(flatten)]
    pub params: ParamSource,
    /// `odd`: the static term carries sign(v) (default); `printed`: the equations as printed.
    #[arg(long, value_name = "odd|printed", default_value = "odd")]
    pub variant: Variant,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_declared_defaults_are_the_documented_ones() {
        // docs/inputs.md: auto at rtol 1e-8, atol 1e-10 (dopri5 with a fixed step), at most
        // 1e7 steps, event-driven with event switching, the paper's parameters in the
        // sign-consistent reading.
        let s = SolverSettings::default();
        assert_eq!(
            (s.rtol, s.atol, s.limits.max_steps),
            (1e-8, 1e-10, 10_000_000)
        );
        assert_eq!(
            (s.solver, s.theta, s.dt, s.fixed_step),
            (None, None, None, false)
        );
        assert_eq!(s.scheme.scheme, SchemeName::EventDriven);
        assert_eq!(s.scheme(1e-3).unwrap(), Scheme::events(Solver::AUTO));
        let fixed = SolverSettings {
            fixed_step: true,
            ..s
        };
        assert_eq!(fixed.scheme(1e-3).unwrap(), Scheme::events(Solver::DOPRI5));
        let m = ModelSettings::default();
        assert_eq!((m.params.set_name(), m.variant), ("paper", Variant::Odd));
        // docs/phenomena.md: every protocol with BDF at rtol 1e-10, atol 1e-12.
        let t = crate::study::PhenomenaRequest::default();
        assert_eq!((t.solver, t.rtol, t.atol), (Solver::BDF, 1e-10, 1e-12));
        assert!(t.models.is_empty() && t.params.set.is_empty());
    }
}
