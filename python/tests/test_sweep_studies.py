"""sweep() in process and on Dask, the studies, the GIL and Ctrl-C."""

import json
import os
import signal
import threading
import time

import numpy as np
import pandas as pd
import pytest

import friction_lab as fl
from csvfiles import read

GRID = {"v_belt": [0.01, 0.02, 0.05, 0.1], "k": [10, 100, 1000]}




def test_an_in_process_sweep_equals_the_command_lines(cli, tmp_path):
    df = fl.sweep("belt", model="CVS", grid=GRID)
    done = cli("sweep", "belt", "--model", "CVS", "--grid", "v_belt=0.01,0.02,0.05,0.1",
               "--grid", "k=10,100,1000", "--out", tmp_path / "s")
    assert done.returncode == 0, done.stderr
    pd.testing.assert_frame_equal(df, read(tmp_path / "s" / "sweep.csv"), check_exact=True)
    assert len(df) == 12 and list(df.columns[:2]) == ["v_belt", "k"]
    # The grid's order: the first axis varies slowest.
    assert df["v_belt"].tolist() == [v for v in GRID["v_belt"] for _ in GRID["k"]]
    # Stick-slip at k = 100 below the Stribeck velocity: the closed-form period of the belt
    # test (docs/sweep.md) is near one second at v_belt = 0.05.
    row = df[(df.v_belt == 0.05) & (df.k == 100)].iloc[0]
    assert row.stick_phases > 0 and 0.9 < row.period < 1.3
    assert (df["status"] == "ok").all()


def test_a_sweep_on_a_two_worker_local_cluster_equals_the_in_process_one():
    distributed = pytest.importorskip("distributed")
    local = fl.sweep("belt", model="CVS", grid=GRID, threads=1)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        on_dask = fl.sweep("belt", model="CVS", grid=GRID, client=client, chunk_size=5)
        # Bad input is refused before any task is sent.
        with pytest.raises(ValueError, match="v_belt"):
            fl.sweep("belt", model="CVS", grid={"v_belt": [0.1, -1.0e300 * 1e10]}, client=client)
    pd.testing.assert_frame_equal(on_dask, local, check_exact=True)


def test_sweep_checks_its_grid():
    with pytest.raises(ValueError, match="option `grid`"):
        fl.sweep("belt", model="CVS", grid={"v_belt": "1:2"})
    # Named as the keyword argument it was given by.
    with pytest.raises(ValueError, match="option `point_range` = `0:5` is out of range"):
        fl.sweep("belt", model="CVS", grid={"v_belt": [0.1]}, point_range="0:5")


def test_a_convergence_study_measures_rk4s_fourth_order():
    s = fl.converge("free-vibration", model="viscous", solvers=["rk4", "bdf"],
                    dt_list=[0.02, 0.01, 0.005, 0.0025], tol_list=[1e-4, 1e-6], t_end=2.0)
    assert "converge" in s.tables and len(s.runs) == 6
    # A step size in `h`, a tolerance in `tol`: one quantity per column.
    rk4, bdf = s.runs[s.runs.solver == "rk4"], s.runs[s.runs.solver == "bdf"]
    assert rk4["h"].tolist() == [0.02, 0.01, 0.005, 0.0025] and rk4["tol"].isna().all()
    assert bdf["tol"].tolist() == [1e-4, 1e-6] and bdf["h"].isna().all()
    assert set(s.runs["step"]) == {"fixed", "adaptive"}
    orders = [o for o in s.summary["orders"] if o["solver"] == "rk4"]
    assert orders and all(abs(o["order"] - 4.0) < 0.3 for o in orders), orders
    assert all(o["order_ci"][0] <= 4.0 <= o["order_ci"][1] for o in orders), orders
    # BDF's runs are over tolerances: tolerance proportionality, never called an order.
    bdf = [o for o in s.summary["orders"] if o["solver"] == "bdf"]
    assert bdf and all("order" not in o and "tolerance_exponent" in o for o in bdf), bdf
    assert any(n.startswith("rk4") and " order 4." in n for n in s.notes), s.notes


def test_a_studys_tables_and_document_are_the_command_lines_files(cli, tmp_path):
    # Crossed as the library's values (typed columns, a JSON document), not as text: the
    # same numbers and the same column types as the files read back.
    options = dict(model="viscous", solvers=["rk4", "bdf"], dt_list=[0.02, 0.01],
                   tol_list=[1e-4], t_end=1.0)
    s = fl.converge("free-vibration", **options)
    done = cli("converge", "free-vibration", "--model", "viscous", "--solvers", "rk4,bdf",
               "--dt-list", "0.02,0.01", "--tol-list", "1e-4", "--t-end", "1",
               "--out", tmp_path / "c")
    assert done.returncode == 0, done.stderr
    pd.testing.assert_frame_equal(s.runs, read(tmp_path / "c" / "converge.csv"),
                                  check_exact=True)
    assert s.runs["steps"].dtype == np.int64 and s.runs["tol"].dtype == np.float64
    written = json.loads((tmp_path / "c" / "converge.json").read_text())
    for document in (written, s.summary):
        document.pop("provenance")
    assert s.summary == written


