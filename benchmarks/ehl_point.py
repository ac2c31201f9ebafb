"""The EHL point contact: mesh convergence of the films against Hamrock & Dowson's fits,
and what it costs (time, Newton iterations), the multilevel Newton-Krylov route against
the dense one, plus the dry contact against Hertz.

    python -m benchmarks.ehl_point            # nodes 33 ... 193 (a few minutes)
    python -m benchmarks.ehl_point --quick    # a smoke run (CI)

Steel ball on steel plane, R = 12.7 mm, E' = 226 GPa; a Barus (alpha = 2e-8 1/Pa) and
Dowson-Higginson oil of 0.04 Pa s (G = 4520). The cases sit inside Hamrock & Dowson's
(1977) parameter range for k = 1 (U 1.7e-12 ... 1.7e-11, W 3.7e-7 ... 7.4e-6). All times
in one run; the Richardson lines extrapolate 49, 97, 193 nodes (cells halved each time)
with the measured order.
"""
from __future__ import annotations

import argparse
import contextlib
import math

import numpy as np

from bearingfem import Lubricant, point_contact
from bearingfem.ehl import point
from bearingfem.ehl.pointcontact import hamrock_dowson_point
from bearingfem.ehl.pointspace import dry_point_contact

from .common import best_of

OIL = Lubricant(viscosity=0.04, barus=2e-8, density="dowson-higginson")
R, E = 0.0127, 2.26e11


def case(U, W):
    """(mean speed [m/s], load [N]) of Hamrock's U and W for this ball and oil."""
    return U * E * R / OIL.viscosity, W * E * R**2


def film_rows(cases, grids):
    rows = []
    for U, W in cases:
        u, w = case(U, W)
        fit = hamrock_dowson_point(R, E, OIL.viscosity, u, w, OIL.pressure_viscosity)
        for n in grids:
            t = best_of(lambda: point_contact(radius=R, reduced_modulus=E, lubricant=OIL,
                                              mean_speed=u, load=w, nodes=n))
            r = t.out
            rows.append(dict(U=U, W=W, nodes=n, M=r.moes_M, L=r.moes_L,
                             time=t.wall, iterations=r.iterations,
                             hc_fit=r.film_central / fit.central,
                             hmin_fit=r.film_min / fit.minimum,
                             p_max=r.pressure_max / r.hertz_pressure))
    return rows


@contextlib.contextmanager
def dense_route():
    """Every grid by the dense Newton step (the route before the multilevel one)."""
    saved = point.DENSE_POINT_NODES
    point.DENSE_POINT_NODES = 10**6
    try:
        yield
    finally:
        point.DENSE_POINT_NODES = saved


def route_rows(U, W, grids):
    """The same contact by both routes, back to back in one run."""
    u, w = case(U, W)
    rows = []
    for n in grids:
        def run():
            return point_contact(radius=R, reduced_modulus=E, lubricant=OIL, mean_speed=u,
                                 load=w, nodes=n)
        new = best_of(run)
        with dense_route():
            old = best_of(run)
        rows.append(dict(nodes=n, dense=old.cpu, multilevel=new.cpu,
                         iterations=new.out.iterations,
                         film=np.abs(new.out.film - old.out.film).max() / old.out.film_central))
    return rows


def dry_rows(grids):
    rows = []
    for n in grids:
        t = best_of(lambda: dry_point_contact(n))
        d = t.out
        r = np.hypot(d.x[:, None], d.y[None, :])
        err = np.abs(d.pressure - np.sqrt(np.clip(1 - r**2, 0, None)))
        rows.append(dict(nodes=n, time=t.wall, max_err=err.max(),
                         inner_err=err[r < 0.8].max(), approach_err=abs(d.approach + 1)))
    return rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args(argv)
    grids = (17, 25) if args.quick else (33, 49, 65, 97, 129, 193)
    cases = [(1.683e-11, 3.686e-7)] if args.quick else [(1.683e-11, 3.686e-7), (1.0e-11, 7.37e-7)]
    routes = route_rows(*cases[0], (41,) if args.quick else (49, 97))
    print("Newton step: dense LU (before) vs multilevel Newton-Krylov, one run, CPU time")
    print(f"{'nodes':>5} {'dense [s]':>9} {'multilevel [s]':>14} {'Newton':>6} {'film diff':>9}")
    for r in routes:
        print(f"{r['nodes']:5d} {r['dense']:9.2f} {r['multilevel']:14.2f} {r['iterations']:6d} "
              f"{r['film']:9.1e}")
    print()
    rows = film_rows(cases, grids)
    print("EHL point contact (k = 1) against Hamrock & Dowson (1977)")
    print(f"{'U':>9} {'W':>9} {'nodes':>5} {'M':>6} {'L':>5} {'time s':>7} {'iter':>4} "
          f"{'h_c/fit':>8} {'h_min/fit':>9} {'p_max/p_h':>9}")
    for r in rows:
        print(f"{r['U']:9.3g} {r['W']:9.3g} {r['nodes']:5d} {r['M']:6.1f} {r['L']:5.1f} "
              f"{r['time']:7.2f} {r['iterations']:4d} {r['hc_fit']:8.4f} {r['hmin_fit']:9.4f} "
              f"{r['p_max']:9.4f}")
    for U, W in cases:
        sub = {r["nodes"]: r for r in rows if r["U"] == U and r["W"] == W}
        if all(n in sub for n in (49, 97, 193)):
            for key in ("hc_fit", "hmin_fit", "p_max"):
                a, b, c = (sub[n][key] for n in (49, 97, 193))
                order = math.log(abs((b - a) / (c - b))) / math.log(2.0) if c != b else float("nan")
                limit = c + (c - b) / (2.0**order - 1)
                print(f"U {U:.3g} W {W:.3g}: {key} observed order {order:.2f}, "
                      f"Richardson limit {limit:.4f}")
    dry = dry_rows((13, 25) if args.quick else (13, 25, 49, 97))
    print("\nDry contact against Hertz (P = sqrt(1 - r^2), H0 = -1)")
    print(f"{'nodes':>5} {'time s':>7} {'max err':>9} {'r<0.8 err':>9} {'H0 err':>9}")
    for r in dry:
        print(f"{r['nodes']:5d} {r['time']:7.2f} {r['max_err']:9.2e} {r['inner_err']:9.2e} "
              f"{r['approach_err']:9.2e}")
    return rows + routes


if __name__ == "__main__":
    main()
