//! Python's keyword arguments as the library's typed settings: `simulate`'s as a
//! [`Simulation`], `sweep`'s as a [`Sweep`]. Each keyword is one field; its value is taken as
//! the field's type (a number, a whole number, a name, a list) or refused with a `ValueError`
//! naming the keyword; an unknown keyword is a `TypeError` naming it and its close match. The
//! ranges and the checks between settings are the library's ([`Simulation::run`],
//! [`Sweep::run`]), the command line's too.

use friction_lab::settings::SolverSettings;
use friction_lab::simulate::{Simulation, Target};
use friction_lab::sweep::{parse_point_range, points, Axis, Start, Sweep, DEFAULT_SETTLE};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyList, PyString, PyTuple};
use std::path::PathBuf;
use std::str::FromStr;

/// The keyword arguments of `simulate` besides the scenario and `system`.
pub const SIMULATE: &[&str] = &[
    "model",
    "params",
    "param_set",
    "variant",
    "scheme",
    "switching",
    "solver",
    "theta",
    "dt",
    "fixed_step",
    "rtol",
    "atol",
    "max_steps",
    "time_limit",
    "t_end",
    "points",
    "bodies",
];

/// The keyword arguments of `sweep` besides those of [`SIMULATE`] and `grid`.
pub const SWEEP: &[&str] = &["settle", "start", "threads", "point_range"];

/// A `ValueError` for keyword `key` = `value`: `what` is expected.
fn expected(key: &str, value: &Bound<'_, PyAny>, what: &str) -> PyErr {
    let shown = value.repr().map_or_else(|_| "?".into(), |r| r.to_string());
    PyValueError::new_err(format!("`{key}` = {shown}: {what} is expected"))
}

/// `value` as a `T`, `what` the message says is expected; `refused` a value that would
/// convert but is not one (a bool as a number).
fn typed<'py, T>(key: &str, value: &Bound<'py, PyAny>, refused: bool, what: &str) -> PyResult<T>
where
    T: for<'a> FromPyObject<'a, 'py>,
{
    match refused {
        true => Err(expected(key, value, what)),
        false => value.extract().map_err(|_| expected(key, value, what)),
    }
}

/// A real number (a bool or a string is not one).
fn number(key: &str, value: &Bound<'_, PyAny>) -> PyResult<f64> {
    let refused = value.is_instance_of::<PyBool>() || value.is_instance_of::<PyString>();
    typed(key, value, refused, "a number")
}

/// A whole number: an int, or a numpy integer (a float is refused, even a whole one).
fn whole(key: &str, value: &Bound<'_, PyAny>) -> PyResult<i64> {
    let refused = value.is_instance_of::<PyBool>() || value.is_instance_of::<PyFloat>();
    typed(key, value, refused, "a whole number")
}

/// A name (a string or a path).
fn name(key: &str, value: &Bound<'_, PyAny>) -> PyResult<String> {
    value
        .extract::<PathBuf>()
        .map(|p| p.display().to_string())
        .map_err(|_| expected(key, value, "a name (a string)"))
}

/// A name parsed as `T`, its parser's message naming `key`.
fn parsed<T: FromStr<Err = String>>(key: &str, value: &Bound<'_, PyAny>) -> PyResult<T> {
    let text = name(key, value)?;
    text.parse()
        .map_err(|e: String| PyValueError::new_err(format!("`{key}` = '{text}': {e}")))
}

/// A list, tuple or one-dimensional array as its items; anything else as one item.
fn items<'py>(value: &Bound<'py, PyAny>) -> PyResult<Vec<Bound<'py, PyAny>>> {
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        return value.try_iter()?.collect();
    }
    if value.hasattr("tolist")? && !value.is_instance_of::<PyString>() {
        let listed = value.call_method0("tolist")?;
        if listed.is_instance_of::<PyList>() {
            return listed.try_iter()?.collect();
        }
        return Ok(vec![listed]);
    }
    Ok(vec![value.clone()])
}

/// The `TypeError` of a keyword `function` does not take (the Python layer names the close
/// match before it calls: `friction_lab._command.check_keywords`).
fn unknown(function: &str, key: &str, known: &[&str]) -> PyErr {
    let mut all = known.to_vec();
    all.sort_unstable();
    PyTypeError::new_err(format!(
        "{function}() got an unexpected keyword argument '{key}'; it takes: {}",
        all.join(", ")
    ))
}

/// The keyword arguments given, by name; those given as `None` left out.
fn given<'py>(options: &Bound<'py, PyDict>) -> PyResult<Vec<(String, Bound<'py, PyAny>)>> {
    let mut pairs = Vec::new();
    for (key, value) in options.iter() {
        if !value.is_none() {
            pairs.push((key.extract()?, value));
        }
    }
    Ok(pairs)
}