def test_a_stiffness_study_of_the_chain_sweeps_its_coupling():
    # Each value builds the chain again: Dormand-Prince pays for the stiff coupling, BDF not.
    s = fl.stiffness("chain", model="CS", parameter="k_chain", values=np.array([100, 1e6]),
                     solvers=["dopri5", "bdf"])
    cost = s.runs.set_index(["value", "solver"])["rhs_evals"]
    assert cost[(1e6, "dopri5")] > 10 * cost[(100.0, "dopri5")]
    assert cost[(1e6, "bdf")] < 2 * cost[(100.0, "bdf")]
    assert s.summary["crossover"] == 1e6
    with pytest.raises(ValueError, match="parameter `sigma` is not read by model `CS`"):
        fl.stiffness("chain", model="CS", parameter="sigma", values=[1, 2])


#: A comparison small enough for a test: two event-driven solvers, BDF regularised at four
#: widths, Moreau–Jean.
SMALL_COMPARISON = dict(model="CS", event_solvers=["dopri5", "radau5"],
                        regularized_solvers=["bdf"], epsilons=[1e-2, 1e-3, 1e-4, 1e-5],
                        no_naive=True, tol_list=[1e-3, 1e-4, 1e-5], ts_dt_list=[0.01, 0.005],
                        targets=[1e-2, 1e-3], repeats=1, max_steps=200000)


def test_compare_scores_every_scheme_against_the_true_solution():
    study = fl.compare("belt", **SMALL_COMPARISON)
    runs = study.runs
    assert set(runs["scheme"]) == {"dopri5 (event)", "radau5 (event)", "bdf (regularized)",
                                   "moreau-jean (timestepping)"}
    # Only a regularised run has an ε and a discretisation error.
    regularised = runs["scheme"] == "bdf (regularized)"
    assert runs.loc[regularised, "epsilon"].notna().all()
    assert runs.loc[~regularised, "discretisation_error"].isna().all()
    cost = study.tables["compare-cost"]
    assert list(cost["target"].unique()) == [1e-2, 1e-3]
    cheapest = cost[cost["cheapest"] == "yes"]
    assert list(cheapest["scheme"]) == ["dopri5 (event)", "dopri5 (event)"]
    # A scheme that missed a target says why.
    assert cost.loc[cost["reached"] == "false", "reason"].str.len().gt(0).all()
    assert study.summary["regularisation"]["falls"] is True
    with pytest.raises(ValueError, match=r"option `switching` does not apply to compare"):
        fl.compare("belt", model="CS", switching="regularized")


def test_a_comparison_on_a_two_worker_local_cluster_equals_the_in_process_one():
    distributed = pytest.importorskip("distributed")
    local = fl.compare("belt", threads=1, **SMALL_COMPARISON)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        on_dask = fl.compare("belt", client=client, **SMALL_COMPARISON)
        # Bad input is refused before any task is sent.
        with pytest.raises(ValueError, match="epsilons"):
            fl.compare("belt", client=client, **dict(SMALL_COMPARISON, epsilons=[-1.0]))
    assert set(on_dask.tables) == set(local.tables)
    # Every table but the two of wall times, bit for bit.
    for name in set(local.tables) - {"compare-timing", "compare-cost-timing"}:
        pd.testing.assert_frame_equal(on_dask.tables[name], local.tables[name],
                                      check_exact=True)
    for study in (local, on_dask):
        study.summary.pop("provenance")
    assert on_dask.summary == local.summary and on_dask.notes == local.notes


def test_an_independence_study_with_a_failed_level_raises_and_keeps_the_others():
    # RK4 at h = 0.5 on the belt is past its stability bound (h*omega = 5): level 0 fails,
    # levels 1 to 3 finish and are judged.
    with pytest.raises(fl.SolverError, match="levels 1 to 3 are judged") as e:
        fl.independence("belt", model="CS", solver="rk4", start=0.5, levels=4, t_end=200.0)
    study = e.value.result
    assert study.summary["first_level"] == 1 and study.summary["failed"][0]["level"] == 0
    assert not study.summary["independent"]


def test_a_long_run_releases_the_gil():
    counted = []

    def work():
        with pytest.raises(fl.SolverError, match="time limit"):
            fl.simulate("chain", model="coulomb", params={"n_bodies": 2000}, t_end=1000.0,
                        scheme="time-stepping", points=101, time_limit=1.0)

    worker = threading.Thread(target=work)
    worker.start()
    n = 0
    while worker.is_alive():
        n += 1
    worker.join()
    counted.append(n)
    # Python ran beside the solver: a held GIL would have allowed a few switches at most.
    assert counted[0] > 100_000, counted


