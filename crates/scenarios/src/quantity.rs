//! The quantities of a body's state that the studies measure, with their units.

use serde::Serialize;

/// A quantity of a body's state that the studies compare.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// The displacement x, m.
    Position,
    /// The velocity v, m/s.
    Velocity,
    /// The friction law's internal state z (Dahl's and LuGre's bristle deflection, the mean
    /// of GMS's), m.
    InternalState,
}

impl Quantity {
    /// Its symbol: `x`, `v`, `z`.
    pub fn symbol(self) -> &'static str {
        match self {
            Quantity::Position => "x",
            Quantity::Velocity => "v",
            Quantity::InternalState => "z",
        }
    }

    /// Its unit.
    pub fn unit(self) -> &'static str {
        match self {
            Quantity::Velocity => "m/s",
            Quantity::Position | Quantity::InternalState => "m",
        }
    }
}
