"""simulate(): rigs and systems, equal to the command line's files and to closed forms."""

import json
import os
import warnings

import numpy as np
import pandas as pd
import pytest

import friction_lab as fl
from csvfiles import read

CHAIN_TOML = """
[[body]]
name = "b1"
m = 1.0

[[body]]
name = "b2"
m = 2.0

[[anchor]]
name = "driver"
v = 0.1

[[spring]]
between = ["driver", "b1"]
k = 10.0

[[spring]]
between = ["b1", "b2"]
k = 100.0

[[contact]]
body = "b1"
model = "coulomb"

[[contact]]
body = "b2"
model = "coulomb"
params = { F_c = 3.0 }
"""

CHAIN_DICT = {
    "body": [{"name": "b1", "m": 1.0}, {"name": "b2", "m": 2.0}],
    "anchor": [{"name": "driver", "v": 0.1}],
    "spring": [{"between": ["driver", "b1"], "k": 10.0}, {"between": ["b1", "b2"], "k": 100.0}],
    "contact": [{"body": "b1", "model": "coulomb"},
                {"body": "b2", "model": "coulomb", "params": {"F_c": 3.0}}],
}




def test_every_result_names_its_provenance_and_the_call_that_made_it(cli):
    assert fl.__version__ == cli("--version").stdout.split()[-1]
    r = fl.simulate("belt", model="CVS", t_end=2.0, params={"v_belt": 0.1})
    assert r.provenance["command"] == \
        "friction_lab.simulate('belt', model='CVS', t_end=2.0, params={'v_belt': 0.1})"
    assert r.provenance["friction_lab"] == fl.__version__
    assert next(iter(r.summary)) == "provenance" and r.summary["provenance"] == r.provenance
    # A study takes its system by keyword alone; its provenance keeps the study's threads.
    s = fl.converge(system=CHAIN_DICT, t_end=0.5, solvers=["rk4"],
                    dt_list=[0.01, 0.005, 0.0025], threads=1)
    assert s.provenance["threads"] == 1 == s.summary["provenance"]["threads"]
    assert s.provenance["command"].startswith("friction_lab.converge(system={'body': ")
    frame = fl.sweep("belt", model="CVS", grid={"v_belt": [0.1, 0.2]}, t_end=5.0)
    assert frame.attrs["provenance"]["command"] == \
        "friction_lab.sweep('belt', model='CVS', grid={'v_belt': [0.1, 0.2]}, t_end=5.0)"


def test_a_rig_equals_the_command_lines_trajectory(cli, tmp_path):
    r = fl.simulate("belt", model="CVS", solver="dopri5", switching="event",
                    params={"v_belt": 0.1}, t_end=20.0, rtol=1e-8, atol=1e-10)
    done = cli("simulate", "belt", "--model", "CVS", "--solver", "dopri5", "--set", "v_belt=0.1", "--t-end", "20",
               "--rtol", "1e-8", "--atol", "1e-10", "--out", tmp_path / "belt")
    assert done.returncode == 0, done.stderr
    pd.testing.assert_frame_equal(r.to_pandas(), read(tmp_path / "belt" / "trajectory.csv"),
                                  check_exact=True)
    for name in ("events", "final"):
        pd.testing.assert_frame_equal(getattr(r, name), read(tmp_path / "belt" / f"{name}.csv"),
                                      check_exact=True)
    written = json.loads((tmp_path / "belt" / "summary.json").read_text())
    assert r.summary.keys() == written.keys()
    for kept in (written, r.summary):
        kept.pop("wall_time_s")
        # Where it comes from: the same version and commit, another date and command.
        provenance = kept.pop("provenance")
        assert provenance["friction_lab"] == fl.__version__
    assert r.summary == written
    # The record reaches Python as values, not as the files the command line writes of it.
    assert not {"summary.json", "trajectory.csv", "events.csv", "final.csv"} & set(r._made.files)
    assert r.t.shape == r.x.shape == r.v.shape == r.friction.shape == r.mode.shape
    assert r.summary["status"] == "ok" and r.stats["events"] == len(r.events) > 10
    assert list(r.events.columns) == ["t", "body", "from", "to"]
    # During stick the block moves with the belt; each event leaves the mode the last one
    # entered.
    assert np.all(r.v[r.mode == "stick"] == 0.1)
    assert (r.events["from"].iloc[1:].to_numpy() == r.events["to"].iloc[:-1].to_numpy()).all()
    # The one body's final state is the trajectory's last point.
    assert list(r.final["body"]) == ["body"]
    assert (r.final["x"].iloc[0], r.final["v"].iloc[0]) == (r.x[-1], r.v[-1])
    assert r.summary["t_reached"] == r.t[-1] == 20.0


