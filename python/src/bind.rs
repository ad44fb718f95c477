//! Python's keyword arguments as the library's requests, through their one declaration.
//!
//! Each function fills the request the library declares for it ([`SimulationRequest`], [`SweepRequest`],
//! [`ConvergeRequest`], [`IndependenceRequest`], [`WorkPrecisionRequest`], [`StiffnessRequest`], [`CurveRequest`],
//! [`PhenomenaRequest`]) as the command line does: the keyword `t_end` is the option `--t-end`, and
//! its value, checked as the option's type (a number, a whole number, a name, a list of them,
//! `True` for a flag), is given to the option's own parser. So the keywords a function takes,
//! their defaults, their ranges and the checks between them are the declaration's: an option
//! added to a request is a keyword in Python with no edit here. Python's own forms are taken
//! besides: `params` a mapping (the command line's `--set NAME=VALUE`), `model` a law object
//! (registered under its name), `window` and `point_range` a pair, `bodies` names or indices,
//! and `grid` a mapping of names to values or range texts.

use clap::{ArgAction, Args, FromArgMatches};
use friction_lab::curve::CurveRequest;
use friction_lab::error::{spell_fields, AppError};
use friction_lab::made::Made;
use friction_lab::reproduce::ReproduceRequest;
use friction_lab::simulate::SimulationRequest;
use friction_lab::study::solver_studies::STUDIES;
use friction_lab::study::{CompareRequest, PhenomenaRequest};
use friction_lab::sweep::SweepRequest;
use friction_lab::testset::TestSetRequest;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyList, PyString, PyTuple};
use std::any::TypeId;
use std::path::{Path, PathBuf};

/// A request filled from Python, to be run into a folder (in memory).
pub type Conduct = Box<dyn FnOnce(&Path) -> Result<Made, AppError> + Send>;

/// The options of the request the function `function` fills, as clap declares them; `None`
/// for a function that binds none.
fn declared(function: &str) -> Option<clap::Command> {
    let command = clap::Command::new("friction_lab").no_binary_name(true);
    Some(match function {
        "simulate" => SimulationRequest::augment_args(command),
        "sweep" => SweepRequest::augment_args(command),
        "curve" => CurveRequest::augment_args(command),
        "phenomena" => PhenomenaRequest::augment_args(command),
        "testset" => TestSetRequest::augment_args(command),
        "reproduce" => ReproduceRequest::augment_args(command),
        study => STUDIES.find(&study.replace('_', "-"))?.declare(command),
    })
}

/// Whether the long option `long` is a keyword of its own in Python: not `--system` (an
/// argument of its own), `--set` (the mapping `params`) nor the parameter file `--params` (the
/// command line's alone).
fn is_keyword(long: &str) -> bool {
    !matches!(long, "system" | "set" | "params")
}

/// The keyword arguments of the function `function` bound to the library, besides its
/// positional argument and `system`: the long options of its request (`--set` as `params`;
/// the parameter file `--params` is the command line's alone); `None` for a function that is
/// not bound.
pub fn keywords(function: &str) -> Option<Vec<String>> {
    let command = declared(function)?;
    let longs: Vec<&str> = command
        .get_arguments()
        .filter_map(|a| a.get_long())
        .collect();
    let mut names: Vec<String> = (longs.iter())
        .filter(|long| is_keyword(long))
        .map(|long| long.replace('-', "_"))
        .chain(longs.contains(&"set").then(|| "params".to_string()))
        .collect();
    names.sort_unstable();
    Some(names)
}

/// A `ValueError` for keyword `key` = `value`: `what` is expected.
fn expected(key: &str, value: &Bound<'_, PyAny>, what: &str) -> PyErr {
    let shown = value.repr().map_or_else(|_| "?".into(), |r| r.to_string());
    PyValueError::new_err(format!("`{key}` = {shown}: {what} is expected"))
}

/// A real number as the text that parses back to it exactly (a bool or a string is not one).
fn number(key: &str, value: &Bound<'_, PyAny>) -> PyResult<String> {
    let refused = value.is_instance_of::<PyBool>() || value.is_instance_of::<PyString>();
    match (refused, value.extract::<f64>()) {
        (false, Ok(x)) => Ok(format!("{x:?}")),
        _ => Err(expected(key, value, "a number")),
    }
}

