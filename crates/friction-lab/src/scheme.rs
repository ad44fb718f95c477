//! The scheme of a run by name: event-driven or time-stepping, as `--scheme` and
//! `summary.json` spell it.

use scenarios::SwitchingKind;

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

    /// The scheme that integrates under `switching`: time-stepping or event-driven.
    pub fn of(switching: SwitchingKind) -> SchemeName {
        match switching.is_time_stepping() {
            true => SchemeName::TimeStepping,
            false => SchemeName::EventDriven,
        }
    }

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
