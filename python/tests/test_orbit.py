"""The periodic orbit from Python: the same study as ``friction-lab orbit``."""
import math

import friction_lab as fl


def test_the_belts_stick_slip_orbit_has_its_closed_form_period():
    # m = 1 kg, k = 100 N/m, v_belt = 0.05 m/s, F_s = 7.5 N, F_c = 6 N (the static law).
    omega, d, v_belt = 10.0, 0.015, 0.05
    exact = (2 * math.pi - 2 * math.atan(d / (v_belt / omega))) / omega + 2 * d / v_belt
    study = fl.orbit("belt", model="static", samples=101)
    assert abs(study.summary["period"] - exact) < 1e-9
    trivial, collapsed = study.summary["floquet"]["multipliers"]
    assert abs(trivial[0] - 1) < 1e-9 and math.hypot(*collapsed) < 1e-9
    assert list(study.runs.columns) == ["t", "x_body", "v_body"]
    assert len(study.runs) == 101
    assert set(study.tables["orbit-segments"]["ends_with"].dropna()) == {"v_rel=0", "break-away-"}


def test_continuation_finds_the_hopf_point_of_steady_sliding_on_a_stribeck_belt():
    study = fl.continuation("belt", model="CVS", parameter="v_belt", range="0.02:0.5")
    special = study.tables["special_points"]
    hopf = special[special["kind"] == "hopf"]["v_belt"]
    assert len(hopf) == 1 and 0.2 < hopf.iloc[0] < 0.25
    kinds = set(study.runs["kind"])
    assert kinds == {"equilibrium", "cycle"}
    # The stick-slip cycles are stable all along; steady sliding only beyond the Hopf point.
    cycles = study.runs[study.runs["kind"] == "cycle"]
    assert cycles["stable"].all()
    assert (cycles["segments"] == "stick slip- stick").all()
