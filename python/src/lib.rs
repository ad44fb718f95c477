//! `friction_lab._native`: the friction-lab library called from Python, in memory.
//!
//! One function per front-end call of the library: `simulate`, `sweep`, `study` (the four
//! solver studies), `curve` and `phenomena`. Their keyword arguments become the library's
//! typed settings (`bind.rs`), checked by the library as for the command line, and what the
//! run made comes back as values, not text: tables as typed columns, documents as Python
//! values, the trajectory as the bytes of its doubles; no figure is drawn. So every default,
//! every check and every message is the library's, and no law, rig or solver exists twice.
//! The run happens on a worker thread with the GIL released; the calling thread watches for
//! Ctrl-C and stops the solvers through [`integrators::interrupt`].

mod bind;
mod law;
mod law_interrupt;

use friction_lab::artifacts::{open_with, Data};
use friction_lab::columns::Column;
use friction_lab::delivery::Delivery;
use friction_lab::destination;
use friction_lab::error::{bounded, spell_fields, AppError, ErrorKind};
use friction_lab::friction_systems::mode_name;
use friction_lab::provenance::Provenance;
use friction_lab::run_record::RunValues;
use friction_lab::trajectory::{RecordAs, Trajectory};
use integrators::{Mode, SolverError as RunError};
use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{mpsc, Arc, Mutex};
use std::time::Duration;

create_exception!(
    _native,
    SolverError,
    PyRuntimeError,
    "A run failed in the solver (or a sweep had failed points); `result` keeps what was computed."
);

create_exception!(
    _native,
    Cancelled,
    PyRuntimeError,
    "A run stopped because its caller's `stop` said so (a Dask task of an interrupted sweep)."
);

/// How often the calling thread looks for Ctrl-C while a run goes on.
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// The folder the runs are told to write into: only a prefix stripped from the names of the
/// files returned; nothing is written.
const IN_MEMORY: &str = ".";

/// What a command made, for the Python layer: `(files, notes, warnings, failure, run)`,
/// where `files` maps each data file's name (relative to the output folder, e.g.
/// `stiffness.csv`) to its content ([`data`]: a table's columns, a JSON document as Python
/// values, or a text file's bytes), `notes` and `warnings` are the lines the command line prints
/// on stdout and stderr, `failure` is the message of a run that failed after computing part of
/// its result (the values keep that part), or `None`, and `run` is `simulate`'s record as
/// values ([`run_values`]), or `None`.
type Made = (
    Vec<(String, Py<PyAny>)>,
    Vec<String>,
    Vec<String>,
    Option<String>,
    Option<Py<PyDict>>,
);

/// The little-endian bytes of `values`, from which numpy makes its array without a copy
/// through text (`numpy.frombuffer(b, "<f8")`).
fn doubles<'py>(py: Python<'py>, values: &[f64]) -> Bound<'py, PyBytes> {
    let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    PyBytes::new(py, &bytes)
}

/// A run's record for the Python layer, from its values (no file in between): `summary`
/// (Python values), `trajectory` ([`trajectory`]), `final` and `events` (tables as [`data`]
/// gives them); the summary opens with `provenance`, as `summary.json` does.
fn run_values<'py>(
    py: Python<'py>,
    run: &RunValues,
    provenance: &Provenance,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let failed = |e: serde_json::Error| PyRuntimeError::new_err(format!("the run's summary: {e}"));
    let mut summary = serde_json::to_value(&run.summary).map_err(failed)?;
    if let Some(object) = summary.as_object_mut() {
        open_with(object, &serde_json::to_value(provenance).map_err(failed)?);
    }
    d.set_item("summary", json_value(py, &summary)?)?;
    d.set_item("trajectory", trajectory(py, &run.trajectory)?)?;
    d.set_item("final", data(py, Data::Table(&run.finals))?)?;
    d.set_item("events", data(py, Data::Table(&run.events))?)?;
    Ok(d)
}

