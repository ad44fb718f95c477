"""``fl.reproduce``: the command line's ``reproduce`` request, checked before anything runs.
A whole run (six minutes on two cores) is the docs test's: it compares the reports with
docs/, made by the same library request."""

import pytest

import friction_lab as fl


def test_reproduce_refuses_bad_input_before_running_anything(tmp_path):
    out = tmp_path / "paper"
    with pytest.raises(ValueError, match="parameter `v_belt` is not a friction parameter"):
        fl.reproduce(out, params={"v_belt": 0.2})
    with pytest.raises(ValueError, match=r"option `threads` = 0 is out of range"):
        fl.reproduce(out, threads=0)
    with pytest.raises(ValueError, match=r"figure_size"):
        fl.reproduce(out, figure_size="0x4")
    with pytest.raises(ValueError, match=r"a pair \(width, height\)"):
        fl.reproduce(out, figure_size=(6,))
    with pytest.raises(TypeError, match="solver"):
        fl.reproduce(out, solver="radau5")
    # A folder of the user's own is never replaced.
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("mine")
    with pytest.raises(ValueError, match="not empty"):
        fl.reproduce(mine)
    assert not out.exists() and (mine / "notes.txt").read_text() == "mine"
