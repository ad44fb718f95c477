//! The registry of rigs (`docs/scenarios.md`): a [`Scenario`] is a [`Rig`], the built-in
//! ones listed in [`Scenario::ALL`] and a user's own through [`Scenario::own`] (registered
//! with [`Scenario::register`], found by its name too).

use crate::params::ScenarioParams;
use crate::rig::Rig;
use crate::rigs::{
    Belt, ForceRamp, FreeVibration, Oscillation, PaperBlock, PrescribedMotion, Presliding, Servo,
    VelocityOscillation, VelocitySweep,
};
use friction_models::FrictionParams;

registry::handle!(
    /// A test rig of friction-lab: a [`Rig`], built in or a user's own.
    Scenario => dyn Rig, SCENARIOS
);

/// Every rig by name: the built-in ones ([`Scenario::ALL`]) and those registered with
/// [`Scenario::register`].
pub static SCENARIOS: registry::Registry<Scenario> =
    registry::Registry::new("scenario", "scenarios", &Scenario::ALL);

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

    /// The rig.
    pub fn rig(self) -> &'static dyn Rig {
        self.0.item()
    }

    /// The default end time, s.
    pub fn default_t_end(self, p: &ScenarioParams, f: &FrictionParams) -> f64 {
        self.end_time(p, f).value()
    }
}