/// A run's trajectory for the Python layer: `t`, `x`, `v`, `friction` and `z` (or `None`) as
/// the bytes of little-endian doubles, the modes as one byte each (`mode`) indexing
/// `mode_names`, and `bodies` (a system's bodies written, or `None` for a rig).
fn trajectory<'py>(py: Python<'py>, t: &Trajectory) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("t", doubles(py, &t.t))?;
    d.set_item("x", doubles(py, &t.x))?;
    d.set_item("v", doubles(py, &t.v))?;
    d.set_item("friction", doubles(py, &t.friction))?;
    d.set_item("z", t.z.as_deref().map(|z| doubles(py, z)))?;
    let mut modes: Vec<Option<Mode>> = Vec::new();
    let codes: Vec<u8> = t
        .mode
        .iter()
        .map(|m| match modes.iter().position(|n| n == m) {
            Some(k) => k as u8,
            None => {
                modes.push(*m);
                (modes.len() - 1) as u8
            }
        })
        .collect();
    d.set_item("mode", PyBytes::new(py, &codes))?;
    let names: Vec<&str> = modes.iter().map(|m| m.map_or("none", mode_name)).collect();
    d.set_item("mode_names", names)?;
    d.set_item("bodies", t.bodies.clone())?;
    Ok(d)
}

/// A data file's content for the Python layer, from the values it was made of (no text in
/// between): a table as `("table", [(column, kind, values)])`, `kind` one of `"<f8"` and
/// `"<i8"` (`values` the bytes of little-endian numbers, NaN for an empty cell), `"bool"`
/// and `"text"` (a list; `None` for an empty cell); a JSON document as `("json", value)`; any
/// other file as `("bytes", bytes)`.
fn data<'py>(py: Python<'py>, content: Data<'_>) -> PyResult<Bound<'py, PyAny>> {
    match content {
        Data::Table(table) => {
            let columns: Vec<(&str, &str, Bound<'py, PyAny>)> = (table.columns().into_iter())
                .map(|(name, column)| {
                    Ok(match column {
                        Column::Numbers(v) => (name, "<f8", doubles(py, &v).into_any()),
                        Column::Integers(v) => {
                            let bytes: Vec<u8> = v.iter().flat_map(|i| i.to_le_bytes()).collect();
                            (name, "<i8", PyBytes::new(py, &bytes).into_any())
                        }
                        Column::Booleans(v) => (name, "bool", v.into_pyobject(py)?.into_any()),
                        Column::Texts(v) => (name, "text", v.into_pyobject(py)?.into_any()),
                    })
                })
                .collect::<PyResult<_>>()?;
            ("table", columns).into_pyobject(py).map(Bound::into_any)
        }
        Data::Json(value) => ("json", json_value(py, value)?)
            .into_pyobject(py)
            .map(Bound::into_any),
        Data::Bytes(bytes) => ("bytes", PyBytes::new(py, bytes))
            .into_pyobject(py)
            .map(Bound::into_any),
    }
}

/// A JSON document as Python values: objects as dicts (in the document's order), arrays as
/// lists, integers as `int`, other numbers as `float`.
fn json_value<'py>(py: Python<'py>, value: &serde_json::Value) -> PyResult<Bound<'py, PyAny>> {
    use serde_json::Value;
    Ok(match value {
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => b.into_pyobject(py)?.to_owned().into_any(),
        Value::Number(n) => match (n.as_i64(), n.as_u64()) {
            (Some(i), _) => i.into_pyobject(py)?.into_any(),
            (None, Some(u)) => u.into_pyobject(py)?.into_any(),
            _ => n.as_f64().unwrap_or(f64::NAN).into_pyobject(py)?.into_any(),
        },
        Value::String(s) => s.into_pyobject(py)?.into_any(),
        Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(json_value(py, item)?)?;
            }
            list.into_any()
        }
        Value::Object(fields) => {
            let dict = PyDict::new(py);
            for (key, item) in fields {
                dict.set_item(key, json_value(py, item)?)?;
            }
            dict.into_any()
        }
    })
}

/// Runs `simulate`: the library's [`friction_lab::simulate::SimulationRequest`] of `scenario` (a
/// rig's name or `chain`) or of the system file `system`, with the keyword arguments
/// `options` ([`bind::simulation`]); the trajectory as columns. Errors, `stop` and `call` as [`deliver`].
#[pyfunction]
#[pyo3(signature = (scenario, system, options, stop=None, call=None))]
fn simulate(
    py: Python<'_>,
    scenario: Option<String>,
    system: Option<std::path::PathBuf>,
    options: Bound<'_, PyDict>,
    stop: Option<Bound<'_, PyAny>>,
    call: Option<String>,
) -> PyResult<Made> {
    let run = bind::simulation(scenario.as_deref(), system, &options)?;
    deliver(py, stop.as_ref(), call, move || {
        run.run(Path::new(IN_MEMORY), RecordAs::Values)
    })
}

