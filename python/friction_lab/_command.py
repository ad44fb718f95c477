"""Keyword arguments to the library's typed settings, and what a run made back as tables.

Every function of the package calls the library in memory (``_native``): its keyword
arguments become the fields of the library's settings (``python/src/bind.rs``), so each
default and range check is the library's, the command line's too (docs/python.md lists them).
What Python is told is in Python's words: an unknown keyword argument is a ``TypeError``
naming it and its close match, and the messages name the keyword arguments (``t_end``,
``params``), not the command line's options (``--t-end``, ``--set``): the library's errors
name each option as data, which the native binding spells as its keyword.
"""

from __future__ import annotations

import difflib
import functools
import json
import math
import numbers
import os
import warnings
from contextvars import ContextVar
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Mapping, Optional, Tuple

import numpy as np
import pandas as pd

from . import _native


def _listed(what: str, value: Any) -> Optional[list]:
    """``value`` as a list if it is one, a tuple, a range or a one-dimensional numpy array
    (``None`` for a single value); an array of more dimensions is refused, naming ``what``."""
    if isinstance(value, (list, tuple, range)):
        return list(value)
    if isinstance(value, np.ndarray):
        if value.ndim == 0:
            return None
        if value.ndim > 1:
            raise ValueError(f"{what}: an array of shape {value.shape}: a list of values "
                             "(one dimension) is expected")
        return value.tolist()
    return None


def _mapping(name: str, value: Any, example: str) -> Mapping:
    """``value`` as a mapping of names to values: a dict, a pandas Series of named values, or
    pairs (what ``dict`` takes); anything else is refused, naming the option, an ``example``
    and what it got."""
    if isinstance(value, Mapping):
        return value
    pairs = None
    if isinstance(value, pd.Series):
        pairs = list(value.items())
    elif not isinstance(value, (str, bytes)):
        try:
            pairs = [tuple(pair) for pair in value]
            dict(pairs)
        except (TypeError, ValueError):
            pairs = None
    if pairs is not None:
        seen: Dict[Any, Any] = {}
        for key, v in pairs:
            if key in seen:
                raise ValueError(f"option `{name}`: `{key}` is given twice, {seen[key]!r} and "
                                 f"{v!r}: give each name once (only the last would be used)")
            seen[key] = v
        return seen
    raise ValueError(f"option `{name}`: a mapping of parameter names to values is expected, "
                     f"e.g. {example}, not {type(value).__name__} {value!r}")


@functools.lru_cache(maxsize=None)
def keywords(command: str) -> Dict[str, str]:
    """The keyword arguments of ``command``'s function (``_native.keywords``), each with the
    command-line option it is: the name with ``-`` for ``_``, ``params`` for ``--set``."""
    names = {k: k.replace("_", "-") for k in _native.keywords(command.replace("-", "_"))}
    names["system"] = "system"
    names["params"] = "set"
    return names


def check_keywords(command: str, options: Mapping[str, Any]) -> None:
    """A ``TypeError`` for a keyword argument ``command``'s function does not take, naming it
    and the closest one it takes (or all of them)."""
    known = keywords(command)
    for name in options:
        if name in known:
            continue
        close = difflib.get_close_matches(name, known, n=1)
        hint = (f"; did you mean '{close[0]}'?" if close
                else "; it takes: " + ", ".join(sorted(known)))
        raise TypeError(f"{command.replace('-', '_')}() got an unexpected keyword argument "
                        f"'{name}'{hint}")


def _name(command: str, argument: Any) -> None:
    """Refuses a positional ``argument`` that is neither ``None`` nor a string: passed on, it
    would fail as the native call's TypeError, naming no argument."""
    if argument is not None and not isinstance(argument, str):
        raise ValueError(f"`{command}`: argument {argument!r} is not a name: a string is "
                         f"expected, as `friction-lab {command} --help` lists them")


