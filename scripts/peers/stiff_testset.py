#!/usr/bin/env python3
"""The standard stiff test set and two stiff friction cases run by friction-lab's solvers and by
scipy's, side by side: significant correct digits (scd) against wall time, the IVP test set's
plot.

Not part of the test suite (scipy and matplotlib are peers, not dependencies). Run after a
release build, with an interpreter that has numpy, scipy and matplotlib:

    python3 -m venv /tmp/peers && /tmp/peers/bin/pip install scipy numpy matplotlib
    cargo build --release
    /tmp/peers/bin/python scripts/peers/stiff_testset.py --out /tmp/stiff-peers

For every problem (van-der-pol, robertson, hires, orego: integrators::testset, whose
references the Test Set for IVP Solvers 2.4 publishes) and every tolerance, each solver runs
`--repeats` times: friction-lab's through `friction-lab testset` (its summary.json's
`wall_time_s`, the solve alone, and `scd`), scipy's `solve_ivp` (Radau, BDF, LSODA, with the
analytic Jacobian) timed around the call. rtol = atol = tol, but Robertson's atol = 1e-14·tol
(its second species is of order 1e-13 at t = 1e11).

The friction cases (friction_cases.py: the belt with LuGre at σ0 = 1e5, and with CS regularised
at ε = 1e-4) run through `friction-lab simulate` (its final.csv and summary.json) and through
scipy on the same equations written in Python. Their reference is friction-lab's radau5 at
rtol = atol = 1e-12, checked against scipy's Radau at 1e-12 (the script stops if the two agree
to fewer than 8 digits: the equations would differ); their scd is that of x and v at the end.
Writes `stiff-testset.csv` (problem,
solver, tol, scd, median, min and max wall time, evaluations of f) and `stiff-testset.png`
(scd against median wall time, one panel a problem), and prints two Markdown tables: scd and
median ms at each tolerance, and the median ms to reach 5 and 7 digits, interpolated in log time
between the two runs that bracket them (— where no two do).
"""

import argparse
import csv
import math
import os
import statistics
import time

import numpy as np
from scipy.integrate import solve_ivp

import friction_cases
from common import TESTSET, atol_of, run_friction_lab, scd, simulate, time_to_reach


def vdp(t, y):
    return [y[1], ((1 - y[0] ** 2) * y[1] - y[0]) / 1e-6]


def vdp_jac(t, y):
    return [[0.0, 1.0], [(-2 * y[0] * y[1] - 1) / 1e-6, (1 - y[0] ** 2) / 1e-6]]


def rober(t, y):
    f1 = -0.04 * y[0] + 1e4 * y[1] * y[2]
    f3 = 3e7 * y[1] ** 2
    return [f1, -f1 - f3, f3]


def rober_jac(t, y):
    p1, p2, p3 = 1e4 * y[1], 1e4 * y[2], 6e7 * y[1]
    return [[-0.04, p2, p1], [0.04, -p2 - p3, -p1], [0.0, p3, 0.0]]


def hires(t, y):
    return [
        -1.71 * y[0] + 0.43 * y[1] + 8.32 * y[2] + 0.0007,
        1.71 * y[0] - 8.75 * y[1],
        -10.03 * y[2] + 0.43 * y[3] + 0.035 * y[4],
        8.32 * y[1] + 1.71 * y[2] - 1.12 * y[3],
        -1.745 * y[4] + 0.43 * y[5] + 0.43 * y[6],
        -280 * y[5] * y[7] + 0.69 * y[3] + 1.71 * y[4] - 0.43 * y[5] + 0.69 * y[6],
        280 * y[5] * y[7] - 1.81 * y[6],
        -280 * y[5] * y[7] + 1.81 * y[6],
    ]


def hires_jac(t, y):
    j = np.zeros((8, 8))
    j[0, :3] = [-1.71, 0.43, 8.32]
    j[1, :2] = [1.71, -8.75]
    j[2, 2:5] = [-10.03, 0.43, 0.035]
    j[3, 1:4] = [8.32, 1.71, -1.12]
    j[4, 4:7] = [-1.745, 0.43, 0.43]
    j[5, 3:8] = [0.69, 1.71, -280 * y[7] - 0.43, 0.69, -280 * y[5]]
    j[6, 5:8] = [280 * y[7], -1.81, 280 * y[5]]
    j[7, 5:8] = [-280 * y[7], 1.81, -280 * y[5]]
    return j


S, Q, W = 77.27, 8.375e-6, 0.161


def orego(t, y):
    return [
        S * (y[1] + y[0] * (1 - Q * y[0] - y[1])),
        (y[2] - (1 + y[0]) * y[1]) / S,
        W * (y[0] - y[2]),
    ]


def orego_jac(t, y):
    return [
        [S * (1 - 2 * Q * y[0] - y[1]), S * (1 - y[0]), 0.0],
        [-y[1] / S, -(1 + y[0]) / S, 1 / S],
        [W, 0.0, -W],
    ]


# name: (f, jac, y0, t_end, reference), as integrators::testset declares them.
PROBLEMS = {
    name: (f, jac, y0, *TESTSET[name])
    for name, f, jac, y0 in [
        ("van-der-pol", vdp, vdp_jac, [2.0, 0.0]),
        ("robertson", rober, rober_jac, [1.0, 0.0, 0.0]),
        ("hires", hires, hires_jac, [1, 0, 0, 0, 0, 0, 0, 0.0057]),
        ("orego", orego, orego_jac, [1.0, 2.0, 3.0]),
    ]
}


