"""friction_lab: dry-friction models and the solvers that integrate them, in a notebook.

The same models, rigs, systems and solvers as the ``friction-lab`` command line, the library
called in memory: keyword arguments are the library's settings, named as the command line's
options (``rtol=1e-8`` is ``--rtol 1e-8``, ``params={"v_belt": 0.1}`` is ``--set
v_belt=0.1``), results are numpy arrays and pandas DataFrames with the columns of the files
the command line writes (docs/files.md). Bad input raises ``ValueError`` naming the keyword
argument; a solver failure raises
:class:`SolverError`, whose ``result`` keeps what was computed. Long runs release the GIL,
and Ctrl-C stops them. See docs/python.md.
"""

from __future__ import annotations

import io
import json
import os
import pathlib
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np
import pandas as pd

from . import _native
from ._command import SolverError, _name, call, current_call, recorded, system_value, values
from ._result import Result, Study, Table2
from ._sweep import sweep
from ._compare import compare


#: The friction-lab version, the library's (``provenance.json``'s ``friction_lab``).
__version__: str = _native.__version__

__all__ = ["models", "curve", "simulate", "converge", "independence", "work_precision",
           "stiffness", "compare", "orbit", "continuation", "closed_loop", "phenomena", "testset", "reproduce", "sweep", "Result", "Study", "Table2", "SolverError"]


def models() -> List[Dict[str, Any]]:
    """Every model: ``name``, ``title``, ``equation`` (and ``equation_printed`` where the
    paper prints another), and ``parameters``, each a dict with ``name``, ``unit``,
    ``default``, ``range`` (``min``, ``max``, inclusive flags) and ``range_text``."""
    listing = json.loads(_native.models_json())
    by_name = {p["name"]: p for p in listing["parameters"]}
    keep = ("name", "unit", "meaning", "default", "range", "range_text")
    return [dict(m, parameters=[{k: by_name[p][k] for k in keep} for p in m["parameters"]])
            for m in listing["models"]]


@recorded
def curve(model: str, params: Optional[Dict[str, float]] = None, **options: Any) -> Dict[str, np.ndarray]:
    """One friction curve, as ``friction-lab curve MODEL`` writes it: a dict of the CSV's
    columns (``v`` or ``x``, ``F``, and the admissible band at rest where there is one).
    Options: ``points``, ``v_max``, ``variant``, ``param_set``, ... (``friction-lab curve
    --help``)."""
    _name("curve", model)
    made = call("curve", model, values("curve", params=params, **options))
    name = next(n for n in made.files if n.endswith(".csv"))
    frame = made.table(name)
    return {c: frame[c].to_numpy() for c in frame.columns}


@recorded
def simulate(scenario: Optional[str] = None, *, system: Any = None,
             params: Optional[Dict[str, float]] = None, **options: Any) -> Result:
    """One run of a rig (``"belt"``, ``"paper-block"``, ...), of the chain (``"chain"``), or
    of a system (``system=`` a TOML or JSON file, or a dict with the keys of docs/systems.md).
    Options: ``model``, ``scheme``, ``solver``, ``switching``, ``theta``, ``t_end``, ``rtol``, ``atol``,
    ``dt``, ``fixed_step``, ``points``, ``bodies``, ``variant``, ``param_set``,
    ``max_steps``, ``time_limit``, ``window`` (``(T0, T1)``: the span the spectrum is taken
    over) (``friction-lab simulate --help``)."""
    _name("simulate", scenario)
    given = values("simulate", params=params, **options)
    made = call("simulate", scenario, system_value(system), given)
    result = Result(made)
    if made.failure is not None:
        raise SolverError(made.failure, result)
    return result


def _study(command: str, scenario: Optional[str], params: Optional[Dict[str, float]],
           options: Dict[str, Any], main: Optional[str] = None) -> Study:
    _name(command, scenario)
    system = options.pop("system", None)
    given = values(command, params=params, **options)
    made = call(command, scenario, system_value(system), given)
    study = Study(made, command, main)
    if made.failure is not None:
        # Written and failed (an independence level): the study keeps what finished.
        raise SolverError(made.failure, study)
    return study


@recorded
def converge(scenario: Optional[str] = None, *, params: Optional[Dict[str, float]] = None, **options: Any) -> Study:
    """Observed orders against a reference (``friction-lab converge --help``)."""
    return _study("converge", scenario, params, options)


@recorded
def independence(scenario: Optional[str] = None, *, params: Optional[Dict[str, float]] = None, **options: Any) -> Study:
    """Step-size independence with a Richardson estimate (``friction-lab independence``)."""
    return _study("independence", scenario, params, options)


@recorded
def work_precision(scenario: Optional[str] = None, *, params: Optional[Dict[str, float]] = None, **options: Any) -> Study:
    """Error against work for every solver (``friction-lab work-precision --help``)."""
    return _study("work-precision", scenario, params, options)


@recorded
def stiffness(scenario: Optional[str] = None, *, params: Optional[Dict[str, float]] = None, **options: Any) -> Study:
    """Where the implicit solvers overtake the explicit ones (``friction-lab stiffness``)."""
    return _study("stiffness", scenario, params, options)


