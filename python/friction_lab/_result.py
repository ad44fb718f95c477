"""The result of ``simulate``: numpy arrays, the events and the summary, as the command
line's ``trajectory.csv``, ``events.csv`` and ``summary.json`` hold them; all are made from
the run's record as the library hands it over (its values), not from a file."""

from __future__ import annotations

import io
from typing import Any, Dict, List, Optional

import numpy as np
import pandas as pd

from ._command import Made, frame


class Result:
    """One run of a rig or a system.

    For a rig, ``t``, ``x``, ``v``, ``friction`` and ``mode`` (and ``z``, the internal state of
    a model that has one) are 1-D arrays over the output times. For a system they are 2-D,
    time × body, over the bodies written (``bodies``: the ``bodies`` option, or the command
    line's default: every body up to 20, else 20 evenly spaced), and ``t`` is 1-D.
    ``friction`` is the force the contact exerts on the body along +x (docs/files.md).
    """

    def __init__(self, made: Made):
        self._made = made
        run = made.run
        #: The fields of ``summary.json`` (docs/files.md): parameters, status, error, time
        #: reached, event counts, energy.
        self.summary: Dict[str, Any] = run["summary"]
        #: Solver statistics (steps, rejected, rhs_evals, jacobian_evals, ..., events).
        self.stats: Dict[str, Any] = self.summary["stats"]
        #: Where the run comes from (the summary's ``provenance``): version, commit, date,
        #: machine, threads and the call that made it.
        self.provenance: Dict[str, Any] = made.provenance
        # The library's numbers, as bytes of doubles: no text between (docs/python.md).
        c = run["trajectory"]
        doubles = lambda name: np.frombuffer(c[name], dtype="<f8")  # noqa: E731
        #: The bodies the arrays hold, in column order (systems only).
        self.bodies: Optional[List[str]] = c["bodies"]
        self.is_system = self.bodies is not None
        shape = (-1, len(self.bodies)) if self.is_system else (-1,)
        self.t: np.ndarray = doubles("t")
        self.x: np.ndarray = doubles("x").reshape(shape)
        self.v: np.ndarray = doubles("v").reshape(shape)
        self.friction: np.ndarray = doubles("friction").reshape(shape)
        names = np.array(c["mode_names"], dtype=object)
        self.mode: np.ndarray = names[np.frombuffer(c["mode"], dtype=np.uint8)].reshape(shape)
        self.z: Optional[np.ndarray] = None if c["z"] is None else doubles("z").reshape(shape)
        #: Every switch of a contact: t, body, from, to (a rig's one body is ``body``).
        self.events: pd.DataFrame = frame(run["events"][1])
        #: Every body's state at the last recorded point: body, x, v, friction, mode[, z].
        self.final: pd.DataFrame = frame(run["final"][1])

    def to_pandas(self) -> pd.DataFrame:
        """The tidy trajectory: the rows and columns of ``trajectory.csv`` (``t``, for a system
        ``body``, then ``x``, ``v``, ``friction``, ``mode`` and, where a model has one, ``z``:
        NaN for a body whose model has none)."""
        rows = {"t": self.t}
        if self.is_system:
            rows = {"t": np.repeat(self.t, len(self.bodies)),
                    "body": np.tile(np.array(self.bodies, dtype=object), len(self.t))}
        for name in ("x", "v", "friction", "mode", "z"):
            column = getattr(self, name)
            if column is not None:
                rows[name] = column.reshape(-1)
        return pd.DataFrame(rows)

    def __repr__(self) -> str:
        what = self.summary["system"]
        return (f"<friction_lab.Result {what}: {len(self.t)} points, "
                f"{self.stats['steps']} steps, status {self.summary['status']}>")


class Study:
    """The files of a study (``converge``, ``independence``, ``work_precision``,
    ``stiffness``, ``compare``, ``orbit``, ``continue``, ``closed-loop``): ``tables`` maps each CSV's stem to a DataFrame, ``summary`` is the
    study's JSON, ``notes`` the lines the command line prints (orders, verdicts)."""

    def __init__(self, made: Made, stem: str, main: Optional[str] = None):
        self.tables: Dict[str, pd.DataFrame] = {
            name[: -len(".csv")]: made.table(name) for name in made.files if name.endswith(".csv")
        }
        self.summary: Any = made.json(f"{stem}.json")
        self.notes: List[str] = made.notes
        #: Where the study comes from: version, commit, date, machine, threads and the call.
        self.provenance: Dict[str, Any] = made.provenance
        #: The study's main table: one row per run (``continue``: one per point of a branch).
        self.runs: pd.DataFrame = self.tables[main or stem]

    def __repr__(self) -> str:
        return f"<friction_lab.Study: {', '.join(self.tables)}>"


def _cheapest(entry: Dict[str, Any]) -> Dict[str, Any]:
    """One law's simulation cost on one system as a row of ``Table2.cost``."""
    run = entry["cheapest"] or {}
    return {"solver": run.get("solver"), "tolerance": run.get("tolerance"),
            "error": run.get("error"), "work": run.get("work"),
            "relative_work": entry["relative_work"], "failed": entry["failed"]}


class Table2:
    """Table 2 decided by simulation (``phenomena``): ``cells`` has one row per law and
    phenomenon (``law``, ``phenomenon``, ``measured``: True, False, or None where its protocol
    run failed, ``paper``: the paper's claim or None, ``failed``: why); ``cost`` one row per law
    and stick–slip system (``law``, ``system``, the cheapest adequate run's ``solver``,
    ``tolerance``, grid ``error`` and ``work``, ``relative_work``: over Coulomb's, ``failed``:
    why no solver reached the target); ``timing`` the wall times of those runs
    (``table2-timing.csv``); ``json`` is ``table2.json`` (its ``provenance``, and under
    ``models`` each cell's evidence and its verdict over a grid of rig parameters, and each
    law's ``simulation_cost``) and ``markdown`` the text of ``table2.md``."""

    def __init__(self, made: Made):
        self.json: Dict[str, Any] = made.json("table2.json")
        self.markdown: str = made.text("table2.md")
        #: Where the table comes from: version, commit, date, machine, threads and the call.
        self.provenance: Dict[str, Any] = made.provenance
        rows = [{"law": law, "phenomenon": phenomenon, "measured": cell["measured"],
                 "paper": cell["paper"], "failed": cell["failed"]}
                for law, cells in self.json["models"].items()
                for phenomenon, cell in cells.items() if phenomenon != "simulation_cost"]
        self.cells: pd.DataFrame = pd.DataFrame(
            rows, columns=["law", "phenomenon", "measured", "paper", "failed"])
        cost = [{"law": law, "system": system, **_cheapest(entry)}
                for law, cells in self.json["models"].items()
                for system, entry in cells["simulation_cost"].items()]
        self.cost: pd.DataFrame = pd.DataFrame(
            cost, columns=["law", "system", "solver", "tolerance", "error", "work",
                           "relative_work", "failed"])
        self.timing: pd.DataFrame = pd.read_csv(io.StringIO(made.text("table2-timing.csv")))

    def __repr__(self) -> str:
        return f"<friction_lab.Table2: {', '.join(self.json['models'])}>"
