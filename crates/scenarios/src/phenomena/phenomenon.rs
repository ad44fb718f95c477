//! The rows of Table 2: a [`Phenomenon`] is an [`Experiment`] that decides it, the built-in
//! ones listed in [`Phenomenon::ALL`] and a user's own through [`Phenomenon::own`]
//! (registered with [`Phenomenon::register`], found by its name too).

use super::bench::Bench;
use super::experiments::{
    Hunting, Hysteresis, Presliding, RisingStaticFriction, StickSlip, Stiction, Stribeck, Viscous,
};
use super::Verdict;
use crate::error::ScenarioError;
use friction_models::ModelId;

/// The grid of rig parameters a verdict is also decided over: each axis a scenario parameter
/// with its values.
pub type Axes = &'static [(&'static str, &'static [f64])];

/// How a phenomenon is decided by simulation: the runs on a [`Bench`] and the measured
/// numbers that decide the cell against a stated threshold (`docs/phenomena.md`).
pub trait Experiment: Send + Sync {
    /// The name used in `table2.json` (`stick_slip`).
    fn name(&self) -> &'static str;

    /// The row's label in the table (`Stick-slip`).
    fn label(&self) -> &'static str;

    /// The grid of rig parameters the verdict is also decided over (docs/phenomena.md), the
    /// default rig among its points; empty for an experiment without rig parameters.
    fn region(&self) -> Axes {
        &[]
    }

    /// What the paper's Table 2 claims for its six models, in the order of
    /// [`ModelId::PAPER`]; `None` for a row the paper does not have.
    fn paper_row(&self) -> Option<[bool; 6]> {
        None
    }

    /// Decides the cell for the law on `bench`: whether the phenomenon is observed, with the
    /// numbers that decided it.
    fn decide(&self, bench: &Bench) -> Result<Verdict, ScenarioError>;
}

registry::handle!(
    /// A row of Table 2: an [`Experiment`], built in or a user's own.
    Phenomenon => dyn Experiment, PHENOMENA
);

/// Every row by name: the built-in ones ([`Phenomenon::ALL`]) and those registered with
/// [`Phenomenon::register`].
pub static PHENOMENA: registry::Registry<Phenomenon> =
    registry::Registry::new("phenomenon", "phenomena", &Phenomenon::ALL);

impl Phenomenon {
    /// The body stays put under a force below break-away.
    pub const STICTION: Phenomenon = Phenomenon::built_in(&Stiction);
    /// A small, partly reversible displacement before sliding.
    pub const PRESLIDING: Phenomenon = Phenomenon::built_in(&Presliding);
    /// Steady friction falls with velocity at low speed.
    pub const STRIBECK: Phenomenon = Phenomenon::built_in(&Stribeck);
    /// Steady friction grows with velocity at high speed.
    pub const VISCOUS: Phenomenon = Phenomenon::built_in(&Viscous);
    /// Friction is a loop, not a single-valued function of velocity, under oscillation.
    pub const HYSTERESIS: Phenomenon = Phenomenon::built_in(&Hysteresis);
    /// A spring-held body on a slow belt alternates between sticking and slipping.
    pub const STICK_SLIP: Phenomenon = Phenomenon::built_in(&StickSlip);
    /// The break-away force depends on how fast the applied force rises.
    pub const RISING_STATIC_FRICTION: Phenomenon = Phenomenon::built_in(&RisingStaticFriction);
    /// A PID-positioned mass settles on a limit cycle around its set point (the paper's
    /// closed-loop criterion; not a row of its Table 2).
    pub const HUNTING: Phenomenon = Phenomenon::built_in(&Hunting);

    /// Every built-in row: the paper's seven in its order, then closed-loop hunting.
    pub const ALL: [Phenomenon; 8] = [
        Phenomenon::STICTION,
        Phenomenon::PRESLIDING,
        Phenomenon::STRIBECK,
        Phenomenon::VISCOUS,
        Phenomenon::HYSTERESIS,
        Phenomenon::STICK_SLIP,
        Phenomenon::RISING_STATIC_FRICTION,
        Phenomenon::HUNTING,
    ];

    /// The experiment that decides it.
    pub fn experiment(self) -> &'static dyn Experiment {
        self.0.item()
    }

    /// What Table 2 of the paper claims for `model`: `None` for a model or a row the paper
    /// does not cover.
    pub fn paper_claim(self, model: ModelId) -> Option<bool> {
        let column = ModelId::PAPER.iter().position(|&m| m == model)?;
        Some(self.paper_row()?[column])
    }
}