/// A whole number: an int, or a numpy integer (a float is refused, even a whole one).
fn whole(key: &str, value: &Bound<'_, PyAny>) -> PyResult<String> {
    let refused = value.is_instance_of::<PyBool>() || value.is_instance_of::<PyFloat>();
    match (refused, value.extract::<i64>()) {
        (false, Ok(n)) => Ok(n.to_string()),
        _ => Err(expected(key, value, "a whole number")),
    }
}

/// A name (a string or a path).
fn name(key: &str, value: &Bound<'_, PyAny>) -> PyResult<String> {
    value
        .extract::<PathBuf>()
        .map(|p| p.display().to_string())
        .map_err(|_| expected(key, value, "a name (a string)"))
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

/// `T0:T1` from a text, or from a pair of numbers (`what` names the pair's meaning).
fn span(
    key: &str,
    value: &Bound<'_, PyAny>,
    parts: fn(&str, &Bound<'_, PyAny>) -> PyResult<String>,
    what: &str,
) -> PyResult<String> {
    if value.is_instance_of::<PyString>() {
        return name(key, value);
    }
    match &items(value)?[..] {
        [a, b] => Ok(format!("{}:{}", parts(key, a)?, parts(key, b)?)),
        _ => Err(expected(key, value, what)),
    }
}

/// The command-line words of keyword `key` = `value` for the option `arg`: the option and its
/// value as text, each value checked as the option's type.
fn words(arg: &clap::Arg, key: &str, value: &Bound<'_, PyAny>) -> PyResult<Vec<String>> {
    let long = format!("--{}", arg.get_long().unwrap_or(key));
    if matches!(arg.get_action(), ArgAction::SetTrue) {
        return match value.extract::<bool>() {
            Ok(true) => Ok(vec![long]),
            Ok(false) => Ok(Vec::new()),
            Err(_) => Err(expected(key, value, "True or False")),
        };
    }
    let of_type = arg.get_value_parser().type_id();
    let text = |item: &Bound<'_, PyAny>| -> PyResult<String> {
        match key {
            "model" if !item.is_instance_of::<PyString>() => crate::law::register_law(item),
            "bodies" => whole(key, item).or_else(|_| name(key, item)),
            _ if of_type == TypeId::of::<f64>() => number(key, item),
            _ if of_type == TypeId::of::<i64>() => whole(key, item),
            _ => name(key, item),
        }
    };
    let values: Vec<String> = match key {
        "window" => vec![span(key, value, number, "a pair (T0, T1) or \"T0:T1\"")?],
        "point_range" => vec![span(
            key,
            value,
            whole,
            "a pair (start, end) or 'START:END'",
        )?],
        _ if matches!(arg.get_action(), ArgAction::Append) => {
            items(value)?.iter().map(text).collect::<PyResult<_>>()?
        }
        _ => vec![text(value)?],
    };
    Ok(match arg.get_value_delimiter() {
        Some(delimiter) => vec![long, values.join(&delimiter.to_string())],
        None => values.into_iter().flat_map(|v| [long.clone(), v]).collect(),
    })
}

/// The words of `params`, a mapping of parameter names to values: `--set NAME=VALUE` each, a
/// number as its shortest exact text, anything else as its text (refused by the library as
/// the command line refuses `--set p=text`).
fn assignments(value: &Bound<'_, PyAny>) -> PyResult<Vec<String>> {
    let params = value
        .cast::<PyDict>()
        .map_err(|_| expected("params", value, "a mapping of parameter names to values"))?;
    let mut out = Vec::new();
    for (p, v) in params.iter() {
        let p = name("params", &p)?;
        let v = match number(&p, &v) {
            Ok(x) => x,
            Err(_) => v.str()?.to_string(),
        };
        out.extend(["--set".to_string(), format!("{p}={v}")]);
    }
    Ok(out)
}

/// The words of a sweep's `grid`, a mapping of names to lists of values or to range texts:
/// `--grid NAME=V1,V2,…` or `--grid NAME=TEXT` each.
fn grid(value: &Bound<'_, PyDict>) -> PyResult<Vec<String>> {
    let mut out = Vec::new();
    for (key, axis) in value.iter() {
        let key = name("grid", &key)?;
        let values = match axis.is_instance_of::<PyString>() {
            true => axis.extract::<String>()?,
            false => (items(&axis)?.iter())
                .map(|v| number(&format!("grid[{key:?}]"), v))
                .collect::<PyResult<Vec<_>>>()?
                .join(","),
        };
        out.extend(["--grid".to_string(), format!("{key}={values}")]);
    }
    if out.is_empty() {
        return Err(PyValueError::new_err(
            "option `grid`: no axis: give at least one parameter and its values",
        ));
    }
    Ok(out)
}

/// The `TypeError` of a keyword `function` does not take (the Python layer names the close
/// match before it calls: `friction_lab._command.check_keywords`).
fn unknown(function: &str, key: &str) -> PyErr {
    PyTypeError::new_err(format!(
        "{function}() got an unexpected keyword argument '{key}'; it takes: {}",
        keywords(function).unwrap_or_default().join(", ")
    ))
}

/// The request `R` of `function` with the positional `words` (a scenario, a model) and the
/// keyword arguments `options` (those given as `None` left out), parsed by its declaration
/// as the command line parses its options. A value the option's parser refuses is a
/// `ValueError` naming the keyword.
pub fn request<R: Args + FromArgMatches>(
    function: &str,
    words: Vec<String>,
    options: &Bound<'_, PyDict>,
) -> PyResult<R> {
    let command = R::augment_args(clap::Command::new("friction_lab").no_binary_name(true));
    let matches = parse(command, function, words, options)?;
    R::from_arg_matches(&matches).map_err(|e| refused(function, &[], e))
}

/// The options of `command` (a request's declaration) parsed from the positional `words` and
/// the keyword arguments `options` ([`request`]).
fn parse(
    command: clap::Command,
    function: &str,
    mut words: Vec<String>,
    options: &Bound<'_, PyDict>,
) -> PyResult<clap::ArgMatches> {
    for (key, value) in options.iter() {
        if value.is_none() {
            continue;
        }
        let key: String = key.extract()?;
        match key.as_str() {
            "params" => words.extend(assignments(&value)?),
            "grid" => words.extend(grid(value.cast::<PyDict>().map_err(|_| {
                expected("grid", &value, "a mapping of parameter names to values")
            })?)?),
            _ => {
                let long = key.replace('_', "-");
                let arg = (command.get_arguments())
                    .find(|a| a.get_long() == Some(long.as_str()) && is_keyword(&long))
                    .ok_or_else(|| unknown(function, &key))?;
                words.extend(self::words(arg, &key, &value)?);
            }
        }
    }
    let longs: Vec<String> = (command.get_arguments())
        .filter_map(|a| a.get_long().map(str::to_string))
        .collect();
    command
        .try_get_matches_from(&words)
        .map_err(|e| refused(function, &longs, e))
}

/// A value or a combination the declaration refuses, as `ValueError`: a value its option's
/// parser refused as "`keyword` = 'value': why", anything else as clap's message without its
/// usage lines, each of the command's options `longs` it names (`--t-end`) spelled as its
/// keyword (`t_end`).
fn refused(function: &str, longs: &[String], e: clap::Error) -> PyErr {
    use clap::error::{ContextKind, ContextValue};
    use std::error::Error as _;
    let text = |kind| match e.get(kind) {
        Some(ContextValue::String(s)) => Some(s.clone()),
        _ => None,
    };
    let (arg, value) = (
        text(ContextKind::InvalidArg),
        text(ContextKind::InvalidValue),
    );
    if let (Some(arg), Some(value), Some(why)) = (arg, value, e.source()) {
        // `--t-end <T>` or `[SCENARIO]`: the option's or the argument's name.
        let option = arg.trim_start_matches('-');
        let option = option.split([' ', '=']).next().unwrap_or(option);
        let keyword = match option.trim_matches(['[', ']', '<', '>']) {
            "set" => "params".to_string(),
            other => other.to_lowercase().replace('-', "_"),
        };
        let why = spell_fields(&why.to_string(), &crate::keyword);
        return PyValueError::new_err(format!("`{keyword}` = '{value}': {why}"));
    }
    let text = e.render().to_string();
    let message: Vec<&str> = (text.lines())
        .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"))
        .map(|l| l.strip_prefix("error: ").unwrap_or(l))
        .filter(|l| !l.trim().is_empty())
        .collect();
    let mut message = message.join("\n");
    // Longest first: `--dt-list` before `--dt`.
    let mut longs: Vec<&String> = longs.iter().collect();
    longs.sort_by_key(|l| std::cmp::Reverse(l.len()));
    for long in longs {
        let keyword = crate::keyword(&long.replace('-', "_"));
        message = message.replace(&format!("--{long}"), &keyword);
    }
    PyValueError::new_err(format!("{function}(): {message}"))
}

/// The positional words of a run or a study: the rig or `chain` named `scenario`, and
/// `--system PATH`.
fn problem(scenario: Option<&str>, system: Option<PathBuf>) -> PyResult<Vec<String>> {
    if scenario.is_some() && system.is_some() {
        return Err(PyValueError::new_err(
            "give a scenario or a `system`, not both",
        ));
    }
    let mut words: Vec<String> = scenario.map(str::to_string).into_iter().collect();
    if let Some(path) = system {
        words.extend(["--system".to_string(), path.display().to_string()]);
    }
    Ok(words)
}

/// The run `simulate(scenario, system=..., **options)` asks for.
pub fn simulation(
    scenario: Option<&str>,
    system: Option<PathBuf>,
    options: &Bound<'_, PyDict>,
) -> PyResult<SimulationRequest> {
    if scenario.is_none() && system.is_none() {
        return Err(PyValueError::new_err(
            "a scenario (a rig's name or \"chain\") or a `system` is required",
        ));
    }
    request("simulate", problem(scenario, system)?, options)
}

/// The sweep `sweep(scenario, grid=..., **options)` asks for: `grid` maps names to lists of
/// values or to range texts (`"0.1:1:10"`, `"log:0.01:1:9"`).
pub fn sweep(
    scenario: Option<&str>,
    system: Option<PathBuf>,
    grid: &Bound<'_, PyDict>,
    options: &Bound<'_, PyDict>,
) -> PyResult<SweepRequest> {
    let mut words = problem(scenario, system)?;
    words.extend(self::grid(grid)?);
    request("sweep", words, options)
}

/// The comparison `compare(scenario, **options)` asks for, as a request of its own (its
/// parts made and merged on a Dask cluster).
pub fn compare(
    scenario: Option<&str>,
    system: Option<PathBuf>,
    options: &Bound<'_, PyDict>,
) -> PyResult<CompareRequest> {
    request("compare", problem(scenario, system)?, options)
}

/// The study `function` of [`STUDIES`] (`converge`, `independence`, `work_precision`,
/// `stiffness`, or one a program registered) of `scenario` or `system` with the keyword
/// arguments `options`, run into `out`.
pub fn study(
    function: &str,
    scenario: Option<&str>,
    system: Option<PathBuf>,
    options: &Bound<'_, PyDict>,
) -> PyResult<Conduct> {
    let study = STUDIES
        .get(&function.replace('_', "-"))
        .map_err(PyValueError::new_err)?;
    let command = study.declare(clap::Command::new("friction_lab").no_binary_name(true));
    let matches = parse(command, function, problem(scenario, system)?, options)?;
    Ok(Box::new(move |out| study.run(&matches, out)))
}

/// The curve `curve(model, **options)` asks for.
pub fn curve(model: &str, options: &Bound<'_, PyDict>) -> PyResult<CurveRequest> {
    request("curve", vec![model.to_string()], options)
}

/// The run of a test problem `testset(problem, **options)` asks for.
pub fn testset(problem: &str, options: &Bound<'_, PyDict>) -> PyResult<TestSetRequest> {
    request("testset", vec![problem.to_string()], options)
}

/// The paper as `reproduce(out, **options)` asks for it.
pub fn reproduce(options: &Bound<'_, PyDict>) -> PyResult<ReproduceRequest> {
    request("reproduce", Vec::new(), options)
}

/// Table 2 as `phenomena(**options)` asks for it.
pub fn phenomena(options: &Bound<'_, PyDict>) -> PyResult<PhenomenaRequest> {
    request("phenomena", Vec::new(), options)
}