def test_ctrl_c_stops_a_long_run_and_the_next_run_works():
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        # About a minute of work if nothing stopped it.
        fl.simulate("chain", model="coulomb", params={"n_bodies": 2000}, t_end=1000.0,
                    scheme="time-stepping", points=101)
    assert time.monotonic() - start < 5.0
    r = fl.simulate("belt", model="CVS", t_end=1.0)
    assert r.summary["status"] == "ok" and np.isclose(r.t[-1], 1.0)


@pytest.mark.parametrize("processes", [True, False], ids=["processes", "threads"])
def test_ctrl_c_stops_a_sweep_on_dask_and_the_next_call_starts_at_once(processes):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=processes,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        # The workers have the package loaded before the clock starts.
        fl.sweep("belt", model="CVS", grid={"v_belt": [0.1, 0.2]}, client=client, chunk_size=1)
        timer = threading.Timer(1.0, os.kill, (os.getpid(), signal.SIGINT))
        start = time.monotonic()
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            # Four chunks of about a minute each (the chain of the in-process test).
            fl.sweep("chain", model="coulomb", params={"n_bodies": 2000}, t_end=1000.0,
                     scheme="time-stepping", points=101,
                     grid={"k_chain": [1e3, 2e3, 3e3, 4e3]}, client=client, chunk_size=1)
        stopped = time.monotonic() - start
        # The next call finds the workers free: the chunks stopped at their next step.
        df = fl.sweep("belt", model="CVS", grid={"v_belt": [0.05, 0.1]}, client=client,
                      chunk_size=1)
        again = time.monotonic() - start - stopped
        assert (df["status"] == "ok").all()
        assert stopped < 5.0, stopped
        assert again < 10.0, again


def test_the_functions_bind_the_library_not_the_command_line():
    from friction_lab import _native
    # The native module runs no command line: it has no entry point taking argv.
    assert not hasattr(_native, "run") and not hasattr(_native, "options")
    r = fl.simulate("belt", model="CVS", t_end=2.0, params={"v_belt": 0.2})
    assert r.summary["parameters"]["v_belt"] == 0.2 and r.summary["t_end"] == 2.0
    whole = fl.sweep("belt", model="CVS", grid={"v_belt": [0.05, 0.1], "k": "10:100:2"})
    assert len(whole) == 4 and whole["k"].tolist() == [10, 100, 10, 100]
    study = fl.converge("free-vibration", model="viscous", solvers=["rk4"], dt_list=[0.02, 0.01],
                        t_end=1.0)
    assert study.runs["h"].tolist() == [0.02, 0.01]
    with pytest.raises(ValueError, match=r"^`dt_list` = 'a': a number is expected$"):
        fl.converge("free-vibration", model="viscous", dt_list=[0.02, "a"])
    # A part of the grid by a pair of indices or by its text: the whole's rows.
    for part in ((1, 3), "1:3"):
        rows = fl.sweep("belt", model="CVS", grid={"v_belt": [0.05, 0.1], "k": "10:100:2"},
                        point_range=part)
        pd.testing.assert_frame_equal(rows, whole.iloc[1:3].reset_index(drop=True),
                                      check_exact=True)
    # Each value is taken as its field's type, or refused naming the keyword.
    with pytest.raises(ValueError, match=r"^`points` = 2\.5: a whole number is expected$"):
        fl.simulate("belt", model="CVS", points=2.5)
    with pytest.raises(ValueError, match=r"^`rtol` = '1e-6': a number is expected$"):
        fl.simulate("belt", model="CVS", rtol="1e-6")
    with pytest.raises(ValueError, match=r"^`point_range` = \[1, 2, 3\]: a pair"):
        fl.sweep("belt", model="CVS", grid={"k": [1.0]}, point_range=(1, 2, 3))


def test_testset_solves_a_problem_of_the_stiff_test_set():
    solved = fl.testset("hires", rtol=1e-6)
    summary = solved["summary"]
    # radau5 at rtol = atol = 1e-6 gets four digits of the published y(321.8122).
    assert summary["solver"] == "radau5" and summary["status"] == "ok"
    assert 3.5 < summary["stats"]["scd"] < 5.5
    assert list(solved["final"].columns) == ["t"] + [f"y{i}" for i in range(1, 9)]
    assert solved["final"]["t"].iloc[0] == 321.8122
    # No correct digit: inaccurate, with a warning naming the digits.
    with pytest.warns(RuntimeWarning, match="digit"):
        bad = fl.testset("robertson", solver="implicit-euler", rtol=1.0, atol=1.0)
    assert bad["summary"]["status"] == "inaccurate"
    with pytest.raises(ValueError, match=r"option `solver='rk4'` takes a fixed step"):
        fl.testset("hires", solver="rk4")


def test_an_unknown_parameter_name_gets_its_close_match():
    with pytest.raises(ValueError, match=r"unknown parameter `vbelt` \(did you mean `v_belt`\?\)"):
        fl.simulate("belt", model="CVS", params={"vbelt": 0.1})
