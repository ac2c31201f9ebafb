"""The two-groove film at the limit: Lund & Thomsen's (1978) two-axial-groove bearing,
20 deg grooves across the load (at 0 and 180 deg, load downward), L/D 1, D 0.1 m,
c 100 um, mu 0.02 Pa s, 3000 rpm, Reynolds' condition.

    python -m benchmarks.grooved [--quick] [--repeat N]

The film at the limit (one run, best of ``repeat``): one static film at eps 0.6, journal
angle -45 deg (as benchmarks/ross31.py) - "build" the first solve on a mesh (mesh, operator
and the seven harmonic tables), "new angle" a cold solve at a journal angle not seen before
(tables reused, the cavitated set from the coarser levels), "warm" a new angle started from
the previous angle's cavitated set (fe_force's ``warm``, as in time integration), "moving
mesh" the route before: a mesh and operator built per journal angle; equilibrium + K/C at
S 0.635 (cold: caches cleared; warm: tables built); the design chart (S 10..0.01, 20
points). Errors against P2 192x32 (the chart: the largest over its points, against P2
144x24). The rows are :func:`benchmarks.common.two_groove_rows`, which gives the same
numbers to benchmarks/ross31.py.
"""
from __future__ import annotations

import argparse
import math

from .common import STATIC, two_groove_rows


def print_rows(rows):
    print(f"{'case':18s} {'mesh':10s} {'error':>9s} {'time [ms]':>10s} {'warm [ms]':>10s} "
          f"{'cpu [ms]':>10s} {'build [ms]':>10s} {'film [ms]':>10s} {'before [ms]':>10s}")
    for r in rows:
        extra = "".join(f" {1e3 * r[k]:10.2f}" if k in r else f" {'':10s}"
                        for k in ("cpu_s", "build_s", "solution_s", "before_s"))
        print(f"{r['case']:18s} {r['mesh']:10s} {r['error']:9.2e} {1e3 * r['time_s']:10.2f} "
              f"{1e3 * r['warm_s']:10.2f}{extra}")


def main(argv=None):
    ap = argparse.ArgumentParser(description="grooved films at the limit")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="fewer meshes, coarse reference")
    args = ap.parse_args(argv)
    rows, _ = two_groove_rows(args.quick, args.repeat)
    print(f"Lund & Thomsen two-groove bearing, L/D 1, 3000 rpm; static film at eps "
          f"{STATIC[0]}, journal angle {math.degrees(STATIC[1]):g} deg; equilibrium at "
          f"S 0.635; chart S 10..0.01, 20 points")
    print_rows(rows)
    return rows


if __name__ == "__main__":
    main()