def test_coulomb_block_pushed_past_friction_follows_the_closed_form():
    # paper-block: m = 1 kg pushed by F_ex = 15 N against Coulomb F_c = 6 N from rest:
    # a = 9 m/s², x = 4.5 t², until the end.
    r = fl.simulate("paper-block", model="coulomb", params={"F_c": 6.0}, t_end=2.0)
    assert r.summary["parameters"]["F_ex"] == 15.0
    assert np.allclose(r.v, 9.0 * r.t, rtol=0, atol=1e-9)
    assert np.allclose(r.x, 4.5 * r.t ** 2, rtol=0, atol=1e-9)


def test_a_parameter_the_model_does_not_read_is_a_runtime_warning():
    # Coulomb reads F_c only: F_s changes nothing, and the run is the closed form's.
    with pytest.warns(RuntimeWarning, match="parameter `F_s` is not read by model `coulomb`"):
        r = fl.simulate("paper-block", model="coulomb", params={"F_c": 6.0, "F_s": 9.0},
                        t_end=1.0)
    assert np.allclose(r.v, 9.0 * r.t, rtol=0, atol=1e-9)


def test_an_unsettled_loop_warns_and_a_stuck_one_says_so():
    # Coulomb friction under the servo's PID sticks ever closer to the set point: after 800 s
    # a transient, which Python warns of as the command line does.
    with pytest.warns(RuntimeWarning, match="closed loop: not settled"):
        r = fl.simulate("servo", model="coulomb")
    assert r.summary["closed_loop"]["hunting"] is None
    # Under P control (ki = kd = 0) kp·1 m = 3 N < F_c = 6 N: the body never moves, a rest
    # state that is neither converged nor a warning.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = fl.simulate("servo", model="coulomb", params={"ki": 0.0, "kd": 0.0}, t_end=50.0)
    loop = r.summary["closed_loop"]
    assert (loop["stuck"], loop["hunting"], loop["final_error"]) == (True, False, 1.0)


def test_a_system_from_a_dict_equals_the_same_file_and_is_time_by_body(tmp_path):
    path = tmp_path / "chain.toml"
    path.write_text(CHAIN_TOML)
    a = fl.simulate(system=str(path), t_end=10.0)
    b = fl.simulate(system=CHAIN_DICT, t_end=10.0)
    pd.testing.assert_frame_equal(a.to_pandas(), b.to_pandas(), check_exact=True)
    assert b.bodies == ["b1", "b2"]
    assert b.x.shape == (len(b.t), 2) and b.mode.shape == (len(b.t), 2)
    assert np.array_equal(b.x[:, 1], b.to_pandas().query("body == 'b2'")["x"].to_numpy())
    assert list(b.events.columns) == ["t", "body", "from", "to"] and len(b.events) > 0
    assert set(b.events["body"]) <= {"b1", "b2"}


def test_the_chain_by_name_time_stepped():
    r = fl.simulate("chain", model="coulomb", params={"n_bodies": 30}, t_end=5.0,
                    scheme="time-stepping", dt=1e-3, bodies=[1, 15, 30])
    assert r.bodies == ["b1", "b15", "b30"]
    assert r.x.shape == (len(r.t), 3)
    assert r.summary["stats"]["steps"] == 5000


