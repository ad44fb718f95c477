#!/usr/bin/env python3
"""The Burridge-Knopoff chain of docs/systems.md under Siconos 4.4's Moreau-Jean
time-stepping, for a side-by-side check of friction-lab's `--switching timestepping`.

Not part of the test suite: Siconos is a Debian package for the system python3
(`apt-get install python3-siconos`), not a PyPI one. Run with the system interpreter:

    /usr/bin/python3 scripts/peers/siconos_chain.py --n 10 --h 1e-3 --theta 0.5 \
        --t-end 10 --every 100 --out siconos-chain-10.csv

The chain (docs/systems.md, `coulomb` at the paper's F_c = 6 N): N blocks of mass m = 1 kg, each
pulled by a spring k_driver = 10 N/m from one anchor moving at v_driver = 0.1 m/s, neighbours
joined by springs k_chain = 100 N/m, block i on a fixed floor with Coulomb friction of level
F_c,i = 6·(1 + 0.1·sin i) N, all at rest at x = 0. As a first-order linear system with a relay
(Acary & Brogliato 2008, ch. 9):

    X = (x_1..x_N, v_1..v_N, x_d),   dX/dt = A·X + b + r,   y = C·X,   r = B·lambda,
    -y in N_[-1, 1](lambda)   (Siconos's RelayNSL: lambda = -1 while y = v_i > 0),

with B[v_i, i] = F_c,i / m, so that the friction force is F_c,i·lambda_i. EulerMoreauOSI
with weight theta on A·X and the relay's r at the end of the step is the theta-method on the
smooth forces with the friction impulse implicit: the scheme friction-lab integrates
(docs/timestepping.md). Lemke's algorithm solves each step's relay problem exactly.

Writes a CSV of t, x_1..x_N, v_1..v_N every `--every` steps (and at the end) and prints the
wall time per step of the time loop.
"""

import argparse
import math
import time

import numpy as np
import siconos.kernel as sk
import siconos.numerics as sn


def chain(n, m=1.0, k_chain=100.0, k_driver=10.0, v_driver=0.1, spread=0.1, f_c=6.0):
    """A, b, C, B and the initial state of the chain of `n` blocks."""
    dim = 2 * n + 1
    d = 2 * n  # the driver's position
    a = np.zeros((dim, dim))
    for i in range(n):
        a[i, n + i] = 1.0
        a[n + i, d] += k_driver / m
        a[n + i, i] -= k_driver / m
        for j in (i - 1, i + 1):
            if 0 <= j < n:
                a[n + i, j] += k_chain / m
                a[n + i, i] -= k_chain / m
    b = np.zeros(dim)
    b[d] = v_driver
    c = np.zeros((n, dim))
    bb = np.zeros((dim, n))
    for i in range(n):
        c[i, n + i] = 1.0
        bb[n + i, i] = f_c * (1.0 + spread * math.sin(i + 1)) / m
    return a, b, c, bb, np.zeros(dim)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--n", type=int, default=10)
    p.add_argument("--h", type=float, default=1e-3)
    p.add_argument("--theta", type=float, default=0.5)
    p.add_argument("--t-end", type=float, default=10.0)
    p.add_argument("--every", type=int, default=100)
    p.add_argument("--out", default=None)
    args = p.parse_args()
    n = args.n
    a, b, c, bb, x0 = chain(n)
    ds = sk.FirstOrderLinearDS(x0, a, b)
    relation = sk.FirstOrderLinearR(c, bb)
    interaction = sk.Interaction(sk.RelayNSL(n), relation)
    nsds = sk.NonSmoothDynamicalSystem(0.0, args.t_end)
    nsds.insertDynamicalSystem(ds)
    nsds.link(interaction, ds)
    simulation = sk.TimeStepping(
        nsds,
        sk.TimeDiscretisation(0.0, args.h),
        sk.EulerMoreauOSI(args.theta),
        sk.Relay(sn.SICONOS_RELAY_LEMKE),
    )
    steps = int(round(args.t_end / args.h))
    rows = [[0.0] + list(x0[: 2 * n])]
    start = time.perf_counter()
    for k in range(1, steps + 1):
        simulation.computeOneStep()
        simulation.nextStep()
        if k % args.every == 0 or k == steps:
            rows.append([k * args.h] + list(ds.x()[: 2 * n]))
    elapsed = time.perf_counter() - start
    print(f"siconos EulerMoreauOSI theta={args.theta}: N = {n}, {steps} steps of h = {args.h}, "
          f"{elapsed:.3f} s, {1e6 * elapsed / steps:.1f} us per step")
    if args.out:
        header = ["t"] + [f"x{i}" for i in range(1, n + 1)] + [f"v{i}" for i in range(1, n + 1)]
        np.savetxt(args.out, np.array(rows), delimiter=",", header=",".join(header),
                   comments="", fmt="%.17g")


if __name__ == "__main__":
    main()
