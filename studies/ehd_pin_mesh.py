"""Which mesh direction does the crowned seed pin's least film need? The steady EHD film
at the run's eccentricities near top dead centre (the pin's relative speed 62.5 rad/s;
eps 0.99 and 1.02; the runs of docs/ehd-states.md reach 1.29 under a 3500 N joint load,
carried by the squeeze, which the steady film has not: beyond eps ~1.025 the steady solve
stops, the bush not opening the gap further), the 3-D-equivalent per-harmonic solid bronze bush of
``paper-short-ehd-sharp``, a 2 um crown over the whole length, the benchmarks' isoviscous oil
with Dowson-Higginson density, Reynolds' condition, no summits; theta and z refined
separately: load |F|, peak pressure, least film and where it sits (|z|/L, theta from the
film's origin), wall time, one run.

    python -m studies.ehd_pin_mesh [--eps 0.99 1.02] [--meshes 48 4 48 16 96 8 ...]
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from bearingfem import ElasticBush, solve_reynolds
from bearingfem.bearing import ElasticJournalState, seed_bearing
from bearingfem.fields import EdgeProfile

from benchmarks.common import OILS

BUSH = ElasticBush(outer_radius=0.016, modulus=110e9, poisson=0.34, model="solid")
CROWN = EdgeProfile("crown", 2e-6)
MESHES = [48, 4, 48, 16, 96, 8]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--eps", type=float, nargs="+", default=[0.99, 1.02])
    ap.add_argument("--omega", type=float, default=62.5)
    ap.add_argument("--meshes", type=int, nargs="+", default=MESHES)
    a = ap.parse_args(argv)
    b = seed_bearing(0.2)
    print(f"{'eps':>5} {'mesh':>8} {'|F| [N]':>8} {'p_max[MPa]':>10} {'h_min[um]':>9} "
          f"{'|z|/L':>6} {'theta[deg]':>10} {'wall[s]':>7}", flush=True)
    for eps in a.eps:
        state = ElasticJournalState(eps=eps, gamma=0.0, omega=a.omega)
        for nt, nz in zip(a.meshes[::2], a.meshes[1::2]):
            t = time.perf_counter()
            sol = solve_reynolds(b, state, nt, nz, bush=BUSH, profile=CROWN,
                                 lubricant=OILS["iso"])
            s = time.perf_counter() - t
            i = int(np.argmin(sol.film_thickness))
            print(f"{eps:5.2f} {nt:>4}x{nz:<3} {np.hypot(*sol.force_local):8.1f} "
                  f"{sol.pressure_max / 1e6:10.2f} {sol.film_thickness[i] * 1e6:9.4f} "
                  f"{abs(float(sol.z[i])) / b.length:6.3f} "
                  f"{np.degrees(float(sol.theta[i])):10.1f} {s:7.2f}", flush=True)


if __name__ == "__main__":
    main()
