"""Effectivity of the film-force error estimate (bearingfem.accuracy): estimate / true error
over meshes, states, elements and cavitation models, the true error against a converged
film (P2 on 384 x 64 cells, within ~3e-6 of the 768 x 128 film at eps <= 0.9).

    python -m studies.effectivity                 # ~2 min (run it with no other heavy job on the machine)
    python -m studies.effectivity --coefficients  # K and C on Lund & Thomsen's rows, ~2 min

Prints one row per (state, element, mesh) and the least and largest effectivity per
element and cavitation model: the estimate is meant to err high (effectivity >= 1).

``--coefficients``: the same for K and C (``coefficients(estimate=True)``: the h/2h pair
with the half mesh, at the order :mod:`bearingfem.design.coefficients` uses) of the
two-groove bearing at Lund & Thomsen's ten equilibria (studies/lund_thomsen.py), P2 on
uniform meshes and on meshes graded toward the least film as the search grades them,
against P2 on 288 cells around graded (benchmarks/accuracy_rtol.py's reference). On the
graded meshes also the estimate with a second half-mesh partner whose grading focus is
moved by 7.5 deg (its nodes shifted against the cavitation boundary, studies/kc_phase.py).
"""
from __future__ import annotations

import argparse
import itertools
import math

import numpy as np

from bearingfem import Bearing, JournalState, solve_reynolds
from bearingfem.accuracy import estimate_error, force_difference, nominal_order
from bearingfem.design import coefficients, equilibrium
from bearingfem.design.groups import load_from_sommerfeld
from bearingfem.design.tolerance import GRADING_STRENGTH

from .lund_thomsen import GROOVES, LOAD_DIRECTION, OMEGA, TABLE, bearing
from .lund_thomsen import mesh as study_mesh

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


#: cells around of the coefficients' meshes (multiples of 18: nodes on the grooves' edges)
KC_LEVELS = (72, 108, 144, 216)
#: the second partner's grading focus moved by half the search's 15 deg grid [rad]
SHIFT = math.radians(7.5)


def coefficient_effectivities(progress=print):
    """[(L/D, S, graded, mesh, estimate, true error)] of K and C (the larger of the two
    matrices' largest-entry errors, relative to each one's largest entry) at Lund &
    Thomsen's ten equilibria."""
    film = dict(grooves=GROOVES, cavitation="reynolds", element="P2")
    rows = []
    for ld, table in TABLE.items():
        for S, *_ in table:
            b = bearing(ld)
            eq = equilibrium(b, load_from_sommerfeld(b, S, OMEGA), OMEGA, "fem",
                             direction=LOAD_DIRECTION, **study_mesh(ld, 144, "P2"))
            s = eq.state
            step = math.pi / 12.0       # the search's grading: the angle on a 15 deg grid
            grading = (step * round(s.gamma / step), GRADING_STRENGTH)
            reference = dict(study_mesh(ld, 288, "P2"), grading=(s.gamma, GRADING_STRENGTH))
            ref = coefficients(b, s, "fem", **reference)
            for graded, nt in itertools.product((False, True), KC_LEVELS):
                nz = max(4, 2 * round(nt * ld / math.pi / 2.0))
                o = dict(film, n_theta=nt, n_z=nz, **({"grading": grading} if graded else {}))
                kc = coefficients(b, s, "fem", estimate=True, **o)
                true = _kc_difference(kc, ref)
                two = None
                if graded:
                    # a second half-mesh partner, its nodes shifted against the boundary
                    o2 = dict(o, n_theta=kc.accuracy.partner[0], n_z=kc.accuracy.partner[1],
                              grading=(grading[0] + SHIFT, GRADING_STRENGTH))
                    two = max(kc.error, kc.accuracy.factor
                              * _kc_difference(kc, coefficients(b, s, "fem", **o2)))
                rows.append((ld, S, graded, (nt, nz), kc.error, true, two))
                progress(f"{ld:4g} {S:6g} {'graded' if graded else 'uniform':>8} "
                         f"{nt:4d}x{nz:<3d} {kc.error:9.2e} {true:9.2e} {kc.error / true:7.2f}"
                         + ("" if two is None else f" {two:9.2e} {two / true:7.2f}"))
    return rows


def _kc_difference(kc, other) -> float:
    """The larger of max|dK| / max|K| and max|dC| / max|C| (``kc``'s largest entries)."""
    return max(np.abs(kc.K - other.K).max() / np.abs(kc.K).max(),
               np.abs(kc.C - other.C).max() / np.abs(kc.C).max())


def coefficients_main():
    print(f"{'L/D':>4} {'S':>6} {'mesh':>8} {'':>8} {'estimate':>9} {'true':>9} {'eff':>7} "
          f"{'2 partners':>10} {'eff':>7}")
    rows = coefficient_effectivities()
    print("\n mesh     pairs  least  median effectivity  largest true error  low (< 1)")
    for nt in KC_LEVELS:
        e = [(est / true, true) for _, _, _, m, est, true, _ in rows if m[0] == nt]
        eff = [x for x, _ in e]
        print(f"{nt:5d}   {len(e):6d} {min(eff):6.2f} {np.median(eff):7.2f} "
              f"{max(t for _, t in e):19.2e} {sum(x < 1.0 for x in eff):10d}")
    graded = [(est / true, two / true, two / est) for *_, est, true, two in rows
              if two is not None]
    one, two, ratio = (np.array(v) for v in zip(*graded))
    print(f"\ngraded meshes, {len(graded)} pairs: the pair's least effectivity {one.min():.2f} "
          f"({int(np.sum(one < 1.0))} below 1); with a second partner shifted "
          f"{math.degrees(SHIFT):g} deg: {two.min():.2f} ({int(np.sum(two < 1.0))} below 1), "
          f"the estimate {np.median(ratio):.2f}x the pair's (median)")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--coefficients", action="store_true",
                   help="K and C on Lund & Thomsen's rows instead of the film force")
    if p.parse_args(argv).coefficients:
        return coefficients_main()
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
