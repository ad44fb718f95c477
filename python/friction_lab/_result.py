"""The result of ``simulate``: numpy arrays, the events and the summary, as the command
line's ``trajectory.csv``, ``events.csv`` and ``summary.json`` hold them."""

from __future__ import annotations

from typing import Any, Dict, List, Optional

import numpy as np
import pandas as pd

from ._command import Made


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
        #: The fields of ``summary.json``: parameters, status, error, final state, energy.
        self.summary: Dict[str, Any] = made.json("summary.json")
        #: Solver statistics (steps, rejected, rhs_evals, jacobian_evals, ..., events).
        self.stats: Dict[str, Any] = self.summary["stats"]
        self._tidy = made.table("trajectory.csv")
        self.is_system = "body" in self._tidy.columns
        if self.is_system:
            names = list(dict.fromkeys(self._tidy["body"]))
            #: The bodies the arrays hold, in column order (systems only).
            self.bodies: Optional[List[str]] = names
            shape = (-1, len(names))
            self.t = self._tidy["t"].to_numpy()[:: len(names)]
        else:
            self.bodies = None
            shape = (-1,)
            self.t = self._tidy["t"].to_numpy()
        columns = {c: self._tidy[c].to_numpy().reshape(shape)
                   for c in ("x", "v", "friction", "mode", "z") if c in self._tidy}
        self.x: np.ndarray = columns["x"]
        self.v: np.ndarray = columns["v"]
        self.friction: np.ndarray = columns["friction"]
        self.mode: np.ndarray = columns["mode"]
        self.z: Optional[np.ndarray] = columns.get("z")
        #: Every mode switch: t, body, from, to.
        self.events: pd.DataFrame = (made.table("events.csv") if self.is_system
                                     else self._rig_events())

    def _rig_events(self) -> pd.DataFrame:
        """A rig's events of ``summary.json`` (t, kind) with the mode each one leaves."""
        rows, mode = [], (self.mode[0] if len(self.mode) else "")
        for e in self.summary["events"]:
            rows.append({"t": e["t"], "body": "body", "from": mode, "to": e["kind"]})
            if e["kind"] != "reversal":
                mode = e["kind"]
        return pd.DataFrame(rows, columns=["t", "body", "from", "to"])

    def to_pandas(self) -> pd.DataFrame:
        """The tidy trajectory, exactly as ``trajectory.csv`` holds it."""
        return self._tidy.copy()

    def __repr__(self) -> str:
        what = self.summary.get("scenario") or self.summary.get("system")
        return (f"<friction_lab.Result {what}: {len(self.t)} points, "
                f"{self.stats['steps']} steps, status {self.summary['status']}>")


class Study:
    """The files of a study (``converge``, ``independence``, ``work_precision``,
    ``stiffness``): ``tables`` maps each CSV's stem to a DataFrame, ``summary`` is the
    study's JSON, ``notes`` the lines the command line prints (orders, verdicts)."""

    def __init__(self, made: Made, stem: str):
        self.tables: Dict[str, pd.DataFrame] = {
            name[: -len(".csv")]: made.table(name) for name in made.files if name.endswith(".csv")
        }
        self.summary: Any = made.json(f"{stem}.json")
        self.notes: List[str] = made.notes
        #: The study's main table: one row per run.
        self.runs: pd.DataFrame = self.tables[stem]

    def __repr__(self) -> str:
        return f"<friction_lab.Study: {', '.join(self.tables)}>"
