//! Continuation against Bautin's normal form in polar coordinates, r' = r·(μ + 2r² − r⁴),
//! θ' = 1: the origin's eigenvalues are μ ± i (a Hopf point at μ = 0), the cycles are the
//! circles r² = 1 ± √(1 + μ) of period 2π, which meet in a fold at μ = −1 (r = 1), the outer
//! stable and the inner unstable, with the nontrivial multiplier exp(2π·h'(r)),
//! h'(r) = μ + 6r² − 5r⁴ = 4r²(1 − r²) on a cycle.

use integrators::{Mode, OdeProblem};
use periodic::{
    continue_cycles, continue_equilibria, find_orbit, ContinuationOptions, Family, OrbitError,
    ShootingOptions, SpecialKind, Stability,
};

struct Bautin {
    mu: f64,
}

impl OdeProblem for Bautin {
    fn dim(&self) -> usize {
        2
    }

    fn rhs(&self, _t: f64, y: &[f64], _modes: &[Mode], dy: &mut [f64]) {
        let r2 = y[0] * y[0] + y[1] * y[1];
        let g = self.mu + 2.0 * r2 - r2 * r2;
        dy[0] = y[0] * g - y[1];
        dy[1] = y[1] * g + y[0];
    }

    /// Analytic: with g = μ + 2r² − r⁴, ∂g/∂x = (4 − 4r²)·x, ∂g/∂y = (4 − 4r²)·y. (Finite
    /// differences would put their rounding noise into the variational equations, which the
    /// step control at 1e-12 then resolves with thousands of times more steps.)
    fn jacobian(
        &self,
        _t: f64,
        y: &[f64],
        _modes: &[Mode],
        jac: &mut Vec<integrators::Entry>,
    ) -> bool {
        let r2 = y[0] * y[0] + y[1] * y[1];
        let g = self.mu + 2.0 * r2 - r2 * r2;
        let (gx, gy) = ((4.0 - 4.0 * r2) * y[0], (4.0 - 4.0 * r2) * y[1]);
        jac.extend([
            (0, 0, g + y[0] * gx),
            (0, 1, y[0] * gy - 1.0),
            (1, 0, y[1] * gx + 1.0),
            (1, 1, g + y[1] * gy),
        ]);
        true
    }
}

struct Family_;

impl Family for Family_ {
    fn with_problem(
        &self,
        p: f64,
        f: &mut dyn FnMut(&dyn OdeProblem) -> Result<(), OrbitError>,
    ) -> Result<(), OrbitError> {
        f(&Bautin { mu: p })
    }
}

#[test]
fn the_cycles_fold_at_minus_one_and_change_stability_there() {
    let mu0: f64 = 0.5;
    let r0 = (1.0 + (1.0 + mu0).sqrt()).sqrt();
    let start = find_orbit(
        &Bautin { mu: mu0 },
        0.0,
        (&[r0 * 1.001, 0.0], &[Mode(0)], 6.3),
        &ShootingOptions::default(),
    )
    .unwrap();
    // Stopped on the inner branch before it shrinks onto the origin at μ = 0 (where the
    // continuation would turn back along the same circles).
    let options = ContinuationOptions {
        max_points: 28,
        ..ContinuationOptions::over((-1.5, 0.5))
    };
    let branch = continue_cycles(
        &Family_,
        mu0,
        (&start.y0, &[Mode(0)], start.period),
        false,
        &options,
    )
    .unwrap();
    let folds: Vec<f64> = (branch.special.iter())
        .filter(|s| s.kind == SpecialKind::Fold)
        .map(|s| s.p)
        .collect();
    assert_eq!(
        folds.len(),
        1,
        "{:?}, ended: {}",
        branch.special,
        branch.ended
    );
    assert!((folds[0] + 1.0).abs() < 1e-3, "fold at {}", folds[0]);
    let mut inner = 0;
    for point in &branch.points {
        let r2 = point.y0[0].powi(2) + point.y0[1].powi(2);
        // On the branch: μ = −2r² + r⁴, the period 2π, the multiplier exp(2π·4r²(1 − r²)).
        assert!(
            (point.p - (r2 * r2 - 2.0 * r2)).abs() < 1e-8,
            "{} at r² = {r2}",
            point.p
        );
        assert!((point.period - 2.0 * std::f64::consts::PI).abs() < 1e-8);
        let exact = (2.0 * std::f64::consts::PI * 4.0 * r2 * (1.0 - r2)).exp();
        let mu = point.floquet.multipliers[1];
        assert!(
            (mu.0 - exact).abs() < 1e-6 * exact.max(1.0),
            "{mu:?} vs {exact}"
        );
        if (r2 - 1.0).abs() > 1e-3 {
            let expected = if r2 > 1.0 {
                Stability::Stable
            } else {
                Stability::Unstable
            };
            assert_eq!(point.floquet.stability, expected, "r² = {r2}");
            inner += usize::from(r2 < 1.0);
        }
    }
    assert!(
        inner >= 3,
        "the branch went on past the fold: {} inner points",
        inner
    );
}

#[test]
fn the_origins_hopf_point_is_at_mu_zero() {
    let options = ContinuationOptions::over((-0.5, 0.5));
    let branch =
        continue_equilibria(&Family_, -0.5, (&[0.0, 0.0], &[Mode(0)]), true, &options).unwrap();
    let hopf: Vec<f64> = (branch.special.iter())
        .filter(|s| s.kind == SpecialKind::Hopf)
        .map(|s| s.p)
        .collect();
    assert_eq!(hopf.len(), 1, "{:?}", branch.special);
    assert!(hopf[0].abs() < 1e-10, "Hopf at {}", hopf[0]);
    assert!(branch.points[0].stable && !branch.points.last().unwrap().stable);
}
