"""What the peer scripts share: the test set's published references, significant correct digits,
the time to reach a number of digits, and friction-lab's own runs (`friction-lab testset` for a
test-set problem, `friction-lab simulate` for a friction case of friction_cases.py), each timed
by the solve alone (summary.json's `wall_time_s`)."""

import csv
import json
import math
import os
import subprocess

import friction_cases

# name: (t_end, y(t_end)), as integrators::testset declares them (Test Set for IVP Solvers 2.4).
TESTSET = {
    "van-der-pol": (2.0, [1.706167732170469, -0.8928097010248125]),
    "robertson": (1e11, [0.2083340149701255e-7, 0.8333360770334713e-13, 0.9999999791665050]),
    "hires": (321.8122, [0.7371312573325668e-3, 0.1442485726316185e-3, 0.5888729740967575e-4,
                         0.1175651343283149e-2, 0.2386356198831331e-2, 0.6238968252742796e-2,
                         0.2849998395185769e-2, 0.2850001604814231e-2]),
    "orego": (360.0, [0.1000814870318523e1, 0.1228178521549917e4, 0.1320554942846706e3]),
}


def atol_of(problem, tol):
    """The absolute tolerance beside rtol = `tol`: `tol`, but Robertson's 1e-14·tol (its second
    species is of order 1e-13 at t = 1e11)."""
    return tol * 1e-14 if problem == "robertson" else tol


def scd(y, reference):
    """Significant correct digits: −log10 of the largest relative error of a component."""
    worst = max(abs((a - r) / r) for a, r in zip(y, reference))
    return math.inf if worst == 0 else -math.log10(worst)


def time_to_reach(rows, problem, solver, target):
    """Median wall time to reach `target` digits, log-interpolated between the two runs that
    bracket it; None where no two do."""
    pts = sorted((r["scd"], r["median_s"]) for r in rows
                 if r["problem"] == problem and r["solver"] == solver and r["scd"] is not None)
    for (s1, t1), (s2, t2) in zip(pts, pts[1:]):
        if s1 <= target <= s2 and s2 > s1:
            w = (target - s1) / (s2 - s1)
            return math.exp(math.log(t1) + w * (math.log(t2) - math.log(t1)))
    return None


def simulate(binary, problem, solver, rtol, atol, out):
    """A friction case by `friction-lab simulate`: (x, v) at the end, wall time, statistics;
    None where the solver failed (exit code 1)."""
    done = subprocess.run([binary, "simulate", *friction_cases.CASES[problem][4], "--solver",
                           solver, "--rtol", str(rtol), "--atol", str(atol), "--points", "2",
                           "--out", out], capture_output=True)
    if done.returncode == 1:
        return None
    done.check_returncode()
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    with open(os.path.join(out, "final.csv")) as f:
        body = next(csv.DictReader(f))
    return [float(body["x"]), float(body["v"])], s["wall_time_s"], s["stats"]


def run_friction_lab(binary, problem, solver, rtol, atol, out, reference):
    """One solve by friction-lab: (scd, wall time of the solve, its statistics); None where
    the solver failed (exit code 1)."""
    if problem in friction_cases.CASES:
        solved = simulate(binary, problem, solver, rtol, atol, out)
        if solved is None:
            return None
        end, t, stats = solved
        return scd(end, reference), t, stats
    done = subprocess.run([binary, "testset", problem, "--solver", solver, "--rtol", str(rtol),
                           "--atol", str(atol), "--out", out], capture_output=True)
    if done.returncode == 1:
        return None
    done.check_returncode()
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    return s["stats"]["scd"], s["wall_time_s"], s["stats"]
