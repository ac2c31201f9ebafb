"""Effectivity of the film-force error estimate (bearingfem.accuracy): estimate / true error
over meshes, states, elements and cavitation models, the true error against a converged
film (P2 on 384 x 64 cells, within ~3e-6 of the 768 x 128 film at eps <= 0.9).

    python -m studies.effectivity          # ~2 min (run under the heavy-work lock)

Prints one row per (state, element, mesh) and the least and largest effectivity per
element and cavitation model: the estimate is meant to err high (effectivity >= 1).
"""
from __future__ import annotations

import itertools

import numpy as np

from bearingfem import Bearing, JournalState, solve_reynolds
from bearingfem.accuracy import estimate_error, force_difference, nominal_order

LEVELS = {"P1": [(24 * 2 ** k, 4 * 2 ** k) for k in range(4)],     # 24 x 4 .. 192 x 32
          "P2": [(12 * 2 ** k, 2 * 2 ** k) for k in range(4)]}     # 12 x 2 .. 96 x 16
REFERENCE = (384, 64)
FLOOR = 5e-5     # true errors below this are within reach of the reference's own error


def effectivities(ld, eps, cavitation, element):
    """[(mesh, estimate, true error)] along the element's mesh sequence at one state."""
    b = Bearing(radius=0.01, length=0.02 * ld, clearance=20e-6, viscosity=0.0117)
    s = JournalState(eps=eps, omega=250.0)
    ref = solve_reynolds(b, s, *REFERENCE, "P2", cavitation)
    sols = [solve_reynolds(b, s, nt, nz, element, cavitation) for nt, nz in LEVELS[element]]
    order = nominal_order(element, cavitation == "none")
    rows = []
    diffs = [None] + [force_difference(f, c) for c, f in zip(sols, sols[1:])]
    for k in range(1, len(sols)):
        # as the search does: the observed order from three meshes once there are three
        est, _ = (estimate_error([1.0, 2.0, 4.0], [diffs[k - 1], diffs[k]], order) if k >= 2
                  else estimate_error([1.0, 2.0], [diffs[k]], order))
        true = force_difference(ref, sols[k])    # |F_ref - F_h| / |F_ref|
        rows.append((LEVELS[element][k], est, true))
    return rows


def main():
    table = {}
    print(f"{'L/D':>4} {'eps':>5} {'cavitation':>10} {'el':>3} {'mesh':>9} "
          f"{'estimate':>9} {'true':>9} {'eff':>6}")
    for ld, eps, cav, el in itertools.product((0.25, 1.0), (0.3, 0.6, 0.9),
                                              ("none", "gumbel", "reynolds"), ("P1", "P2")):
        for mesh, est, true in effectivities(ld, eps, cav, el):
            if true < FLOOR:
                continue
            eff = est / true
            table.setdefault((el, cav), []).append(eff)
            print(f"{ld:4.2f} {eps:5.2f} {cav:>10} {el:>3} {mesh[0]:4d}x{mesh[1]:<4d} "
                  f"{est:9.2e} {true:9.2e} {eff:6.2f}")
    print("\nelement cavitation  pairs  least  median  largest effectivity")
    for (el, cav), e in sorted(table.items()):
        print(f"{el:>7} {cav:>10} {len(e):6d} {min(e):6.2f} {np.median(e):7.2f} {max(e):8.2f}")


if __name__ == "__main__":
    main()
