//! Python's keyword arguments as the library's typed settings: `simulate`'s as a
//! [`Simulation`], `sweep`'s as a [`Sweep`], a solver study's as a [`Problem`] and the study
//! ([`Converge`], [`Independence`], [`WorkPrecision`], [`Stiffness`]), `curve`'s as a
//! [`FrictionCurve`], `phenomena`'s as [`Phenomena`]. Each keyword is one field; its value is
//! taken as the field's type (a number, a whole number, a name, a list) or refused with a
//! `ValueError` naming the keyword; an unknown keyword is a `TypeError` naming it and those
//! taken (the Python layer names the close match before it calls). The ranges and the checks
//! between settings are the library's ([`Simulation::run`], [`Sweep::run`], …), the command
//! line's too.

use friction_lab::artifacts::Made;
use friction_lab::curve::FrictionCurve;
use friction_lab::error::AppError;
use friction_lab::laws::ModelChoice;
use friction_lab::settings::{ModelSettings, RunLimits, SchemeChoice, SolverSettings};
use friction_lab::simulate::{Simulation, Target};
use friction_lab::study::{Converge, Independence, Phenomena, Problem, Stiffness, WorkPrecision};
use friction_lab::sweep::{point_range, Axis, Start, Sweep, DEFAULT_SETTLE};
use integrators::Solver;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyList, PyString, PyTuple};
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// Keyword arguments by name.
type Keywords<'py> = Vec<(String, Bound<'py, PyAny>)>;

/// A study set up, to be run into a folder (in memory).
pub type Conduct = Box<dyn FnOnce(&Path) -> Result<Made, AppError> + Send>;

/// The keyword arguments every run and study takes ([`Shared`]).
const SHARED: &[&str] = &[
    "model",
    "params",
    "param_set",
    "variant",
    "scheme",
    "switching",
    "max_steps",
    "time_limit",
    "t_end",
    "bodies",
];

/// The keyword arguments of `simulate` besides the scenario, `system` and [`SHARED`].
const SIMULATE_OWN: &[&str] = &[
    "solver",
    "theta",
    "dt",
    "fixed_step",
    "rtol",
    "atol",
    "points",
];

/// The keyword arguments of `sweep` besides those of `simulate` and `grid`.
const SWEEP_OWN: &[&str] = &["settle", "start", "threads", "point_range"];

/// The keyword arguments of `curve` besides the model.
const CURVE: &[&str] = &["params", "param_set", "variant", "v_max", "t_end", "points"];

/// The keyword arguments of `phenomena`.
const PHENOMENA: &[&str] = &[
    "model",
    "params",
    "param_set",
    "solver",
    "rtol",
    "atol",
    "threads",
    "max_steps",
    "time_limit",
];

/// The keyword arguments of a study besides [`SHARED`] and its own.
const PROBLEM_OWN: &[&str] = &["threads"];

/// The keyword arguments of each study of its own.
const STUDY_OWN: [(&str, &[&str]); 4] = [
    ("converge", &["solvers", "dt_list", "tol_list"]),
    (
        "independence",
        &["solver", "start", "ratio", "levels", "tol"],
    ),
    (
        "work_precision",
        &["testset", "solvers", "dt_list", "tol_list", "repeats"],
    ),
    (
        "stiffness",
        &[
            "parameter",
            "values",
            "solvers",
            "target",
            "dt_list",
            "tol_list",
        ],
    ),
];

/// The keyword arguments of the function `function` bound to the library, besides its
/// scenario and `system`; `None` for a function that is not.
pub fn keywords(function: &str) -> Option<Vec<&'static str>> {
    let own: &[&[&str]] = match function {
        "curve" => return Some(CURVE.to_vec()),
        "phenomena" => return Some(PHENOMENA.to_vec()),
        "simulate" => &[SIMULATE_OWN, &["window"]],
        "sweep" => &[SIMULATE_OWN, &["window"], SWEEP_OWN, &["grid"]],
        _ => {
            let (_, study) = STUDY_OWN.iter().find(|(name, _)| *name == function)?;
            &[PROBLEM_OWN, study]
        }
    };
    Some([&[SHARED], own].concat().concat())
}

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
fn unknown(function: &str, key: &str) -> PyErr {
    let mut all = keywords(function).unwrap_or_default();
    all.sort_unstable();
    PyTypeError::new_err(format!(
        "{function}() got an unexpected keyword argument '{key}'; it takes: {}",
        all.join(", ")
    ))
}