/// Runs `sweep`: the library's [`friction_lab::sweep::SweepRequest`] over `grid` (names to lists
/// of values or range texts) of the run `simulate` would make ([`bind::sweep`]). Errors and
/// `stop` as [`deliver`].
#[pyfunction]
#[pyo3(signature = (scenario, system, grid, options, stop=None, call=None))]
fn sweep(
    py: Python<'_>,
    scenario: Option<String>,
    system: Option<std::path::PathBuf>,
    grid: Bound<'_, PyDict>,
    options: Bound<'_, PyDict>,
    stop: Option<Bound<'_, PyAny>>,
    call: Option<String>,
) -> PyResult<Made> {
    let sweep = bind::sweep(scenario.as_deref(), system, &grid, &options)?;
    deliver(py, stop.as_ref(), call, move || {
        sweep.run(Path::new(IN_MEMORY))
    })
}

/// Runs the solver study `function` (`converge`, `independence`, `work_precision`,
/// `stiffness`): the library's study of `scenario` or `system` with the keyword arguments
/// `options` ([`bind::study`]). Errors, `stop` and `call` as [`deliver`].
#[pyfunction]
#[pyo3(signature = (function, scenario, system, options, stop=None, call=None))]
fn study(
    py: Python<'_>,
    function: &str,
    scenario: Option<String>,
    system: Option<std::path::PathBuf>,
    options: Bound<'_, PyDict>,
    stop: Option<Bound<'_, PyAny>>,
    call: Option<String>,
) -> PyResult<Made> {
    let study = bind::study(function, scenario.as_deref(), system, &options)?;
    deliver(py, stop.as_ref(), call, move || study(Path::new(IN_MEMORY)))
}

/// How many independent parts the comparison of `scenario` or `system` with the keyword
/// arguments `options` divides into ([`friction_lab::study::CompareRequest::part_count`]);
/// every option is checked.
#[pyfunction]
fn compare_parts(
    scenario: Option<String>,
    system: Option<std::path::PathBuf>,
    options: Bound<'_, PyDict>,
) -> PyResult<usize> {
    let request = bind::compare(scenario.as_deref(), system, &options)?;
    request.part_count().map_err(to_python)
}

/// Makes part `index` of that comparison ([`friction_lab::study::CompareRequest::part`]),
/// encoded: one Dask task. Errors, `stop` and `call` as [`deliver`].
#[pyfunction]
#[pyo3(signature = (scenario, system, options, index, stop=None))]
fn compare_part<'py>(
    py: Python<'py>,
    scenario: Option<String>,
    system: Option<std::path::PathBuf>,
    options: Bound<'py, PyDict>,
    index: usize,
    stop: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyBytes>> {
    let request = bind::compare(scenario.as_deref(), system, &options)?;
    let part = interruptible(py, stop.as_ref(), move || request.part(index))?;
    if let Some(e) = law::take_error() {
        integrators::interrupt::clear();
        return Err(e);
    }
    Ok(PyBytes::new(py, &part.map_err(to_python)?))
}

/// The comparison made of `parts` (each of [`compare_part`], in any order)
/// ([`friction_lab::study::CompareRequest::merge`]): what `study("compare", ...)` makes.
/// Errors, `stop` and `call` as [`deliver`].
#[pyfunction]
#[pyo3(signature = (scenario, system, options, parts, stop=None, call=None))]
fn compare_merge(
    py: Python<'_>,
    scenario: Option<String>,
    system: Option<std::path::PathBuf>,
    options: Bound<'_, PyDict>,
    parts: Vec<Bound<'_, PyBytes>>,
    stop: Option<Bound<'_, PyAny>>,
    call: Option<String>,
) -> PyResult<Made> {
    let request = bind::compare(scenario.as_deref(), system, &options)?;
    let parts: Vec<Vec<u8>> = parts.iter().map(|p| p.as_bytes().to_vec()).collect();
    deliver(py, stop.as_ref(), call, move || {
        request.merge(Path::new(IN_MEMORY), &parts)
    })
}

/// Draws the curve of `model` ([`bind::curve`]). Errors and `call` as [`deliver`].
#[pyfunction]
#[pyo3(signature = (model, options, call=None))]
fn curve(
    py: Python<'_>,
    model: &str,
    options: Bound<'_, PyDict>,
    call: Option<String>,
) -> PyResult<Made> {
    let curve = bind::curve(model, &options)?;
    deliver(py, None, call, move || curve.run(Path::new(IN_MEMORY)))
}