@recorded
def orbit(scenario: Optional[str] = None, *, params: Optional[Dict[str, float]] = None, **options: Any) -> Study:
    """The periodic orbit of a rig's body or a system, by shooting through its switches from the
    cycle its run settles onto by ``t_end`` (``friction-lab orbit --help``): ``study.runs`` is
    the orbit sampled (``t``, each body's ``x_NAME`` and ``v_NAME``),
    ``study.tables["orbit-segments"]`` its segments (modes, the switch that ends each), and
    ``study.summary`` its ``period``, ``residual``, ``floquet`` (``multipliers`` as (re, im)
    pairs, the trivial one first; ``stability``) and ``amplitudes``."""
    return _study("orbit", scenario, params, options)


@recorded
def continuation(scenario: Optional[str] = None, *, params: Optional[Dict[str, float]] = None,
                 **options: Any) -> Study:
    """The branches of equilibria and periodic orbits over one parameter, by pseudo-arclength
    continuation (``friction-lab continue --help``; ``parameter="v_belt"``, ``range="0.02:0.5"``):
    ``study.runs`` is ``branch.csv`` (``kind``, the parameter under its name, ``period``,
    ``amplitude``, ``spectrum``, ``stable``, ``segments``), ``study.tables["special_points"]``
    the folds, Hopf points, period doublings and segment changes."""
    return _study("continue", scenario, params, options, main="branch")


@recorded
def closed_loop(scenario: Optional[str] = None, *, params: Optional[Dict[str, float]] = None,
                **options: Any) -> Study:
    """The closed loop of the servo rig (``"servo"``, its gains, mass and set point in
    ``params``: ``kp``, ``ki``, ``kd``, ``m``, ``x_ref``) or of a system with a controller
    (``system=``), run under the hunting protocol for 800 s unless ``t_end`` is given
    (``friction-lab closed-loop --help``): ``study.summary`` holds the simulated loop
    (``simulated``: ``hunting``, ``period``, ``amplitude``, ``stuck``, ``final_error``, ...),
    its ``regime``, and the describing function's ``idealised`` plant, ``break_away_gain``
    and ``predicted`` cycles, or ``not_predicted``, why the loop is not of its form;
    ``study.runs`` is the trace (``t``, ``r``, ``x``, ``error``),
    ``study.tables["closed-loop-predicted"]`` the predicted cycles. An unsettled loop warns
    (``RuntimeWarning``)."""
    return _study("closed-loop", scenario, params, options)


@recorded
def testset(problem: str, **options: Any) -> Dict[str, Any]:
    """One problem of the stiff test set (``"van-der-pol"``, ``"robertson"``, ``"hires"``,
    ``"orego"``, ``"pollution"``) solved by one adaptive solver, as ``friction-lab testset``
    solves it (``solver``, default radau5; ``rtol``; ``atol``, default the problem's own;
    ``h0``; ``t_end``; ``max_steps``; ``time_limit``): a dict with ``summary`` (the counts,
    ``scd``: the significant correct digits against the published reference, ``status`` and
    ``reason``) and ``final`` (the state at the end time, ``final.csv``, as a DataFrame). A run
    with fewer than one correct digit is ``inaccurate`` and warns."""
    _name("testset", problem)
    made = call("testset", problem, values("testset", **options))
    final = pd.read_csv(io.StringIO(made.text("final.csv")))
    solved = {"summary": made.json("summary.json"), "final": final}
    if made.failure is not None:
        raise SolverError(made.failure, solved)
    return solved


@recorded
def phenomena(models: Any = None, *, params: Optional[Dict[str, float]] = None,
              **options: Any) -> Table2:
    """Table 2 decided by simulation (``friction-lab phenomena --help``): every phenomenon's
    verdict for each law of ``models`` (names of the catalog, or laws written in Python;
    default: every model of the catalog), beside the paper's claim, with its evidence."""
    made = call("phenomena", values("phenomena", params=params, model=models, **options))
    table = Table2(made)
    if made.failure is not None:
        # Undecided cells: the table keeps the decided ones.
        raise SolverError(made.failure, table)
    return table


@recorded
def reproduce(out: Union[str, os.PathLike], *, params: Optional[Dict[str, float]] = None,
              param_set: Optional[str] = None, threads: Optional[int] = None,
              figure_size: Union[str, Tuple[float, float], None] = None,
              dpi: Optional[float] = None, replace: bool = False) -> pathlib.Path:
    """The paper reproduced into the folder ``out``, as ``friction-lab reproduce --out OUT``
    writes it (docs/reproduction.md): Figures 2-7, the experiment, Table 2, the solver studies,
    the comparison of schemes, the chain, the stick-slip map, the closed loop and the limit
    cycles, each linked from ``report.md``. ``params`` changes friction parameters of
    ``param_set`` (a rig's parameter is refused: every rig runs at the paper's settings);
    ``threads`` (default: all cores) does not change the results. ``figure_size`` (``"6x4"``
    or ``(6, 4)``, inches), ``dpi`` and ``replace`` as the command line's options. Returns the
    folder written; a part that failed raises :class:`SolverError` after writing, the folder
    as its ``result`` (its section of ``report.md`` says why)."""
    given = values("reproduce", params=params, param_set=param_set, threads=threads)
    if isinstance(figure_size, (tuple, list)):
        if len(figure_size) != 2:
            raise ValueError(f"option `figure_size` = {figure_size!r}: a pair (width, height) "
                             "in inches is expected, e.g. (6, 4)")
        figure_size = "x".join(repr(float(side)) for side in figure_size)
    folder, failure = _native.reproduce(os.fspath(out), given, figure_size, dpi, replace,
                                        None, call=current_call())
    written = pathlib.Path(folder)
    if failure is not None:
        raise SolverError(failure, written)
    return written
