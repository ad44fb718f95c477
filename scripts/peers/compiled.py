#!/usr/bin/env python3
"""friction-lab's stiff solvers against compiled peers on the stiff test set and the two stiff
friction cases: SUNDIALS CVODE (BDF, dense direct solver, analytic Jacobian) in C, and Hairer's
RADAU5 and RODAS in Fortran 77, compiled with gfortran -O2. Significant correct digits (scd)
against wall time, one solve a process, the solvers interleaved, several repeats, one run.

Not part of the test suite: the peers are not dependencies of friction-lab. Needs gcc, gfortran
and SUNDIALS from Debian, and a release build:

    apt-get install gfortran libsundials-dev
    cargo build --release
    python3 scripts/peers/compiled.py --out /tmp/compiled-peers

Where the peers come from:
- CVODE: Debian's libsundials-dev (SUNDIALS 6.4.1 on Debian 12), called by compiled/peer.c.
- RADAU5 and RODAS: Hairer's Fortran as the Python package Assimulo 3.0 ships it in its source
  distribution on PyPI (assimulo/thirdparty/hairer/radau_decsol.f and rodas_decsol.f: radau5.f
  and rodas.f with decsol.f appended, radau5 of July 9, 1996). The archive is downloaded from
  PyPI, checked against its published SHA-256 and unpacked into OUT/build; nothing of it is kept
  in this repository.

Each peer is compiled/peer.c built with -DPEER_CVODE, -DPEER_RADAU5 or -DPEER_RODAS: the
problems written once in C (the same equations, initial values and end times as
integrators::testset and friction_cases.py), every solver control at its default, the
analytic Jacobian, the solve timed inside the process with CLOCK_MONOTONIC around the solver
call, as friction-lab's summary.json times its solve (`wall_time_s`).

For every problem and tolerance (rtol = atol = tol, Robertson's atol = 1e-14·tol), each solver
runs `--repeats` times, one process a solve, the solvers taking turns. The friction cases'
reference is friction-lab's radau5 at 1e-12, checked against RADAU5's at 1e-12 (the script
stops if the two agree to fewer than 8 digits: the equations would differ).

Writes OUT/compiled-peers.csv (problem, solver, tol, scd, median, quartiles, least and greatest
wall time, f evaluations, Jacobians, accepted steps and steps not accepted) and prints three Markdown
tables: scd and median at each tolerance; the median time to reach 5 and 7 digits (interpolated
in log time between the runs that bracket them) with the ratio of friction-lab's best to the
best compiled peer's; and RADAU5 and RODAS beside friction-lab's radau5 and rodas at the same
tolerance: steps and time per step.
"""

import argparse
import csv
import hashlib
import os
import shutil
import statistics
import subprocess
import tarfile
import urllib.request

from common import TESTSET, atol_of, run_friction_lab, scd, simulate, time_to_reach
import friction_cases

HERE = os.path.dirname(os.path.abspath(__file__))
ASSIMULO = (
    "https://files.pythonhosted.org/packages/28/ef/4d8b15a0842410bb4ca8f500dadd5ff76fb3e34559f9"
    "56a51c19b8a4912b/Assimulo-3.0.tar.gz",
    "61cdca4562745078c966cc4fab44d8bc0db11a9e6856b45c470ac65c16af9e8a",
)
HAIRER = "Assimulo-3.0/assimulo/thirdparty/hairer/"
CVODE_LIBS = ["-lsundials_cvode", "-lsundials_nvecserial", "-lsundials_sunmatrixdense",
              "-lsundials_sunlinsoldense"]
OURS = ["radau5", "rodas", "bdf", "auto"]
PEERS = ["cvode", "radau5.f", "rodas.f"]


def hairer_sources(build):
    """radau_decsol.f and rodas_decsol.f from Assimulo 3.0's source archive on PyPI."""
    archive = os.path.join(build, "Assimulo-3.0.tar.gz")
    if not os.path.exists(archive):
        url, _ = ASSIMULO
        with urllib.request.urlopen(url) as r, open(archive + ".part", "wb") as f:
            shutil.copyfileobj(r, f)
        os.replace(archive + ".part", archive)
    with open(archive, "rb") as f:
        digest = hashlib.sha256(f.read()).hexdigest()
    if digest != ASSIMULO[1]:
        raise SystemExit(f"{archive}: SHA-256 {digest}, not PyPI's {ASSIMULO[1]}")
    names = {}
    with tarfile.open(archive) as tar:
        for name in ("radau_decsol.f", "rodas_decsol.f"):
            member = tar.getmember(HAIRER + name)
            with tar.extractfile(member) as src, open(os.path.join(build, name), "wb") as dst:
                shutil.copyfileobj(src, dst)
            names[name] = os.path.join(build, name)
    return names