def test_a_solver_failure_raises_solver_error_with_the_partial_result():
    with pytest.raises(fl.SolverError) as e:
        fl.simulate("belt", model="CVS", max_steps=50)
    assert "too many steps" in str(e.value)
    # The partial run is the error's result: no file is named, none was written.
    assert "the error's `result` keeps the run up to the failure" in str(e.value)
    assert "summary.json" not in str(e.value)
    partial = e.value.result
    assert partial.summary["status"] == "failed"
    assert 0 < partial.t[-1] < 20.0 and partial.stats["steps"] == 50


def test_a_runaway_raises_as_on_the_command_line():
    # The servo time-stepped at h = 1 s: its sampled loop runs away (7.4e84 m, once `ok`);
    # beyond 10^3 times the system's reach the run stops, `diverged`, and raises with what it
    # had.
    with pytest.raises(fl.SolverError) as e:
        fl.simulate("servo", model="static", t_end=100.0, scheme="time-stepping", dt=1.0)
    partial = e.value.result
    assert partial.summary["status"] == "diverged"
    assert "is beyond 1e3 times" in partial.summary["reason"]
    # Stopped at t = 13.4 s, 1.1e9 m away, not at 7.4e84 m: only what came before is kept.
    assert partial.t[-1] < 13.4 and np.abs(partial.x).max() < 1e10


def test_errors_speak_python_not_the_command_line(cli, tmp_path):
    # An unknown keyword argument is Python's TypeError, with the closest one it takes.
    with pytest.raises(TypeError, match=r"simulate\(\) got an unexpected keyword argument "
                                        r"'tend'; did you mean 't_end'\?"):
        fl.simulate("belt", model="CVS", tend=5)
    with pytest.raises(TypeError, match=r"work_precision\(\) got an unexpected keyword "
                                        r"argument 'solver'; did you mean 'solvers'\?"):
        fl.work_precision("belt", model="CS", solver="rk4")
    # A bad value names the keyword argument, as Python spells it; the message is otherwise
    # the command line's.
    with pytest.raises(ValueError) as e:
        fl.simulate("belt", model="CVS", t_end=-1.0)
    assert str(e.value) == "option `t_end` = -1 is out of range: allowed [1e-6, 1e6] s"
    done = cli("simulate", "belt", "--model", "CVS", "--t-end", "-1", "--out", tmp_path / "x")
    assert done.stderr.strip() == "error: option `--t-end` = -1 is out of range: allowed [1e-6, 1e6] s"
    with pytest.raises(ValueError) as e:
        fl.simulate("belt", model="CVS", scheme="time-stepping", solver="rk4")
    assert str(e.value).startswith("option `solver='rk4'` does not apply to scheme time-stepping")
    assert "--" not in str(e.value)
    with pytest.raises(ValueError) as e:
        fl.simulate("belt", model="CVS", params={"F_s": "abc"})
    assert str(e.value) == "params F_s=abc: `abc` is not a number"