/// The keyword arguments given, by name; those given as `None` left out.
fn given<'py>(options: &Bound<'py, PyDict>) -> PyResult<Keywords<'py>> {
    let mut pairs = Vec::new();
    for (key, value) in options.iter() {
        if !value.is_none() {
            pairs.push((key.extract()?, value));
        }
    }
    Ok(pairs)
}

/// What a run integrates: the rig or `chain` named `scenario`, or the system file `system`;
/// `None` when neither is given.
fn target(scenario: Option<&str>, system: Option<PathBuf>) -> PyResult<Option<Target>> {
    Ok(Some(match (scenario, system) {
        (Some(_), Some(_)) => {
            return Err(PyValueError::new_err(
                "give a scenario or a `system`, not both",
            ))
        }
        (None, Some(path)) => Target::System(path),
        (Some(name), None) => Target::named(name).map_err(PyValueError::new_err)?,
        (None, None) => return Ok(None),
    }))
}

/// The settings every run and study shares, each set by its keyword in [`SHARED`].
struct Shared<'a> {
    model: &'a mut Option<ModelChoice>,
    settings: &'a mut ModelSettings,
    scheme: &'a mut SchemeChoice,
    limits: &'a mut RunLimits,
    t_end: &'a mut Option<f64>,
    bodies: &'a mut Vec<String>,
}

impl Shared<'_> {
    /// Sets the setting of keyword `k` to `value`; false if `k` is none of [`SHARED`].
    fn set(&mut self, k: &str, value: &Bound<'_, PyAny>) -> PyResult<bool> {
        match k {
            "model" => *self.model = Some(model_choice(k, value)?),
            _ if model_setting(k, value, self.settings)? => {}
            "scheme" => self.scheme.scheme = parsed(k, value)?,
            "switching" => self.scheme.switching = Some(parsed(k, value)?),
            "max_steps" => self.limits.max_steps = whole(k, value)?,
            "time_limit" => self.limits.time_limit = Some(number(k, value)?),
            "t_end" => *self.t_end = Some(number(k, value)?),
            "bodies" => {
                *self.bodies = items(value)?
                    .iter()
                    .map(|b| match whole(k, b) {
                        Ok(i) => Ok(i.to_string()),
                        Err(_) => name(k, b),
                    })
                    .collect::<PyResult<_>>()?
            }
            _ => return Ok(false),
        }
        Ok(true)
    }
}

/// A friction model: a name of the catalog or of a registered law, or a law written in
/// Python (registered under its name).
fn model_choice(k: &str, value: &Bound<'_, PyAny>) -> PyResult<ModelChoice> {
    let law = if value.is_instance_of::<PyString>() {
        name(k, value)?
    } else {
        crate::law::register_law(value)?
    };
    parsed(k, &PyString::new(value.py(), &law).into_any())
}

/// Sets the model setting of keyword `k` (`params`, `param_set`, `variant`) to `value`;
/// false if `k` is none of them.
fn model_setting(
    k: &str,
    value: &Bound<'_, PyAny>,
    settings: &mut ModelSettings,
) -> PyResult<bool> {
    match k {
        "params" => {
            let params = value
                .cast::<PyDict>()
                .map_err(|_| expected(k, value, "a mapping of parameter names to values"))?;
            for (p, v) in params.iter() {
                let p = name(k, &p)?;
                // A number as its shortest round-trip text; anything else as its text,
                // refused by the library as the command line refuses `--set p=text`.
                let v = match number(&p, &v) {
                    Ok(x) => format!("{x:?}"),
                    Err(_) => v.str()?.to_string(),
                };
                settings.params.set.push(format!("{p}={v}"));
            }
        }
        "param_set" => settings.params.param_set = Some(name(k, value)?),
        "variant" => settings.variant = parsed(k, value)?,
        _ => return Ok(false),
    }
    Ok(true)
}