def solve_scipy(problem, method, rtol, atol):
    """scipy's run: the state at the end it compares (x, v for a friction case), or None."""
    f, jac, y0, t_end, _ = PROBLEMS[problem]
    start = time.perf_counter()
    sol = solve_ivp(f, (0.0, t_end), y0, method=method, rtol=rtol, atol=atol, jac=jac)
    elapsed = time.perf_counter() - start
    end = list(sol.y[:, -1]) if sol.success else None
    if end is not None and problem in friction_cases.CASES:
        end = end[:2]
    return end, elapsed, sol.nfev


def run_scipy(problem, method, rtol, atol):
    end, elapsed, nfev = solve_scipy(problem, method, rtol, atol)
    if end is None:
        return None, elapsed, nfev
    return scd(end, PROBLEMS[problem][4]), elapsed, nfev


def friction_references(binary, out):
    """Each friction case's (x, v) at the end by friction-lab's radau5 at 1e-12, checked against
    scipy's Radau at 1e-12; added to PROBLEMS."""
    for name, (f, jac, y0, t_end, _) in friction_cases.CASES.items():
        ours, _, _ = simulate(binary, name, "radau5", 1e-12, 1e-12,
                              os.path.join(out, "runs", f"{name}-reference"))
        PROBLEMS[name] = (f, jac, y0, t_end, ours)
        theirs, _, _ = solve_scipy(name, "Radau", 1e-12, 1e-12)
        agree = scd(theirs, ours)
        print(f"{name}: reference (x, v)(t_end) = {ours}; scipy Radau at 1e-12 agrees to "
              f"{agree:.1f} digits", flush=True)
        if agree < 8:
            raise SystemExit(f"{name}: friction-lab and scipy disagree ({agree:.1f} digits): "
                             "the equations of friction_cases.py differ from friction-lab's")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--friction-lab", default="./target/release/friction-lab")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--tols", default="1e-4,1e-6,1e-8,1e-10")
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    friction_references(args.friction_lab, args.out)
    ours = ["radau5", "rodas", "auto", "bdf", "esdirk34"]
    theirs = ["Radau", "BDF", "LSODA"]
    rows = []
    for problem in PROBLEMS:
        for tol in map(float, args.tols.split(",")):
            atol = atol_of(problem, tol)
            for solver in ours + theirs:
                times, digits, evals = [], None, None
                for k in range(args.repeats):
                    if solver in ours:
                        out = os.path.join(args.out, "runs", f"{problem}-{solver}-{tol:g}")
                        solved = run_friction_lab(args.friction_lab, problem, solver, tol, atol,
                                                  out, PROBLEMS[problem][4])
                        if solved is None:  # the solver failed: no digits, no time
                            digits, t, evals = None, math.nan, None
                        else:
                            digits, t, stats = solved
                            evals = stats["rhs_evals"]
                    else:
                        digits, t, evals = run_scipy(problem, solver, tol, atol)
                    times.append(t)
                name = solver if solver in ours else f"scipy {solver}"
                rows.append(dict(problem=problem, solver=name, tol=tol, scd=digits,
                                 median_s=statistics.median(times), min_s=min(times),
                                 max_s=max(times), rhs_evals=evals))
                print(f"{problem:12} {name:12} {tol:7.0e} scd {digits if digits is None else round(digits, 2)!s:6} "
                      f"{statistics.median(times) * 1e3:9.3f} ms", flush=True)
    with open(os.path.join(args.out, "stiff-testset.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 3, figsize=(15, 8))
    for ax, problem in zip(axes.flat, PROBLEMS):
        for name in dict.fromkeys(r["solver"] for r in rows):
            pts = [(r["median_s"], r["scd"]) for r in rows
                   if r["problem"] == problem and r["solver"] == name and r["scd"] is not None]
            if pts:
                ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", label=name)
        ax.set_xscale("log")
        ax.set_title(problem)
        ax.set_xlabel("median wall time of the solve (s)")
        ax.set_ylabel("significant correct digits")
    axes.flat[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "stiff-testset.png"), dpi=120)
    print("\n| problem | tol | " + " | ".join(dict.fromkeys(r["solver"] for r in rows)) + " |")
    names = list(dict.fromkeys(r["solver"] for r in rows))
    print("|---|---|" + "---|" * len(names))
    for problem in PROBLEMS:
        for tol in map(float, args.tols.split(",")):
            cells = []
            for name in names:
                r = next(r for r in rows
                         if r["problem"] == problem and r["tol"] == tol and r["solver"] == name)
                digits = "failed" if r["scd"] is None else f"{r['scd']:.1f}"
                cells.append(f"{digits} / {r['median_s'] * 1e3:.2f}")
            print(f"| {problem} | {tol:.0e} | " + " | ".join(cells) + " |")
    print("\n| problem | scd | " + " | ".join(names) + " |")
    print("|---|---|" + "---|" * len(names))
    for problem in PROBLEMS:
        for target in (5.0, 7.0):
            cells = []
            for name in names:
                t = time_to_reach(rows, problem, name, target)
                cells.append("—" if t is None else f"{t * 1e3:.2f}")
            print(f"| {problem} | {target:.0f} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
