//! The generalized Maxwell-slip model (GMS) of Al-Bender, Lampaert and Swevers (2005), IEEE
//! TAC 50(11): n elementary slip blocks in parallel, block i a spring of stiffness k_i with
//! deflection z_i whose force may not exceed its share α_i of the Stribeck curve g(v)
//! (Σ α_i = 1),
//!
//! `F = Σ_i (k_i·z_i + σ_i·ż_i) + σ2·v`,
//!
//! each block sticking (`ż_i = v`) until its force reaches α_i·g(v), then slipping with
//! `dF_i/dt = sign(v)·C·(α_i − F_i/s(v))`, s(v) = sign(v)·g(v) (their eqs. (5)–(6)), until the
//! motion reverses. Because every block is elastic–perfectly-plastic at low speed, the
//! pre-sliding force is a Masing/Preisach hysteresis with non-local memory: an inner loop
//! closes where it began and the outer curve goes on as if it had never been.
//!
//! Our formulation (docs/models.md): the two laws of a block joined without a mode flag,
//! `ż_i = sign(v)·min(|v|, (C/k_i)·(α_i − k_i·z_i·sign(v)/g(v)))`: the block follows the
//! stick law while it is the slower of the two and the slip law after. It is continuous in
//! z_i and steady sliding is exact (k_i·z_i = α_i·s(v)); the block leaves the stick law a
//! force k_i·|v|·g/C before its limit, so it equals the switched model as C → ∞. With
//! `|v| = v·sign(v)` evaluated by the sign law, the frozen and smooth laws apply as to LuGre.
//!
//! The blocks friction-lab builds from n (`n_gms`): equal stiffness k_i = σ0/n (σ0 stays the
//! stiffness at rest), shares α_i = (2i − 1)/n², so that the blocks slip one after the other
//! at deflections (2i − 1)·F_s/(n·σ0), and damping σ_i = σ1/n.

use crate::id::ModelId;
use crate::model::{FrictionModel, Partials, StatePartials, StickInterval};
use crate::sign::SignLaw;
use crate::terms;

/// One slip block of GMS.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Block {
    /// Stiffness k_i, N/m.
    pub stiffness: f64,
    /// Share α_i of the Stribeck curve the block carries when it slips.
    pub share: f64,
    /// Damping σ_i, N·s/m.
    pub damping: f64,
}

/// The generalized Maxwell-slip model.
#[derive(Clone, Debug, PartialEq)]
pub struct Gms {
    /// The slip blocks, at most [`MAX_STATES`](crate::MAX_STATES).
    pub blocks: Vec<Block>,
    /// Attraction C of the slip law, N/s.
    pub attraction: f64,
    /// Viscous coefficient σ2, N·s/m.
    pub sigma2: f64,
    /// Coulomb level F_c, N.
    pub f_c: f64,
    /// Static level F_s, N.
    pub f_s: f64,
    /// Stribeck velocity v_s, m/s.
    pub v_s: f64,
}

impl Gms {
    /// The blocks of friction-lab's GMS with n ≤ [`MAX_STATES`](crate::MAX_STATES) blocks: k_i = σ0/n,
    /// α_i = (2i − 1)/n², σ_i = σ1/n.
    pub fn blocks(n: usize, sigma0: f64, sigma1: f64) -> Vec<Block> {
        let nf = n as f64;
        (1..=n)
            .map(|i| Block {
                stiffness: sigma0 / nf,
                share: (2 * i - 1) as f64 / (nf * nf),
                damping: sigma1 / nf,
            })
            .collect()
    }
}

impl FrictionModel for Gms {
    fn name(&self) -> &str {
        ModelId::Gms.name()
    }

    fn n_states(&self) -> usize {
        self.blocks.len()
    }

    /// Block by block, `ż_i = s·min(u, q_i)` with s = sign(v), u = v·s and
    /// `q_i = (C/k_i)·(α_i − k_i·z_i·s/g)`; `F = Σ (k_i·z_i + σ_i·ż_i) + σ2·v`.
    fn evaluate(
        &self,
        _x: f64,
        v: f64,
        z: &[f64],
        law: SignLaw,
        rate: &mut [f64],
        states: &mut [StatePartials],
    ) -> (f64, Partials) {
        let b = law.released(v).branches(v);
        let (s, ds) = (b.sign(), b.dsign_dv());
        let g = terms::stribeck_level(self.f_c, self.f_s, self.v_s, v);
        let u = v * s;
        let du = s + v * ds;
        let c = self.attraction;
        let mut force = self.sigma2 * v;
        let mut force_dv = self.sigma2;
        for (i, block) in self.blocks.iter().enumerate() {
            let k = block.stiffness;
            let q = c / k * (block.share - k * z[i] * s / g.value);
            // ∂q/∂v and ∂q/∂z_i.
            let dq_dv = -c * z[i] * (ds * g.value - s * g.dv) / (g.value * g.value);
            let dq_dz = -c * s / g.value;
            let (value, dv, dz) = if u <= q {
                (s * u, ds * u + s * du, 0.0)
            } else {
                (s * q, ds * q + s * dq_dv, s * dq_dz)
            };
            rate[i] = value;
            states[i] = StatePartials {
                force_dz: k + block.damping * dz,
                rate_dx: 0.0,
                rate_dv: dv,
                rate_dz: dz,
            };
            force += k * z[i] + block.damping * value;
            force_dv += block.damping * dv;
        }
        (
            force,
            Partials {
                force_dx: 0.0,
                force_dv,
            },
        )
    }

    /// GMS is continuous at v = 0 (every block at rest holds its spring force): the
    /// admissible set is the single force Σ k_i·z_i.
    fn stick_interval(&self, x: f64, z: &[f64]) -> StickInterval {
        StickInterval::point(self.force(x, 0.0, z, SignLaw::Discontinuous))
    }

    /// The bristles' law involves v and z only.
    fn depends_on_position(&self) -> bool {
        false
    }

    /// Every block at its limit: `k_i·z_i = α_i·sign(v)·g(v)`.
    fn steady_state(&self, v: f64, z: &mut [f64]) {
        let s = SignLaw::Discontinuous.branches(v).sign();
        let g = terms::stribeck_level(self.f_c, self.f_s, self.v_s, v).value;
        for (z, block) in z.iter_mut().zip(&self.blocks) {
            *z = block.share * s * g / block.stiffness;
        }
    }
}
