//! The two friction curves of the paper: force against velocity in steady sliding
//! (`velocity-sweep`, Figures 2–4) and force against displacement under the prescribed
//! motion `X(t) = t³/3 + t²/2` and its mirror image (`prescribed-motion`, Figures 5–7).

use friction_models::{CurveAxis, Direction, FrictionModel, SignLaw, StickInterval};
use serde::Serialize;
use thiserror::Error;

/// One point of a curve.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Sample {
    /// Time of the prescribed motion, s (0 for a velocity sweep).
    pub t: f64,
    /// Displacement, m (0 for a velocity sweep).
    pub x: f64,
    /// Velocity, m/s.
    pub v: f64,
    /// Internal state (the Dahl force, N; the bristle deflection, m; see
    /// [`friction_models::reported_state`]), 0 for stateless models.
    pub z: f64,
    /// Friction force, N.
    pub force: f64,
}

/// A friction curve: its two branches (v < 0 and v > 0, or mirrored and forward motion) and
/// the admissible forces at rest between them.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Curve {
    /// What the curve is drawn against.
    pub axis: CurveAxis,
    /// The v < 0 branch (velocity sweep) or the mirrored motion (prescribed motion), ordered
    /// away from zero.
    pub negative: Vec<Sample>,
    /// The v > 0 branch or the forward motion, ordered away from zero.
    pub positive: Vec<Sample>,
    /// The set of forces at rest at the origin (a vertical segment on the plot).
    pub at_rest: StickInterval,
    /// Force just left of zero: the one-sided limit as v → 0−.
    pub left_of_zero: f64,
    /// Force just right of zero: the one-sided limit as v → 0+.
    pub right_of_zero: f64,
}

/// A curve request that cannot be drawn.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum CurveError {
    /// An option outside its range.
    #[error("option `{name}` = {} is out of range: allowed {allowed}", friction_models::params::show(*.value))]
    OutOfRange {
        /// The option's name.
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// The allowed range.
        allowed: &'static str,
    },
    /// A displacement curve asked of a model whose state depends on the rate.
    #[error("model `{0}` has no rate-independent state; draw it against velocity")]
    RateDependentState(String),
}

/// Bounds on the number of points per branch.
pub const MAX_POINTS: usize = 1_000_000;

fn check_range(name: &'static str, value: f64) -> Result<(), CurveError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(CurveError::OutOfRange {
            name,
            value,
            allowed: "(0, inf)",
        })
    }
}

fn check_points(points: usize) -> Result<(), CurveError> {
    if (2..=MAX_POINTS).contains(&points) {
        Ok(())
    } else {
        Err(CurveError::OutOfRange {
            name: "points",
            value: points as f64,
            allowed: "[2, 1000000]",
        })
    }
}

/// The one-sided limits of the force at rest with states `z`.
fn limits_at_rest(model: &dyn FrictionModel, z: &[f64]) -> (f64, f64) {
    let limit = |d| model.force(0.0, 0.0, z, SignLaw::Frozen(d));
    (limit(Direction::Negative), limit(Direction::Positive))
}

fn sample(model: &dyn FrictionModel, t: f64, x: f64, v: f64, z: &[f64]) -> Sample {
    Sample {
        t,
        x,
        v,
        z: friction_models::reported_state(z).unwrap_or(0.0),
        force: model.force(x, v, z, SignLaw::Discontinuous),
    }
}

/// Friction against velocity in steady sliding, `points` samples per branch on
/// `0 < |v| ≤ v_max` (uniform); a stateful model is at its steady state at each v.
/// Inside a Karnopp stick band the stick law applies, so the branches start at |v| = Δv.
pub fn velocity_sweep(
    model: &dyn FrictionModel,
    v_max: f64,
    points: usize,
) -> Result<Curve, CurveError> {
    check_range("v_max", v_max)?;
    check_points(points)?;
    let band = model.stick_band().min(v_max);
    let branch = |sign: f64| -> Vec<Sample> {
        let mut z = vec![0.0; model.n_states()];
        (1..=points)
            .map(|k| {
                let v = sign * (band + (v_max - band) * k as f64 / points as f64);
                model.steady_state(v, &mut z);
                sample(model, 0.0, 0.0, v, &z)
            })
            .collect()
    };
    let rest = vec![0.0; model.n_states()];
    let (left_of_zero, right_of_zero) = limits_at_rest(model, &rest);
    Ok(Curve {
        axis: CurveAxis::Velocity,
        negative: branch(-1.0),
        positive: branch(1.0),
        at_rest: model.stick_interval(0.0, &rest),
        left_of_zero,
        right_of_zero,
    })
}

/// The paper's prescribed motion: `X(t) = t³/3 + t²/2`, `Ẋ(t) = t(t+1)`.
pub fn paper_motion(t: f64) -> (f64, f64) {
    (t.powi(3) / 3.0 + t * t / 2.0, t * (t + 1.0))
}

/// Friction against displacement under the paper's motion on `t ∈ (0, t_end]`
/// (`points` uniform instants) and its mirror image `X → −X`, starting at rest with z = 0.
/// The internal state follows its own law exactly between samples (Dahl's law is
/// rate-independent, see [`FrictionModel::state_after_displacement`]).
pub fn prescribed_motion(
    model: &dyn FrictionModel,
    t_end: f64,
    points: usize,
) -> Result<Curve, CurveError> {
    check_range("t_end", t_end)?;
    check_points(points)?;
    let branch = |sign: f64| -> Result<Vec<Sample>, CurveError> {
        let mut z = vec![0.0; model.n_states()];
        let mut x_prev = 0.0;
        (1..=points)
            .map(|k| {
                let t = t_end * k as f64 / points as f64;
                let (x, v) = paper_motion(t);
                let (x, v) = (sign * x, sign * v);
                let z0 = z.clone();
                if !model.state_after_displacement(&z0, x - x_prev, &mut z) {
                    return Err(CurveError::RateDependentState(model.name().to_string()));
                }
                x_prev = x;
                Ok(sample(model, t, x, v, &z))
            })
            .collect()
    };
    let rest = vec![0.0; model.n_states()];
    let (left_of_zero, right_of_zero) = limits_at_rest(model, &rest);
    Ok(Curve {
        axis: CurveAxis::Displacement,
        negative: branch(-1.0)?,
        positive: branch(1.0)?,
        at_rest: model.stick_interval(0.0, &rest),
        left_of_zero,
        right_of_zero,
    })
}

/// The model's curve along its own axis (see [`FrictionModel::curve_axis`]),
/// with `extent` the largest |v| (m/s) of a velocity sweep or the end time (s) of the
/// prescribed motion.
pub fn curve(model: &dyn FrictionModel, extent: f64, points: usize) -> Result<Curve, CurveError> {
    match model.curve_axis() {
        CurveAxis::Velocity => velocity_sweep(model, extent, points),
        CurveAxis::Displacement => prescribed_motion(model, extent, points),
    }
}

/// The default extent of a model's curve: |v| ≤ 1 m/s (`docs/scenarios.md`) or t ∈ [0, 2] s
/// (`docs/models.md`: the paper's "zero to two seconds").
pub fn default_extent(axis: CurveAxis) -> f64 {
    match axis {
        CurveAxis::Velocity => 1.0,
        CurveAxis::Displacement => 2.0,
    }
}
