//! The pieces of Newton's method shared by implicit solvers: the Jacobian ∂f/∂y (analytic,
//! or forward differences) and the iteration matrix `M − c·J`.

use crate::problem::Entry;
use crate::stats::Stats;
use crate::stepper::Ode;

/// The unit round-off used for finite-difference increments (UROUND of radau5.f).
const UROUND: f64 = 1e-16;

/// How Newton's iteration treats the Jacobian.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NewtonKind {
    /// A new Jacobian and factorisation at every iteration.
    Full,
    /// One Jacobian reused across iterations and steps until convergence slows down; the
    /// matrix is refactorised only when the step size changes.
    Modified,
}

/// Evaluates ∂f/∂y at (t, y) into `jac` (cleared first): the problem's analytic Jacobian,
/// or forward differences with increments `sqrt(UROUND·max(1e-5, |y_j|))` (as radau5.f),
/// which need `f0 = f(t, y)`. Either counts as one Jacobian; the evaluations of f that forward
/// differences make are not counted in `rhs_evals` (as radau5.f's NFCN), since the counted
/// work charges a Jacobian `n` evaluations ([`Stats::work`]).
pub fn jacobian(ode: &Ode, t: f64, y: &[f64], f0: &[f64], jac: &mut Vec<Entry>, stats: &mut Stats) {
    jac.clear();
    stats.jacobian_evals += 1;
    stats.matrix_order = y.len();
    if ode.problem.jacobian(t, y, ode.modes, jac) {
        stats.matrix_entries = stats.matrix_entries.max(jac.len());
        return;
    }
    let n = y.len();
    let mut yd = y.to_vec();
    let mut fd = vec![0.0; n];
    for j in 0..n {
        let delta = (UROUND * y[j].abs().max(1e-5)).sqrt();
        yd[j] = y[j] + delta;
        ode.problem.rhs(t, &yd, ode.modes, &mut fd);
        yd[j] = y[j];
        for i in 0..n {
            let d = (fd[i] - f0[i]) / delta;
            if d != 0.0 {
                jac.push((i, j, d));
            }
        }
    }
    stats.matrix_entries = stats.matrix_entries.max(jac.len());
}

/// The iteration matrix `M − c·J` as entries (M the diagonal mass matrix, identity when
/// absent).
pub fn iteration_matrix(
    mass: Option<&[f64]>,
    n: usize,
    c: f64,
    jac: &[Entry],
    out: &mut Vec<Entry>,
) {
    out.clear();
    out.extend((0..n).map(|i| (i, i, mass.map_or(1.0, |m| m[i]))));
    out.extend(jac.iter().map(|&(i, j, v)| (i, j, -c * v)));
}
