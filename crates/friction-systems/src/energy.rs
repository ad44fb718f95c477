//! The energy balance of a system, kept by the solver itself: the state carries three
//! accumulators integrated with it (see [`crate::hybrid`]),
//!
//! - `W_ext = ∫(Σ F_ext,i·v_i + Σ anchor power − Σ c·Δv²) dt`: work of the external forces and
//!   of the moving anchors through their springs, less the dampers' losses;
//! - `D = ∫Σ F_j·v_rel,j dt`: energy taken by the contacts (dissipated, or for Dahl and LuGre
//!   partly stored in the bristles);
//! - `W_belt = −∫Σ F_j·v_s,j dt`: work the moving surfaces put in through friction;
//!
//! so that `Δ(Σ ½m_i·v_i² + Σ ½k·Δx²) = W_ext + W_belt − D`. The residual of that balance,
//! computed from states the solver integrated separately, measures the solver's error.

use crate::hybrid::FrictionSystem;
use serde::Serialize;

/// The terms of the energy balance over a run, J.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct EnergyBalance {
    /// Change of kinetic energy.
    pub kinetic: f64,
    /// Change of spring energy.
    pub spring: f64,
    /// Work of the external forces and the anchors, less the dampers' losses.
    pub external_work: f64,
    /// Work put in by the moving surfaces.
    pub belt_work: f64,
    /// Energy taken by the contacts (∫F·v_rel dt).
    pub friction_work: f64,
    /// `Δ(kinetic + spring) − external − belt + friction`.
    pub residual: f64,
    /// |residual| over the largest term.
    pub relative_residual: f64,
}

impl FrictionSystem<'_> {
    /// Kinetic and spring energy at (t, y).
    pub fn energies(&self, t: f64, y: &[f64]) -> (f64, f64) {
        let kinetic = self
            .system
            .bodies
            .iter()
            .enumerate()
            .map(|(i, b)| 0.5 * b.m * y[self.layout.v(i)].powi(2))
            .sum();
        let spring = self
            .system
            .springs
            .iter()
            .map(|s| {
                let position = |end| match end {
                    crate::system::End::Body(i) => y[self.layout.x[i]],
                    crate::system::End::Anchor(a) => self.system.anchors[a].at(t).0,
                };
                0.5 * s.k * (position(s.b) - position(s.a)).powi(2)
            })
            .sum();
        (kinetic, spring)
    }

    /// The energy balance between (t0, y0) and (t1, y1), accumulators included.
    pub fn balance(&self, t0: f64, y0: &[f64], t1: f64, y1: &[f64]) -> EnergyBalance {
        let a = self.layout.accumulators;
        let (k0, s0) = self.energies(t0, y0);
        let (k1, s1) = self.energies(t1, y1);
        let (kinetic, spring) = (k1 - k0, s1 - s0);
        let (w_ext, dissipated, w_belt) =
            (y1[a] - y0[a], y1[a + 1] - y0[a + 1], y1[a + 2] - y0[a + 2]);
        let residual = kinetic + spring - w_ext - w_belt + dissipated;
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
