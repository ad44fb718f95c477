"""``sweep``: one run per point of a grid, in Rust's threads or as Dask tasks.

On a Dask cluster the grid's points are cut into chunks of consecutive points; each task runs
the library's sweep of its points START <= i < END (the same Rust code, one thread), and the
chunks' tables are joined in grid order. Every point is computed by the same code from the
same inputs whatever the split, so the two ways give the same DataFrame, bit for bit.

Ctrl-C (or any exception) while the chunks run stops them (``_dask.gather``).
"""

from __future__ import annotations

import math
from typing import Any, Dict, Optional, Sequence, Tuple, Union

import pandas as pd

from ._command import Made, SolverError, _name, call, recorded, system_value, values
from ._dask import gather, stopped


@recorded
def sweep(scenario: Optional[str] = None, *, grid: Dict[str, Union[Sequence[float], str]],
          params: Optional[Dict[str, float]] = None, client: Any = None,
          chunk_size: Optional[int] = None, **options: Any) -> pd.DataFrame:
    """The settled state at every point of a grid: one row per point, in grid order (the
    first axis varying slowest), the columns of ``sweep.csv`` (docs/files.md).

    ``grid`` maps parameter names to lists of values, or to range strings as the command line
    takes them (``"0.01:0.1:10"``, ``"log:0.001:1:13"``). ``client``: ``None`` runs the points
    on Rust threads in this process (``threads=`` to choose how many); a
    ``dask.distributed.Client`` runs chunks of ``chunk_size`` points as Dask tasks (default:
    about four chunks per worker). Other options as ``simulate`` and ``friction-lab sweep``
    (``model``, ``solver``, ``switching``, ``t_end``, ``settle``, ...). Points whose run
    failed or diverged raise :class:`SolverError` with the whole table as ``result``
    (``status`` and ``reason`` say which and why; their measures are empty).
    ``frame.attrs["provenance"]`` says where the table comes from (``provenance.json``).
    """
    _name("sweep", scenario)
    system = options.pop("system", None)
    given = values("sweep", params=params, grid=grid, **options)
    axes = given.pop("grid")
    arguments = (scenario, system_value(system), axes, given)
    if client is None:
        made = call("sweep", *arguments)
        frame = made.table("sweep.csv")
        failure = made.failure
        provenance = made.provenance
    else:
        frame, provenance = _on_dask(client, arguments, chunk_size)
        failed = int(frame["status"].isin(["diverged", "failed"]).sum())
        failure = (f"{failed} of {len(frame)} runs failed or diverged; sweep.csv says which "
                   "and why"
                   if failed else None)
    frame.attrs["provenance"] = provenance
    if failure is not None:
        raise SolverError(failure, frame)
    return frame


def _chunk(arguments: Tuple[Any, ...], start: int, end: int, stop: str) -> pd.DataFrame:
    """One Dask task: the points START <= i < END of the sweep ``arguments`` (those of
    ``_native.sweep``), as ``sweep.csv``'s rows. A friction law written in Python, the
    ``model`` of the options, is registered in the worker's process by the binding. The run
    stops at its next step once the sweep's Event ``stop`` is set. The stop reaches every run
    of the worker's process, as Ctrl-C would (docs/python.md)."""
    scenario, system, axes, given = arguments
    part = dict(given, point_range=(start, end))
    made: Made = call("sweep", scenario, system, axes, part, stop=stopped(stop))
    return made.table("sweep.csv")


def _on_dask(client: Any, arguments: Tuple[Any, ...],
             chunk_size: Optional[int]) -> Tuple[pd.DataFrame, Dict[str, Any]]:
    """The sweep ``arguments`` as Dask tasks of ``chunk_size`` points: its rows, and the
    provenance of the check made in this process before any task is sent."""
    scenario, system, axes, given = arguments
    # Every point is checked here, before any task is sent (bad input raises ValueError).
    head = call("sweep", scenario, system, axes, dict(given, point_range=(0, 0)))
    n = head.json("sweep.json")["grid_points"]
    if chunk_size is None:
        workers = max(1, len(client.scheduler_info().get("workers", {})))
        chunk_size = max(1, math.ceil(n / (4 * workers)))
    if not (isinstance(chunk_size, int) and chunk_size >= 1):
        raise ValueError(f"option `chunk_size` = {chunk_size!r} is out of range: allowed [1, inf)")
    # One Rust thread per task unless told otherwise: Dask's workers are the parallelism.
    given = dict(given, threads=given.get("threads", 1))
    bounds = [(s, min(s + chunk_size, n)) for s in range(0, n, chunk_size)]
    results = gather(client, "sweep", _chunk, [(scenario, system, axes, given)] * len(bounds),
                     [b[0] for b in bounds], [b[1] for b in bounds])
    if not results:
        return head.table("sweep.csv"), head.provenance
    return pd.concat(results, ignore_index=True), head.provenance
