//! The registry of rigs (`docs/scenarios.md`): a [`Scenario`] is a [`Rig`], the built-in
//! ones listed in [`Scenario::ALL`] and a user's own through [`Scenario::own`].

use crate::params::ScenarioParams;
use crate::rig::{EndTime, Rig};
use crate::rigs::{
    Belt, ForceRamp, FreeVibration, Oscillation, PaperBlock, PrescribedMotion, Presliding, Servo,
    VelocityOscillation, VelocitySweep,
};
use friction_models::FrictionParams;
use serde::{Serialize, Serializer};
use std::fmt;
use std::hash::{Hash, Hasher};

/// A test rig of friction-lab: a [`Rig`], built in or a user's own.
#[derive(Clone, Copy)]
pub struct Scenario {
    rig: &'static dyn Rig,
    /// Whether it is a user's own ([`Scenario::own`]).
    own: bool,
}

impl Scenario {
    /// m·v' = F_ex − F(v) from rest: the paper's experiment.
    pub const PAPER_BLOCK: Scenario = Scenario::built_in(&PaperBlock);
    /// X(t) = t³/3 + t²/2 and its mirror image (Figures 5–7).
    pub const PRESCRIBED_MOTION: Scenario = Scenario::built_in(&PrescribedMotion);
    /// Steady friction on a grid of velocities (Figures 2–4).
    pub const VELOCITY_SWEEP: Scenario = Scenario::built_in(&VelocitySweep);
    /// A spring-held body on a moving belt: m·ẍ + c·ẋ + k·x = −F(ẋ − v_belt).
    pub const BELT: Scenario = Scenario::built_in(&Belt);
    /// m·ẍ + c·ẋ + k·x = −F(ẋ), released from x0 at v0.
    pub const FREE_VIBRATION: Scenario = Scenario::built_in(&FreeVibration);
    /// Prescribed x = amplitude·sin(omega·t).
    pub const OSCILLATION: Scenario = Scenario::built_in(&Oscillation);
    /// Prescribed v = v_mean + v_amplitude·cos(omega·t), x(0) = 0, internal states from zero.
    pub const VELOCITY_OSCILLATION: Scenario = Scenario::built_in(&VelocityOscillation);
    /// m·v' = rate·t − F from rest.
    pub const FORCE_RAMP: Scenario = Scenario::built_in(&ForceRamp);
    /// A load of `fraction`·F_s applied (1 s ramp), held 1 s, released (1 s), then 1 s at rest.
    pub const PRESLIDING: Scenario = Scenario::built_in(&Presliding);
    /// A PID-controlled mass on the floor: the hunting example of the LuGre paper (1995).
    pub const SERVO: Scenario = Scenario::built_in(&Servo);

    /// Every built-in rig, in listing order: the ones the command line names.
    pub const ALL: [Scenario; 10] = [
        Scenario::PAPER_BLOCK,
        Scenario::PRESCRIBED_MOTION,
        Scenario::VELOCITY_SWEEP,
        Scenario::BELT,
        Scenario::FREE_VIBRATION,
        Scenario::OSCILLATION,
        Scenario::VELOCITY_OSCILLATION,
        Scenario::FORCE_RAMP,
        Scenario::PRESLIDING,
        Scenario::SERVO,
    ];

    const fn built_in(rig: &'static dyn Rig) -> Scenario {
        Scenario { rig, own: false }
    }

    /// A rig of the user's own, run wherever a built-in one runs.
    pub const fn own(rig: &'static dyn Rig) -> Scenario {
        Scenario { rig, own: true }
    }

    /// The rig.
    pub fn rig(self) -> &'static dyn Rig {
        self.rig
    }

    /// The name the command line takes.
    pub fn name(self) -> &'static str {
        self.rig.name()
    }

    /// The built-in rig called `name`.
    pub fn from_name(name: &str) -> Result<Scenario, String> {
        Scenario::ALL
            .into_iter()
            .find(|s| s.name() == name)
            .ok_or_else(|| {
                format!(
                    "unknown scenario `{name}`; known scenarios: {}",
                    Scenario::names().join(", ")
                )
            })
    }

    /// The names of the built-in rigs, in listing order.
    pub fn names() -> Vec<&'static str> {
        Scenario::ALL.iter().map(|s| s.name()).collect()
    }

    /// The equation of the rig, in words.
    pub fn equation(self) -> &'static str {
        self.rig.equation()
    }

    /// The scenario parameters the rig reads.
    pub fn parameters(self) -> &'static [&'static str] {
        self.rig.parameters()
    }

    /// Whether a body is integrated (rather than a motion imposed).
    pub fn has_body(self) -> bool {
        self.rig.has_body()
    }

    /// The rig's default parameters (`docs/scenarios.md`).
    pub fn defaults(self) -> ScenarioParams {
        self.rig.defaults()
    }

    /// The end time of a run that asks for none, and how it follows from the parameters.
    pub fn end_time(self, p: &ScenarioParams, f: &FrictionParams) -> EndTime {
        self.rig.end_time(p, f)
    }

    /// The law the rig runs when a run names none ([`Rig::default_law`]).
    pub fn default_law(self) -> Option<(friction_models::ModelId, &'static str)> {
        self.rig.default_law()
    }

    /// The default end time, s.
    pub fn default_t_end(self, p: &ScenarioParams, f: &FrictionParams) -> f64 {
        self.end_time(p, f).value()
    }
}

/// A built-in rig shows as its name, an own one as `own NAME`.
impl fmt::Debug for Scenario {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.own {
            f.write_str("own ")?;
        }
        f.write_str(self.name())
    }
}

/// Built-in rigs are equal when they have the same name, and so are own rigs; an own rig is
/// never equal to a built-in one.
impl PartialEq for Scenario {
    fn eq(&self, other: &Scenario) -> bool {
        self.own == other.own && self.name() == other.name()
    }
}

impl Eq for Scenario {}

impl Hash for Scenario {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.own.hash(state);
        self.name().hash(state);
    }
}

/// Written as its name.
impl Serialize for Scenario {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl fmt::Display for Scenario {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Scenario {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Scenario::from_name(s)
    }
}
