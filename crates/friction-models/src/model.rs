//! The interface every friction model implements and the integrators use.

use crate::catalog::CurveAxis;
use crate::sign::SignLaw;
use serde::Serialize;
use std::fmt;

/// The friction force and the rate of the internal state at one point (x, v, z).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Response {
    /// Friction force F(x, v, z), N, acting against the motion for positive v.
    pub force: f64,
    /// dz/dt of the internal state (0 for models without one).
    pub state_rate: f64,
}

/// The analytic partial derivatives of the force F and of the state rate ż = g(x, v, z),
/// as implicit solvers need them for their Newton Jacobians.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Partials {
    /// ∂F/∂x.
    pub force_dx: f64,
    /// ∂F/∂v.
    pub force_dv: f64,
    /// ∂F/∂z.
    pub force_dz: f64,
    /// ∂ż/∂x.
    pub rate_dx: f64,
    /// ∂ż/∂v.
    pub rate_dv: f64,
    /// ∂ż/∂z.
    pub rate_dz: f64,
}

/// The admissible friction forces at v = 0 (the stick law of `models.md`):
/// `[F_smooth + L−, F_smooth + L+]`, with L± the one-sided limits of the discontinuous part.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct StickInterval {
    /// Lowest admissible friction force, N.
    pub lower: f64,
    /// Highest admissible friction force, N.
    pub upper: f64,
}

impl StickInterval {
    /// Whether a body needing friction `force` to stay at rest can stick.
    pub fn contains(&self, force: f64) -> bool {
        self.lower <= force && force <= self.upper
    }

    /// The friction force at rest under the applied force `applied`:
    /// `F = min(max(applied, lower), upper)` (eqs. 6–7: `sign(F)·min(|F|, F_s)`).
    pub fn clamp(&self, applied: f64) -> f64 {
        applied.max(self.lower).min(self.upper)
    }
}

/// Which reading of the paper's equations a model follows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Variant {
    /// Sign-consistent: the static term of eqs. (2), (10), (11) is F_s·sign(v).
    #[default]
    Odd,
    /// Exactly as printed: the static term is +F_s whatever the direction.
    Printed,
}

impl Variant {
    /// The variant's name as the command line takes it.
    pub fn name(self) -> &'static str {
        match self {
            Variant::Odd => "odd",
            Variant::Printed => "printed",
        }
    }
}

impl fmt::Display for Variant {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Variant {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "odd" => Ok(Variant::Odd),
            "printed" => Ok(Variant::Printed),
            _ => Err(format!("unknown variant `{s}`; allowed: odd, printed")),
        }
    }
}

/// A friction model: a force law F(x, v, z) with an optional internal state z.
///
/// - the slip force for v ≠ 0 is `response(x, v, z, SignLaw::Discontinuous).force`, or with
///   `SignLaw::Frozen(direction)` inside a slip mode;
/// - the smooth regularised form of width ε is `response(x, v, z, SignLaw::Smooth { epsilon })`;
/// - the admissible forces at rest are [`stick_interval`](FrictionModel::stick_interval);
/// - the state obeys `ż = response(..).state_rate` and, while stuck (v = 0), does not move.
///
/// The trait is public so that a model written in another crate runs in every rig, system
/// and study of friction-lab (see `examples/own_friction_law.rs`).
pub trait FrictionModel: fmt::Debug + Send + Sync {
    /// The model's name, as listings and output files print it.
    fn name(&self) -> &str;

    /// How the model's curve is drawn: force against velocity in steady sliding (the
    /// default), or against displacement under the paper's prescribed motion (Dahl types).
    fn curve_axis(&self) -> CurveAxis {
        CurveAxis::Velocity
    }

    /// Number of internal states: 0, or 1 for Dahl-type and LuGre models.
    fn n_states(&self) -> usize;

    /// Force and state rate at (x, v, z) with sign(v) evaluated by `law`.
    fn response(&self, x: f64, v: f64, z: f64, law: SignLaw) -> Response;

    /// Analytic partial derivatives of force and state rate at (x, v, z) under `law`.
    fn partials(&self, x: f64, v: f64, z: f64, law: SignLaw) -> Partials;

    /// [`response`](FrictionModel::response) and [`partials`](FrictionModel::partials) at
    /// one point together, for solvers that need both (the Newton iterations of
    /// time-stepping); a model overrides it to share the work of the two.
    fn evaluate(&self, x: f64, v: f64, z: f64, law: SignLaw) -> (Response, Partials) {
        (self.response(x, v, z, law), self.partials(x, v, z, law))
    }

    /// The admissible friction forces at rest with state `z`.
    fn stick_interval(&self, x: f64, z: f64) -> StickInterval;

    /// The internal state reached by steady sliding at velocity `v` (0 for stateless models).
    fn steady_state(&self, v: f64) -> f64;

    /// The state after a displacement `dx` in one direction from state `z0`, for a
    /// rate-independent state (Dahl); `None` when the state depends on the rate (LuGre) or
    /// there is none.
    fn state_after_displacement(&self, z0: f64, dx: f64) -> Option<f64>;

    /// Half-width of a stick band |v| < Δv inside which the stick law applies (Karnopp);
    /// 0 for models that stick only at v = 0.
    fn stick_band(&self) -> f64 {
        0.0
    }
}
