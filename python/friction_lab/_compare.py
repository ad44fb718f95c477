"""``compare``: every scheme at v = 0 against the true nonsmooth solution, in process or as
Dask tasks.

On a Dask cluster the comparison is cut into its independent parts (the cross-check by
another family; each scheme without a width ε; each width ε with the regularised schemes at
it, which share its tight solution): each task computes the true solution and makes one
part's runs (the same Rust code, one thread); the parts travel back encoded and the library
merges them into the comparison made in one piece, its costs, crossovers and regularisation
fit computed once from all runs. Every run is made by the same code from the same inputs
whatever the split, so the two ways give the same tables, bit for bit (the wall times
apart). The true solution is computed by every task and once more for the merge.
"""

from __future__ import annotations

from typing import Any, Dict, Optional, Tuple

from . import _native
from ._command import SolverError, _made, _name, call, current_call, recorded, system_value, values
from ._dask import gather, stopped
from ._result import Study


@recorded
def compare(scenario: Optional[str] = None, *, params: Optional[Dict[str, float]] = None,
            client: Any = None, **options: Any) -> Study:
    """Every scheme at v = 0 (events, regularised over ε, naive, time-stepping) against the
    true nonsmooth solution, with each scheme's cost at target errors (``friction-lab
    compare --help``): ``study.runs`` holds the runs (``scheme``, ``epsilon``, errors against
    the true solution, ``discretisation_error``), ``study.tables["compare-cost"]`` each
    scheme's cost at each target, ``study.tables["compare-epsilon"]`` the model error against
    ε. ``client``: ``None`` runs in this process on Rust threads (``threads=``); a
    ``dask.distributed.Client`` runs the comparison's parts as Dask tasks, one Rust thread
    each, and gives the same tables."""
    _name("compare", scenario)
    system = system_value(options.pop("system", None))
    given = values("compare", params=params, **options)
    if client is None:
        made = call("compare", scenario, system, given)
    else:
        # Every option is checked here, before any task is sent (bad input: ValueError).
        count = _native.compare_parts(scenario, system, given)
        task = (scenario, system, dict(given, threads=given.get("threads", 1)))
        parts = gather(client, "compare", _part, [task] * count, list(range(count)))
        made_by = current_call()
        made = _made("compare", lambda: _native.compare_merge(scenario, system, given, parts,
                                                             None, call=made_by))
    study = Study(made, "compare", None)
    if made.failure is not None:
        raise SolverError(made.failure, study)
    return study


def _part(arguments: Tuple[Any, ...], index: int, stop: str) -> bytes:
    """One Dask task: part ``index`` of the comparison ``arguments`` (those of
    ``_native.compare_part``), encoded. It stops at its next step once the comparison's Event
    ``stop`` is set."""
    scenario, system, given = arguments
    try:
        return _native.compare_part(scenario, system, given, index, stopped(stop))
    except _native.SolverError as e:
        raise SolverError(str(e)) from None