/// Solves the test problem `problem` ([`bind::testset`]). Errors, `stop` and `call` as [`deliver`].
#[pyfunction]
#[pyo3(signature = (problem, options, stop=None, call=None))]
fn testset(
    py: Python<'_>,
    problem: &str,
    options: Bound<'_, PyDict>,
    stop: Option<Bound<'_, PyAny>>,
    call: Option<String>,
) -> PyResult<Made> {
    let run = bind::testset(problem, &options)?;
    deliver(py, stop.as_ref(), call, move || {
        run.run(Path::new(IN_MEMORY))
    })
}

/// Decides Table 2 ([`bind::phenomena`]). Errors, `stop` and `call` as [`deliver`].
#[pyfunction]
#[pyo3(signature = (options, stop=None, call=None))]
fn phenomena(
    py: Python<'_>,
    options: Bound<'_, PyDict>,
    stop: Option<Bound<'_, PyAny>>,
    call: Option<String>,
) -> PyResult<Made> {
    let table = bind::phenomena(&options)?;
    deliver(py, stop.as_ref(), call, move || {
        table.run(Path::new(IN_MEMORY))
    })
}

/// Reproduces the paper into the folder `out` ([`friction_lab::reproduce::ReproduceRequest`],
/// the keyword arguments `options` read by [`bind::reproduce`]) and writes it as the command
/// line does ([`Delivery`]: `figure_size`, `dpi`, `replace`; its provenance naming `call`).
/// Returns the folder written (`out`, or `out.stopped` beside a complete result when a stop
/// cut it short) and the failure of a part that did not finish, if one did not. Errors and
/// `stop` as [`deliver`].
#[pyfunction]
#[pyo3(signature = (out, options, figure_size=None, dpi=None, replace=false, stop=None, call=None))]
#[allow(clippy::too_many_arguments)]
fn reproduce(
    py: Python<'_>,
    out: std::path::PathBuf,
    options: Bound<'_, PyDict>,
    figure_size: Option<String>,
    dpi: Option<f64>,
    replace: bool,
    stop: Option<Bound<'_, PyAny>>,
    call: Option<String>,
) -> PyResult<(String, Option<String>)> {
    let request = bind::reproduce(&options)?;
    let made_by = call.unwrap_or_default();
    let delivery = Delivery::parse(figure_size.as_deref(), dpi, replace, &made_by);
    let delivery = delivery.map_err(to_python)?;
    let threads = request.threads().map_err(to_python)?;
    destination::check(&out, replace).map_err(to_python)?;
    let done = interruptible(py, stop.as_ref(), move || {
        let _claim = destination::claim(&out)?;
        let made = request.run(&out)?;
        let written = delivery.write(made.files, &out, threads)?;
        Ok::<_, AppError>((written.folder, made.failure))
    })?;
    if let Some(e) = law::take_error() {
        integrators::interrupt::clear();
        return Err(e);
    }
    let (folder, failure) = done.map_err(to_python)?;
    Ok((
        folder.display().to_string(),
        failure.as_ref().map(failure_message),
    ))
}

/// The keyword arguments of the function `name` that binds the library directly
/// (`simulate`, `sweep`, the solver studies), besides its scenario and `system`.
#[pyfunction]
fn keywords(name: &str) -> PyResult<Vec<String>> {
    bind::keywords(name).ok_or_else(|| {
        PyValueError::new_err(format!("`{name}` is no function bound to the library"))
    })
}