def build_peers(build):
    """The three peer programs, built into `build`: {solver name: path}."""
    os.makedirs(build, exist_ok=True)
    source = os.path.join(HERE, "compiled", "peer.c")
    fortran = hairer_sources(build)
    run = lambda *cmd: subprocess.run(cmd, check=True)
    peers = {}
    peers["cvode"] = os.path.join(build, "cvode")
    run("gcc", "-O2", "-DPEER_CVODE", source, "-o", peers["cvode"], *CVODE_LIBS, "-lm")
    for name, macro, code in [("radau5.f", "PEER_RADAU5", "radau_decsol.f"),
                              ("rodas.f", "PEER_RODAS", "rodas_decsol.f")]:
        obj = os.path.join(build, code.replace(".f", ".o"))
        # Hairer's Fortran 77 passes arrays where scalars are declared: legacy mode.
        run("gfortran", "-O2", "-std=legacy", "-fallow-argument-mismatch", "-w", "-c",
            fortran[code], "-o", obj)
        peers[name] = os.path.join(build, name.replace(".f", "-f"))
        run("gcc", "-O2", f"-D{macro}", source, obj, "-o", peers[name], "-lgfortran", "-lm")
    return peers


def run_peer(program, problem, rtol, atol):
    """One solve by a peer: (the state at the end, wall time, statistics), or None if it
    failed."""
    out = subprocess.run([program, problem, repr(rtol), repr(atol), "1"], capture_output=True,
                         text=True)
    if out.returncode != 0:
        return None
    state, times, counts = out.stdout.split("|")
    nfev, njac, accepted, rejected = map(int, counts.split())
    stats = dict(rhs_evals=nfev, jacobian_evals=njac, accepted=accepted, rejected=rejected)
    return [float(v) for v in state.split()], float(times.split()[0]), stats


def references(binary, peers, out):
    """Every problem's (t_end, y(t_end)): the test set's published values; for a friction case,
    friction-lab's radau5 at 1e-12, checked against RADAU5 at 1e-12."""
    refs = dict(TESTSET)
    for name in friction_cases.CASES:
        ours, _, _ = simulate(binary, name, "radau5", 1e-12, 1e-12,
                              os.path.join(out, "runs", f"{name}-reference"))
        theirs = run_peer(peers["radau5.f"], name, 1e-12, 1e-12)
        agree = scd(theirs[0][:2], ours)
        print(f"{name}: reference (x, v)(t_end) = {ours}; RADAU5 at 1e-12 agrees to "
              f"{agree:.1f} digits", flush=True)
        if agree < 8:
            raise SystemExit(f"{name}: friction-lab and RADAU5 disagree ({agree:.1f} digits): "
                             "the equations of compiled/peer.c differ from friction-lab's")
        refs[name] = (friction_cases.T_END, ours)
    return refs


