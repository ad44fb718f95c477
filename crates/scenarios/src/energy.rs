//! The energy balance of a body on a surface, kept by the solver itself: the body's state is
//! extended by three accumulators, integrated with it,
//!
//! - `W_ext = ∫(F0 + profile(t) − c·v)·v dt`: work of the applied forces other than the spring;
//! - `D = ∫F·v_rel dt`: energy taken by the contact (dissipated, or for Dahl and LuGre partly
//!   stored in the bristles);
//! - `W_belt = −∫F·v_surf dt`: work the moving surface puts in through friction;
//!
//! so that `Δ(½m·v² + ½k·x²) = W_ext + W_belt − D`. The residual of that balance, computed from
//! states the solver integrated separately, measures the solver's error.

use integrators::friction::FrictionBody;
use integrators::{Control, Entry, EventSpec, Mode, OdeProblem};
use serde::Serialize;

/// A [`FrictionBody`] with the three energy accumulators appended to its state.
pub struct Tracked<'a> {
    /// The body.
    pub body: FrictionBody<'a>,
}

impl Tracked<'_> {
    /// Number of the body's own unknowns.
    pub fn body_dim(&self) -> usize {
        self.body.dim()
    }

    /// The energy balance between the states `y0` and `y1` (accumulators included).
    pub fn balance(&self, y0: &[f64], y1: &[f64]) -> EnergyBalance {
        let n = self.body_dim();
        let (m, k) = (self.body.mass, self.body.applied.stiffness);
        let energy = |y: &[f64]| 0.5 * m * y[1] * y[1] + 0.5 * k * y[0] * y[0];
        let kinetic = 0.5 * m * (y1[1] * y1[1] - y0[1] * y0[1]);
        let spring = 0.5 * k * (y1[0] * y1[0] - y0[0] * y0[0]);
        let (w_ext, dissipated, w_belt) =
            (y1[n] - y0[n], y1[n + 1] - y0[n + 1], y1[n + 2] - y0[n + 2]);
        let residual = energy(y1) - energy(y0) - w_ext - w_belt + dissipated;
        let scale = [kinetic, spring, w_ext, dissipated, w_belt]
            .iter()
            .fold(f64::MIN_POSITIVE, |a, b| a.max(b.abs()));
        EnergyBalance {
            kinetic,
            spring,
            external_work: w_ext,
            belt_work: w_belt,
            friction_work: dissipated,
            residual,
            relative_residual: residual.abs() / scale,
        }
    }
}

/// The terms of the energy balance over a run, J.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct EnergyBalance {
    /// Change of kinetic energy.
    pub kinetic: f64,
    /// Change of spring energy.
    pub spring: f64,
    /// Work of the applied forces other than the spring.
    pub external_work: f64,
    /// Work put in by the moving surface.
    pub belt_work: f64,
    /// Energy taken by the contact (∫F·v_rel dt).
    pub friction_work: f64,
    /// `Δ(kinetic + spring) − external − belt + friction`.
    pub residual: f64,
    /// |residual| over the largest term.
    pub relative_residual: f64,
}

impl OdeProblem for Tracked<'_> {
    fn dim(&self) -> usize {
        self.body_dim() + 3
    }

    fn rhs(&self, t: f64, y: &[f64], mode: Mode, dy: &mut [f64]) {
        let n = self.body_dim();
        let b = &self.body;
        let friction = b.rhs_with_friction(t, &y[..n], mode, &mut dy[..n]);
        let (x, v) = (y[0], y[1]);
        let non_spring = b.applied.at(t, x, v) + b.applied.stiffness * x;
        dy[n] = non_spring * v;
        dy[n + 1] = friction * (v - b.surface_velocity);
        dy[n + 2] = -friction * b.surface_velocity;
    }

    /// The body's analytic Jacobian; the accumulators do not act back on the body, and their
    /// own rows are left out (an inexact Newton matrix only for the accumulators).
    fn jacobian(&self, t: f64, y: &[f64], mode: Mode, jac: &mut Vec<Entry>) -> bool {
        self.body.jacobian(t, &y[..self.body_dim()], mode, jac)
    }

    fn events(&self, mode: Mode) -> &[EventSpec] {
        self.body.events(mode)
    }

    fn event(&self, i: usize, t: f64, y: &[f64], mode: Mode) -> f64 {
        self.body.event(i, t, &y[..self.body_dim()], mode)
    }

    fn on_event(&self, i: usize, t: f64, y: &mut [f64], mode: Mode) -> Control {
        let n = self.body_dim();
        self.body.on_event(i, t, &mut y[..n], mode)
    }
}
