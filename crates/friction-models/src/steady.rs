//! Steady sliding of any model: its internal states, force and slope at a constant relative
//! velocity, and the rates of its states around it.

use crate::model::{FrictionModel, Partials, StatePartials};
use crate::sign::SignLaw;

/// The internal states z*(v) of steady sliding at velocity v.
pub fn states(model: &dyn FrictionModel, v: f64) -> Vec<f64> {
    let mut z = vec![0.0; model.n_states()];
    model.steady_state(v, &mut z);
    z
}

/// The friction force of steady sliding, F(0, v, z*(v)), under `law`.
pub fn force(model: &dyn FrictionModel, v: f64, law: SignLaw) -> f64 {
    model.force(0.0, v, &states(model, v), law)
}

/// The steady states z*(v) with the partials there under `law`.
fn linearised(
    model: &dyn FrictionModel,
    v: f64,
    law: SignLaw,
) -> (Vec<f64>, Partials, Vec<StatePartials>) {
    let z = states(model, v);
    let mut d = vec![StatePartials::default(); z.len()];
    let p = model.partials(0.0, v, &z, law, &mut d);
    (z, p, d)
}

/// The slope dF/dv of steady sliding under `law`, along the steady states:
/// `∂F/∂v + Σ_i ∂F/∂z_i·dz_i*/dv`, with `dz_i*/dv = −(∂ż_i/∂v)/(∂ż_i/∂z_i)`.
pub fn slope(model: &dyn FrictionModel, v: f64, law: SignLaw) -> f64 {
    let (_, p, d) = linearised(model, v, law);
    p.force_dv
        + d.iter()
            .filter(|d| d.rate_dz != 0.0)
            .map(|d| -d.force_dz * d.rate_dv / d.rate_dz)
            .sum::<f64>()
}

/// The time constant of the internal states on their way to steady sliding at velocity v:
/// the longer of their slowest relaxation, `1/min_i |∂ż_i/∂z_i|`, and the time to slide the
/// length the states carry, `|F(0, 0, z*) − F(0, 0, 0)| / k_rest` at |v| (the force the steady
/// states hold at rest over the stiffness at rest: for Dahl and LuGre the two times are one,
/// about g(v)/(σ0·|v|); GMS's blocks stick, ∂ż_i/∂z_i = 0, until they have slid that length).
/// `None` for a model without states.
pub fn time_constant(model: &dyn FrictionModel, v: f64) -> Option<f64> {
    let (z, _, d) = linearised(model, v, SignLaw::Discontinuous);
    let slowest = d.iter().map(|d| d.rate_dz.abs()).reduce(f64::min)?;
    let at_rest = |z: &[f64]| model.force(0.0, 0.0, z, SignLaw::Discontinuous);
    let carried = at_rest(&z) - at_rest(&vec![0.0; z.len()]);
    let length = carried.abs() / rest_stiffness(model, 1e-9 * v.abs());
    Some((1.0 / slowest).max(length / v.abs()))
}

/// The stiffness at rest, dF/dx along a small motion at velocity v → 0⁺ from the unloaded
/// state z = 0: `Σ_i (∂F/∂z_i)·ż_i/v` (σ for Dahl, σ0 for LuGre and GMS; 0 without states).
pub fn rest_stiffness(model: &dyn FrictionModel, v: f64) -> f64 {
    let n = model.n_states();
    let (z, mut rate) = (vec![0.0; n], vec![0.0; n]);
    let mut d = vec![StatePartials::default(); n];
    model.response(0.0, v, &z, SignLaw::Discontinuous, &mut rate);
    model.partials(0.0, v, &z, SignLaw::Discontinuous, &mut d);
    d.iter()
        .zip(&rate)
        .fold(0.0, |k, (d, r)| k + d.force_dz * r / v)
}