/// The curve `curve(model, **options)` asks for.
pub fn curve(model: &str, options: &Bound<'_, PyDict>) -> PyResult<FrictionCurve> {
    let model = parsed("model", &PyString::new(options.py(), model).into_any())?;
    let mut curve = FrictionCurve::new(model);
    for (key, value) in given(options)? {
        let k = key.as_str();
        if model_setting(k, &value, &mut curve.model_settings)? {
            continue;
        }
        match k {
            "v_max" => curve.v_max = Some(number(k, &value)?),
            "t_end" => curve.t_end = Some(number(k, &value)?),
            "points" => curve.points = whole(k, &value)?,
            _ => return Err(unknown("curve", k)),
        }
    }
    Ok(curve)
}

/// Table 2 as `phenomena(models, **options)` asks for it.
pub fn phenomena(options: &Bound<'_, PyDict>) -> PyResult<Phenomena> {
    let mut table = Phenomena::default();
    let mut settings = ModelSettings::default();
    for (key, value) in given(options)? {
        let k = key.as_str();
        if k != "variant" && model_setting(k, &value, &mut settings)? {
            continue;
        }
        match k {
            "model" => {
                table.models = (items(&value)?.iter())
                    .map(|m| model_choice(k, m))
                    .collect::<PyResult<_>>()?
            }
            "solver" => table.solver = parsed(k, &value)?,
            "rtol" => table.rtol = number(k, &value)?,
            "atol" => table.atol = number(k, &value)?,
            "threads" => table.threads = Some(whole(k, &value)?),
            "max_steps" => table.limits.max_steps = whole(k, &value)?,
            "time_limit" => table.limits.time_limit = Some(number(k, &value)?),
            _ => return Err(unknown("phenomena", k)),
        }
    }
    table.params = settings.params;
    Ok(table)
}

/// A list of numbers.
fn numbers(key: &str, value: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    items(value)?.iter().map(|v| number(key, v)).collect()
}

/// A list of solvers by name.
fn solvers(key: &str, value: &Bound<'_, PyAny>) -> PyResult<Vec<Solver>> {
    items(value)?.iter().map(|v| parsed(key, v)).collect()
}

/// The run `simulate(scenario, system=..., **options)` asks for; the keywords of `also` (a
/// sweep's own) are left to the caller.
pub fn simulation(
    scenario: Option<&str>,
    system: Option<PathBuf>,
    options: &Bound<'_, PyDict>,
    function: &str,
    also: &[&str],
) -> PyResult<Simulation> {
    let target = target(scenario, system)?.ok_or_else(|| {
        PyValueError::new_err("a scenario (a rig's name or \"chain\") or a `system` is required")
    })?;
    let mut run = Simulation::new(target, None);
    for (key, value) in given(options)? {
        let k = key.as_str();
        let solver: &mut SolverSettings = &mut run.solver;
        let mut shared = Shared {
            model: &mut run.model,
            settings: &mut run.model_settings,
            scheme: &mut solver.scheme,
            limits: &mut solver.limits,
            t_end: &mut run.t_end,
            bodies: &mut run.bodies,
        };
        if shared.set(k, &value)? {
            continue;
        }
        match k {
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
            "points" => run.points = Some(whole(k, &value)?),
            // `--window T0:T1`: the text, or a pair of numbers.
            "window" => {
                run.window = Some(match value.is_instance_of::<PyString>() {
                    true => name(k, &value)?,
                    false => match &items(&value)?[..] {
                        [a, b] => format!("{}:{}", number(k, a)?, number(k, b)?),
                        _ => return Err(expected(k, &value, "a pair (T0, T1) or \"T0:T1\"")),
                    },
                })
            }
            _ if also.contains(&k) => {}
            _ => return Err(unknown(function, k)),
        }
    }
    Ok(run)
}

