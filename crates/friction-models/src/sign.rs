//! How a model evaluates sign(v): the one place where the discontinuity at v = 0 lives.
//!
//! Every model writes its velocity dependence through [`Branches`]: the weight of the
//! positive branch (v > 0) and of the negative branch (v < 0), so that
//! `sign(v) = plus − minus` and `|v| = v·sign(v)`. The three laws differ only in how those
//! weights are computed, which lets one model implementation serve event-driven switching
//! (frozen direction), the naive discontinuous law and the regularised law.

use serde::Serialize;

/// Direction of sliding of a slip mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Direction {
    /// Sliding with v > 0 (mode `slip+`).
    Positive,
    /// Sliding with v < 0 (mode `slip-`).
    Negative,
}

impl Direction {
    /// The direction as a number: +1 or −1.
    pub fn sign(self) -> f64 {
        match self {
            Direction::Positive => 1.0,
            Direction::Negative => -1.0,
        }
    }

    /// The direction of a non-zero number, `None` for zero or NaN.
    pub fn of(value: f64) -> Option<Direction> {
        if value > 0.0 {
            Some(Direction::Positive)
        } else if value < 0.0 {
            Some(Direction::Negative)
        } else {
            None
        }
    }
}

/// How sign(v) is evaluated inside a model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SignLaw {
    /// sign(v) with sign(0) = 0, eq. (9) of the paper: the discontinuous law.
    Discontinuous,
    /// sign(v) replaced by the direction of the current slip mode: no sign(v) is evaluated,
    /// so the force stays smooth inside a step even if v crosses zero there.
    Frozen(Direction),
    /// The regularised law sign(v) ≈ tanh(v/ε), of width `epsilon` (m/s).
    Smooth {
        /// Regularisation width ε > 0, in m/s.
        epsilon: f64,
    },
}

/// Weights of the positive and negative velocity branches at one velocity.
///
/// `sign(v) = plus − minus`; for the discontinuous and frozen laws the weights are 0 or 1,
/// for the smooth law `plus = (1 + tanh(v/ε))/2` and `minus = 1 − plus`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Branches {
    /// Weight of the v > 0 branch.
    pub plus: f64,
    /// Weight of the v < 0 branch.
    pub minus: f64,
    /// d(plus)/dv; d(minus)/dv = −d(plus)/dv.
    pub dplus_dv: f64,
}

impl Branches {
    /// sign(v) under the law that produced these weights.
    pub fn sign(&self) -> f64 {
        self.plus - self.minus
    }

    /// d sign(v)/dv = 2·d(plus)/dv (zero away from the smooth law).
    pub fn dsign_dv(&self) -> f64 {
        2.0 * self.dplus_dv
    }
}

impl SignLaw {
    /// The law with the frozen direction released where v lies strictly on the other side of
    /// zero: `Frozen(d)` evaluates sign(v) = d there, a smooth extension that only a law with a
    /// true stick law needs (the events end the mode at the crossing). A law continuous at rest
    /// (LuGre, GMS: sign(v) only enters through |v| = v·sign(v)) takes this instead, so that a
    /// mode left behind at an equilibrium, where the sign of v is rounding, never evaluates
    /// |v| = −v.
    pub fn released(self, v: f64) -> SignLaw {
        match self {
            SignLaw::Frozen(d) if v * d.sign() < 0.0 => SignLaw::Discontinuous,
            law => law,
        }
    }

    /// The branch weights at velocity `v`.
    pub fn branches(self, v: f64) -> Branches {
        let (plus, minus) = match self {
            SignLaw::Discontinuous => match Direction::of(v) {
                Some(Direction::Positive) => (1.0, 0.0),
                Some(Direction::Negative) => (0.0, 1.0),
                None => (0.0, 0.0),
            },
            SignLaw::Frozen(Direction::Positive) => (1.0, 0.0),
            SignLaw::Frozen(Direction::Negative) => (0.0, 1.0),
            SignLaw::Smooth { epsilon } => {
                let t = (v / epsilon).tanh();
                return Branches {
                    plus: 0.5 * (1.0 + t),
                    minus: 0.5 * (1.0 - t),
                    dplus_dv: 0.5 * (1.0 - t * t) / epsilon,
                };
            }
        };
        Branches {
            plus,
            minus,
            dplus_dv: 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn discontinuous_sign_of_zero_is_zero() {
        let b = SignLaw::Discontinuous.branches(0.0);
        assert_eq!(b.sign(), 0.0);
        assert_eq!(SignLaw::Discontinuous.branches(-3.0).sign(), -1.0);
    }

    #[test]
    fn frozen_direction_ignores_velocity() {
        let b = SignLaw::Frozen(Direction::Positive).branches(-1.0);
        assert_eq!(b.sign(), 1.0);
    }

    #[test]
    fn smooth_sign_is_tanh_with_its_derivative() {
        let law = SignLaw::Smooth { epsilon: 0.01 };
        let b = law.branches(0.005);
        assert!((b.sign() - (0.5f64).tanh()).abs() < 1e-15);
        let h = 1e-7;
        let fd = (law.branches(0.005 + h).sign() - law.branches(0.005 - h).sign()) / (2.0 * h);
        assert!((b.dsign_dv() - fd).abs() < 1e-6 * fd.abs());
    }
}