def values(command: str, params: Any = None, grid: Any = None,
           **options: Any) -> Dict[str, Any]:
    """The keyword arguments of ``command``'s function, checked and made plain for the native
    binding: an unknown keyword is a ``TypeError`` (:func:`check_keywords`); a numpy
    value of no dimension is its value, a one-dimensional array a list, a larger one
    refused; ``params`` a dict (from a mapping, a pandas Series or pairs), ``grid`` a dict of
    lists or range texts; ``None`` and ``False`` leave a keyword out. The values are then taken
    by the native binding as the library's types (``python/src/bind.rs``)."""
    check_keywords(command, options)
    out: Dict[str, Any] = {}
    for name, value in options.items():
        if value is None or value is False:
            continue
        if isinstance(value, np.ndarray) and value.ndim == 0:
            value = value.item()
        listed = None if name == "model" else _listed(f"option `{name}`", value)
        out[name] = value if listed is None else listed
    if params is not None:
        out["params"] = {key: v.item() if isinstance(v, np.ndarray) and v.ndim == 0 else v
                         for key, v in _mapping("params", params, "{'v_belt': 0.1}").items()}
    if grid is not None:
        axes = {}
        for key, axis in _mapping("grid", grid, "{'v_belt': [0.1, 0.2]}").items():
            listed = axis if isinstance(axis, str) else _listed(f"option `grid`, axis `{key}`", axis)
            if listed is None:
                listed = [axis]
            elif not listed:
                raise ValueError(f"option `grid`, axis `{key}`: no values")
            axes[key] = listed
        out["grid"] = axes
    return out


#: The public call being made in this context (``friction_lab.simulate('belt', t_end=5.0)``),
#: which the files' provenance names (:func:`recorded`).
_CALL: ContextVar[Optional[str]] = ContextVar("friction_lab_call", default=None)


def recorded(function: Callable) -> Callable:
    """``function`` (a public function of the package) with its call, arguments and keyword
    arguments as ``repr`` writes them, named as what made the files' provenance
    (``provenance.json``, and the ``provenance`` every JSON document opens with). A call made
    inside another (``compare`` running its parts) keeps the outer one."""
    @functools.wraps(function)
    def with_call(*args: Any, **kwargs: Any) -> Any:
        if _CALL.get() is not None:
            return function(*args, **kwargs)
        words = [repr(a) for a in args] + [f"{k}={v!r}" for k, v in kwargs.items()]
        token = _CALL.set(f"friction_lab.{function.__name__}({', '.join(words)})")
        try:
            return function(*args, **kwargs)
        finally:
            _CALL.reset(token)
    return with_call


def current_call() -> Optional[str]:
    """The public call being made in this context (:func:`recorded`), if any."""
    return _CALL.get()


def call(command: str, *arguments: Any, stop: Optional[Callable[[], bool]] = None) -> "Made":
    """Calls the library's ``command`` with ``arguments`` (GIL released, Ctrl-C honoured):
    ``_native.simulate``, ``_native.sweep``, ``_native.curve``, ``_native.phenomena``,
    ``_native.testset``, or for a
    solver study ``_native.study(name, ...)``. Bad input raises ``ValueError``; a failure with
    no result raises ``SolverError``. ``stop``, if given, is asked every 50 ms while the run
    goes on: once it returns true the run stops as on Ctrl-C and ``_native.Cancelled`` is
    raised."""
    made_by = _CALL.get()
    if command == "curve":
        return _made(command, lambda: _native.curve(*arguments, call=made_by))
    if command in ("simulate", "sweep", "phenomena", "testset"):
        native = getattr(_native, command)
    else:
        native = functools.partial(_native.study, command.replace("-", "_"))
    return _made(command, lambda: native(*arguments, stop, call=made_by))