def test_bad_options_raise_value_error_naming_the_field(cli, tmp_path):
    with pytest.raises(ValueError) as e:
        fl.simulate("belt", model="CVS", rtol=-1.0)
    assert str(e.value) == "option `rtol` = -1 is out of range: allowed [1e-14, 1]"
    done = cli("simulate", "belt", "--model", "CVS", "--rtol", "-1", "--out", tmp_path / "x")
    # One error, spelled by each front end: Python's keyword, the command line's option.
    assert (done.returncode, done.stderr.strip()) == (
        2, "error: " + str(e.value).replace("`rtol`", "`--rtol`"))
    with pytest.raises(ValueError, match="v_belt"):
        fl.simulate("belt", model="CVS", params={"v_belt": float("nan")})
    import glob
    import tempfile
    left = set(glob.glob(os.path.join(tempfile.gettempdir(), "friction-lab-system-*")))
    with pytest.raises(ValueError, match="not a finite number"):
        fl.simulate(system={"body": [{"name": "b", "m": float("inf")}]})
    with pytest.raises(TypeError, match=r"^system: \{1\} \(set\) is not a number"):
        fl.simulate(system={"body": [{"name": "b", "m": {1}}]})
    with pytest.raises(TypeError, match="^system: expected a path .* or a dict .*, got int$"):
        fl.simulate(system=123)
    # A dict refused before the native call leaves no temporary file behind.
    assert set(glob.glob(os.path.join(tempfile.gettempdir(), "friction-lab-system-*"))) <= left
    with pytest.raises(ValueError, match="unknown field `mass`") as e:
        fl.simulate(system={"body": [{"name": "b", "mass": 1.0}]})
    # The message names the system given, which reaches the library as a value (its JSON
    # text), through no file.
    assert str(e.value).startswith("system (given as JSON): "), e.value
    assert "friction-lab-system-" not in str(e.value)
    # params and grid are mappings (or pairs, or a Series); anything else is named, not left
    # to dict()'s "'int' object is not iterable".
    for bad in (1, [1, 2], "F_s=7", True):
        with pytest.raises(ValueError, match="option `params`: a mapping of parameter names"):
            fl.simulate("belt", model="CVS", params=bad)
    with pytest.raises(ValueError, match=r"option `grid`: .* e\.g\. \{'v_belt': \[0\.1, 0\.2\]\}"):
        fl.sweep("belt", model="CVS", grid=0.1)
    # A scenario or a model that is not a string is named, not left to the native call's
    # TypeError "'int' object is not an instance of 'str'".
    for call, bad in ((lambda b: fl.simulate(b, model="CVS"), 3),
                      (lambda b: fl.stiffness(b, model="CS"), ["belt"]),
                      (lambda b: fl.sweep(b, model="CS", grid={"k": [1]}), 1.0),
                      (fl.curve, np.array(["CS"]))):
        with pytest.raises(ValueError, match=r"argument .* is not a name: a string is expected"):
            call(bad)
    pairs = fl.simulate("belt", model="CVS", params=[("v_belt", 0.2)], t_end=1.0)
    series = fl.simulate("belt", model="CVS", params=pd.Series({"v_belt": 0.2}), t_end=1.0)
    assert np.array_equal(pairs.v, series.v)


def test_a_number_given_twice_is_refused_naming_both():
    # Pairs or a Series with a repeated name: refused before anything runs, both values named
    # (a dict keeps only the last, which would run silently).
    with pytest.raises(ValueError, match=r"option `params`: `v_belt` is given twice, 0.1 and 0.5"):
        fl.simulate("belt", model="CVS", params=[("v_belt", 0.1), ("v_belt", 0.5)])
    with pytest.raises(ValueError, match=r"option `params`: `v_belt` is given twice"):
        fl.simulate("belt", model="CVS", params=pd.Series([0.1, 0.5], index=["v_belt"] * 2))
    # One number of a system by its name and by its index.
    with pytest.raises(ValueError, match=r"`body.b2.m` and `body.2.m` set the same number, m "
                                         r"of \[\[body\]\] 2"):
        fl.simulate(system=CHAIN_DICT, params={"body.b2.m": 2.0, "body.2.m": 3.0}, t_end=1.0)


def test_numpy_arrays_are_lists_and_their_scalars_values():
    from friction_lab._command import values
    # A one-dimensional array is a list, a value of no dimension that value; the doubles
    # cross exactly.
    given = values("stiffness", values=np.array([0.1, 1e-2 / 3]), t_end=np.array(2.0))
    assert given == {"values": [0.1, 1e-2 / 3], "t_end": 2.0}
    assert type(given["t_end"]) is float
    given = values("sweep", grid={"k": np.arange(1, 3), "v_belt": 0.5})
    assert given == {"grid": {"k": [1, 2], "v_belt": [0.5]}}
    with pytest.raises(ValueError, match=r"option `values`: an array of shape \(2, 1\)"):
        values("stiffness", values=np.zeros((2, 1)))
    with pytest.raises(ValueError, match="option `grid`, axis `k`: no values"):
        values("sweep", grid={"k": np.array([])})
    study = fl.stiffness("belt", model="CS", values=np.array([0.1, 0.01]), t_end=np.array(1.0),
                         solvers=["dopri5"])
    assert study.summary["parameter"] == "epsilon" and len(study.summary["points"]) == 2
    # Bodies chosen by an array of indices: the same run as by a list.
    by_array = fl.simulate("chain", model="CS", t_end=1.0, bodies=np.array([1, 3]))
    by_list = fl.simulate("chain", model="CS", t_end=1.0, bodies=[1, 3])
    assert by_array.bodies == by_list.bodies
    assert np.array_equal(by_array.x, by_list.x)


