//! The rigs of `docs/scenarios.md`: what each one is, its parameters and defaults.

use crate::params::ScenarioParams;
use friction_models::FrictionParams;
use serde::Serialize;
use std::fmt;

/// A test rig.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum Scenario {
    /// m·v' = F_ex − F(v) from rest: the paper's experiment.
    PaperBlock,
    /// X(t) = t³/3 + t²/2 and its mirror image (Figures 5–7).
    PrescribedMotion,
    /// Steady friction on a grid of velocities (Figures 2–4).
    VelocitySweep,
    /// A spring-held body on a moving belt: m·ẍ + k·x = −F(ẋ − v_belt).
    Belt,
    /// m·ẍ + k·x = −F(ẋ), released from x0 at rest.
    FreeVibration,
    /// Prescribed x = amplitude·sin(omega·t).
    Oscillation,
    /// Prescribed v = v_mean + v_amplitude·cos(omega·t), x(0) = 0, internal states from zero.
    VelocityOscillation,
    /// m·v' = rate·t − F from rest.
    ForceRamp,
    /// A load of `fraction`·F_s applied (1 s ramp), held 1 s, released (1 s), then 1 s at rest.
    Presliding,
}

impl Scenario {
    /// Every scenario.
    pub const ALL: [Scenario; 9] = [
        Scenario::PaperBlock,
        Scenario::PrescribedMotion,
        Scenario::VelocitySweep,
        Scenario::Belt,
        Scenario::FreeVibration,
        Scenario::Oscillation,
        Scenario::VelocityOscillation,
        Scenario::ForceRamp,
        Scenario::Presliding,
    ];

    /// The name the command line takes.
    pub fn name(self) -> &'static str {
        match self {
            Scenario::PaperBlock => "paper-block",
            Scenario::PrescribedMotion => "prescribed-motion",
            Scenario::VelocitySweep => "velocity-sweep",
            Scenario::Belt => "belt",
            Scenario::FreeVibration => "free-vibration",
            Scenario::Oscillation => "oscillation",
            Scenario::VelocityOscillation => "velocity-oscillation",
            Scenario::ForceRamp => "force-ramp",
            Scenario::Presliding => "presliding",
        }
    }

    /// The scenario called `name`.
    pub fn from_name(name: &str) -> Result<Scenario, String> {
        Scenario::ALL
            .into_iter()
            .find(|s| s.name() == name)
            .ok_or_else(|| {
                let known: Vec<_> = Scenario::ALL.iter().map(|s| s.name()).collect();
                format!(
                    "unknown scenario `{name}`; known scenarios: {}",
                    known.join(", ")
                )
            })
    }

    /// The equation of the rig, in words.
    pub fn equation(self) -> &'static str {
        match self {
            Scenario::PaperBlock => "m*v' = F_ex - F(v), from x0, v0 (rest)",
            Scenario::PrescribedMotion => "X(t) = t^3/3 + t^2/2 and X -> -X; the model's state follows its law",
            Scenario::VelocitySweep => "steady friction at constant v on +-v_max*k/20, k = 1..20",
            Scenario::Belt => "m*x'' + c*x' + k*x = -F(x' - v_belt), from x0, v0",
            Scenario::FreeVibration => "m*x'' + c*x' + k*x = -F(x'), released from x0 at v0",
            Scenario::Oscillation => "x = amplitude*sin(omega*t) prescribed",
            Scenario::VelocityOscillation => {
                "v = v_mean + v_amplitude*cos(omega*t) prescribed, x(0) = 0, internal states from zero"
            }
            Scenario::ForceRamp => "m*v' = rate*t - F(v), from rest",
            Scenario::Presliding => "m*v' = L(t) - F(v), L: 0 -> fraction*F_s in 1 s, held 1 s, back to 0 in 1 s, 1 s at 0",
        }
    }

    /// The scenario parameters the rig reads.
    pub fn parameters(self) -> &'static [&'static str] {
        match self {
            Scenario::PaperBlock => &["m", "F_ex", "x0", "v0"],
            Scenario::PrescribedMotion => &[],
            Scenario::VelocitySweep => &["v_max"],
            Scenario::Belt => &["m", "k", "c", "v_belt", "x0", "v0"],
            Scenario::FreeVibration => &["m", "k", "c", "x0", "v0"],
            Scenario::Oscillation => &["amplitude", "omega"],
            Scenario::VelocityOscillation => &["v_mean", "v_amplitude", "omega"],
            Scenario::ForceRamp => &["m", "rate"],
            Scenario::Presliding => &["m", "fraction"],
        }
    }

    /// Whether a body is integrated (rather than a motion imposed).
    pub fn has_body(self) -> bool {
        !matches!(
            self,
            Scenario::PrescribedMotion
                | Scenario::VelocitySweep
                | Scenario::Oscillation
                | Scenario::VelocityOscillation
        )
    }

    /// The rig's default parameters (`docs/scenarios.md`).
    pub fn defaults(self) -> ScenarioParams {
        let base = ScenarioParams::default();
        match self {
            Scenario::FreeVibration => ScenarioParams { x0: 0.5, ..base },
            _ => base,
        }
    }

    /// How [`Scenario::default_t_end`] derives the end time from the parameters, with their
    /// values (`2·max(F_s, F_c)/rate with F_s = 7.5, F_c = 5, rate = 1`), for a rig whose end
    /// time depends on them; `None` for a fixed one.
    pub fn t_end_rule(self, p: &ScenarioParams, f: &FrictionParams) -> Option<String> {
        use friction_models::params::show;
        match self {
            Scenario::Oscillation | Scenario::VelocityOscillation => Some(format!(
                "three periods, 6π/omega with omega = {}",
                show(p.omega)
            )),
            Scenario::ForceRamp => Some(format!(
                "2·max(F_s, F_c)/rate with F_s = {}, F_c = {}, rate = {}",
                show(f.f_s),
                show(f.f_c),
                show(p.rate)
            )),
            _ => None,
        }
    }

    /// The default end time, s.
    pub fn default_t_end(self, p: &ScenarioParams, f: &FrictionParams) -> f64 {
        match self {
            Scenario::PaperBlock => 5.0,
            Scenario::PrescribedMotion => 2.0,
            Scenario::VelocitySweep => 0.0,
            Scenario::Belt => 20.0,
            Scenario::FreeVibration => 10.0,
            Scenario::Oscillation | Scenario::VelocityOscillation => {
                3.0 * 2.0 * std::f64::consts::PI / p.omega
            }
            Scenario::ForceRamp => 2.0 * f.f_s.max(f.f_c) / p.rate,
            Scenario::Presliding => 4.0,
        }
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