def frame(columns: List[Tuple[str, str, Any]]) -> pd.DataFrame:
    """A table of the library as a DataFrame, from its typed columns (``Made.files``): the
    numbers from the bytes of the library's doubles and integers, booleans and text as
    lists, an empty cell as NaN; typed as pandas' ``read_csv`` types the same CSV file."""
    data = {}
    for name, kind, values in columns:
        if kind in ("<f8", "<i8"):
            data[name] = np.frombuffer(values, dtype=kind).copy()
        elif kind == "bool":
            data[name] = np.array(values, dtype=bool)
        else:
            data[name] = np.array([np.nan if v is None else v for v in values], dtype=object)
    return pd.DataFrame(data, columns=[name for name, _, _ in columns])


@dataclass
class Made:
    """What one command made: its data files by name, each as ``(kind, content)`` (a table's
    typed columns, a JSON document's value, or a text file's bytes), the lines it would
    print, the message of a run that failed part-way (the files keep what was computed),
    and ``simulate``'s record as values: its summary, trajectory as numbers, final states and
    events (see :class:`Result`)."""

    files: Dict[str, Tuple[str, Any]]
    notes: List[str] = field(default_factory=list)
    failure: Optional[str] = None
    run: Optional[Dict[str, Any]] = None

    @property
    def provenance(self) -> Dict[str, Any]:
        """Where the files come from (``provenance.json``'s ``provenance``): ``friction_lab``
        (the version), ``commit``, ``date``, ``machine``, ``threads``, and ``command``: the
        Python call with its keyword arguments."""
        return self.json("provenance.json")["provenance"]

    def table(self, name: str) -> pd.DataFrame:
        """The table ``name`` (a CSV file of the command line) as a DataFrame."""
        return frame(self._content(name, "table"))

    def json(self, name: str) -> Any:
        """The document ``name`` (a JSON file of the command line) as Python values."""
        return self._content(name, "json")

    def text(self, name: str) -> str:
        """The text file ``name`` (a Markdown report)."""
        return self._content(name, "bytes").decode()

    def _content(self, name: str, kind: str) -> Any:
        made_as, content = self.files[name]
        if made_as != kind:
            raise TypeError(f"{name} is made as {made_as}, not {kind} (a bug: please report it)")
        return content


class SolverError(RuntimeError):
    """A run failed in the solver, or a sweep had failed points; ``result`` keeps what was
    computed (a :class:`Result`, a :class:`Study` or a sweep's DataFrame), or is ``None``
    when the failure left nothing to keep."""

    def __init__(self, message: str, result: Any = None):
        super().__init__(message)
        self.result = result


def _made(command: str, native: Callable[[], Any]) -> Made:
    """What the native call ``native`` made for ``command``; its messages name the options as
    keywords (the library spells them so for Python)."""
    try:
        files, notes, advice, failure, run = native()
    except _native.SolverError as e:
        raise SolverError(str(e)) from None
    for line in advice:
        warnings.warn(line, RuntimeWarning, stacklevel=3)
    return Made(dict(files), list(notes), failure, run)


def system_value(system: Any) -> Optional[str]:
    """What the library's ``system`` takes for a system given as a path (the path), as a dict
    with the keys of ``docs/systems.md`` (its JSON text: the system reaches the library as a
    value, through no file), or none (``None``)."""
    if system is None:
        return None
    if isinstance(system, Mapping):
        # Made whole (and refused, naming `system`) before the call.
        return json.dumps(_plain(system))
    if isinstance(system, (str, os.PathLike)):
        return os.fspath(system)
    raise TypeError("system: expected a path (str or os.PathLike) or a dict with the "
                    f"keys of docs/systems.md, got {type(system).__name__}")


def _plain(value: Any) -> Any:
    """``value`` with numpy scalars and tuples made plain JSON; a non-finite number, and a
    value JSON cannot hold, refused naming ``system``."""
    if isinstance(value, Mapping):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, bool) or isinstance(value, str):
        return value
    if isinstance(value, numbers.Integral):
        return int(value)
    if isinstance(value, numbers.Real):
        if not math.isfinite(value):
            raise ValueError(f"system: {value!r} is not a finite number")
        return float(value)
    if value is None:
        return value
    raise TypeError(f"system: {value!r} ({type(value).__name__}) is not a number, a string, "
                    "a list or a dict")
