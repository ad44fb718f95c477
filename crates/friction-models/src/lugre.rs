//! The LuGre model of Canudas de Wit, Olsson, Åström and Lischinsky (1995).
//!
//! `F = σ0·z + σ1·ż + σ2·v`, `ż = v − σ0·|v|·z/g(v)`,
//! `g(v) = F_c + (F_s − F_c)·exp(−(v/v_s)²)`, with `|v| = v·sign(v)` evaluated by the
//! sign law (so the frozen and smooth laws apply to LuGre as to every other model).

use crate::catalog::ModelId;
use crate::model::{FrictionModel, Partials, Response, StickInterval};
use crate::sign::SignLaw;

/// LuGre parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LuGre {
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
        let e = (-(v / self.v_s).powi(2)).exp();
        let amplitude = self.f_s - self.f_c;
        (
            self.f_c + amplitude * e,
            -2.0 * v / (self.v_s * self.v_s) * amplitude * e,
        )
    }

    fn rate(&self, v: f64, z: f64, law: SignLaw) -> Rate {
        let b = law.branches(v);
        let (s, ds) = (b.sign(), b.dsign_dv());
        let (g, dg) = self.g(v);
        let abs_v = v * s;
        let dabs_v = s + v * ds;
        Rate {
            rate: v - self.sigma0 * abs_v * z / g,
            dv: 1.0 - self.sigma0 * z * (dabs_v * g - abs_v * dg) / (g * g),
            dz: -self.sigma0 * abs_v / g,
        }
    }
}

impl FrictionModel for LuGre {
    fn name(&self) -> &str {
        ModelId::LuGre.name()
    }

    fn n_states(&self) -> usize {
        1
    }

    fn response(&self, x: f64, v: f64, z: f64, law: SignLaw) -> Response {
        self.evaluate(x, v, z, law).0
    }

    fn partials(&self, x: f64, v: f64, z: f64, law: SignLaw) -> Partials {
        self.evaluate(x, v, z, law).1
    }

    fn evaluate(&self, _x: f64, v: f64, z: f64, law: SignLaw) -> (Response, Partials) {
        let r = self.rate(v, z, law);
        (
            Response {
                force: self.sigma0 * z + self.sigma1 * r.rate + self.sigma2 * v,
                state_rate: r.rate,
            },
            Partials {
                force_dv: self.sigma1 * r.dv + self.sigma2,
                force_dz: self.sigma0 + self.sigma1 * r.dz,
                rate_dv: r.dv,
                rate_dz: r.dz,
                ..Partials::default()
            },
        )
    }

    fn stick_interval(&self, x: f64, z: f64) -> StickInterval {
        // LuGre is smooth at v = 0: the admissible set is the single force σ0·z.
        let force = self.response(x, 0.0, z, SignLaw::Discontinuous).force;
        StickInterval {
            lower: force,
            upper: force,
        }
    }

    fn steady_state(&self, v: f64) -> f64 {
        self.g(v).0 * SignLaw::Discontinuous.branches(v).sign() / self.sigma0
    }

    fn state_after_displacement(&self, _z0: f64, _dx: f64) -> Option<f64> {
        None
    }
}
