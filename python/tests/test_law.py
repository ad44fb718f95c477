"""Friction laws written in Python run as the catalog's laws do (docs/python.md)."""

import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import friction_lab as fl


# The laws of the example that measures their cost (python/examples/law_cost.py): Coulomb's
# F = F_c·s and Dahl's F = z, ż = σ·(v − v·s·z/F_c), as the catalog writes them.
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))
from law_cost import Coulomb, Dahl  # noqa: E402


def test_a_python_coulomb_law_runs_the_belt_as_the_catalogs_to_the_bit():
    # Event switching with Dormand–Prince: s is ±1 in a slip mode, the stick test reads the
    # interval, and no partial derivative is used, so every number is the catalog's.
    mine = fl.simulate("belt", model=Coulomb(6.0), t_end=10.0)
    builtin = fl.simulate("belt", model="coulomb", params={"F_c": 6.0}, t_end=10.0)
    assert mine.summary["model"] == "py-coulomb" and mine.summary["variant"] is None
    assert len(mine.events) == len(builtin.events) >= 2
    for column in ("t", "x", "v", "friction"):
        assert np.array_equal(getattr(mine, column), getattr(builtin, column)), column
    assert (mine.mode == builtin.mode).all()
    assert mine.stats == builtin.stats


def test_a_python_law_with_a_state_follows_the_catalogs_dahl():
    # The paper's prescribed motion drives the state: F = z through the hysteresis loop.
    # Dormand–Prince, bit for bit: the default `auto` switches to Radau IIA at t = 3.27 s,
    # whose Jacobian is forward differences for a Python law and analytic for the catalog's.
    params = {"F_c": 6.0, "sigma": 5.0}
    mine = fl.simulate("prescribed-motion", model=Dahl(5.0, 6.0), t_end=4.0, solver="dopri5")
    builtin = fl.simulate("prescribed-motion", model="dahl", params=params, t_end=4.0,
                          solver="dopri5")
    assert mine.z is not None
    assert np.array_equal(mine.friction, builtin.friction)
    assert np.array_equal(mine.z, builtin.z)
    assert mine.summary["loop_area"] == builtin.summary["loop_area"]


def test_an_implicit_solver_takes_finite_difference_partials_of_a_python_law():
    # Regularised Coulomb under BDF: the Jacobian of the Python law is forward differences,
    # the catalog's is analytic; the trajectories agree to the solver's tolerance.
    options = dict(solver="bdf", switching="regularized", t_end=5.0, rtol=1e-8, atol=1e-10,
                   params={"epsilon": 1e-3})
    mine = fl.simulate("belt", model=Coulomb(6.0), **options)
    builtin = fl.simulate("belt", model="coulomb", **{**options,
                                                      "params": {"epsilon": 1e-3, "F_c": 6.0}})
    assert mine.stats["jacobian_evals"] > 0
    scale = np.abs(builtin.x).max()
    assert np.abs(mine.x - builtin.x).max() < 1e-5 * scale


def test_analytic_partials_replace_the_differences():
    class Differenced(Coulomb):
        name = "py-viscous-differenced"

        def force(self, x, v, s, z):
            return self.f_c * s + 0.5 * v

    class Analytic(Differenced):
        name = "py-viscous"
        calls = 0

        def partials(self, x, v, s, z):
            Analytic.calls += 1
            return (0.0, 0.5, self.f_c)

    options = dict(solver="implicit-euler", switching="regularized", t_end=2.0,
                   params={"epsilon": 1e-2})
    analytic = fl.simulate("belt", model=Analytic(6.0), **options)
    # Once for each Jacobian the solver takes, and once at each recorded point where simulate
    # measures the stiffness (the spectral radius of the Jacobian there).
    measured = analytic.summary["stiffness"]["points"]
    assert analytic.stats["jacobian_evals"] > 0 and measured > 0
    assert Analytic.calls == analytic.stats["jacobian_evals"] + measured
    differenced = fl.simulate("belt", model=Differenced(6.0), **options)
    assert np.abs(analytic.x - differenced.x).max() < 1e-9


