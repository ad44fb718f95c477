//! The classical friction terms, each a value and its derivative with respect to v, written
//! through the [`Branches`] of a [`SignLaw`](crate::SignLaw) so that one formula serves the
//! discontinuous, frozen-direction and regularised laws.

use crate::sign::Branches;

/// A term's value and its partial derivative with respect to the velocity v.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Term {
    /// The force, N.
    pub value: f64,
    /// ∂(force)/∂v, N·s/m.
    pub dv: f64,
}

impl std::ops::Add for Term {
    type Output = Term;
    fn add(self, other: Term) -> Term {
        Term {
            value: self.value + other.value,
            dv: self.dv + other.dv,
        }
    }
}

/// Coulomb friction `F_c·sign(v)`.
pub fn coulomb(f_c: f64, b: &Branches) -> Term {
    Term {
        value: f_c * b.sign(),
        dv: f_c * b.dsign_dv(),
    }
}

/// The static term of eqs. (2), (10), (11): `F_s·sign(v)` in the sign-consistent ("odd")
/// reading, or `F_s` exactly as printed (`signed = false`).
pub fn static_level(f_s: f64, signed: bool, b: &Branches) -> Term {
    if signed {
        coulomb(f_s, b)
    } else {
        Term {
            value: f_s,
            dv: 0.0,
        }
    }
}

/// Viscous friction `μ_v·v`.
pub fn viscous(mu_v: f64, v: f64) -> Term {
    Term {
        value: mu_v * v,
        dv: mu_v,
    }
}

/// The Stribeck terms C1, C2 of eqs. (3)–(4):
/// `S(v) = exp(−(v/v_s)²)·(C1·[v > 0] − C2·[v < 0])`, with the indicator functions given by
/// the branch weights (so S(0) = 0 under the discontinuous law).
pub fn stribeck(c1: f64, c2: f64, v_s: f64, v: f64, b: &Branches) -> Term {
    if c1 == 0.0 && c2 == 0.0 {
        // No Stribeck term (Coulomb, static, Dahl models): spare the exponential.
        return Term {
            value: 0.0,
            dv: 0.0,
        };
    }
    let e = (-(v / v_s).powi(2)).exp();
    let de = -2.0 * v / (v_s * v_s) * e;
    let level = c1 * b.plus - c2 * b.minus;
    Term {
        value: e * level,
        dv: de * level + e * (c1 + c2) * b.dplus_dv,
    }
}

/// The Stribeck curve of LuGre and GMS, `g(v) = F_c + (F_s − F_c)·exp(−(v/v_s)²)` (the
/// steady friction level at speed |v|), with its derivative in v.
pub fn stribeck_level(f_c: f64, f_s: f64, v_s: f64, v: f64) -> Term {
    let e = (-(v / v_s).powi(2)).exp();
    let amplitude = f_s - f_c;
    Term {
        value: f_c + amplitude * e,
        dv: -2.0 * v / (v_s * v_s) * amplitude * e,
    }
}

/// Dahl's differential law, `dz/dt = σ·(v − |v|·z/F_c)` with `|v| = v·sign(v)`:
/// the state's rate and its partial derivatives with respect to v and z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DahlRate {
    /// dz/dt, N/s.
    pub rate: f64,
    /// ∂(dz/dt)/∂v.
    pub dv: f64,
    /// ∂(dz/dt)/∂z.
    pub dz: f64,
}

/// Evaluates Dahl's law at velocity `v` and state `z` (see [`DahlRate`]).
pub fn dahl_rate(sigma: f64, f_c: f64, v: f64, z: f64, b: &Branches) -> DahlRate {
    let s = b.sign();
    DahlRate {
        rate: sigma * (v - v * s * z / f_c),
        dv: sigma * (1.0 - (s + v * b.dsign_dv()) * z / f_c),
        dz: -sigma * v * s / f_c,
    }
}

/// The paper's closed form of the Dahl force (eqs. 8, 10, 11):
/// `F_c·(1 − exp(−σ|X|/F_c))·sign(Ẋ)`, the solution of Dahl's law for motion in one
/// direction from z = 0 at X = 0.
pub fn dahl_closed_form(sigma: f64, f_c: f64, x: f64, v: f64) -> f64 {
    let s = if v > 0.0 {
        1.0
    } else if v < 0.0 {
        -1.0
    } else {
        0.0
    };
    // 1 − exp(−a) as −expm1(−a): no cancellation for small displacements.
    -f_c * (-sigma * x.abs() / f_c).exp_m1() * s
}

/// The exact Dahl state after a displacement `dx` in one direction, starting from `z0`.
///
/// Dahl's law is rate-independent: `dz/dx = σ·(1 − z·sign(dx)/F_c)` is linear in z on a
/// monotone path, so `z = s·F_c + (z0 − s·F_c)·exp(−σ|dx|/F_c)` with `s = sign(dx)`,
/// evaluated as `z0·exp(−a) − s·F_c·expm1(−a)` to keep full precision for small steps.
pub fn dahl_after_displacement(sigma: f64, f_c: f64, z0: f64, dx: f64) -> f64 {
    if dx == 0.0 {
        return z0;
    }
    let a = sigma * dx.abs() / f_c;
    z0 * (-a).exp() - dx.signum() * f_c * (-a).exp_m1()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sign::SignLaw;
    use approx::assert_relative_eq;

    #[test]
    fn stribeck_terms_are_eqs_3_and_4() {
        let b = SignLaw::Discontinuous.branches(0.1);
        let s = stribeck(1.5, 2.0, 0.1, 0.1, &b);
        assert_relative_eq!(s.value, 1.5 * (-1.0f64).exp(), max_relative = 1e-15);
        let b = SignLaw::Discontinuous.branches(-0.2);
        let s = stribeck(1.5, 2.0, 0.1, -0.2, &b);
        assert_relative_eq!(s.value, -2.0 * (-4.0f64).exp(), max_relative = 1e-15);
        let b = SignLaw::Discontinuous.branches(0.0);
        assert_eq!(stribeck(1.5, 2.0, 0.1, 0.0, &b).value, 0.0);
    }

    #[test]
    fn dahl_closed_form_solves_dahls_law() {
        // Along X(t) = t³/3 + t²/2, Ẋ = t(t+1): d/dt of the closed form equals Dahl's rate
        // evaluated on the closed form itself.
        let (sigma, f_c) = (5.0, 6.0);
        for i in 1..=200 {
            let t = i as f64 * 0.01;
            let x = t.powi(3) / 3.0 + t * t / 2.0;
            let v = t * (t + 1.0);
            let z = dahl_closed_form(sigma, f_c, x, v);
            let dz_dt = sigma * v * (-sigma * x / f_c).exp();
            let b = SignLaw::Discontinuous.branches(v);
            let rate = dahl_rate(sigma, f_c, v, z, &b).rate;
            assert_relative_eq!(rate, dz_dt, max_relative = 1e-12);
        }
    }

    #[test]
    fn exact_dahl_steps_compose_to_the_closed_form() {
        let (sigma, f_c) = (5.0, 6.0);
        let mut z = 0.0;
        let n = 1000;
        let x_end = 4.0;
        for _ in 0..n {
            z = dahl_after_displacement(sigma, f_c, z, x_end / n as f64);
        }
        assert_relative_eq!(
            z,
            dahl_closed_form(sigma, f_c, x_end, 1.0),
            max_relative = 1e-12
        );
    }
}
