"""Accuracy against time of the grooved design chart (Lund & Thomsen's two-groove bearing,
S 10 .. 0.01, 20 points; benchmarks/grooved.py's bearing, in benchmarks/common.py).

    python -m benchmarks.chart_accuracy [--quick]

Each mesh's chart (:func:`bearingfem.design.design_chart`, FE P2, Reynolds' condition,
caches cleared, one run) against the chart on the reference mesh (P2 384x32, or --reference N M;
--quick 192x16). Columns: CPU time [s] of the chart, and over its points the largest relative
error of the position (|d eps| / eps, |d attitude| [rad]) and of the coefficients
(max|dK| / max|K|, max|dB| / max|B|, dimensionless in the load frame), each over all 20
points and over the heavy loads S < 0.1 (eps 0.69 .. 0.94) alone. Rows marked "gr" are on
a theta-graded mesh (the "fem" model's ``grading``, from
:func:`~bearingfem.design.chart_grading`: one mesh for the whole chart).
"""
from __future__ import annotations

import argparse

import numpy as np

from bearingfem.design import chart_grading

from .common import TWO_GROOVE_BEARING, TWO_GROOVE_OMEGA, best_of, two_groove_chart

MESHES = [(24, 4), (48, 8), (96, 8), (96, 16), (192, 8), (192, 16)]
#: theta-graded meshes (:func:`bearingfem.design.chart_grading`: cells towards the heavy
#: loads' minimum film, sized like 1 - 0.9 cos)
GRADED = [(48, 8), (48, 12), (64, 12), (96, 12)]
REFERENCE = (384, 32)


def chart(mesh, grading=None):
    """(the chart on ``mesh``, its cold CPU time [s])."""
    t = best_of(lambda: two_groove_chart(mesh, grading=grading), cold=True)
    return t.out, t.cpu


def errors(ch, ref):
    """Per point: (position error, coefficient error)."""
    pos = [max(abs(p.eps - q.eps) / q.eps, abs(p.attitude - q.attitude))
           for p, q in zip(ch.points, ref.points)]
    kb = [max(np.abs(p.K - q.K).max() / np.abs(q.K).max(),
              np.abs(p.B - q.B).max() / np.abs(q.B).max())
          for p, q in zip(ch.points, ref.points)]
    return np.array(pos), np.array(kb)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="coarser meshes and reference")
    ap.add_argument("--reference", type=int, nargs=2, default=None,
                    help="the reference chart's P2 mesh (default 384 32)")
    args = ap.parse_args(argv)
    meshes = MESHES[:3] if args.quick else MESHES
    ref_mesh = tuple(args.reference) if args.reference else \
        (192, 16) if args.quick else REFERENCE
    ref, t_ref = chart(ref_mesh)
    heavy = np.array([p.sommerfeld < 0.1 for p in ref.points])
    print(f"reference P2 {ref_mesh[0]}x{ref_mesh[1]}: {t_ref:.2f} s CPU")
    print(f"{'mesh':10s} {'CPU [s]':>8s} {'pos. all':>9s} {'pos. S<.1':>9s} {'K,B all':>9s} "
          f"{'K,B S<.1':>9s} {'K,B S>=.1':>9s}")
    rows = []
    grading = chart_grading(TWO_GROOVE_BEARING, TWO_GROOVE_OMEGA)
    runs = [(m, None) for m in meshes] + [(m, grading) for m in
                                          (GRADED[:2] if args.quick else GRADED)]
    for mesh, g in runs:
        ch, t = chart(mesh, g)
        pos, kb = errors(ch, ref)
        rows.append(dict(mesh=mesh, graded=g is not None, cpu_s=t, pos=pos.max(),
                         pos_heavy=pos[heavy].max(), kb=kb.max(), kb_heavy=kb[heavy].max(),
                         kb_light=kb[~heavy].max()))
        name = f"P2 {mesh[0]}x{mesh[1]}" + (" gr" if g is not None else "")
        print(f"{name:13s} {t:8.3f} {pos.max():9.2e} {pos[heavy].max():9.2e} "
              f"{kb.max():9.2e} {kb[heavy].max():9.2e} {kb[~heavy].max():9.2e}", flush=True)
    return rows


if __name__ == "__main__":
    main()