def test_a_system_files_numbers_are_set_by_their_paths():
    from pathlib import Path
    brake = Path(__file__).resolve().parents[2] / "examples" / "brake.toml"
    plain = fl.simulate(system=brake, t_end=1.0)
    stiffer = fl.simulate(system=brake, t_end=1.0, params={"spring.2.k": 8e4})
    assert stiffer.summary["parameters"] == {"spring.2.k": 8e4}
    assert plain.stats["steps"] != stiffer.stats["steps"]
    rows = fl.sweep(None, system=str(brake), t_end=10.0,
                    grid={"contact.pad.surface_velocity": [0.05, 1.0]})
    assert rows["regime"].tolist() == ["StickSlip", "SteadySliding"]


def test_one_refusal_names_its_options_as_each_front_end_spells_them(cli, tmp_path):
    # The library marks the options a message names; Python writes each as its keyword, the
    # command line as its option, in the same sentence.
    with pytest.raises(ValueError) as e:
        fl.simulate("belt", model="CS", theta=0.7)
    python = str(e.value)
    assert python == ("option `theta=0.7` applies to scheme time-stepping, the weight of its "
                      "θ-method: the event-driven solvers have none; drop theta, or choose "
                      "scheme time-stepping")
    done = cli("simulate", "belt", "--model", "CS", "--theta", "0.7", "--out", tmp_path / "x")
    # The option with its value as each writes it: `theta=0.7` in Python, `--theta 0.7`.
    command_line = (python.replace("theta=", "theta ").replace("theta", "--theta")
                    .replace("scheme", "--scheme"))
    assert (done.returncode, done.stderr.strip()) == (2, "error: " + command_line)
    # An advice too: the command line's `--set` is Python's `params`.
    with pytest.warns(RuntimeWarning, match=r"^option `params`: parameter `F_s` is not read"):
        fl.simulate("paper-block", model="coulomb", params={"F_s": 9.0}, t_end=0.1)


def test_closed_loop_analyses_ones_own_gains_beside_the_describing_function():
    # The 1995 servo with the static law: Table 2's hunting cycle (38.24 s) beside the
    # describing function's (11.94 s), as the command line gives them.
    c = fl.closed_loop("servo", model="static")
    assert c.summary["regime"] == "Hunting"
    assert abs(c.summary["simulated"]["period"] - 38.24) < 0.01
    assert abs(c.summary["predicted"][0]["period"] - 11.94) < 0.01
    assert list(c.runs.columns) == ["t", "r", "x", "error"]
    assert np.allclose(c.runs["error"], c.runs["r"] - c.runs["x"])
    assert len(c.tables["closed-loop-predicted"]) == 1
    # One's own gains: without integral action and kp = 20 N/m, it stops within F_s/kp.
    d = fl.closed_loop("servo", model="static", params={"ki": 0.0, "kp": 20.0})
    assert d.summary["regime"] == "DeadZone"
    assert 0 < abs(d.summary["simulated"]["final_error"]) <= 7.5 / 20.0
    # Ten seconds do not settle the loop: a RuntimeWarning, as the command line's note.
    with pytest.warns(RuntimeWarning, match="closed loop: not settled"):
        e = fl.closed_loop("servo", model="static", t_end=10.0)
    assert e.summary["regime"] == "Unsettled"