def test_a_python_law_runs_in_a_chain():
    # Without the spread of force levels along the chain, which scales the catalog's laws
    # only (said as a warning): every block breaks away when the driver's pull reaches F_c.
    with pytest.warns(RuntimeWarning, match="law `py-coulomb` is your own"):
        fl.simulate("chain", model=Coulomb(5.0), params={"n_bodies": 3}, t_end=1.0)
    params = {"n_bodies": 3, "spread": 0.0}
    mine = fl.simulate("chain", model=Coulomb(5.0), params=params, t_end=8.0)
    builtin = fl.simulate("chain", model="coulomb", params={**params, "F_c": 5.0}, t_end=8.0)
    assert np.array_equal(mine.x, builtin.x) and len(mine.t) == 2001
    assert mine.events.equals(builtin.events) and len(mine.events) >= 3


def test_an_exception_in_a_law_stops_the_run_and_is_raised():
    class Broken(Coulomb):
        name = "py-broken"

        def force(self, x, v, s, z):
            if x > 1e-3:
                raise ZeroDivisionError("the law's own error")
            return self.f_c * s

    with pytest.raises(ZeroDivisionError, match="the law's own error"):
        fl.simulate("paper-block", model=Broken(6.0), t_end=2.0)
    # The next run is not stopped by the one before.
    assert fl.simulate("paper-block", model=Coulomb(6.0), t_end=2.0).summary["status"] == "ok"


def test_a_nan_from_stick_is_an_error_not_never_sticks():
    class NanStick(Coulomb):
        name = "py-nan-stick"

        def stick(self, x, z):
            return float("nan")

    with pytest.raises(ValueError, match=r"law `py-nan-stick`: `stick` returned \(NaN, NaN\) "
                                         r"at x = .*: a bound is NaN"):
        fl.simulate("belt", model=NanStick(6.0), t_end=2.0)


def test_ctrl_c_stops_a_law_that_never_returns():
    import os
    import signal
    import threading
    import time

    class Stuck(Coulomb):
        name = "py-stuck"

        def force(self, x, v, s, z):
            # Loops 20 s at its first call (a bound, so that a failure fails the test
            # instead of hanging it); Ctrl-C must stop it within its call.
            if not getattr(self, "looped", False):
                self.looped = True
                deadline = time.monotonic() + 20.0
                while time.monotonic() < deadline:
                    pass
            return self.f_c * s

    threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        fl.simulate("belt", model=Stuck(6.0), t_end=2.0)
    assert time.monotonic() - start < 3.0
    # Nothing is left pending: the next run is not stopped.
    assert fl.simulate("belt", model=Coulomb(6.0), t_end=2.0).summary["status"] == "ok"


