//! A switch of a hybrid flow and its saltation matrix: how a perturbation of the state just
//! before the switch maps to one just after it, the switching time moving with it
//! (Aizerman & Gantmacher 1958; Leine & Nijmeijer 2004, §7.1; di Bernardo et al. 2008, §2.5):
//!
//! ```text
//! S = R_y + (f⁺ − R_y·f⁻ − R_t)·∇gᵀ / (∇gᵀ·f⁻ + g_t)
//! ```
//!
//! `g` is the event function that fired, in the modes before the switch; `R(t, y⁻)` the reset
//! the problem's handler applies (the identity for most switches of a friction system; an
//! arriving body's velocity set onto its surface's); `f⁻ = f(t, y⁻, q⁻)` and
//! `f⁺ = f(t, y⁺, q⁺)`. The derivatives of g and R are central differences, exact for the
//! linear functions of a friction system's switches (its velocities, its springs' forces) up to
//! rounding.

use crate::variational::field;
use crate::OrbitError;
use integrators::{Mode, OdeProblem};
use nalgebra::{DMatrix, DVector};

/// Relative step of the central differences of g and R, over `max(|y_i|, 1)`.
const DIFFERENCE_STEP: f64 = 1e-6;

/// Below this, relative to `|∇g|·|f⁻|`, the crossing rate `∇gᵀ·f⁻ + g_t` is a grazing.
pub const GRAZING_RATE: f64 = 1e-9;

/// One switch: where, which event, the modes on each side and the saltation matrix.
#[derive(Clone, Debug, PartialEq)]
pub struct Switch {
    /// Time, s.
    pub t: f64,
    /// The event function that fired, by index.
    pub event: usize,
    /// Its name, as the problem records it.
    pub name: &'static str,
    /// The modes before.
    pub before: Vec<Mode>,
    /// The modes after.
    pub after: Vec<Mode>,
    /// The saltation matrix S over the dynamic unknowns.
    pub saltation: DMatrix<f64>,
}

/// The switch of `problem` where the event functions `fired` (ascending) have their root at
/// (t, y⁻) in `modes`: the state and modes after it, from the problem's handler, and its
/// [`Switch`]. Two events at once, and a grazing crossing, are errors.
pub fn switch(
    problem: &dyn OdeProblem,
    fired: &[usize],
    name: &'static str,
    t: f64,
    y_minus: &[f64],
    modes: &[Mode],
) -> Result<(Vec<f64>, Vec<Mode>, Switch), OrbitError> {
    let &[event] = fired else {
        return Err(OrbitError::SimultaneousEvents {
            t,
            fired: fired.to_vec(),
        });
    };
    let n = problem.dim() - problem.quadratures();
    let reset = |t: f64, y: &[f64]| {
        let (mut y, mut after) = (y.to_vec(), modes.to_vec());
        problem.on_events(fired, t, &mut y, &mut after);
        (y, after)
    };
    let (y_plus, after) = reset(t, y_minus);
    let (f_minus, f_plus) = (
        field(problem, t, y_minus, modes, n),
        field(problem, t, &y_plus, &after, n),
    );
    // ∇g, R_y by central differences in each unknown; g_t, R_t in time.
    let g = |t: f64, y: &[f64]| problem.event(event, t, y, modes);
    let mut grad = DVector::zeros(n);
    let mut r_y = DMatrix::zeros(n, n);
    let mut yd = y_minus.to_vec();
    for c in 0..n {
        let delta = DIFFERENCE_STEP * y_minus[c].abs().max(1.0);
        yd[c] = y_minus[c] + delta;
        let (g_up, (r_up, _)) = (g(t, &yd), reset(t, &yd));
        yd[c] = y_minus[c] - delta;
        let (g_down, (r_down, _)) = (g(t, &yd), reset(t, &yd));
        yd[c] = y_minus[c];
        grad[c] = (g_up - g_down) / (2.0 * delta);
        for r in 0..n {
            r_y[(r, c)] = (r_up[r] - r_down[r]) / (2.0 * delta);
        }
    }
    let dt = DIFFERENCE_STEP * t.abs().max(1.0);
    let g_t = (g(t + dt, y_minus) - g(t - dt, y_minus)) / (2.0 * dt);
    let (r_later, _) = reset(t + dt, y_minus);
    let (r_earlier, _) = reset(t - dt, y_minus);
    let r_t = DVector::from_iterator(n, (0..n).map(|i| (r_later[i] - r_earlier[i]) / (2.0 * dt)));
    let rate = grad.dot(&f_minus) + g_t;
    if rate.abs() <= GRAZING_RATE * grad.norm() * f_minus.norm() {
        return Err(OrbitError::Grazing { t, event, rate });
    }
    let jump = &f_plus - &r_y * &f_minus - r_t;
    let saltation = &r_y + jump * grad.transpose() / rate;
    let switch = Switch {
        t,
        event,
        name,
        before: modes.to_vec(),
        after: after.clone(),
        saltation,
    };
    Ok((y_plus, after, switch))
}
