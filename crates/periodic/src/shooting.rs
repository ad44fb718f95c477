//! Newton's method on a periodic orbit: the unknowns are the initial state y₀ (its dynamic
//! unknowns) and the period T; the equations are the closure of the orbit and a phase
//! condition that fixes where on it y₀ lies (the hyperplane through a reference point y_r
//! normal to the flow there, a Poincaré section):
//!
//! ```text
//! φ_T(y₀) − y₀ = 0,   nᵀ(y₀ − y_r) = 0,   n = f(y_r)/|f(y_r)|,
//! ```
//!
//! whose Jacobian is the bordered matrix `[[M − I, f(φ_T(y₀))], [nᵀ, 0]]` with M the
//! monodromy matrix through every switch ([`mod@crate::flow`]). It is regular where the trivial
//! multiplier 1 is simple (an isolated orbit) and the section is transversal: Newton then
//! converges quadratically (Seydel 2010, §7.3; Doedel's AUTO for smooth orbits; COCO's `hspo`
//! for hybrid ones). The mode sequence is that of the flow from each iterate; it must close.

use crate::flow::{flow, FlowOptions, HybridFlow};
use crate::variational::field;
use crate::{Floquet, OrbitError};
use integrators::{Mode, OdeProblem};
use nalgebra::{DMatrix, DVector};

/// Newton's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShootingOptions {
    /// The flow's integration.
    pub flow: FlowOptions,
    /// The residual `‖φ_T(y₀) − y₀‖∞` to reach, relative to `max(1, ‖y₀‖∞)`.
    pub tolerance: f64,
    /// The most Newton iterations.
    pub max_iterations: usize,
}

impl Default for ShootingOptions {
    /// Residual 1e-10 in at most 30 iterations, the flow at [`FlowOptions::default`].
    fn default() -> Self {
        ShootingOptions {
            flow: FlowOptions::default(),
            tolerance: 1e-10,
            max_iterations: 30,
        }
    }
}

/// A periodic orbit found.
#[derive(Clone, Debug, PartialEq)]
pub struct PeriodicOrbit {
    /// Where the orbit starts: the time (of a non-autonomous problem's clock), s.
    pub t0: f64,
    /// The state at the start, on the section.
    pub y0: Vec<f64>,
    /// The modes at the start.
    pub modes0: Vec<Mode>,
    /// The period, s.
    pub period: f64,
    /// The flow over one period: the segments and the monodromy matrix.
    pub flow: HybridFlow,
    /// The Floquet multipliers and the stability.
    pub floquet: Floquet,
    /// The final residual, relative to the orbit's scale.
    pub residual: f64,
    /// Newton iterations made.
    pub iterations: usize,
}

impl PeriodicOrbit {
    /// The monodromy matrix.
    pub fn monodromy(&self) -> &DMatrix<f64> {
        &self.flow.sensitivity
    }
}

/// The periodic orbit of an autonomous `problem` near the guess (y, modes, period T) at time
/// `t0`, by Newton's method on (y₀, T) with the section through the guess normal to the flow.
pub fn find_orbit(
    problem: &dyn OdeProblem,
    t0: f64,
    (y_guess, modes0, period_guess): (&[f64], &[Mode], f64),
    options: &ShootingOptions,
) -> Result<PeriodicOrbit, OrbitError> {
    let n = problem.dim() - problem.quadratures();
    let field = |y: &[f64], modes: &[Mode]| field(problem, t0, y, modes, n);
    let normal = field(y_guess, modes0);
    if normal.norm() == 0.0 {
        return Err(OrbitError::NoGuess(
            "the guess is an equilibrium (f = 0): no section through it".into(),
        ));
    }
    let normal = normal.normalize();
    let reference = DVector::from_column_slice(&y_guess[..n]);
    let (mut y, mut period) = (y_guess.to_vec(), period_guess);
    let mut residual = f64::INFINITY;
    for iteration in 0..=options.max_iterations {
        let hybrid = flow(problem, (t0, period), &y, modes0, &options.flow)?;
        let gap = DVector::from_iterator(n, (0..n).map(|i| hybrid.y_end[i] - y[i]));
        let scale = y[..n].iter().fold(1.0_f64, |a, v| a.max(v.abs()));
        residual = gap.amax() / scale;
        if residual <= options.tolerance {
            if hybrid.modes_end != modes0 {
                return Err(OrbitError::ModesDoNotClose {
                    start: modes0.iter().map(|m| m.0).collect(),
                    end: hybrid.modes_end.iter().map(|m| m.0).collect(),
                });
            }
            let floquet = Floquet::of(&hybrid.sensitivity).ok_or(OrbitError::Singular)?;
            return Ok(PeriodicOrbit {
                t0,
                y0: y,
                modes0: modes0.to_vec(),
                period,
                flow: hybrid,
                floquet,
                residual,
                iterations: iteration,
            });
        }
        if iteration == options.max_iterations {
            break;
        }
        // The bordered Newton system.
        let mut a = DMatrix::zeros(n + 1, n + 1);
        a.view_mut((0, 0), (n, n))
            .copy_from(&(&hybrid.sensitivity - DMatrix::identity(n, n)));
        a.view_mut((0, n), (n, 1))
            .copy_from(&field(&hybrid.y_end, &hybrid.modes_end));
        a.view_mut((n, 0), (1, n)).copy_from(&normal.transpose());
        let mut b = DVector::zeros(n + 1);
        b.rows_mut(0, n).copy_from(&(-&gap));
        let offset = DVector::from_column_slice(&y[..n]) - &reference;
        b[n] = -normal.dot(&offset);
        let step = a.lu().solve(&b).ok_or(OrbitError::Singular)?;
        for i in 0..n {
            y[i] += step[i];
        }
        period += step[n];
        if period.is_nan() || period <= 0.0 {
            return Err(OrbitError::NoConvergence {
                iterations: iteration + 1,
                residual,
                wanted: options.tolerance,
            });
        }
    }
    Err(OrbitError::NoConvergence {
        iterations: options.max_iterations,
        residual,
        wanted: options.tolerance,
    })
}