def test_a_second_ctrl_c_abandons_a_run_whose_law_is_blocked():
    import os
    import signal
    import threading
    import time

    class Sleeping(Coulomb):
        name = "py-sleeping"

        def force(self, x, v, s, z):
            # Blocked 3 s in a call into C at its first call: the first Ctrl-C cannot stop
            # it before the call returns; the second abandons the run.
            if not getattr(self, "slept", False):
                self.slept = True
                time.sleep(3.0)
            return self.f_c * s

    for delay in (0.3, 0.6):
        threading.Timer(delay, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        fl.simulate("belt", model=Sleeping(6.0), t_end=2.0)
    assert time.monotonic() - start < 1.5
    # While the abandoned run's law sleeps, a new run would be stopped by its request: refused.
    with pytest.raises(RuntimeError, match="abandoned by a second Ctrl-C is still finishing"):
        fl.simulate("belt", model=Coulomb(6.0), t_end=2.0)
    # Once the law returns, the abandoned run ends and lowers its request.
    time.sleep(3.5)
    assert fl.simulate("belt", model=Coulomb(6.0), t_end=2.0).summary["status"] == "ok"


def test_a_law_without_its_methods_or_with_a_catalog_name_is_refused():
    class NoStick:
        name = "py-no-stick"

        def force(self, x, v, s, z):
            return 0.0

    with pytest.raises(TypeError, match=r"law `py-no-stick` has no method `stick\(x, z\)`"):
        fl.simulate("belt", model=NoStick())

    class Stateful(Coulomb):
        name = "py-stateful"
        n_states = 1

    with pytest.raises(TypeError, match=r"has no method `rates\(x, v, s, z\)`"):
        fl.simulate("belt", model=Stateful(6.0))

    class TooMany(Dahl):
        n_states = 17

    with pytest.raises(ValueError, match=r"`n_states` = 17 is out of range: allowed \[0, 16\]"):
        fl.simulate("belt", model=TooMany(5.0, 6.0))

    class Named(Coulomb):
        name = "coulomb"

    with pytest.raises(ValueError, match="the catalog has a model of that name"):
        fl.simulate("belt", model=Named(6.0))

    # Without a `name`, the class's name is the law's, and a class named as a model of the
    # catalog is told to take a name of its own.
    class CS:
        def force(self, x, v, s, z):
            return 6.0 * s

        def stick(self, x, z):
            return 6.0

    with pytest.raises(ValueError, match="law class `CS` has no `name`.*model `CS`"):
        fl.simulate("belt", model=CS())


def test_a_study_runs_a_python_law_as_the_catalogs():
    # The runs of a convergence study on the pool's threads: the same numbers as the
    # catalog's Coulomb (the description names the law).
    options = dict(solvers=["rk4", "dopri5"], t_end=3.0, threads=2)
    mine = fl.converge("belt", model=Coulomb(6.0), **options)
    builtin = fl.converge("belt", model="coulomb", params={"F_c": 6.0}, **options)
    assert mine.summary["case"]["description"] == "belt with py-coulomb (event switching)"
    assert mine.runs.drop(columns="wall_time_s", errors="ignore").equals(
        builtin.runs.drop(columns="wall_time_s", errors="ignore"))
    assert len(mine.runs) >= 8


def test_table_2_judges_a_python_law_as_the_catalogs():
    # Every protocol run on the Python Coulomb law gives the catalog's Coulomb's verdicts and
    # evidence (at the paper's parameters, which both are judged at); a law of one's own has
    # no claim of the paper to stand beside.
    t = fl.phenomena(["coulomb", Coulomb(6.0)], threads=2)
    assert list(t.json) == ["provenance", "models"]
    assert list(t.json["models"]) == ["coulomb", "py-coulomb"]
    models = t.json["models"]
    assert models["py-coulomb"] == models["coulomb"]
    # One cell a phenomenon; the simulation cost is a frame of its own.
    assert len(t.cells) == 2 * (len(models["coulomb"]) - 1) >= 16
    assert t.cells["paper"].isna().all() and t.cells["failed"].isna().all()
    assert "| phenomenon | coulomb | py-coulomb |" in t.markdown
    assert "(its own)" in t.markdown
    # The simulation cost: each law on the belt and the two masses, Coulomb's own work
    # over Coulomb's is 1, and the Python law costs what the catalog's does in counted work.
    assert list(t.cost["system"]) == ["belt", "two_mass"] * 2
    assert (t.cost[t.cost["law"] == "coulomb"]["relative_work"] == 1.0).all()
    assert list(t.cost["work"][:2]) == list(t.cost["work"][2:])
    assert set(t.timing["system"]) == {"belt", "two_mass"}


def test_a_sweep_of_a_python_law_in_process_and_on_dask_is_the_catalogs():
    # On Dask the law travels with each task (pickled) and is registered in the worker's
    # process before its points run.
    distributed = pytest.importorskip("distributed")
    grid = {"v_belt": [0.05, 0.1], "k": [10, 100]}
    builtin = fl.sweep("belt", model="coulomb", params={"F_c": 6.0}, grid=grid, t_end=20.0)
    local = fl.sweep("belt", model=Coulomb(6.0), grid=grid, t_end=20.0)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        on_dask = fl.sweep("belt", model=Coulomb(6.0), grid=grid, t_end=20.0, client=client,
                           chunk_size=1)
    pd.testing.assert_frame_equal(local, builtin, check_exact=True)
    pd.testing.assert_frame_equal(on_dask, local, check_exact=True)
    assert (local["status"] == "ok").all() and len(local) == 4
