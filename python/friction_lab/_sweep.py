"""``sweep``: one run per point of a grid, in Rust's threads or as Dask tasks.

On a Dask cluster the grid's points are cut into chunks of consecutive points; each task runs
``friction-lab sweep ... --point-range START:END`` (the same Rust code, one thread), and the
chunks' tables are joined in grid order. Every point is computed by the same code from the
same inputs whatever the split, so the two ways give the same DataFrame, bit for bit.
"""

from __future__ import annotations

import math
import os
from typing import Any, Dict, List, Optional, Sequence, Union

import pandas as pd

from . import _native
from ._command import Made, SolverError, run, table, words


def sweep(scenario: str, *, grid: Dict[str, Union[Sequence[float], str]],
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
    failed raise :class:`SolverError` with the whole table as ``result`` (``status`` says
    which and why).
    """
    argv = words("sweep", scenario, params=params, grid=grid, **options)
    if client is None:
        made = run(argv)
        frame = made.table("sweep.csv")
        failure = made.failure
    else:
        model = options.get("model")
        laws = [] if model is None or isinstance(model, (str, os.PathLike)) else [model]
        frame = _on_dask(client, argv, chunk_size, laws)
        failed = int((frame["status"] != "ok").sum())
        failure = f"{failed} of {len(frame)} runs failed; sweep.csv says which and why" if failed else None
    if failure is not None:
        raise SolverError(failure, frame)
    return frame


def _chunk(argv: List[str], start: int, end: int, laws: List[Any]) -> bytes:
    """One Dask task: the points START <= i < END of the sweep, as ``sweep.csv`` bytes; a
    friction law written in Python (``laws``) is registered in the worker's process first."""
    for law in laws:
        _native.register_law(law)
    made: Made = run(argv + ["--point-range", f"{start}:{end}"])
    return made.files["sweep.csv"]


def _on_dask(client: Any, argv: List[str], chunk_size: Optional[int],
             laws: List[Any]) -> pd.DataFrame:
    # Every point is checked here, before any task is sent (bad input raises ValueError).
    head = run(argv + ["--point-range", "0:0"])
    n = head.json("sweep.json")["grid_points"]
    if chunk_size is None:
        workers = max(1, len(client.scheduler_info().get("workers", {})))
        chunk_size = max(1, math.ceil(n / (4 * workers)))
    if not (isinstance(chunk_size, int) and chunk_size >= 1):
        raise ValueError(f"option `chunk_size` = {chunk_size!r} is out of range: allowed [1, inf)")
    if "--threads" not in argv:
        # One Rust thread per task: Dask's workers are the parallelism.
        argv = argv + ["--threads", "1"]
    bounds = [(s, min(s + chunk_size, n)) for s in range(0, n, chunk_size)]
    futures = client.map(_chunk, [argv] * len(bounds), [b[0] for b in bounds],
                         [b[1] for b in bounds], [laws] * len(bounds), pure=False)
    parts = [table(data) for data in client.gather(futures)]
    if not parts:
        return head.table("sweep.csv")
    return pd.concat(parts, ignore_index=True)
