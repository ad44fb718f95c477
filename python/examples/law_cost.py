"""The cost of a friction law written in Python, per evaluation, against the catalog's law.

    .venv/bin/python python/examples/law_cost.py

prints the table of docs/performance.md ("A friction law written in Python"): each run seven
times with the Python law and with the catalog's, the medians with their min–max, and the
difference of the medians over the evaluations the Python law counted in a run of its own.
"""
import statistics
import time
import warnings

import friction_lab as fl


class Coulomb:
    """F = F_c·s, stuck while the needed force is within ±F_c (the catalog's `coulomb`)."""

    name = "py-coulomb"

    def __init__(self, f_c):
        self.f_c = f_c

    def force(self, x, v, s, z):
        return self.f_c * s

    def stick(self, x, z):
        return self.f_c


class Dahl:
    """F = z, ż = σ·(v − v·s·z/F_c) (the catalog's `dahl`)."""

    name = "py-dahl"
    n_states = 1

    def __init__(self, sigma, f_c):
        self.sigma, self.f_c = sigma, f_c

    def force(self, x, v, s, z):
        return z[0]

    def rates(self, x, v, s, z):
        return (self.sigma * (v - v * s * z[0] / self.f_c),)

    def stick(self, x, z):
        return (z[0], z[0])


def timed(f, n=7):
    """Median, fastest and slowest wall time of n calls of f, s."""
    times = []
    for _ in range(n):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    times.sort()
    return statistics.median(times), times[0], times[-1]


def ms(m):
    """A timing of :func:`timed` as `median ms (fastest–slowest)`."""
    return f"{m[0] * 1e3:.1f} ms ({m[1] * 1e3:.1f}–{m[2] * 1e3:.1f})"


def counting(law):
    """A copy of `law` that counts its calls of `force` and `stick` in `calls`."""
    base = type(law)

    class Counting(base):
        name = base.name + "-counted"
        calls = 0

        def force(self, *args):
            Counting.calls += 1
            return super().force(*args)

        def stick(self, *args):
            Counting.calls += 1
            return super().stick(*args)

    counted = Counting.__new__(Counting)
    counted.__dict__.update(law.__dict__)
    return counted


def main():
    """Prints the two tables."""
    # Dormand–Prince finds the long Dahl run stiff, which is the same for both laws.
    warnings.simplefilter("ignore", RuntimeWarning)

    #: (what, rig, Python law, catalog's law, the catalog law's parameters, options).
    CASES = [
        ("belt, Coulomb, dopri5, event switching, 200 s", "belt", Coulomb(6.0), "coulomb",
         {"F_c": 6.0}, dict(t_end=200.0)),
        ("belt, Coulomb, bdf, regularised (ε = 1e-3), 50 s", "belt", Coulomb(6.0), "coulomb",
         {"F_c": 6.0}, dict(t_end=50.0, solver="bdf", switching="regularized",
                            params={"epsilon": 1e-3})),
        ("prescribed motion, Dahl (one state), dopri5, 40 s", "prescribed-motion", Dahl(5.0, 6.0),
         "dahl", {"F_c": 6.0, "sigma": 5.0}, dict(t_end=40.0)),
    ]

    print("| run | evaluations | Python law | catalog's law | ratio | per evaluation |")
    print("|---|---|---|---|---|---|")
    for what, rig, law, builtin, params, options in CASES:
        counted = counting(law)
        fl.simulate(rig, model=counted, **options)
        calls = type(counted).calls
        own = timed(lambda: fl.simulate(rig, model=law, **options))
        catalog_params = {**options.get("params", {}), **params}
        ours = timed(lambda: fl.simulate(rig, model=builtin, **{**options, "params": catalog_params}))
        per = (own[0] - ours[0]) / calls * 1e6
        print(f"| {what} | {calls} | {ms(own)} | {ms(ours)} | {own[0] / ours[0]:.1f} | {per:.2f} µs |")

    # Table 2's protocols run on a pool of threads: each worker keeps its Python thread state.
    print()
    print("| Table 2 of one law (2 threads) | Python law | catalog's law | ratio |")
    print("|---|---|---|---|")
    own = timed(lambda: fl.phenomena([Coulomb(6.0)], threads=2), n=5)
    ours = timed(lambda: fl.phenomena(["coulomb"], threads=2), n=5)
    print(f"| Coulomb | {ms(own)} | {ms(ours)} | {own[0] / ours[0]:.1f} |")


if __name__ == "__main__":
    main()
