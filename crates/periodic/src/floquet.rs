//! Floquet multipliers of a periodic orbit: the eigenvalues of its monodromy matrix M. One is
//! 1, the flow's own direction (the trivial multiplier: a shift along the orbit stays a
//! shift); the orbit is asymptotically stable when every other lies inside the unit circle,
//! unstable when one lies outside (Hartman–Grobman on the Poincaré map; for hybrid orbits
//! with saltation matrices, Leine & Nijmeijer 2004, §7.2).

use nalgebra::DMatrix;
use serde::Serialize;

/// How far from 1 (and from the unit circle) a multiplier is taken as 1 (on it).
pub const UNIT_TOLERANCE: f64 = 1e-6;

/// An orbit's stability by its nontrivial multipliers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Stability {
    /// Every nontrivial multiplier inside the unit circle.
    Stable,
    /// One outside.
    Unstable,
    /// None outside, one on it (within [`UNIT_TOLERANCE`]): a bifurcation point, or a
    /// continuous family of orbits.
    Neutral,
}

/// The multipliers of a monodromy matrix.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Floquet {
    /// Every multiplier as (re, im), the trivial one first, then by decreasing modulus.
    pub multipliers: Vec<(f64, f64)>,
    /// The distance of the trivial multiplier from 1: a measure of the orbit's accuracy.
    pub trivial_error: f64,
    /// The stability by the others.
    pub stability: Stability,
}

impl Floquet {
    /// The multipliers of `monodromy` (Schur); `None` where the decomposition fails.
    pub fn of(monodromy: &DMatrix<f64>) -> Option<Floquet> {
        let schur = nalgebra::linalg::Schur::try_new(monodromy.clone(), f64::EPSILON, 10_000)?;
        let mut mu: Vec<(f64, f64)> = (schur.complex_eigenvalues().iter())
            .map(|l| (l.re, l.im))
            .collect();
        let from_one = |&(re, im): &(f64, f64)| (re - 1.0).hypot(im);
        let trivial =
            (0..mu.len()).min_by(|&a, &b| from_one(&mu[a]).total_cmp(&from_one(&mu[b])))?;
        let first = mu.remove(trivial);
        mu.sort_by(|a, b| b.0.hypot(b.1).total_cmp(&a.0.hypot(a.1)));
        let largest = mu.first().map_or(0.0, |&(re, im)| re.hypot(im));
        let stability = if largest > 1.0 + UNIT_TOLERANCE {
            Stability::Unstable
        } else if largest >= 1.0 - UNIT_TOLERANCE {
            Stability::Neutral
        } else {
            Stability::Stable
        };
        mu.insert(0, first);
        Some(Floquet {
            trivial_error: from_one(&first),
            multipliers: mu,
            stability,
        })
    }
}
