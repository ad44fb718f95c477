//! A friction law written in Python, run by the library as any law of the catalog: an object
//! with the methods
//!
//! - `force(x, v, s, z)`: the friction force F, N, at displacement x, velocity v and internal
//!   states z (a tuple of `n_states` floats), where `s` is sign(v) as the run's treatment of
//!   v = 0 evaluates it: ±1 in a slip mode of event switching, tanh(v/ε) regularised, sign(v)
//!   with sign(0) = 0 naive;
//! - `stick(x, z)`: the admissible forces at rest, a pair (lower, upper) or one number f for
//!   [−f, f];
//! - `rates(x, v, s, z)`, for a law with states: ż, one float per state;
//! - optionally `partials(x, v, s, z)`: (∂F/∂x, ∂F/∂v, ∂F/∂s) at fixed s; without it the
//!   partials are forward differences (so are the states' always);
//! - optionally `steady_state(v)`: the states reached by steady sliding at v;
//!
//! and the attributes `name` (default: the class's name) and `n_states` (default 0). Each
//! evaluation takes the GIL; the first exception a law raises stops every run (through the
//! solvers' interrupt) and is raised by the call that ran it.

use friction_lab::friction_models::{
    FrictionModel, ModelId, Partials, SignLaw, StatePartials, StickInterval, MAX_STATES,
};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use std::sync::{Arc, Mutex};

/// The first exception a law raised during the current call, raised by [`take_error`].
static RAISED: Mutex<Option<PyErr>> = Mutex::new(None);

/// The relative step of the forward differences: √ε of double precision, the step that
/// balances truncation against rounding for a first derivative (Nocedal & Wright, Numerical
/// Optimization, §8.1).
const RELATIVE_STEP: f64 = 1.490_116_119_384_765_6e-8;

/// The exception a law raised during the call that just ended, if any (and forgets it).
pub fn take_error() -> Option<PyErr> {
    RAISED.lock().unwrap_or_else(|e| e.into_inner()).take()
}

/// A law written in Python.
#[derive(Debug)]
pub struct PyLaw {
    object: Py<PyAny>,
    name: String,
    n_states: usize,
    analytic: bool,
    steady: bool,
}

/// sign(v) under `law` and its derivative ds/dv: `plus − minus` of the branch weights.
fn sign(law: SignLaw, v: f64) -> (f64, f64) {
    let b = law.branches(v);
    (b.plus - b.minus, 2.0 * b.dplus_dv)
}

/// The forward-difference step for a variable at `u`.
fn step(u: f64) -> f64 {
    RELATIVE_STEP * u.abs().max(1.0)
}

impl PyLaw {
    /// The law `object` describes, its methods and attributes checked: a `TypeError` names a
    /// missing method, a `ValueError` an `n_states` out of range.
    pub fn new(object: &Bound<'_, PyAny>) -> PyResult<PyLaw> {
        let py = object.py();
        let name: String = match object.getattr_opt(intern!(py, "name"))? {
            Some(n) => n
                .extract()
                .map_err(|_| PyTypeError::new_err("a law's `name` must be a string"))?,
            None => {
                let class: String = object.get_type().name()?.extract()?;
                if let Ok(model) = ModelId::from_name(&class) {
                    return Err(PyValueError::new_err(format!(
                        "law class `{class}` has no `name`, and its class's name is the \
                         catalog's model `{model}`: give the law a `name` of its own"
                    )));
                }
                class
            }
        };
        let n_states: i64 = match object.getattr_opt(intern!(py, "n_states"))? {
            Some(n) => n.extract().map_err(|_| {
                PyTypeError::new_err(format!("law `{name}`: `n_states` must be an integer"))
            })?,
            None => 0,
        };
        if !(0..=MAX_STATES as i64).contains(&n_states) {
            return Err(PyValueError::new_err(format!(
                "law `{name}`: `n_states` = {n_states} is out of range: allowed [0, {MAX_STATES}]"
            )));
        }
        let has = |method: &str| -> PyResult<bool> {
            Ok(object.getattr_opt(method)?.is_some_and(|m| m.is_callable()))
        };
        let mut required = vec![("force", "force(x, v, s, z)"), ("stick", "stick(x, z)")];
        if n_states > 0 {
            required.push(("rates", "rates(x, v, s, z)"));
        }
        for (method, signature) in required {
            if !has(method)? {
                return Err(PyTypeError::new_err(format!(
                    "law `{name}` has no method `{signature}` (docs/python.md: a friction law \
                     in Python)"
                )));
            }
        }
        Ok(PyLaw {
            object: object.clone().unbind(),
            name,
            n_states: n_states as usize,
            analytic: has("partials")?,
            steady: has("steady_state")?,
        })
    }

