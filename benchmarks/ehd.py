"""EHD journal film: steady solve time against the rigid film on the seed pin's scene mesh,
ring and solid bush, full and reduced compliance, and what the bush changes.

    python -m benchmarks.ehd            # 192 x 8 cells (solid build ~35 s, ~2-4 min)
    python -m benchmarks.ehd --quick    # smoke run (48 x 4, ring only)

Seed pin: R 10 mm, L/D 0.2, c 20 um, mu 0.0117 Pa s, 250 rad/s; bronze bush E 110 GPa,
nu 0.34, outer radius 16 mm. Two states: eps 0.9 (rigid minimum film 2 um) and eps 0.995
(0.1 um, the heavy state), Reynolds cavitation, cold start (the rigid film, then Newton
with load continuation). The compliance is built once per bush ("build") and passed in,
so "solve" is the film solve alone (one cold call); "ratio" is solve / rigid solve (best
of 5, the default half-length mesh) in the same run. "iters": Newton iterations over all
continuation steps (the rigid rows: active-set iterations). h_min is the least nodal film,
h_mid the least at the mid-plane (a ring bush leaves the unloaded end nodes undeformed).
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from bearingfem import ElasticBush, JournalState, solve_reynolds
from bearingfem.bearing import seed_bearing
from bearingfem.elastic import bush_compliance
from bearingfem.lubricant import Lubricant

BRONZE = dict(outer_radius=0.016, modulus=110e9, poisson=0.34)
OIL = Lubricant(viscosity=0.0117, barus=2e-8, density="dowson-higginson")


def timed(fn, repeat=1):
    """(result, best wall time [s] of ``repeat`` calls)."""
    best = np.inf
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t)
    return out, best


def mid_film(sol):
    """Least film thickness at the mid-plane [m]."""
    return float(np.min(sol.film_thickness[np.abs(sol.z) < 1e-12]))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args(argv)
    n_theta, n_z = (48, 4) if args.quick else (192, 8)
    models = ("ring",) if args.quick else ("ring", "solid")
    vectors = (64,) if args.quick else (64, 256)
    b = seed_bearing(0.2)
    print(f"seed pin, {n_theta} x {n_z} cells, Reynolds cavitation, cold start")
    print(f"{'eps':>6} {'bush':>6} {'compliance':>11} {'oil':>5} {'build[s]':>9} "
          f"{'solve[s]':>9} {'ratio':>7} {'iters':>6} {'p_max[MPa]':>11} "
          f"{'h_min[um]':>10} {'h_mid[um]':>10} {'w_max[um]':>10} {'F[N]':>9}")

    rows = []

    def row(eps, bush, kind, oil, build, sol, t, t_rigid):
        w = 0.0 if sol.deformation is None else float(np.max(sol.deformation))
        rows.append(dict(eps=eps, bush=bush, compliance=kind, oil=oil, solve=t,
                         iterations=sol.iterations, pressure_max=sol.pressure_max,
                         film_mid=mid_film(sol), deflection=w, residual=sol.residual))
        print(f"{eps:6.3f} {bush:>6} {kind:>11} {oil:>5} {build:9.2f} {t:9.3f} "
              f"{t / t_rigid:7.1f} {sol.iterations:6d} {sol.pressure_max / 1e6:11.2f} "
              f"{sol.film_min * 1e6:10.3f} {mid_film(sol) * 1e6:10.3f} {w * 1e6:10.3f} "
              f"{np.hypot(*sol.force):9.1f}")

    comps = {}
    for model in models:
        bush = ElasticBush(model=model, **BRONZE)
        comps[model], build = timed(lambda: bush_compliance(bush, b.radius, b.length,
                                                            n_theta, n_z + 1))
        comps[model + "-build"] = build
    for eps in (0.9, 0.995):
        state = JournalState(eps=eps, gamma=0.0, omega=250.0)
        rigid, t_rigid = timed(lambda: solve_reynolds(b, state, n_theta, n_z), repeat=5)
        row(eps, "-", "-", "-", 0.0, rigid, t_rigid, t_rigid)
        for model in models:
            full = comps[model]
            for kind, comp in [("full", full)] + [(f"reduced {k}", full.reduced(k))
                                                  for k in vectors]:
                sol, t = timed(lambda: solve_reynolds(b, state, n_theta, n_z, bush=comp))
                row(eps, model, kind, "-", comps[model + "-build"] if kind == "full" else 0.0,
                    sol, t, t_rigid)
            sol, t = timed(lambda: solve_reynolds(b, state, n_theta, n_z, bush=full,
                                                  lubricant=OIL))
            row(eps, model, "full", "B+DH", 0.0, sol, t, t_rigid)
    return rows


if __name__ == "__main__":
    main()
