"""Where the implicit-step EHD film's evaluations go along the crowned seed pin's run:
per band of crank angle, the film solves, the film evaluations (one EHD residual and the
bush's rate each), their CPU, and the solves that took over 20 evaluations (those where
chord and Newton from the warm start stalled and the continuation in the deflection's
step took over).

    python -m benchmarks.ehd_implicit_evaluations [--turns 0.6] [--mesh 48 4] [--band 30]

The run of benchmarks/ehd_implicit.py (tau 1e-5 s, rtol 1e-6); one process. The band is
the crank angle at the solve's trial time, read from the run's own crank speed at the
start (250 rad/s: the band is approximate where the crank speed varies).
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from bearingfem.ehd.implicit import ImplicitStepEHD

from .ehd_implicit import implicit_run

#: A solve that took more evaluations than this: the warm start failed.
SLOW = 20


def record(rows):
    """ImplicitStepEHD.solve wrapped to append (t, evaluations, CPU [s]) per solve."""
    solve = ImplicitStepEHD.solve

    def counted(self, state, t):
        n0, c0 = self.evaluations, time.process_time()
        try:
            return solve(self, state, t)
        finally:
            rows.append((float(t), self.evaluations - n0, time.process_time() - c0))
    ImplicitStepEHD.solve = counted
    return lambda: setattr(ImplicitStepEHD, "solve", solve)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--turns", type=float, default=0.6)
    ap.add_argument("--mesh", type=int, nargs=2, default=[48, 4])
    ap.add_argument("--band", type=float, default=30.0, help="crank angle band [deg]")
    a = ap.parse_args(argv)
    rows = []
    undo = record(rows)
    try:
        r, cpu = implicit_run(a.turns, *a.mesh, 1e-5, 1e-6)
    finally:
        undo()
    t, n, c = (np.array(x) for x in zip(*rows))
    deg = np.degrees(250.0 * t)
    print(f"{a.mesh[0]} x {a.mesh[1]}, {a.turns:g} turn: {r.stats['steps']} steps, "
          f"{r.stats['rhs_evals']} right-hand sides, {len(t)} solves, {int(n.sum())} "
          f"evaluations, {cpu:.1f} s CPU" + ("  (partial)" if r.partial else ""))
    print(f"{'crank[deg]':>11} {'solves':>6} {'evals':>6} {'CPU[s]':>7} {'slow':>5} "
          f"{'their evals':>11} {'their CPU[s]':>12} {'most':>5}")
    for lo in np.arange(0.0, deg.max() + a.band, a.band):
        m = (deg >= lo) & (deg < lo + a.band)
        if not m.any():
            continue
        slow = m & (n > SLOW)
        print(f"{lo:5.0f}-{lo + a.band:<5.0f} {m.sum():6d} {int(n[m].sum()):6d} "
              f"{c[m].sum():7.1f} {slow.sum():5d} {int(n[slow].sum()):11d} "
              f"{c[slow].sum():12.1f} {int(n[m].max()):5d}")
    slow = n > SLOW
    print(f"{'all':>11} {len(t):6d} {int(n.sum()):6d} {c.sum():7.1f} {slow.sum():5d} "
          f"{int(n[slow].sum()):11d} {c[slow].sum():12.1f} {int(n.max()):5d}")


if __name__ == "__main__":
    main()