/// Runs `work` ([`interruptible`]) and hands its result to Python: the exception of a law
/// written in Python that raised, else the files as values ([`data`]), the notes, the
/// warnings, the failure and the trajectory. Bad input raises `ValueError`; a failure
/// without a result raises `SolverError`; Ctrl-C stops the solvers and raises
/// `KeyboardInterrupt`. `stop`, if given, is called every [`SIGNAL_POLL`] while the run goes
/// on; once it returns true the solvers stop as for Ctrl-C and `Cancelled` is raised (how a
/// Dask task learns that its sweep was cancelled). The files, and a run's summary, are stamped
/// with their provenance ([`Artifacts::stamp`]), `call` (the Python call with its keyword
/// arguments) naming what asked for them.
fn deliver(
    py: Python<'_>,
    stop: Option<&Bound<'_, PyAny>>,
    call: Option<String>,
    work: impl FnOnce() -> Result<friction_lab::made::Made, AppError> + Send + 'static,
) -> PyResult<Made> {
    let made = interruptible(py, stop, work)?;
    // A law written in Python that raised stopped the run: its exception is the answer.
    if let Some(e) = law::take_error() {
        integrators::interrupt::clear();
        return Err(e);
    }
    let mut made = made.map_err(to_python)?;
    let mut provenance = Provenance::now(friction_lab::threads::current());
    provenance.command = call;
    made.files
        .stamp(Path::new(IN_MEMORY), &provenance)
        .map_err(to_python)?;
    let files = made
        .files
        .data(Path::new(IN_MEMORY))
        .into_iter()
        .map(|(name, content)| Ok((name.display().to_string(), data(py, content)?.unbind())))
        .collect::<PyResult<_>>()?;
    let run = (made.run.as_ref())
        .map(|r| run_values(py, r, &provenance).map(Bound::unbind))
        .transpose()?;
    let spelled = |lines: Vec<String>| -> Vec<String> {
        (lines.iter())
            .map(|line| spell_fields(line, &keyword))
            .collect()
    };
    Ok((
        files,
        spelled(made.notes),
        spelled(made.warnings),
        made.failure.as_ref().map(failure_message),
        run,
    ))
}

/// The message of a run that failed part-way, as Python reads it: what was computed is the
/// error's `result`, not files.
fn failure_message(e: &AppError) -> String {
    const KEPT: &str = "the error's `result` keeps the run up to";
    match e {
        AppError::Solver(s @ RunError::Interrupted { .. }) => {
            format!("stopped: {s} ({KEPT} there)")
        }
        AppError::Solver(s) => format!("the solver failed: {s} ({KEPT} the failure)"),
        AppError::Diverged(why) => format!("the run diverged: {why} ({KEPT} its end)"),
        other => other.message(&keyword),
    }
}

/// Python's spelling of a request's field: its keyword argument, the field's own name but
/// `params` for the assignments the command line takes as `--set`.
pub fn keyword(field: &str) -> String {
    match field {
        "set" => "params".to_string(),
        other => other.to_string(),
    }
}

/// The listing of `friction-lab models --json`.
#[pyfunction]
fn models_json() -> String {
    friction_lab::listing::json()
}

/// A failed command: bad input (exit code 2) as `ValueError`, anything else as `SolverError`;
/// the message is the one the command line prints after `error: `, a request's field named
/// as its keyword (`t_end`, where the command line says `--t-end`).
fn to_python(e: AppError) -> PyErr {
    if e.kind() == ErrorKind::BadInput {
        PyValueError::new_err(bounded(&e.message(&keyword)))
    } else {
        SolverError::new_err(bounded(&failure_message(&e)))
    }
}

/// How many runs a second Ctrl-C abandoned whose worker has not returned yet (a law blocked in
/// a call into C): while one lives, the solvers' stop request stays raised, so no new run may
/// start ([`interruptible`] refuses it).
static ABANDONED: AtomicUsize = AtomicUsize::new(0);

/// Where a run's worker and its caller meet when either is done: whether the worker has
/// returned, and whether the caller has left without it.
#[derive(Default)]
struct Parting {
    returned: bool,
    abandoned: bool,
}

