"""Which factor keeps the seed pin's EHD run at 250 rad/s from converging in film step:
the coupling between film steps or the oil law.

    python -m benchmarks.ehd_step [--turns 0.1] [--mesh 48 4] [--modes 16]
        [--steps 2e-4 1e-4 5e-5] [--oils barus roelands iso]

The ``paper-short-ehd-sharp`` scene (sharp bore, modal film) from top dead centre with its
oil replaced by the Barus oil (alpha 2e-8 1/Pa), a Roelands oil of the same
pressure-viscosity coefficient at p = 0 (Z = 2e-8 / ((ln mu0 + 9.67) 5.1e-9) = 0.751) or an
isoviscous one (all with the Dowson-Higginson density), each at the film steps ``--steps``.
Per run: peak eps, the least elastic film and peak pressure over the film steps, and "dF":
the largest distance [N] of the joint force along the run from the next finer film step's
(interpolated in time onto the finer run's samples), with "d_orbit" [um] likewise. A
first-order scheme halves dF and d_orbit with the film step.
"""
from __future__ import annotations

import argparse

import numpy as np

from mechanism import simulate
from mechanism.result import film_column

from .common import OILS, best_of, scene




def run(oil, film_step, turns, nt, nz, modes, coupling="kept", speed=250.0):
    sc = scene("paper-short-ehd-sharp", speed, turns, n_theta=nt, n_z=nz, modes=modes,
               film_step=film_step, lubricant=OILS[oil], coupling=coupling)
    return best_of(lambda: simulate(sc, progress=False))


def distance(fine, coarse, x, y):
    """Largest distance between two runs' (x, y) curves on the finer run's samples."""
    return float(np.max(np.hypot(np.interp(fine.t, coarse.t, getattr(coarse, x))
                                 - getattr(fine, x),
                                 np.interp(fine.t, coarse.t, getattr(coarse, y))
                                 - getattr(fine, y))))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--turns", type=float, default=0.1)
    ap.add_argument("--mesh", type=int, nargs=2, default=(48, 4))
    ap.add_argument("--modes", type=int, default=16)
    ap.add_argument("--steps", type=float, nargs="+", default=(2e-4, 1e-4, 5e-5))
    ap.add_argument("--oils", nargs="+", default=tuple(OILS))
    ap.add_argument("--coupling", choices=("kept", "tangent"), default="kept")
    a = ap.parse_args(argv)
    nt, nz = a.mesh
    print(f"seed pin, 250 rad/s, {a.turns:g} turn from TDC, {nt} x {nz}, {a.modes} modes, "
          f"{a.coupling} coupling",
          flush=True)
    print(f"{'oil':>9} {'film step':>9} {'wall[s]':>8} {'steps':>6} {'peak eps':>9} "
          f"{'p_max[MPa]':>11} {'h_min[um]':>9} {'dF[N]':>8} {'d_orbit[um]':>11}", flush=True)
    rows = []
    for oil in a.oils:
        runs = []
        for fs in a.steps:
            t = run(oil, fs, a.turns, nt, nz, a.modes, a.coupling)
            runs.append((fs, t.out, t.wall))
        for i, (fs, r, t) in enumerate(runs):
            rec = r.film_record
            p = float(np.nanmax(film_column(rec, "pressure_max"))) if len(rec) else np.nan
            h = float(np.nanmin(film_column(rec, "film_min"))) if len(rec) else np.nan
            dF = dO = np.nan
            if i + 1 < len(runs) and not r.partial and not runs[i + 1][1].partial:
                fine = runs[i + 1][1]
                dF = distance(fine, r, "force_x", "force_y")
                dO = 1e6 * distance(fine, r, "e_x", "e_y")
            row = dict(oil=oil, film_step=fs, wall=t, steps=r.stats["steps"],
                       peak_eps=float(r.eps.max()) if len(r.t) else np.nan, pressure_max=p, film_min=h, dF=dF,
                       d_orbit=dO, completed=not r.partial)
            rows.append(row)
            print(f"{oil:>9} {fs:9.3g} {t:8.1f} {row['steps']:6d} {row['peak_eps']:9.4f} "
                  f"{p / 1e6:11.1f} {1e6 * h:9.4f} {dF:8.2f} {dO:11.4f}"
                  + ("" if not r.partial else f"  ({r.message})"), flush=True)
    return rows


if __name__ == "__main__":
    main()
