"""Tasks of one call on a Dask cluster, stopped together.

A call (a sweep's chunks, a comparison's parts) maps one function over its tasks' arguments
and gathers the results in order. Ctrl-C (or any exception) while they run cancels the
call's futures and sets a Dask ``Event`` of the call's own that every task asks for every
half second (:func:`stopped`): the running tasks stop at their next step (as on Ctrl-C in
process) and the workers are free for the next call.
"""

from __future__ import annotations

import time
import uuid
from typing import Any, Callable, List, Sequence

#: How often a task asks whether its call was stopped, s (a round trip to the scheduler).
STOP_POLL_S = 0.5


def stopped(name: str) -> Callable[[], bool]:
    """Whether the Dask ``Event`` ``name`` is set, asked at most every :data:`STOP_POLL_S`."""
    import distributed

    event = distributed.Event(name)
    last = [time.monotonic()]

    def ask() -> bool:
        now = time.monotonic()
        if now - last[0] < STOP_POLL_S:
            return False
        last[0] = now
        return event.is_set()

    return ask


def gather(client: Any, call: str, task: Callable[..., Any],
           *arguments: Sequence[Any]) -> List[Any]:
    """``task(*args, stop)`` for each tuple of ``arguments`` taken side by side, as Dask
    tasks of ``client``, their results in order. ``stop`` is the name of the call's Dask
    ``Event`` (``call``, e.g. ``"sweep"``, names it), set when the call is interrupted."""
    stop = f"friction-lab-{call}-{uuid.uuid4().hex}"
    count = len(arguments[0]) if arguments else 0
    futures = client.map(task, *arguments, [stop] * count, pure=False)
    try:
        return client.gather(futures)
    except BaseException:
        # Ctrl-C, or a task that raised: nothing left should run.
        import distributed

        distributed.Event(stop, client=client).set()
        client.cancel(futures, force=True)
        raise
