//! The variational equations of a hybrid problem in fixed modes: the state `y` and its
//! sensitivity `Φ = ∂y(t)/∂y(t₀)` over the dynamic unknowns, integrated together,
//!
//! ```text
//! y' = f(t, y, q),   Φ' = J(t, y, q)·Φ,   Φ(t₀) = I,
//! ```
//!
//! with `J = ∂f/∂y` (the problem's analytic Jacobian, else forward differences; the mass
//! matrix divided out). The problem's events are watched as in the problem itself, each
//! stopping the integration: the switch is made by [`crate::saltation`], between segments.

use integrators::stability::jacobian;
use integrators::{Control, EventSpec, Mode, OdeProblem};
use nalgebra::DVector;

/// The vector field `M⁻¹·f(t, y, q)` of `problem` over its first `n` unknowns (the dynamic
/// ones).
pub(crate) fn field(
    problem: &dyn OdeProblem,
    t: f64,
    y: &[f64],
    modes: &[Mode],
    n: usize,
) -> DVector<f64> {
    let mut f = vec![0.0; y.len()];
    problem.rhs(t, y, modes, &mut f);
    if let Some(m) = problem.mass() {
        f.iter_mut().zip(m).for_each(|(f, m)| *f /= m);
    }
    DVector::from_column_slice(&f[..n])
}

/// A problem and its variational equations: `dim = N + n²` with N the problem's unknowns and
/// n those other than its quadratures (the sensitivity, column by column, after the state).
pub(crate) struct Variational<'p> {
    pub(crate) inner: &'p dyn OdeProblem,
    /// The problem's unknowns, N.
    pub(crate) big: usize,
    /// Its dynamic unknowns (not quadratures), n.
    pub(crate) n: usize,
}

impl<'p> Variational<'p> {
    /// The variational equations of `inner`.
    pub(crate) fn new(inner: &'p dyn OdeProblem) -> Self {
        let big = inner.dim();
        Variational {
            inner,
            big,
            n: big - inner.quadratures(),
        }
    }

    /// The augmented initial state: `y0` and the identity.
    pub(crate) fn start(&self, y0: &[f64]) -> Vec<f64> {
        let mut out = y0.to_vec();
        out.resize(self.big + self.n * self.n, 0.0);
        for i in 0..self.n {
            out[self.big + i * self.n + i] = 1.0;
        }
        out
    }

    /// The sensitivity in an augmented state, as a matrix.
    pub(crate) fn sensitivity(&self, z: &[f64]) -> nalgebra::DMatrix<f64> {
        nalgebra::DMatrix::from_column_slice(self.n, self.n, &z[self.big..])
    }
}

impl OdeProblem for Variational<'_> {
    fn dim(&self) -> usize {
        self.big + self.n * self.n
    }

    fn rhs(&self, t: f64, z: &[f64], modes: &[Mode], dz: &mut [f64]) {
        let (y, phi) = z.split_at(self.big);
        let (dy, dphi) = dz.split_at_mut(self.big);
        self.inner.rhs(t, y, modes, dy);
        if let Some(m) = self.inner.mass() {
            for (d, &m) in dy.iter_mut().zip(m) {
                *d /= m;
            }
        }
        // A differential–algebraic problem is refused before any integration (`flow`).
        let j = jacobian(self.inner, t, y, modes).expect("an ODE with a regular mass matrix");
        let n = self.n;
        for c in 0..n {
            let column = &phi[c * n..(c + 1) * n];
            for r in 0..n {
                dphi[c * n + r] = (0..n).map(|k| j[(r, k)] * column[k]).sum();
            }
        }
    }

    fn n_events(&self) -> usize {
        self.inner.n_events()
    }

    fn event_spec(&self, index: usize, modes: &[Mode]) -> Option<EventSpec> {
        self.inner.event_spec(index, modes)
    }

    fn event(&self, index: usize, t: f64, z: &[f64], modes: &[Mode]) -> f64 {
        self.inner.event(index, t, &z[..self.big], modes)
    }

    /// Every event ends the segment; the switch is made between segments.
    fn on_events(&self, _: &[usize], _: f64, _: &mut [f64], _: &mut [Mode]) -> Control {
        Control::Stop
    }

    fn time_scale(&self) -> Option<f64> {
        self.inner.time_scale()
    }
}