/// The problem of a study `function(scenario, system=..., **options)`, with the keywords
/// that are the study's own (`own`) returned for the caller to set.
fn problem<'py>(
    scenario: Option<&str>,
    system: Option<PathBuf>,
    options: &Bound<'py, PyDict>,
    function: &str,
    own: &[&str],
) -> PyResult<(Problem, Keywords<'py>)> {
    let target = target(scenario, system)?;
    let mut problem = Problem::default();
    match target {
        Some(Target::System(path)) => problem.system = Some(path),
        named => problem.scenario = named,
    }
    let mut left = Vec::new();
    for (key, value) in given(options)? {
        let k = key.as_str();
        let mut shared = Shared {
            model: &mut problem.model,
            settings: &mut problem.model_settings,
            scheme: &mut problem.scheme,
            limits: &mut problem.limits,
            t_end: &mut problem.t_end,
            bodies: &mut problem.bodies,
        };
        if shared.set(k, &value)? {
            continue;
        }
        match k {
            "threads" => problem.threads = Some(whole(k, &value)?),
            _ if own.contains(&k) => left.push((key, value)),
            _ => return Err(unknown(function, k)),
        }
    }
    Ok((problem, left))
}

/// The solver study `function` (`converge`, `independence`, `work_precision`, `stiffness`)
/// of `scenario` or `system` with the keyword arguments `options`, run into `out`.
pub fn study(
    function: &str,
    scenario: Option<&str>,
    system: Option<PathBuf>,
    options: &Bound<'_, PyDict>,
) -> PyResult<Conduct> {
    let own = (STUDY_OWN.iter())
        .find(|(name, _)| *name == function)
        .map(|(_, own)| *own)
        .ok_or_else(|| PyValueError::new_err(format!("`{function}` is no solver study")))?;
    let (problem, left) = problem(scenario, system, options, function, own)?;
    Ok(match function {
        "converge" => {
            let mut s = Converge::new(problem);
            for (key, v) in left {
                let k = key.as_str();
                match k {
                    "solvers" => s.solvers = solvers(k, &v)?,
                    "dt_list" => s.dt_list = numbers(k, &v)?,
                    _ => s.tol_list = numbers(k, &v)?,
                }
            }
            Box::new(move |out| s.run(out))
        }
        "independence" => {
            let mut s = Independence::new(problem);
            for (key, v) in left {
                let k = key.as_str();
                match k {
                    "solver" => s.solver = Some(parsed(k, &v)?),
                    "start" => s.refinement.start = number(k, &v)?,
                    "ratio" => s.refinement.ratio = number(k, &v)?,
                    "levels" => s.refinement.levels = whole(k, &v)?,
                    _ => s.refinement.tol = number(k, &v)?,
                }
            }
            Box::new(move |out| s.run(out))
        }
        "work_precision" => {
            let mut s = WorkPrecision::new(problem);
            for (key, v) in left {
                let k = key.as_str();
                match k {
                    "testset" => s.testset = Some(name(k, &v)?),
                    "solvers" => s.solvers = solvers(k, &v)?,
                    "dt_list" => s.dt_list = numbers(k, &v)?,
                    "tol_list" => s.tol_list = numbers(k, &v)?,
                    _ => s.repeats = whole(k, &v)?,
                }
            }
            Box::new(move |out| s.run(out))
        }
        _ => {
            let mut s = Stiffness::new(problem);
            for (key, v) in left {
                let k = key.as_str();
                match k {
                    "parameter" => s.parameter = name(k, &v)?,
                    "values" => s.values = numbers(k, &v)?,
                    "solvers" => s.solvers = solvers(k, &v)?,
                    "target" => s.target = number(k, &v)?,
                    "dt_list" => s.dt_list = numbers(k, &v)?,
                    _ => s.tol_list = numbers(k, &v)?,
                }
            }
            Box::new(move |out| s.run(out))
        }
    })
}

/// The sweep `sweep(scenario, grid=..., **options)` asks for: `grid` maps names to lists of
/// values or to range texts (`"0.1:1:10"`, `"log:0.01:1:9"`).
pub fn sweep(
    scenario: Option<&str>,
    system: Option<PathBuf>,
    grid: &Bound<'_, PyDict>,
    options: &Bound<'_, PyDict>,
) -> PyResult<Sweep> {
    let simulation = simulation(scenario, system, options, "sweep", SWEEP_OWN)?;
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
                    point_range(&name(k, &value)?).map_err(PyValueError::new_err)?
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
