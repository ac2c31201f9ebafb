"""The oscillating squeeze film: the transient JFO film against its exact solution.

    python -m studies.squeeze_film -o results/squeeze_film

Parallel plates of length 1 at a uniform gap h(t) = 0.125 cos(4 pi t) + 0.375, oil at
p_a = 0.025 at both ends, mu = 1/12 (Ausas, Jai and Buscaglia 2009 posed this problem; the
exact solution is derived in :mod:`bearingfem.closed.squeeze_film`). Over two periods the
cavity opens at the smallest gap, grows by rupture, shrinks by reformation and collapses,
twice. The computed front (the upstream face of the first cavitated control volume) and
the load per unit width are compared with the exact ones, away from the instants the
cavity opens or collapses (there the exact front jumps and the incompressible pressure with
it), on meshes refined together in space and time. Prints the table and writes
``squeeze_film.csv`` and ``squeeze_film.png``.
"""
from __future__ import annotations

import argparse
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from bearingfem.closed.squeeze_film import oscillating_squeeze
from bearingfem.fe.planar import PlanarJFO
from bearingfem.outputs.tables import write_csv
from bearingfem.planar import PlanarFilm

PERIODS = 2
AMBIENT = 0.025
WIDTH = 0.1
#: Instants closer than this to an opening or a collapse are left out of the comparison.
EVENT_WINDOW = 0.01


def gap(t):
    return 0.125 * np.cos(4.0 * np.pi * t) + 0.375


def gap_rate(t):
    return -0.5 * np.pi * np.sin(4.0 * np.pi * t)


def film() -> PlanarFilm:
    return PlanarFilm(length=1.0, width=WIDTH, viscosity=1.0 / 12.0,
                      gap=lambda x, y, t: gap(t) + 0.0 * x,
                      inlet_pressure=AMBIENT, outlet_pressure=AMBIENT)


def exact():
    return oscillating_squeeze(gap, gap_rate, 0.5 * PERIODS, ambient_pressure=AMBIENT)


@dataclass(frozen=True)
class Run:
    """One transient run against the exact film: errors away from the events."""

    n_x: int
    n_t: int
    front_error: float        # max |x_c - exact| [plate lengths]
    load_error: float         # max |W - exact| / max |W exact|
    mass_balance: float       # max |balance| / max throughput of the run
    fraction_range: tuple
    pressure_min: float
    iterations: float         # mean solver iterations per step
    wall_time: float
    t: np.ndarray
    front: np.ndarray
    load: np.ndarray


def run(n_x: int, n_t: int, ex=None) -> Run:
    """``n_x`` cells along the plates, ``n_t`` backward-Euler steps over two periods."""
    ex = exact() if ex is None else ex
    events = np.array(ex.rupture_times + ex.collapse_times)
    f = PlanarJFO(film(), n_x, 1)
    dt = 0.5 * PERIODS / n_t
    t, xc, W, bal, thr, its = [], [], [], [], [], 0
    lo, hi, pmin = 1.0, 0.0, 0.0
    start = time.perf_counter()
    for _ in range(n_t):
        s = f.step(dt)
        t.append(s.t)
        xc.append(min(s.cavity_start(), 0.5))
        W.append(s.load / WIDTH)
        bal.append(abs(s.mass_balance))
        thr.append(max(abs(s.flow_in), abs(s.flow_out), abs(s.storage)))
        its += s.iterations
        lo, hi = min(lo, float(s.fraction.min())), max(hi, float(s.fraction.max()))
        pmin = min(pmin, float(s.pressure.min()))
    wall = time.perf_counter() - start
    t, xc, W = np.array(t), np.array(xc), np.array(W)
    away = np.min(np.abs(t[:, None] - events[None, :]), axis=1) > EVENT_WINDOW
    x_ex = np.interp(t, ex.t, ex.front)
    W_ex = np.interp(t, ex.t, ex.load)
    return Run(n_x, n_t, float(np.max(np.abs(xc - x_ex)[away])),
               float(np.max(np.abs(W - W_ex)[away]) / np.max(np.abs(ex.load))),
               float(np.max(bal) / np.max(thr)), (lo, hi), pmin, its / n_t, wall, t, xc, W)


def orders(values, ratio=2.0):
    v = np.asarray(values, float)
    return np.log(v[:-1] / v[1:]) / np.log(ratio)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--output", default="results/squeeze_film")
    ap.add_argument("--levels", type=int, default=5, help="meshes 50 x 250 doubled (5)")
    a = ap.parse_args(argv)
    out = Path(a.output)
    out.mkdir(parents=True, exist_ok=True)
    ex = exact()
    runs = []
    print("| cells | steps | front error [l] | load error [max W] | mass balance | "
          "phi range | iterations/step | time [s] |")
    print("|---|---|---|---|---|---|---|---|")
    for k in range(a.levels):
        r = run(50 * 2 ** k, 250 * 2 ** k, ex)
        runs.append(r)
        print(f"| {r.n_x} | {r.n_t} | {r.front_error:.2e} | {r.load_error:.2e} | "
              f"{r.mass_balance:.1e} | [{r.fraction_range[0]:.3f}, "
              f"{r.fraction_range[1]:.3f}] | {r.iterations:.2f} | {r.wall_time:.1f} |",
              flush=True)
    fo, lo_ = orders([r.front_error for r in runs]), orders([r.load_error for r in runs])
    print("observed orders (space and time refined together): front "
          + ", ".join(f"{o:.2f}" for o in fo) + "; load " + ", ".join(f"{o:.2f}" for o in lo_))
    write_csv([dict(n_x=r.n_x, n_t=r.n_t, front_error=r.front_error,
                    load_error=r.load_error, mass_balance=r.mass_balance,
                    wall_time_s=r.wall_time) for r in runs], out / "squeeze_film.csv")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
    ax[0].plot(ex.t, ex.front, "k-", lw=2, label="exact")
    ax[1].plot(ex.t, ex.load, "k-", lw=2, label="exact")
    for r in runs[:3]:
        ax[0].plot(r.t, r.front, "--", label=f"FE JFO {r.n_x} cells, {r.n_t} steps")
        ax[1].plot(r.t, r.load, "--", label=f"FE JFO {r.n_x} cells, {r.n_t} steps")
    ax[0].set(ylabel="end of the full film x_c [plate lengths]",
              title="Oscillating squeeze film: cavity front and load (JFO)")
    ax[1].set(xlabel="time t", ylabel="load per unit width W", yscale="log")
    ax[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "squeeze_film.png", dpi=130)
    print(f"wrote {out / 'squeeze_film.csv'} and {out / 'squeeze_film.png'}")


if __name__ == "__main__":
    main()
