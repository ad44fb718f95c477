//! The interface every friction model implements and the integrators use.

use crate::sign::SignLaw;
use serde::Serialize;
use std::fmt;

/// The most internal states a model may have (GMS with its most elements has 16): the
/// size of the stack buffers [`FrictionModel::force`] and the solvers use.
pub const MAX_STATES: usize = 16;

/// The one number output files report for a model's internal states: the state itself, or the
/// mean of several (for GMS's blocks of equal stiffness, σ0 times it is the spring force, as
/// σ0·z is LuGre's); `None` without states.
pub fn reported_state(z: &[f64]) -> Option<f64> {
    (!z.is_empty()).then(|| z.iter().sum::<f64>() / z.len() as f64)
}

/// The analytic partial derivatives of the force F(x, v, z) in x and v, as implicit solvers
/// need them for their Newton Jacobians (those in the states are [`StatePartials`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Partials {
    /// ∂F/∂x.
    pub force_dx: f64,
    /// ∂F/∂v.
    pub force_dv: f64,
}

/// The partial derivatives that involve one internal state z_i with rate ż_i = g_i(x, v, z_i).
/// The states of a model are coupled only through x and v (∂g_i/∂z_j = 0 for i ≠ j), as in
/// Dahl's, LuGre's and the Maxwell-slip elements' laws, so the state block of the Jacobian is
/// diagonal.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StatePartials {
    /// ∂F/∂z_i.
    pub force_dz: f64,
    /// ∂ż_i/∂x.
    pub rate_dx: f64,
    /// ∂ż_i/∂v.
    pub rate_dv: f64,
    /// ∂ż_i/∂z_i.
    pub rate_dz: f64,
}

/// The admissible friction forces at v = 0 (the stick law of `docs/models.md`):
/// `[F_smooth + L−, F_smooth + L+]`, with L± the one-sided limits of the discontinuous part.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct StickInterval {
    /// Lowest admissible friction force, N.
    pub lower: f64,
    /// Highest admissible friction force, N.
    pub upper: f64,
}

impl StickInterval {
    /// The admissible set of a law continuous at rest (LuGre, GMS): the single force `force`.
    pub fn point(force: f64) -> Self {
        StickInterval {
            lower: force,
            upper: force,
        }
    }

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

/// How a model's curve is drawn (`friction-lab curve`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum CurveAxis {
    /// Force against velocity in steady sliding (Figures 2–4).
    Velocity,
    /// Force against displacement under the paper's prescribed motion (Figures 5–7).
    Displacement,
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

/// Runs `f` on a zeroed scratch slice of length `n`: on the stack up to [`MAX_STATES`] (one
/// entry for the laws with at most one state, so that the right-hand side of a static map does
/// not clear a full buffer at every evaluation), on the heap beyond.
#[inline(always)]
fn scratch<T: Copy + Default, R>(n: usize, f: impl FnOnce(&mut [T]) -> R) -> R {
    if n <= 1 {
        f(&mut [T::default(); 1][..n])
    } else if n <= MAX_STATES {
        f(&mut [T::default(); MAX_STATES][..n])
    } else {
        f(&mut vec![T::default(); n])
    }
}

/// A steady friction law's levels (F_c, F_s, F_v), as [`FrictionModel::stiction_levels`]
/// gives them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StictionLevels {
    /// Coulomb level F_c, N.
    pub f_c: f64,
    /// Static (break-away) level F_s, N (F_c where the law has none above it).
    pub f_s: f64,
    /// Viscous coefficient F_v, N·s/m.
    pub f_v: f64,
}