def quartiles(times):
    q = statistics.quantiles(times, n=4) if len(times) > 1 else [times[0]] * 3
    return dict(median_s=statistics.median(times), q1_s=q[0], q3_s=q[2], min_s=min(times),
                max_s=max(times))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--friction-lab", default="./target/release/friction-lab")
    parser.add_argument("--repeats", type=int, default=15)
    parser.add_argument("--tols", default="1e-3,1e-4,1e-5,1e-6,1e-7,1e-8,1e-9,1e-10")
    parser.add_argument("--problems", default=",".join([*TESTSET, *friction_cases.CASES]))
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    peers = build_peers(os.path.join(args.out, "build"))
    refs = references(args.friction_lab, peers, args.out)
    rows = []
    for problem in args.problems.split(","):
        reference = refs[problem][1]
        for tol in map(float, args.tols.split(",")):
            atol = atol_of(problem, tol)
            times = {s: [] for s in OURS + PEERS}
            result = {}
            for _ in range(args.repeats):
                for solver in OURS + PEERS:
                    if solver in OURS:
                        out = os.path.join(args.out, "runs", f"{problem}-{solver}-{tol:g}")
                        solved = run_friction_lab(args.friction_lab, problem, solver, tol, atol,
                                                  out, reference)
                    else:
                        solved = run_peer(peers[solver], problem, tol, atol)
                        if solved is not None:
                            end, t, stats = solved
                            solved = scd(end[:len(reference)], reference), t, stats
                    if solved is None:
                        result[solver] = (None, {})
                        continue
                    digits, t, stats = solved
                    times[solver].append(t)
                    result[solver] = (digits, stats)
            for solver in OURS + PEERS:
                digits, stats = result[solver]
                row = dict(problem=problem, solver=solver, tol=tol, scd=digits)
                row.update(quartiles(times[solver]) if times[solver] else
                           dict(median_s=None, q1_s=None, q3_s=None, min_s=None, max_s=None))
                row.update({k: stats.get(k) for k in ("rhs_evals", "jacobian_evals", "rejected")})
                # `simulate`'s summary counts accepted steps as `steps`, `testset`'s as
                # `accepted` (its `steps` are every step computed).
                row["accepted"] = stats.get("accepted", stats.get("steps"))
                rows.append(row)
                shown = "failed" if digits is None else f"{digits:.2f}"
                median = "" if row["median_s"] is None else f"{row['median_s'] * 1e3:9.3f} ms"
                print(f"{problem:16} {solver:9} {tol:7.0e} scd {shown:6} {median}", flush=True)
    with open(os.path.join(args.out, "compiled-peers.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    report(rows, args.problems.split(","), list(map(float, args.tols.split(","))))


def report(rows, problems, tols):
    names = OURS + PEERS
    find = lambda p, s, tol: next(r for r in rows
                                  if r["problem"] == p and r["solver"] == s and r["tol"] == tol)
    print("\nscd / median ms of the solve at each tolerance\n")
    print("| problem | tol | " + " | ".join(names) + " |")
    print("|---|---|" + "---|" * len(names))
    for p in problems:
        for tol in tols:
            cells = []
            for s in names:
                r = find(p, s, tol)
                cells.append("failed" if r["scd"] is None else
                             f"{r['scd']:.1f} / {r['median_s'] * 1e3:.2f}")
            print(f"| {p} | {tol:.0e} | " + " | ".join(cells) + " |")
    print("\nmedian ms to reach 5 and 7 digits; the ratio is friction-lab's best to the best "
          "compiled peer's\n")
    print("| problem | scd | " + " | ".join(names) + " | ratio |")
    print("|---|---|" + "---|" * (len(names) + 1))
    for p in problems:
        for target in (5.0, 7.0):
            reach = {s: time_to_reach(rows, p, s, target) for s in names}
            ours = [t for s, t in reach.items() if s in OURS and t is not None]
            theirs = [t for s, t in reach.items() if s in PEERS and t is not None]
            ratio = f"{min(ours) / min(theirs):.2f}" if ours and theirs else "—"
            cells = ["—" if t is None else f"{t * 1e3:.3f}" for t in reach.values()]
            print(f"| {p} | {target:.0f} | " + " | ".join(cells) + f" | {ratio} |")
    print("\nthe same method at the same tolerance: steps (accepted + rejected) and the time per "
          "step, friction-lab's over Hairer's\n")
    print("| problem | tol | radau5 steps | RADAU5 steps | per step, ratio | rodas steps | "
          "RODAS steps | per step, ratio |")
    print("|---|---|---|---|---|---|---|---|")
    for p in problems:
        for tol in tols:
            cells = []
            for ours, theirs in (("radau5", "radau5.f"), ("rodas", "rodas.f")):
                a, b = find(p, ours, tol), find(p, theirs, tol)
                if a["median_s"] is None or b["median_s"] is None:
                    cells += ["—", "—", "—"]
                    continue
                na = a["accepted"] + a["rejected"]
                nb = b["accepted"] + b["rejected"]
                ratio = (a["median_s"] / na) / (b["median_s"] / nb)
                cells += [str(na), str(nb), f"{ratio:.2f}"]
            print(f"| {p} | {tol:.0e} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
