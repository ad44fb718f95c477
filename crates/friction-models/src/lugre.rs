//! The LuGre model of Canudas de Wit, Olsson, Åström and Lischinsky (1995), and the two
//! variants the literature uses beside it.
//!
//! `F = σ0·z + σ1(v)·ż + σ2·v`, `ż = v − α(z, v)·σ0·|v|·z/g(v)`,
//! `g(v) = F_c + (F_s − F_c)·exp(−(v/v_s)²)`, with `|v| = v·sign(v)` evaluated by the
//! sign law (so the frozen and smooth laws apply to LuGre as to every other model).
//! - LuGre: σ1(v) = σ1, α = 1.
//! - LuGre with velocity-dependent damping (Canudas de Wit et al. 1995, eq. (10); Olsson et
//!   al. 1998, §3.4): σ1(v) = σ1·exp(−(v/v_d)²), so that the bristle damping, needed at rest,
//!   vanishes in sliding.
//! - Elasto-plastic (Dupont, Hayward, Armstrong & Altpeter 2002, eqs. (9)–(12)): α(z, v) = 0
//!   while |z| ≤ z_ba (a purely elastic bristle: no drift below break-away), rising as
//!   ½·sin(π·(|z| − (z_max + z_ba)/2)/(z_max − z_ba)) + ½ to 1 at z_max = g(v)/σ0, and 0 when
//!   z and v have opposite signs (unloading is elastic).

use crate::id::ModelId;
use crate::model::{FrictionModel, Partials, StatePartials, StickInterval, StictionLevels};
use crate::sign::SignLaw;
use crate::terms;

/// LuGre parameters, and which variant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LuGre {
    /// Which model of the family this is (its name).
    pub id: ModelId,
    /// Bristle stiffness σ0, N/m.
    pub sigma0: f64,
    /// Bristle damping σ1, N·s/m.
    pub sigma1: f64,
    /// Viscous coefficient σ2, N·s/m.
    pub sigma2: f64,
    /// Coulomb level F_c, N.
    pub f_c: f64,
    /// Static level F_s, N.
    pub f_s: f64,
    /// Stribeck velocity v_s, m/s.
    pub v_s: f64,
    /// Decay velocity v_d of the damping σ1·exp(−(v/v_d)²), m/s; `None`: constant σ1.
    pub damping_decay: Option<f64>,
    /// The elasto-plastic break-away displacement z_ba, m, below z_max = g(v)/σ0 for every
    /// v; `None`: α = 1 (LuGre).
    pub break_away: Option<f64>,
}

/// ż and its partial derivatives.
struct Rate {
    rate: f64,
    dv: f64,
    dz: f64,
}

impl LuGre {
    /// The Stribeck curve g(v) and its derivative.
    fn g(&self, v: f64) -> (f64, f64) {
        let g = terms::stribeck_level(self.f_c, self.f_s, self.v_s, v);
        (g.value, g.dv)
    }

    /// The elasto-plastic weight α(z, v) and its partial derivatives (∂α/∂z, ∂α/∂v), given
    /// g(v), g'(v) and the sign of v.
    fn alpha(&self, v_sign: f64, z: f64, g: f64, dg: f64) -> (f64, f64, f64) {
        let Some(z_ba) = self.break_away else {
            return (1.0, 0.0, 0.0);
        };
        let u = z.abs();
        let z_max = g / self.sigma0;
        if v_sign * z <= 0.0 || u <= z_ba {
            return (0.0, 0.0, 0.0);
        }
        if u >= z_max {
            return (1.0, 0.0, 0.0);
        }
        let (w, mid) = (z_max - z_ba, 0.5 * (z_max + z_ba));
        let theta = std::f64::consts::PI * (u - mid) / w;
        let slope = 0.5 * theta.cos();
        let dtheta_du = std::f64::consts::PI / w;
        let dtheta_dzmax = std::f64::consts::PI * (-0.5 * w - (u - mid)) / (w * w);
        (
            0.5 * theta.sin() + 0.5,
            slope * dtheta_du * z.signum(),
            slope * dtheta_dzmax * dg / self.sigma0,
        )
    }

    /// The damping σ1(v) and its derivative.
    fn damping(&self, v: f64) -> (f64, f64) {
        match self.damping_decay {
            None => (self.sigma1, 0.0),
            Some(v_d) => {
                let e = (-(v / v_d).powi(2)).exp();
                (self.sigma1 * e, -2.0 * v / (v_d * v_d) * self.sigma1 * e)
            }
        }
    }

    fn rate(&self, v: f64, z: f64, law: SignLaw) -> Rate {
        let b = law.released(v).branches(v);
        let (s, ds) = (b.sign(), b.dsign_dv());
        let (g, dg) = self.g(v);
        let abs_v = v * s;
        let dabs_v = s + v * ds;
        let q = self.sigma0 * abs_v * z / g;
        let (alpha, dalpha_dz, dalpha_dv) = self.alpha(s, z, g, dg);
        Rate {
            rate: v - alpha * q,
            dv: 1.0 - alpha * self.sigma0 * z * (dabs_v * g - abs_v * dg) / (g * g) - q * dalpha_dv,
            dz: -alpha * self.sigma0 * abs_v / g - q * dalpha_dz,
        }
    }
}

impl FrictionModel for LuGre {
    fn name(&self) -> &str {
        self.id.name()
    }

    /// LuGre in the limit of a vanishing Stribeck speed and presliding displacement: (F_c,
    /// F_s, σ2); `None` for its variants.
    fn stiction_levels(&self) -> Option<StictionLevels> {
        (self.id == ModelId::LuGre).then_some(StictionLevels {
            f_c: self.f_c,
            f_s: self.f_s,
            f_v: self.sigma2,
        })
    }

    fn n_states(&self) -> usize {
        1
    }

    fn evaluate(
        &self,
        _x: f64,
        v: f64,
        z: &[f64],
        law: SignLaw,
        rate: &mut [f64],
        states: &mut [StatePartials],
    ) -> (f64, Partials) {
        let r = self.rate(v, z[0], law);
        let (sigma1, dsigma1) = self.damping(v);
        rate[0] = r.rate;
        states[0] = StatePartials {
            force_dz: self.sigma0 + sigma1 * r.dz,
            rate_dx: 0.0,
            rate_dv: r.dv,
            rate_dz: r.dz,
        };
        (
            self.sigma0 * z[0] + sigma1 * r.rate + self.sigma2 * v,
            Partials {
                force_dx: 0.0,
                force_dv: dsigma1 * r.rate + sigma1 * r.dv + self.sigma2,
            },
        )
    }

    fn stick_interval(&self, x: f64, z: &[f64]) -> StickInterval {
        // LuGre is smooth at v = 0: the admissible set is the single force σ0·z.
        StickInterval::point(self.force(x, 0.0, z, SignLaw::Discontinuous))
    }

    /// The bristles' law involves v and z only.
    fn depends_on_position(&self) -> bool {
        false
    }

    fn steady_state(&self, v: f64, z: &mut [f64]) {
        z[0] = self.g(v).0 * SignLaw::Discontinuous.branches(v).sign() / self.sigma0;
    }
}