    /// Keeps the first exception and asks every run to stop.
    fn raised(&self, e: PyErr) {
        let mut raised = RAISED.lock().unwrap_or_else(|e| e.into_inner());
        if raised.is_none() {
            *raised = Some(e);
        }
        integrators::interrupt::request();
    }

    /// F at (x, v, s, z), with ż written into `rate`; NaN (and the exception kept) where the
    /// law raised or returned something else than numbers.
    fn response_at(
        &self,
        py: Python<'_>,
        x: f64,
        v: f64,
        s: f64,
        z: &[f64],
        rate: &mut [f64],
    ) -> f64 {
        let result = (|| -> PyResult<f64> {
            let zs = PyTuple::new(py, z)?;
            let o = self.object.bind(py);
            let force: f64 = o
                .call_method1(intern!(py, "force"), (x, v, s, &zs))?
                .extract()?;
            if self.n_states > 0 {
                let rates: Vec<f64> = o
                    .call_method1(intern!(py, "rates"), (x, v, s, &zs))?
                    .extract()?;
                if rates.len() != self.n_states {
                    return Err(PyValueError::new_err(format!(
                        "law `{}`: `rates` returned {} values for its {} states",
                        self.name,
                        rates.len(),
                        self.n_states
                    )));
                }
                rate.copy_from_slice(&rates);
            }
            Ok(force)
        })();
        result.unwrap_or_else(|e| {
            self.raised(e);
            rate.fill(f64::NAN);
            f64::NAN
        })
    }

    /// (∂F/∂x, ∂F/∂v, ∂F/∂s) from the law's `partials`; NaN where it raised.
    fn analytic_partials(
        &self,
        py: Python<'_>,
        x: f64,
        v: f64,
        s: f64,
        z: &[f64],
    ) -> (f64, f64, f64) {
        let result = (|| -> PyResult<(f64, f64, f64)> {
            let zs = PyTuple::new(py, z)?;
            self.object
                .bind(py)
                .call_method1(intern!(py, "partials"), (x, v, s, zs))?
                .extract()
        })();
        result.unwrap_or_else(|e| {
            self.raised(e);
            (f64::NAN, f64::NAN, f64::NAN)
        })
    }
}

impl FrictionModel for PyLaw {
    fn name(&self) -> &str {
        &self.name
    }

    fn n_states(&self) -> usize {
        self.n_states
    }

    fn response(&self, x: f64, v: f64, z: &[f64], law: SignLaw, rate: &mut [f64]) -> f64 {
        Python::attach(|py| self.response_at(py, x, v, sign(law, v).0, z, rate))
    }