/// Runs `work` on a worker thread with the GIL released, looking for Ctrl-C on the calling
/// thread every [`SIGNAL_POLL`]: on `KeyboardInterrupt` (or any exception a signal handler
/// raises) the solvers are asked to stop, the worker is awaited, and the exception is raised.
/// `stop` is asked at the same moments; once it returns true (or raises), the solvers stop
/// likewise and `Cancelled` (or its exception) is raised. A second Ctrl-C while the worker
/// finishes abandons it, as on the command line: `KeyboardInterrupt` is raised at once, and
/// the worker, once its law returns, lowers the stop request itself; until then a new run is
/// refused ([`ABANDONED`]).
fn interruptible<T: Send + 'static>(
    py: Python<'_>,
    stop: Option<&Bound<'_, PyAny>>,
    work: impl FnOnce() -> T + Send + 'static,
) -> PyResult<T> {
    if ABANDONED.load(Ordering::SeqCst) > 0 {
        return Err(PyRuntimeError::new_err(
            "a run abandoned by a second Ctrl-C is still finishing: one of its Python laws has \
             not returned yet (a law blocked in a call into C stops when that call returns); \
             wait for it, or restart the interpreter",
        ));
    }
    let (done, finished) = mpsc::channel();
    let parting = Arc::new(Mutex::new(Parting::default()));
    let worker_parting = Arc::clone(&parting);
    let worker = std::thread::spawn(move || {
        // Attached once, for the worker's whole run, and detached at once: a law written in
        // Python then takes the GIL on a thread state that lives as long as the run, where
        // attaching a bare thread would create and destroy one per evaluation (11.8 µs an
        // evaluation of a Coulomb law on the belt instead of 0.6 µs; docs/python.md).
        let result = Python::attach(|py| {
            let _registered = law_interrupt::register(py);
            py.detach(work)
        });
        let abandoned = {
            let mut parting = worker_parting.lock().unwrap_or_else(|e| e.into_inner());
            parting.returned = true;
            parting.abandoned
        };
        if abandoned {
            // The caller has gone: lower what it raised, as it would have.
            Python::attach(|py| {
                integrators::interrupt::clear();
                law_interrupt::withdraw(py);
                let _ = law::take_error();
            });
            ABANDONED.fetch_sub(1, Ordering::SeqCst);
        }
        // The caller may have gone: then nobody listens.
        let _ = done.send(());
        result
    });
    let mut signal = None;
    // Behind a lock only so that the closure handed to `detach` may borrow it.
    let finished = Mutex::new(finished);
    let wait = || {
        let finished = finished.lock().unwrap_or_else(|e| e.into_inner());
        finished.recv_timeout(SIGNAL_POLL)
    };
    while py.detach(wait).is_err() {
        match signal {
            None => {
                let stopped = match stop.map(|s| s.call0().and_then(|r| r.is_truthy())) {
                    Some(Ok(true)) => Err(Cancelled::new_err(
                        "stopped: the caller cancelled the run (its sweep was interrupted)",
                    )),
                    Some(Err(e)) => Err(e),
                    _ => Ok(()),
                };
                if let Err(e) = py.check_signals().and(stopped) {
                    integrators::interrupt::request();
                    // A law that never returns would never let the solvers see the request.
                    law_interrupt::raise_in_laws(py);
                    signal = Some(e);
                }
            }
            Some(_) => {
                if let Err(second) = py.check_signals() {
                    let mut parting = parting.lock().unwrap_or_else(|e| e.into_inner());
                    if !parting.returned {
                        parting.abandoned = true;
                        ABANDONED.fetch_add(1, Ordering::SeqCst);
                        return Err(second);
                    }
                }
            }
        }
        if worker.is_finished() {
            break;
        }
    }
    let result = py.detach(|| worker.join());
    if let Some(e) = signal {
        integrators::interrupt::clear();
        law_interrupt::withdraw(py);
        // The law's KeyboardInterrupt, if one raised it, is this stop's, not the next run's.
        let _ = law::take_error();
        return Err(e);
    }
    result.map_err(|_| PyRuntimeError::new_err("friction-lab panicked (a bug: please report it)"))
}

/// The module `friction_lab._native`.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // The pools' workers, as the run's worker in `interruptible`: attached once, detached at
    // once, so that a law written in Python takes the GIL on a living thread state.
    friction_lab::threads::set_worker_wrapper(|work| {
        Python::attach(|py| {
            let _registered = law_interrupt::register(py);
            py.detach(work)
        })
    });
    // Progress of long work as on the command line: a bar on a terminal, else a heartbeat
    // line on stderr (a notebook's log); Ctrl-C is watched by `interruptible`.
    friction_lab::progress::observe_with(std::sync::Arc::new(terminal::Terminal));
    m.add("__version__", friction_lab::provenance::VERSION)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(testset, m)?)?;
    m.add_function(wrap_pyfunction!(compare_parts, m)?)?;
    m.add_function(wrap_pyfunction!(compare_part, m)?)?;
    m.add_function(wrap_pyfunction!(compare_merge, m)?)?;
    m.add_function(wrap_pyfunction!(study, m)?)?;
    m.add_function(wrap_pyfunction!(curve, m)?)?;
    m.add_function(wrap_pyfunction!(phenomena, m)?)?;
    m.add_function(wrap_pyfunction!(reproduce, m)?)?;
    m.add_function(wrap_pyfunction!(keywords, m)?)?;
    m.add_function(wrap_pyfunction!(models_json, m)?)?;
    m.add_function(wrap_pyfunction!(law::register_law, m)?)?;
    m.add("SolverError", m.py().get_type::<SolverError>())?;
    m.add("Cancelled", m.py().get_type::<Cancelled>())?;
    Ok(())
}
