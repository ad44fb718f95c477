//! The scheme of a run by name, as `--scheme` and `--switching` spell it, resolved to
//! the one [`friction_systems::Scheme`] value by [`crate::settings::SchemeChoice`].

use friction_systems::Switching;

/// `--scheme`: how a run is integrated, as Siconos's `Simulation` chooses it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SchemeName {
    /// A solver steps between located events; v = 0 is treated by `--switching`.
    EventDriven,
    /// Moreau–Jean time-stepping: fixed steps of `--dt`, no event located, no ODE solver.
    TimeStepping,
}

impl SchemeName {
    /// Every scheme, as `--scheme` takes it.
    pub const ALL: [SchemeName; 2] = [SchemeName::EventDriven, SchemeName::TimeStepping];

    /// The name `--scheme` takes.
    pub fn name(self) -> &'static str {
        match self {
            SchemeName::EventDriven => "event-driven",
            SchemeName::TimeStepping => "time-stepping",
        }
    }
}

impl std::str::FromStr for SchemeName {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        SchemeName::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| format!("unknown scheme `{s}`; known: event-driven, time-stepping"))
    }
}

/// `--switching`: the treatment of v = 0 under the event-driven scheme, by name (the width ε
/// of the regularised one is the friction parameter `epsilon`); `timestepping`, the former
/// spelling of `--scheme time-stepping`, is still taken.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SwitchingName {
    /// [`Switching::Event`].
    Event,
    /// [`Switching::Regularized`].
    Regularized,
    /// [`Switching::Naive`].
    Naive,
    /// The former spelling of the time-stepping scheme.
    TimeStepping,
}

impl SwitchingName {
    /// Every name `--switching` takes.
    pub const ALL: [SwitchingName; 4] = [
        SwitchingName::Event,
        SwitchingName::Regularized,
        SwitchingName::Naive,
        SwitchingName::TimeStepping,
    ];

    /// The name `--switching` takes.
    pub fn name(self) -> &'static str {
        match self {
            SwitchingName::Event => "event",
            SwitchingName::Regularized => "regularized",
            SwitchingName::Naive => "naive",
            SwitchingName::TimeStepping => "timestepping",
        }
    }

    /// The treatment it names, with the regularisation width `epsilon` (m/s); `None` for the
    /// former spelling of time-stepping.
    pub fn switching(self, epsilon: f64) -> Option<Switching> {
        match self {
            SwitchingName::Event => Some(Switching::Event),
            SwitchingName::Regularized => Some(Switching::Regularized { epsilon }),
            SwitchingName::Naive => Some(Switching::Naive),
            SwitchingName::TimeStepping => None,
        }
    }
}

impl std::str::FromStr for SwitchingName {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        SwitchingName::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| {
                format!(
                    "unknown switching `{s}`; allowed: event, regularized, naive \
                     (time-stepping is a scheme: {} time-stepping)",
                    crate::error::field("scheme")
                )
            })
    }
}