/// The run `simulate(scenario, system=..., **options)` asks for.
pub fn simulation(
    scenario: Option<&str>,
    system: Option<PathBuf>,
    options: &Bound<'_, PyDict>,
    function: &str,
    also: &[&str],
) -> PyResult<Simulation> {
    let target = match (scenario, system) {
        (Some(_), Some(_)) => {
            return Err(PyValueError::new_err(
                "give a scenario or a `system`, not both",
            ))
        }
        (None, Some(path)) => Target::System(path),
        (Some("chain"), None) => Target::Chain,
        (Some(s), None) => Target::Rig(
            friction_lab::scenarios::Scenario::from_name(s)
                .map_err(|e| PyValueError::new_err(format!("{e}, chain")))?,
        ),
        (None, None) => {
            return Err(PyValueError::new_err(
                "a scenario (a rig's name or \"chain\") or a `system` is required",
            ))
        }
    };
    let mut run = Simulation::new(target, None);
    let solver: &mut SolverSettings = &mut run.solver;
    for (key, value) in given(options)? {
        let k = key.as_str();
        match k {
            "model" => {
                let law = if value.is_instance_of::<PyString>() {
                    name(k, &value)?
                } else {
                    crate::law::register_law(&value)?
                };
                run.model = Some(parsed(k, &PyString::new(value.py(), &law).into_any())?);
            }
            "params" => {
                let params = value
                    .cast::<PyDict>()
                    .map_err(|_| expected(k, &value, "a mapping of parameter names to values"))?;
                for (p, v) in params.iter() {
                    let p = name(k, &p)?;
                    // A number as its shortest round-trip text; anything else as its text,
                    // refused by the library as the command line refuses `--set p=text`.
                    let v = match number(&p, &v) {
                        Ok(x) => format!("{x:?}"),
                        Err(_) => v.str()?.to_string(),
                    };
                    run.model_settings.params.set.push(format!("{p}={v}"));
                }
            }
            "param_set" => run.model_settings.params.param_set = name(k, &value)?,
            "variant" => run.model_settings.variant = parsed(k, &value)?,
            "scheme" => solver.scheme.scheme = parsed(k, &value)?,
            "switching" => solver.scheme.switching = Some(parsed(k, &value)?),
            "solver" => solver.solver = Some(parsed(k, &value)?),
            "theta" => solver.theta = Some(number(k, &value)?),
            "dt" => solver.dt = Some(number(k, &value)?),
            "fixed_step" => {
                solver.fixed_step = value
                    .extract::<bool>()
                    .map_err(|_| expected(k, &value, "True or False"))?
            }
            "rtol" => solver.rtol = number(k, &value)?,
            "atol" => solver.atol = number(k, &value)?,
            "max_steps" => solver.limits.max_steps = whole(k, &value)?,
            "time_limit" => solver.limits.time_limit = Some(number(k, &value)?),
            "t_end" => run.t_end = Some(number(k, &value)?),
            "points" => run.points = Some(whole(k, &value)?),
            "bodies" => {
                run.bodies = items(&value)?
                    .iter()
                    .map(|b| match whole(k, b) {
                        Ok(i) => Ok(i.to_string()),
                        Err(_) => name(k, b),
                    })
                    .collect::<PyResult<_>>()?
            }
            _ if also.contains(&k) => {}
            _ => {
                let known: Vec<&str> = SIMULATE.iter().chain(also).copied().collect();
                return Err(unknown(function, k, &known));
            }
        }
    }
    Ok(run)
}

/// The sweep `sweep(scenario, grid=..., **options)` asks for: `grid` maps names to lists of
/// values or to range texts (`"0.1:1:10"`, `"log:0.01:1:9"`).
pub fn sweep(
    scenario: Option<&str>,
    system: Option<PathBuf>,
    grid: &Bound<'_, PyDict>,
    options: &Bound<'_, PyDict>,
) -> PyResult<Sweep> {
    let simulation = simulation(scenario, system, options, "sweep", SWEEP)?;
    let axes = grid
        .iter()
        .map(|(key, values)| {
            let key = name("grid", &key)?;
            let bad = |e: friction_lab::error::AppError| {
                PyValueError::new_err(format!("option `grid`, axis `{key}`: {e}"))
            };
            if values.is_instance_of::<PyString>() {
                let text: String = values.extract()?;
                return Axis::parse(&format!("{key}={text}"))
                    .map_err(|e| PyValueError::new_err(e.to_string()));
            }
            let numbers = items(&values)?
                .iter()
                .map(|v| number(&format!("grid[{key:?}]"), v))
                .collect::<PyResult<Vec<f64>>>()?;
            Axis::new(&key, numbers).map_err(bad)
        })
        .collect::<PyResult<Vec<Axis>>>()?;
    if axes.is_empty() {
        return Err(PyValueError::new_err(
            "option `grid`: no axis: give at least one parameter and its values",
        ));
    }
    let mut sweep = Sweep {
        simulation,
        axes,
        settle: DEFAULT_SETTLE,
        start: Start::Rest,
        range: None,
        threads: None,
    };
    for (key, value) in given(options)? {
        let k = key.as_str();
        match k {
            "settle" => sweep.settle = number(k, &value)?,
            "start" => sweep.start = parsed(k, &value)?,
            "threads" => sweep.threads = Some(whole(k, &value)?),
            "point_range" => {
                sweep.range = Some(if value.is_instance_of::<PyString>() {
                    let text = name(k, &value)?;
                    parse_point_range(&text, points(&sweep.axes).len())
                        .map_err(|e| PyValueError::new_err(e.to_string()))?
                } else {
                    let ends = items(&value)?
                        .iter()
                        .map(|v| {
                            usize::try_from(whole(k, v)?).map_err(|_| expected(k, v, "an index"))
                        })
                        .collect::<PyResult<Vec<usize>>>()?;
                    match ends[..] {
                        [start, end] => start..end,
                        _ => return Err(expected(k, &value, "a pair (start, end) or 'START:END'")),
                    }
                })
            }
            _ => {}
        }
    }
    Ok(sweep)
}
