"""models() and curve(): the command line's listing and curves, in memory."""

import json

import numpy as np
import pandas as pd
import pytest

import friction_lab as fl
from csvfiles import read


def test_models_lists_the_papers_six_with_units_defaults_and_ranges(cli):
    models = fl.models()
    names = [m["name"] for m in models]
    assert names[:6] == ["AV", "CS", "CVS", "DV", "SD", "SV"]
    cvs = next(m for m in models if m["name"] == "CVS")
    assert cvs["equation"] == "F = F_c*sign(v) + mu_v*v + S(v); at rest |F| <= F_s"
    f_s = next(p for p in cvs["parameters"] if p["name"] == "F_s")
    assert (f_s["unit"], f_s["default"], f_s["range_text"]) == ("N", 7.5, "[0, inf)")
    assert f_s["range"]["min"] == 0.0 and f_s["range"]["max"] is None
    # The same listing as `friction-lab models --json`.
    listing = json.loads(cli("models", "--json").stdout)
    assert names == [m["name"] for m in listing["models"]]


def test_a_curve_equals_the_command_lines_csv(cli, tmp_path):
    c = fl.curve("SV", params={"sigma": 5.0}, points=301)
    done = cli("curve", "SV", "--set", "sigma=5", "--points", "301", "--out", tmp_path / "sv")
    assert done.returncode == 0, done.stderr
    frame = read(tmp_path / "sv" / "curve-SV.csv")
    assert list(c) == list(frame.columns)
    for column in ("x", "v", "z", "force"):
        assert np.array_equal(c[column], frame[column].to_numpy()), column


def test_a_static_curve_is_the_models_equation():
    # CVS: F = F_c sign(v) + mu_v v + S(v), S(v) = C1 exp(-(v/v_s)^2) for v > 0 (models.md).
    c = fl.curve("CVS", params={"F_c": 6.0, "mu_v": 0.5, "C1": 1.5, "C2": 1.5, "v_s": 0.1})
    v, force = c["v"], c["force"]
    moving = v != 0
    expected = (6.0 * np.sign(v) + 0.5 * v
                + np.where(v > 0, 1.5, -1.5) * np.exp(-(v / 0.1) ** 2))[moving]
    assert np.allclose(force[moving], expected, rtol=0, atol=1e-12)


def test_bad_input_raises_value_error_with_the_command_lines_message(cli, tmp_path):
    with pytest.raises(ValueError) as e:
        fl.curve("CVS", params={"mu_v": -1.0})
    done = cli("curve", "CVS", "--set", "mu_v=-1", "--out", tmp_path / "c")
    assert done.returncode == 2
    assert done.stderr.strip() == f"error: {e.value}"
    assert "mu_v" in str(e.value) and "allowed" in str(e.value)
    with pytest.raises(ValueError, match="unknown model"):
        fl.curve("XYZ")
    with pytest.raises(TypeError, match="curve\\(\\) got an unexpected keyword argument "
                                        "'no_such_option'"):
        fl.curve("CVS", no_such_option=1)
    # A value is taken as its setting's type: True is no number of samples.
    with pytest.raises(ValueError, match=r"`points` = True: a whole number is expected"):
        fl.curve("CVS", points=True)


def test_each_function_takes_the_command_lines_options_as_keywords(cli):
    # The keyword arguments the library's binding takes are the options of the command of
    # the same name: none missing, none extra (`--out` and `--help` aside, `params` for
    # `--set`; `--params FILE` is `params` too on the command line only, and `system` is an
    # argument of its own).
    from friction_lab._command import keywords
    for command in ["curve", "simulate", "converge", "independence", "work-precision",
                    "stiffness", "compare", "sweep", "phenomena"]:
        text = cli(command, "--help").stdout
        options = set()
        for line in text.splitlines():
            words = line.split()
            option = next((w.rstrip(",") for w in words[:2] if w.startswith("--")), None)
            if option:
                options.add(option[2:].replace("-", "_"))
        # `--figure-size` and `--dpi` size the figures the command line draws, `--replace`
        # replaces the folder it writes; a function returns the data in memory, and draws
        # and writes none.
        options -= {"out", "help", "params", "system", "figure_size", "dpi", "replace"}
        options = {"params" if o == "set" else o for o in options}
        taken = set(keywords(command)) - {"system"}
        assert taken == options, (command, taken ^ options)
