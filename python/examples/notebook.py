"""friction-lab in a notebook: the paper's Figure 4 and a small stick-slip map.

Run it as a script (CI does: ``python python/examples/notebook.py --out DIR``) or paste the
cells into Jupyter. It draws
- Figure 4 of the paper, the CVS model (Coulomb + viscous + static + Stribeck) against
  velocity, with the forces admissible at rest, from ``fl.curve``;
- the settled regime of the belt rig with CVS over belt speed × spring stiffness, from
  ``fl.sweep`` (on a two-worker Dask ``LocalCluster`` with ``--dask``): a point is
  stick-slip where the settled motion still sticks once per cycle or more.
"""

import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import friction_lab as fl  # noqa: E402


def figure_4(out: pathlib.Path) -> None:
    # %% The CVS curve, as Figure 4 draws it (paper parameters, Table 1).
    c = fl.curve("CVS")
    cvs = next(m for m in fl.models() if m["name"] == "CVS")
    moving = c["v"] != 0
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(c["v"][moving & (c["v"] > 0)], c["force"][moving & (c["v"] > 0)], "r")
    ax.plot(c["v"][moving & (c["v"] < 0)], c["force"][moving & (c["v"] < 0)], "r")
    at_rest = ~moving
    ax.vlines(0.0, c["force"][at_rest].min(), c["force"][at_rest].max(), colors="g",
              label="admissible at rest")
    ax.set(xlabel="velocity v (m/s)", ylabel="friction force F (N)",
           title=f"Figure 4: CVS, {cvs['equation'].split(';')[0]}")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "figure-4-CVS.png", dpi=120)
    # The jump at rest is 2 F_s wide.
    f_s = next(p["default"] for p in cvs["parameters"] if p["name"] == "F_s")
    band = c["force"][at_rest]
    assert np.isclose(band.max() - band.min(), 2 * f_s), (band.min(), band.max())


def stick_slip_map(out: pathlib.Path, dask: bool) -> None:
    # %% Belt speed × stiffness: settled stick-slip, in parallel (Rust threads or Dask).
    grid = {"v_belt": "log:0.005:0.5:8", "k": [10, 30, 100, 300, 1000]}
    options = dict(model="CVS", grid=grid, t_end=30.0, settle=0.5)
    if dask:
        from distributed import Client, LocalCluster

        with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster, \
                Client(cluster) as client:
            df = fl.sweep("belt", client=client, **options)
    else:
        df = fl.sweep("belt", **options)
    # Sustained stick-slip sticks about once per cycle of the settled oscillation.
    sticking = df["stick_per_cycle"].fillna(0) > 0.5
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.scatter(df["v_belt"][sticking], df["k"][sticking], c="k", label="stick-slip")
    ax.scatter(df["v_belt"][~sticking], df["k"][~sticking], facecolors="none",
               edgecolors="k", label="steady sliding or stuck")
    ax.set(xscale="log", yscale="log", xlabel="belt speed v_belt (m/s)",
           ylabel="spring stiffness k (N/m)", title="belt with CVS: settled regime")
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0))
    fig.tight_layout()
    fig.savefig(out / "stick-slip-map.png", dpi=120)
    df.to_csv(out / "stick-slip-map.csv", index=False)
    # Both regimes appear on this grid (docs/sweep.md has the closed-form period it is tested
    # against; `friction-lab reproduce` draws the full map with its stability boundary).
    assert sticking.any() and (~sticking).any()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=pathlib.Path, default=pathlib.Path("python-example"))
    parser.add_argument("--dask", action="store_true", help="run the sweep on a LocalCluster")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    figure_4(args.out)
    stick_slip_map(args.out, args.dask)
    print(f"wrote figure-4-CVS.png, stick-slip-map.png and stick-slip-map.csv into {args.out}")


if __name__ == "__main__":
    main()
