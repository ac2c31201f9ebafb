"""EHD journal film: steady solve time against the rigid JFO film on the seed pin's scene
mesh, cold and warm, full and reduced (modal) compliance, and what the bush changes.

    python -m benchmarks.ehd            # 192 x 8 cells, ring bush (~1 min)
    python -m benchmarks.ehd --solid    # also the solid bush (per harmonic)
    python -m benchmarks.ehd --quick    # smoke run (48 x 4)

Seed pin: R 10 mm, L/D 0.2, c 20 um, mu 0.0117 Pa s, 250 rad/s; bronze bush E 110 GPa,
nu 0.34, outer radius 16 mm. The heavy state eps 0.995 (rigid minimum film 0.1 um),
Reynolds cavitation. "cold": the rigid film, then Newton with load continuation; "warm":
Newton from the solution of a nearby state (eps 0.9955, gamma -0.01 rad: what a time step
of the mechanism moves), the way the "fem-ehd" model calls it. The compliance is built
once per bush and passed in ("build"). Times are the best of 3 calls; "x JFO" divides by
the rigid JFO solve of the same mesh (best of 5) in the same run. "iters": Newton
iterations over all continuation steps.
"""
from __future__ import annotations

import argparse

import numpy as np

from bearingfem import ElasticBush, solve_reynolds
from bearingfem.bearing import seed_bearing
from bearingfem.elastic import bush_compliance
from bearingfem.lubricant import Lubricant

from .common import BRONZE, HEAVY, NEAR, best_of, mid_film

OIL = Lubricant(viscosity=0.0117, barus=2e-8, density="dowson-higginson")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--solid", action="store_true")
    args = parser.parse_args(argv)
    n_theta, n_z = (48, 4) if args.quick else (192, 8)
    models = ("ring", "solid") if args.solid else ("ring",)
    vectors = (32,) if args.quick else (64, 256)
    b = seed_bearing(0.2)
    t_jfo = best_of(lambda: solve_reynolds(b, HEAVY, n_theta, n_z, cavitation="jfo",
                                           ambient_pressure=1e5), 5).wall
    timed = best_of(lambda: solve_reynolds(b, HEAVY, n_theta, n_z), 5)
    rigid, t_rigid = timed.out, timed.wall
    print(f"seed pin, {n_theta} x {n_z} cells, eps {HEAVY.eps}: rigid JFO solve "
          f"{t_jfo * 1e3:.1f} ms, rigid Reynolds (half mesh) {t_rigid * 1e3:.1f} ms")
    print(f"{'bush':>6} {'compliance':>11} {'oil':>5} {'build[s]':>9} {'cold[s]':>8} "
          f"{'iters':>5} {'warm[s]':>8} {'iters':>5} {'x JFO':>6} {'p_max[MPa]':>11} "
          f"{'h_mid[um]':>10} {'w_max[um]':>10} {'h_min[um]':>10} {'|F|[N]':>8}")
    rows = []
    for model in models:
        bush = ElasticBush(model=model, **BRONZE)
        timed = best_of(lambda: bush_compliance(bush, b.radius, b.length, n_theta,
                                                n_z + 1))
        full, build = timed.out, timed.wall
        for kind, comp in [("full", full)] + [(f"modes {k}", full.reduced(k))
                                              for k in vectors]:
            for oil in (None, OIL):
                kw = dict(bush=comp, lubricant=oil)
                near = solve_reynolds(b, NEAR, n_theta, n_z, **kw)
                timed = best_of(lambda: solve_reynolds(b, HEAVY, n_theta, n_z, **kw))
                cold, t_cold = timed.out, timed.wall
                timed = best_of(lambda: solve_reynolds(b, HEAVY, n_theta, n_z,
                                                       start=near, **kw), 3)
                warm, t_warm = timed.out, timed.wall
                w = float(np.max(warm.deformation))
                rows.append(dict(bush=model, compliance=kind, oil=oil is not None,
                                 cold=t_cold, warm=t_warm, ratio=t_warm / t_jfo,
                                 cold_iterations=cold.iterations,
                                 warm_iterations=warm.iterations,
                                 pressure_max=warm.pressure_max, film_mid=mid_film(warm),
                                 deflection=w, residual=warm.residual,
                                 rigid_pressure_max=rigid.pressure_max,
                                 rigid_film_mid=mid_film(rigid), same=float(np.max(np.abs(
                                     warm.pressure - cold.pressure)) / cold.pressure_max)))
                print(f"{model:>6} {kind:>11} {'B+DH' if oil else '-':>5} "
                      f"{build if kind == 'full' else 0.0:9.2f} {t_cold:8.3f} "
                      f"{cold.iterations:5d} {t_warm:8.3f} {warm.iterations:5d} "
                      f"{t_warm / t_jfo:6.1f} {warm.pressure_max / 1e6:11.2f} "
                      f"{mid_film(warm) * 1e6:10.3f} {w * 1e6:10.3f} "
                      f"{warm.film_min * 1e6:10.3f} {np.linalg.norm(warm.force):8.1f}"
                      + ("" if rows[-1]["same"] < 1e-6 else
                         f"  (cold start found another branch: p_max "
                         f"{cold.pressure_max / 1e6:.0f} MPa)"))
    return rows


if __name__ == "__main__":
    main()
