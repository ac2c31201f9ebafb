"""EHD film with JFO cavitation: steady solve time against the rigid JFO film and the EHD
Reynolds film on the seed pin's heavy state (the rows of benchmarks/ehd.py for the
mass-conserving film).

    python -m benchmarks.ehd_jfo            # 192 x 8 cells, ring bush, 64 modes
    python -m benchmarks.ehd_jfo --quick    # smoke run (48 x 4, 32 modes)

Seed pin (benchmarks/ehd.py): R 10 mm, L/D 0.2, c 20 um, mu 0.0117 Pa s, 250 rad/s,
bronze ring bush, eps 0.995, ambient 0.1 MPa at the ends. Rows: the rigid JFO solve
(whole length, the mesh the EHD film needs; and the half mesh's fast path), EHD-Reynolds
cold (rigid start, continuation) and warm (from the solution of eps 0.9955, gamma -0.01)
and EHD-JFO cold (the rigid JFO film, then continuation) and warm (from its solution of
the same nearby state), each with the compliance
reduced to its leading modes and full. Times are the best of ``repeat`` calls in one run;
"x JFO" divides by the rigid JFO solve of the same whole-length mesh.
"""
from __future__ import annotations

import argparse

import numpy as np

from bearingfem import ElasticBush, solve_reynolds
from bearingfem.bearing import seed_bearing
from bearingfem.elastic import bush_compliance

from .common import BRONZE, HEAVY, NEAR, best_of, mid_film


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args(argv)
    n_theta, n_z = (48, 4) if args.quick else (192, 8)
    modes = 32 if args.quick else 64
    repeat = 1 if args.quick else 3
    b = seed_bearing(0.2)
    supply = dict(cavitation="jfo", ambient_pressure=1e5)
    timed = best_of(lambda: solve_reynolds(b, HEAVY, n_theta, n_z, half=False, **supply),
                    repeat + 2)
    jfo, t_jfo = timed.out, timed.wall
    t_fast = best_of(lambda: solve_reynolds(b, HEAVY, n_theta, n_z, **supply),
                     repeat + 2).wall
    full = bush_compliance(ElasticBush(model="ring", **BRONZE), b.radius, b.length, n_theta,
                           n_z + 1)
    print(f"seed pin, {n_theta} x {n_z} cells, eps {HEAVY.eps}: rigid JFO whole length "
          f"{t_jfo * 1e3:.1f} ms (half mesh {t_fast * 1e3:.1f} ms), p_max "
          f"{jfo.pressure_max / 1e6:.1f} MPa, h_mid {mid_film(jfo) * 1e6:.3f} um")
    print(f"{'film':>16} {'compliance':>10} {'time[s]':>8} {'iters':>5} {'x JFO':>6} "
          f"{'p_max[MPa]':>11} {'h_mid[um]':>10} {'cav[%]':>7} {'F[N]':>8}")
    rows = []
    for kind, comp in ((f"modes {modes}", full.reduced(modes)), ("full", full)):
        near = solve_reynolds(b, NEAR, n_theta, n_z, bush=comp)
        near_jfo = solve_reynolds(b, NEAR, n_theta, n_z, bush=comp, **supply)
        runs = (
            ("EHD-Reynolds cold", lambda: solve_reynolds(b, HEAVY, n_theta, n_z, bush=comp)),
            ("EHD-Reynolds warm", lambda: solve_reynolds(b, HEAVY, n_theta, n_z, bush=comp,
                                                         start=near)),
            ("EHD-JFO cold", lambda: solve_reynolds(b, HEAVY, n_theta, n_z, bush=comp,
                                                    **supply)),
            ("EHD-JFO warm", lambda: solve_reynolds(b, HEAVY, n_theta, n_z, bush=comp,
                                                    start=near_jfo, **supply)))
        for name, fn in runs:
            timed = best_of(fn, repeat)
            sol, t = timed.out, timed.wall
            rows.append(dict(film=name, compliance=kind, time=t, ratio=t / t_jfo,
                             iterations=sol.iterations, pressure_max=sol.pressure_max,
                             film_mid=mid_film(sol), cavitated=sol.cavitated_fraction,
                             force=float(np.hypot(*sol.force)),
                             rigid_pressure_max=jfo.pressure_max,
                             rigid_film_mid=mid_film(jfo)))
            print(f"{name:>16} {kind:>10} {t:8.3f} {sol.iterations:5d} {t / t_jfo:6.1f} "
                  f"{sol.pressure_max / 1e6:11.2f} {mid_film(sol) * 1e6:10.3f} "
                  f"{100 * sol.cavitated_fraction:7.1f} {rows[-1]['force']:8.1f}")
    return rows


if __name__ == "__main__":
    main()