/// A friction model: a force law F(x, v, z) with internal states z = (z_1, …, z_n),
/// n = [`n_states`](FrictionModel::n_states) (0 for static maps, 1 for Dahl and LuGre, the
/// number of elements for the generalized Maxwell-slip model).
///
/// - the slip force for v ≠ 0 is `response(x, v, z, SignLaw::Discontinuous, ż)`, or with
///   `SignLaw::Frozen(direction)` inside a slip mode;
/// - the smooth regularised form of width ε is `response(x, v, z, SignLaw::Smooth { epsilon }, ż)`;
/// - the admissible forces at rest are [`stick_interval`](FrictionModel::stick_interval);
/// - the states obey `ż = g(x, v, z)` (written by `response`) and, while stuck (v = 0), do
///   not move.
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

    /// Its steady friction as a Coulomb level, a static (break-away) level and a viscous
    /// coefficient, F = F_c·sign(v) + F_v·v in slip and |F| ≤ F_s at rest, for the laws of
    /// that form: the input of the describing-function analysis of a servo's hunting cycle.
    /// `None` (the default) for a law of another form.
    fn stiction_levels(&self) -> Option<StictionLevels> {
        None
    }

    /// Number of internal states n, at most [`MAX_STATES`].
    fn n_states(&self) -> usize;

    /// The force F(x, v, z) with sign(v) evaluated by `law`, and its analytic partial
    /// derivatives at that point: returns F with ∂F/∂x and ∂F/∂v, writes the state rates
    /// ż = g(x, v, z) into `rate` and each state's partials into `states` (both of length n).
    /// The one method a law must compute; [`response`](FrictionModel::response) and
    /// [`partials`](FrictionModel::partials) read its two halves.
    fn evaluate(
        &self,
        x: f64,
        v: f64,
        z: &[f64],
        law: SignLaw,
        rate: &mut [f64],
        states: &mut [StatePartials],
    ) -> (f64, Partials);

    /// The force F(x, v, z) under `law`, with the state rates ż = g(x, v, z) written into
    /// `rate` (length n): the first half of [`evaluate`](FrictionModel::evaluate).
    fn response(&self, x: f64, v: f64, z: &[f64], law: SignLaw, rate: &mut [f64]) -> f64 {
        scratch(rate.len(), |states| {
            self.evaluate(x, v, z, law, rate, states).0
        })
    }

    /// The analytic partial derivatives at (x, v, z) under `law`: returns ∂F/∂x and ∂F/∂v,
    /// and writes each state's partials into `states` (length n): the second half of
    /// [`evaluate`](FrictionModel::evaluate).
    fn partials(
        &self,
        x: f64,
        v: f64,
        z: &[f64],
        law: SignLaw,
        states: &mut [StatePartials],
    ) -> Partials {
        scratch(states.len(), |rate| {
            self.evaluate(x, v, z, law, rate, states).1
        })
    }

    /// The force F(x, v, z) alone (the state rates computed into a scratch buffer).
    fn force(&self, x: f64, v: f64, z: &[f64], law: SignLaw) -> f64 {
        scratch(self.n_states(), |rate| self.response(x, v, z, law, rate))
    }

    /// The admissible friction forces at rest with states `z`.
    fn stick_interval(&self, x: f64, z: &[f64]) -> StickInterval;

    /// Writes into `z` the internal states reached by steady sliding at velocity `v`
    /// (nothing for a model without states).
    fn steady_state(&self, v: f64, z: &mut [f64]) {
        let _ = (v, z);
    }

    /// For rate-independent states (Dahl), writes into `z` the states after a displacement
    /// `dx` in one direction from `z0` and returns true; returns false when the states depend
    /// on the rate (LuGre) or there are none.
    fn state_after_displacement(&self, z0: &[f64], dx: f64, z: &mut [f64]) -> bool {
        let _ = (z0, dx, z);
        false
    }

    /// Half-width of a stick band |v| < Δv inside which the stick law applies (Karnopp);
    /// 0 for models that stick only at v = 0.
    fn stick_band(&self) -> f64 {
        0.0
    }

    /// Whether F(x, v, z), its partials and the stick interval depend on the position x.
    /// The default, `true`, is always safe; a law that returns `false` promises
    /// `∂F/∂x = 0` everywhere, and a static map (no internal state) that does so has a stick
    /// interval and one-sided forces at v = 0± that never change, which time-stepping then
    /// evaluates once per run instead of once per step (once it has found them the same to
    /// the bit at x = 0 and x = ±1e3 m; a law that breaks the promise there is evaluated at
    /// every step).
    fn depends_on_position(&self) -> bool {
        true
    }

    /// Whether, in each direction of sliding, the force is affine in the velocity:
    /// `F(x, v, z; Frozen(d)) = F(x, 0, z; Frozen(d)) + ∂F/∂v(x, 0, z; Frozen(d))·v` for every v,
    /// as Coulomb's `F_c·sign(v)`, the viscous `μ_v·v` and their sums are. The default,
    /// `false`, is always safe; a static map that returns `true` and ignores x has a sliding
    /// equation that time-stepping solves in closed form (one division, no evaluation of the
    /// law) instead of by Newton's method, once it has checked the promise at 1e-3, 1 and
    /// 1e3 m/s either way (a law that breaks it is solved by Newton's method).
    fn affine_in_velocity(&self) -> bool {
        false
    }
}