    fn evaluate(
        &self,
        x: f64,
        v: f64,
        z: &[f64],
        law: SignLaw,
        rate: &mut [f64],
        states: &mut [StatePartials],
    ) -> (f64, Partials) {
        Python::attach(|py| {
            let n = self.n_states;
            let (s, ds_dv) = sign(law, v);
            let force = self.response_at(py, x, v, s, z, rate);
            let mut shifted = [0.0; MAX_STATES];
            let shifted = &mut shifted[..n];
            // ż and F at x + h, then at v + h (s re-evaluated there): the states' ∂/∂x and
            // ∂/∂v, and F's where the law gives no partials.
            let (mut fx, mut fv) = (f64::NAN, f64::NAN);
            if !self.analytic || n > 0 {
                // One forward difference over h to (x1, v1) with sign s1: F's, returned, and
                // each state's rate's, written into the field `of` its partials.
                type Field = fn(&mut StatePartials) -> &mut f64;
                let mut forward = |x1: f64, v1: f64, s1: f64, h: f64, of: Field| {
                    let f1 = self.response_at(py, x1, v1, s1, z, shifted);
                    for (d, (r1, r0)) in states.iter_mut().zip(shifted.iter().zip(rate.iter())) {
                        *of(d) = (r1 - r0) / h;
                    }
                    (f1 - force) / h
                };
                let (hx, hv) = (step(x), step(v));
                fx = forward(x + hx, v, s, hx, |d| &mut d.rate_dx);
                fv = forward(x, v + hv, sign(law, v + hv).0, hv, |d| &mut d.rate_dv);
            }
            // Each state's own: the state block of the Jacobian is diagonal.
            let mut zi = [0.0; MAX_STATES];
            let zi = &mut zi[..n];
            zi.copy_from_slice(z);
            for i in 0..n {
                let hz = step(z[i]);
                zi[i] = z[i] + hz;
                let f1 = self.response_at(py, x, v, s, zi, shifted);
                states[i].force_dz = (f1 - force) / hz;
                states[i].rate_dz = (shifted[i] - rate[i]) / hz;
                zi[i] = z[i];
            }
            let partials = if self.analytic {
                let (dx, dv, ds) = self.analytic_partials(py, x, v, s, z);
                Partials {
                    force_dx: dx,
                    force_dv: dv + ds * ds_dv,
                }
            } else {
                Partials {
                    force_dx: fx,
                    force_dv: fv,
                }
            };
            (force, partials)
        })
    }

    fn stick_interval(&self, x: f64, z: &[f64]) -> StickInterval {
        Python::attach(|py| {
            let result = (|| -> PyResult<StickInterval> {
                let zs = PyTuple::new(py, z)?;
                let got = self
                    .object
                    .bind(py)
                    .call_method1(intern!(py, "stick"), (x, zs))?;
                let (lower, upper): (f64, f64) = match got.extract::<f64>() {
                    Ok(f) => (-f.abs(), f.abs()),
                    Err(_) => got.extract()?,
                };
                // NaN compares false with every force: taken as is, it would read "never
                // sticks" without a word.
                if lower.is_nan() || upper.is_nan() {
                    return Err(PyValueError::new_err(format!(
                        "law `{}`: `stick` returned ({lower}, {upper}) at x = {x}: a bound is \
                         NaN; return the largest force at rest, or (lower, upper)",
                        self.name
                    )));
                }
                if lower > upper {
                    return Err(PyValueError::new_err(format!(
                        "law `{}`: `stick` returned ({lower}, {upper}): lower above upper",
                        self.name
                    )));
                }
                Ok(StickInterval { lower, upper })
            })();
            result.unwrap_or_else(|e| {
                self.raised(e);
                StickInterval {
                    lower: f64::NAN,
                    upper: f64::NAN,
                }
            })
        })
    }

    fn steady_state(&self, v: f64, z: &mut [f64]) {
        if !self.steady {
            return;
        }
        Python::attach(|py| {
            let result = (|| -> PyResult<Vec<f64>> {
                self.object
                    .bind(py)
                    .call_method1(intern!(py, "steady_state"), (v,))?
                    .extract()
            })();
            match result {
                Ok(states) if states.len() == z.len() => z.copy_from_slice(&states),
                Ok(states) => self.raised(PyValueError::new_err(format!(
                    "law `{}`: `steady_state` returned {} values for its {} states",
                    self.name,
                    states.len(),
                    z.len()
                ))),
                Err(e) => self.raised(e),
            }
        })
    }
}

/// Registers the Python law `object` under its name, so that `model=` and `--model` choose
/// it; returns the name.
#[pyfunction]
pub fn register_law(object: &Bound<'_, PyAny>) -> PyResult<String> {
    let law = PyLaw::new(object)?;
    let name = law.name.clone();
    friction_lab::laws::register(Arc::new(law)).map_err(PyValueError::new_err)?;
    Ok(name)
}
