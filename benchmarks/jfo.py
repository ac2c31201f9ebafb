"""What a mass-conserving (JFO) film costs against one linear solve of the same mesh.

    python -m benchmarks.jfo [-o results/benchmarks] [--repeat 5]

The seed bearing (L/D 1) at eps 0.6, 250 rad/s, with a flooded groove at the maximum
film: the steady JFO film (cold: no set from an earlier solve; the mesh's operator is
assembled once for both), the Reynolds-condition film and the full (linear) film on the
same P1 mesh, each the best of ``repeat`` calls in one run. Prints the table and writes
``jfo.csv``. The time-integrated paper case is measured by ``python -m studies.jfo_paper``.
"""
from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from bearingfem import Groove, JournalState, fvm_reynolds, solve_reynolds
from bearingfem.bearing import seed_bearing
from bearingfem.outputs.tables import write_csv

from .common import best_of

MESHES = ((120, 20), (240, 40), (480, 80))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--output", default="results/benchmarks")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--quick", action="store_true", help="the 120x20 mesh only")
    a = ap.parse_args(argv)
    b = seed_bearing(1.0)
    s = JournalState(eps=0.6, omega=250.0)
    g = [Groove(angle=np.pi, width=0.1)]
    rows = []
    print("| mesh | linear [ms] | Reynolds [ms] | JFO [ms] | JFO / linear | JFO iterations | "
          "FV JFO [ms] |")
    print("|---|---|---|---|---|---|---|")
    for nt, nz in MESHES[:1] if a.quick else MESHES:
        solve = lambda cav: solve_reynolds(b, s, nt, nz, cavitation=cav, grooves=g)  # noqa
        solve("jfo")       # assemble the operators once (cached), for every method alike
        t_lin = best_of(lambda: solve("none"), a.repeat).wall
        t_rey = best_of(lambda: solve("reynolds"), a.repeat).wall
        timed = best_of(lambda: solve("jfo"), a.repeat)
        t_jfo, sol = timed.wall, timed.out
        t_fv = best_of(lambda: fvm_reynolds(b, s, nt, nz, "jfo", grooves=g), a.repeat).wall
        rows.append(dict(mesh=f"{nt}x{nz}", linear_ms=1e3 * t_lin, reynolds_ms=1e3 * t_rey,
                         jfo_ms=1e3 * t_jfo, jfo_over_linear=t_jfo / t_lin,
                         jfo_iterations=sol.iterations, fv_jfo_ms=1e3 * t_fv))
        w = rows[-1]
        print(f"| {w['mesh']} | {w['linear_ms']:.1f} | {w['reynolds_ms']:.1f} | "
              f"{w['jfo_ms']:.1f} | {w['jfo_over_linear']:.2f} | {w['jfo_iterations']} | "
              f"{w['fv_jfo_ms']:.1f} |", flush=True)
    out = Path(a.output)
    out.mkdir(parents=True, exist_ok=True)
    write_csv(rows, out / "jfo.csv")
    print(f"wrote {out / 'jfo.csv'}")
    return rows


if __name__ == "__main__":
    main()
