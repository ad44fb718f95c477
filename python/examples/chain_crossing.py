"""What a Python call costs over the solve, against the command line, on the 1000-block chain.

    cargo build --release --bin friction-lab
    .venv/bin/python python/examples/chain_crossing.py

prints the table of docs/performance.md ("Python against the command line"): the chain of
1000 blocks time-stepped over 10 s on 2001 output points, with the default 20 bodies'
trajectories and with every body's, five times each through `fl.simulate` (in-process, a warm
interpreter; the solve is the run's own `summary["wall_time_s"]`) and through the command line
(the whole process, which also writes its files and draws its figures); medians with their
min–max. The call is split as `fl.simulate` makes it: the library's call (the solve, the
outputs the command line computes too — each row's friction and mode, the stiffness along the
run, the spectrum, the space–time picture's cells, the final states, the events and the
summary — and their hand-over as typed columns), then Python's part, the numpy arrays and
DataFrames of `Result`.
"""
import statistics
import subprocess
import tempfile
import time

from friction_lab._command import call, values
from friction_lab._result import Result

RUNS = 5
BINARY = "./target/release/friction-lab"


def spread(times):
    """`median s (min–max)` of a list of wall times, s."""
    times = sorted(times)
    return f"{statistics.median(times):.3f} s ({times[0]:.3f}–{times[-1]:.3f})"


def python_call(bodies):
    """The call's wall time, its solve's, Python's part of it, s, and the rows, as
    `fl.simulate("chain", ...)` makes the call."""
    keywords = dict(model="coulomb", params={"n_bodies": 1000}, scheme="time-stepping", t_end=10.0)
    if bodies:
        keywords["bodies"] = bodies
    start = time.perf_counter()
    made = call("simulate", "chain", None, values("simulate", **keywords))
    library = time.perf_counter()
    result = Result(made)
    end = time.perf_counter()
    return end - start, result.summary["wall_time_s"], end - library, result.x.size


def command_line(bodies):
    """Wall time of the whole process, s."""
    with tempfile.TemporaryDirectory() as out:
        argv = [BINARY, "simulate", "chain", "--model", "coulomb", "--set", "n_bodies=1000",
                "--scheme", "time-stepping", "--t-end", "10", "--out", out]
        if bodies:
            argv += ["--bodies", ",".join(map(str, bodies))]
        start = time.perf_counter()
        subprocess.run(argv, check=True, stdout=subprocess.DEVNULL)
        return time.perf_counter() - start


def main():
    print("| trajectories | solve | Python call | library's outputs | Python's part | command line |")
    print("|---|---|---|---|---|---|")
    for label, bodies in [("20 bodies", None), ("1000 bodies", list(range(1, 1001)))]:
        calls = [python_call(bodies) for _ in range(RUNS)]
        cli = [command_line(bodies) for _ in range(RUNS)]
        rows = calls[0][3]
        outputs = [whole - solve - python for whole, solve, python, _ in calls]
        print(f"| {label} ({rows} rows) | {spread([c[1] for c in calls])} "
              f"| {spread([c[0] for c in calls])} | {spread(outputs)} "
              f"| {spread([c[2] for c in calls])} | {spread(cli)} |")


if __name__ == "__main__":
    main()
