"""Why K and C of a cavitated film converge irregularly: the discrete cavitation boundary.

    python -m studies.kc_phase          # ~1 min (run it with no other heavy job on the machine)

The FE film's partials are the exact tangent of the discrete film with its cavitated set
held (:func:`bearingfem.fe.grooved.grooved_derivatives`). Two tables on Lund & Thomsen's
two-groove bearing (studies/lund_thomsen.py), P2, Reynolds' condition:

1. ``eps_sweep``: K_xx and C_xx (each relative to its matrix's largest entry) as eps moves
   in steps of 1e-3 about an equilibrium on one mesh, and the nodes whose status (film or
   cavity) changes at the largest jump: the tangent drifts smoothly while the set holds and
   jumps when a node enters or leaves the film.
2. ``phase_table``: K and C on one resolution with the mesh's grading focus moved by a
   fraction of a cell (the grooves' edges stay mesh lines; the nodes near the cavitation
   boundary shift), against the benchmark's reference (P2 288 graded): the error depends on
   where the nodes fall relative to the boundary, like noise in its phase; the mean over the
   phases is far closer than its members.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from bearingfem.design import coefficients, equilibrium
from bearingfem.design.groups import load_from_sommerfeld
from bearingfem.design.tolerance import GRADING_STRENGTH
from bearingfem.fe.grooved import groove_operator_for, grooved_pressure

from .lund_thomsen import GROOVES, LOAD_DIRECTION, OMEGA, bearing, mesh

#: (L/D, S) of the rows shown: the heaviest L/D 1 row first
ROWS = ((1.0, 0.108), (0.5, 0.58), (1.0, 0.159))
#: grading focus offsets [deg] of the phase table (within the search's 15 deg grid)
OFFSETS = (0.0, 2.5, 5.0, 7.5, 10.0, 12.5)
FILM = dict(grooves=GROOVES, cavitation="reynolds", element="P2")


def _state(ld, S):
    b = bearing(ld)
    eq = equilibrium(b, load_from_sommerfeld(b, S, OMEGA), OMEGA, "fem",
                     direction=LOAD_DIRECTION, **mesh(ld, 144, "P2"))
    return b, eq.state


def _reference(b, ld, s):
    """K, C on the benchmark's reference film (P2 288 cells around, graded 0.6)."""
    return coefficients(b, s, "fem", **dict(mesh(ld, 288, "P2"),
                                            grading=(s.gamma, GRADING_STRENGTH)))


def _error(kc, ref) -> float:
    return max(np.abs(kc.K - ref.K).max() / np.abs(ref.K).max(),
               np.abs(kc.C - ref.C).max() / np.abs(ref.C).max())


def eps_sweep(ld=1.0, S=0.108, n_theta=36, steps=10, de=1e-3):
    """(state, [(d eps, K_xx / max|K|, C_xx / max|C|)] on P2 ``n_theta`` uniform about the
    equilibrium, the nodes (mesh angle [deg], z/R, in the film before -> after) that
    change status across the largest jump of K_xx, the grooves' arcs [deg])."""
    b, s = _state(ld, S)
    o = mesh(ld, n_theta, "P2")
    rows = []
    for k in range(-steps, steps + 1):
        kc = coefficients(b, replace(s, eps=s.eps + k * de), "fem", **o)
        rows.append((k * de, kc.K[0, 0] / np.abs(kc.K).max(), kc.C[0, 0] / np.abs(kc.C).max()))
    jumps = np.abs(np.diff([r[1] for r in rows]))
    k = int(np.argmax(jumps))
    gop = groove_operator_for(b, o["n_theta"], o["n_z"], "P2", GROOVES)
    sets = []
    for d in (rows[k][0], rows[k + 1][0]):
        gop.last.clear()
        sets.append(grooved_pressure(gop, b, replace(s, eps=s.eps + d), GROOVES).active)
    m = gop.op.mesh
    changed = [(math.degrees(m.theta[i]), float(m.zeta[i]), not sets[0][i],
                not sets[1][i]) for i in np.flatnonzero(sets[0] != sets[1])]
    return s, rows, changed, [tuple(math.degrees(a) for a in arc) for arc in m.arcs]


def phase_table(levels=(54, 72, 108, 144)):
    """[(L/D, S, n_theta, errors per offset, error of their mean, largest spread)]."""
    out = []
    step = math.pi / 12.0
    for ld, S in ROWS:
        b, s = _state(ld, S)
        ref = _reference(b, ld, s)
        scale = np.concatenate([np.full(4, np.abs(ref.K).max()), np.full(4, np.abs(ref.C).max())])
        r = np.concatenate([ref.K.ravel(), ref.C.ravel()]) / scale
        for nt in levels:
            nz = max(4, 2 * round(nt * ld / math.pi / 2.0))
            v = []
            for off in OFFSETS:
                kc = coefficients(b, s, "fem", n_theta=nt, n_z=nz, **FILM,
                                  grading=(step * round(s.gamma / step) + math.radians(off),
                                           GRADING_STRENGTH))
                v.append(np.concatenate([kc.K.ravel(), kc.C.ravel()]) / scale)
            v = np.array(v)
            errors = np.abs(v - r).max(axis=1)
            out.append((ld, S, nt, errors, float(np.abs(v.mean(axis=0) - r).max()),
                        float((v.max(axis=0) - v.min(axis=0)).max())))
    return out


def main():
    s, rows, changed, arcs = eps_sweep()
    print(f"L/D 1, S 0.108 (eps {s.eps:.4f}), P2 36 x 12 uniform: K_xx, C_xx / largest entry")
    for d, k, c in rows:
        print(f"  d eps {d:+.3f}  K_xx {k:.5f}  C_xx {c:.5f}")
    print("nodes changing status at the largest jump (mesh angle [deg], z/R, in the film "
          "before -> after); the grooves span " + ", ".join(f"{a:.0f}-{b:.0f}" for a, b in arcs)
          + " deg:")
    for a, z, before, after in changed:
        print(f"  {a:6.1f} {z:6.3f}  {before} -> {after}")
    print(f"\nK, C error against P2 288 graded, grading focus moved by {OFFSETS} deg")
    print(f"{'L/D':>4} {'S':>6} {'n_theta':>7}  {'errors per offset':>47}  {'mean':>8} "
          f"{'spread':>8}")
    for ld, S, nt, errors, mean, spread in phase_table():
        print(f"{ld:4g} {S:6g} {nt:7d}  {' '.join(f'{e:7.1e}' for e in errors)}  "
              f"{mean:8.1e} {spread:8.1e}")


if __name__ == "__main__":
    main()
