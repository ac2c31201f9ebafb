"""A mesh fitted to the cavitation boundary: do the force, K and C then converge regularly?

    python -m studies.kc_fitted             # ~1.5 min CPU (run it with no other heavy job on the machine)
    python -m studies.kc_fitted --quick     # two rows, three levels, P2
    python -m studies.kc_fitted --rows 0 9 --elements P2
    python -m studies.kc_fitted --band      # the band-fitted film's cost, five rows, ~1 min

With Reynolds' condition p = dp/dn = 0 on the rupture boundary theta_c(z), and the first
variation of the film solves the linearised Reynolds equation on the full-film region
with zero pressure on that boundary (the boundary's motion contributes nothing to first
order). The FE film's K and C (the held set's tangent) put that boundary on the first
cavitated node instead, a staircase whose steps move when a node joins or leaves the
film: their error jumps (studies/kc_phase.py). Here the boundary is made a mesh line:

1. solve the film on the mesh (the LCP);
2. on each axial row of nodes and each pad, the pressurised run about the pad's peak;
   where it ends inside the pad (not at a groove) its free end theta_c is where
   sqrt(p), linear through the run's last two nodes, vanishes (p ~ a (theta - theta_c)^2
   near the boundary);
3. one column of vertices per free boundary (the nearest to the boundary's median) is
   moved row by row onto theta_c(z_j), the other vertices of the row mapped piecewise
   linearly between it and the pad's ends (the grooves' edges stay);
4. on the fitted mesh the film is the linear film on the region inside the fitted
   columns, zero pressure on and beyond them (in pads without a fitted boundary the
   LCP's cavitated set); the column then moves to the vertex of the quadratic through its
   node and the two before it on each row (where dp/dtheta = 0), by secant steps per row,
   and steps 3-4 repeat (:data:`FIT_ITERATIONS` operators built);
5. force and partials of that film (the held set's tangent, the same right-hand sides as
   :func:`bearingfem.fe.grooved.grooved_derivatives`), K and C in the inertial frame.

Tables, on Lund & Thomsen's ten rows (studies/lund_thomsen.py) at the states of P2 144
equilibria, P1 and P2 on 36 .. 144 cells around, graded as a search grades them (toward
the least film from eps 0.3 on, uniform below), the film on the mesh ("plain", the LCP's
held set) and fitted: errors of the force (|dF| / |F|) and of K, C (the larger of the two
largest-entry errors, each relative to its matrix's largest entry) against (a) the
benchmark's reference (P2 288 graded, plain) and (b) the fitted P2 288 graded as the
meshes, with the observed orders between consecutive levels; the h/2h pairs' estimates
(order 1 for plain, as the search; 2 for fitted) against the true error; the first pair a
search at rtol 2e-3 would accept and what its two films cost (CPU). ``--band``: the same
fit moving only a band of columns about each boundary, its operator updated in the band's
cells alone (:class:`BandFit`), errors and CPU beside the full fit's. docs/accuracy.md, *A
mesh fitted to the cavitation boundary*, has the numbers.

The fitted mesh is studies/kc_fitted_mesh.py (its band-only form kc_fitted_band.py), the
film on it kc_fitted_film.py; the tables are this module's.
"""
from __future__ import annotations

import argparse
import math

import numpy as np

from bearingfem.design import equilibrium
from bearingfem.design.groups import load_from_sommerfeld
from bearingfem.design.tolerance import GRADED_FROM_EPS, GRADING_STRENGTH

from .kc_fitted_film import films
from .lund_thomsen import LOAD_DIRECTION, OMEGA, TABLE, bearing, mesh

#: cells around of the levels compared (multiples of 18: nodes on the grooves' edges)
LEVELS = (36, 54, 72, 108, 144)
REFERENCE = 288


def _errors(out, ref):
    F, K, C = out
    F0, K0, C0 = ref
    return (float(np.linalg.norm(F - F0) / np.linalg.norm(F0)),
            float(max(np.abs(K - K0).max() / np.abs(K0).max(),
                      np.abs(C - C0).max() / np.abs(C0).max())))


def _nz(ld, n):
    return max(4, round(n * ld / 3))


def reference_grading(state):
    """The grading of the meshes (and the reference) at ``state``: toward the least film
    (the search's, its angle on the 15 deg grid) from GRADED_FROM_EPS on, else None."""
    if state.eps < GRADED_FROM_EPS:
        return None
    step = math.pi / 12.0
    return (step * round(state.gamma / step), GRADING_STRENGTH)


def study(levels=LEVELS, elements=("P2", "P1"), select=None):
    """[(L/D, S, eps, element, n_theta, {"plain"|"fitted": (F, K, C)}, the fit's last
    move [rad], fitted columns, (LCP + plain tangent, plus the fit) seconds)] on the
    meshes graded as a search grades them (:func:`reference_grading`), and per row the
    references {"benchmark": (F, K, C) of P2 288 graded unfitted (the benchmark's),
    "fitted": the fitted P2 288 graded as the meshes}."""
    out, refs = [], {}
    cases = [(ld, S) for ld, table in TABLE.items() for S, *_ in table]
    for i, (ld, S) in enumerate(cases):
        if select is not None and i not in select:
            continue
        b = bearing(ld)
        s = equilibrium(b, load_from_sommerfeld(b, S, OMEGA), OMEGA, "fem",
                        direction=LOAD_DIRECTION, **mesh(ld, 144, "P2")).state
        grading = reference_grading(s)
        bench, _, _, _ = films(b, s, REFERENCE, _nz(ld, REFERENCE), "P2",
                               (s.gamma, GRADING_STRENGTH), iterations=0)
        fitted, _, _, _ = films(b, s, REFERENCE, _nz(ld, REFERENCE), "P2", grading)
        refs[(ld, S)] = {"benchmark": bench["plain"], "fitted": fitted["fitted"]}
        for el in elements:
            for n in levels:
                f, move, ncols, dt = films(b, s, n, _nz(ld, n), el, grading)
                out.append((ld, S, s.eps, el, n, f, move, ncols, dt))
    return out, refs


def _orders(errs, levels):
    return [math.log(a / b) / math.log(n2 / n1) if a > 0 and b > 0 else float("nan")
            for a, b, n1, n2 in zip(errs[:-1], errs[1:], levels[:-1], levels[1:])]


#: the order and safety factor an h/2h pair's estimate would use: the search's (order 1
#: for the held set's K and C, accuracy.py's SAFETY 1.5) and order 2 for the fitted film
PAIR_ORDER = {"plain": 1.0, "fitted": 2.0}
SAFETY = 1.5
#: the first pair (n / 2n) whose estimate is within this is what a search would accept
SEARCH_RTOL = 2e-3


#: the rows of the band table (:func:`band_table`): a light one and the graded ones
BAND_ROWS = ((0.5, 1.656), (0.5, 0.58), (0.5, 0.244), (1.0, 0.235), (1.0, 0.108))


def band_table(levels=LEVELS):
    """[(L/D, S, n_theta, (plain error, seconds), (fitted error, seconds), (band-fitted
    error, seconds))]: K, C errors against the fitted P2 288 (graded as the meshes) and
    CPU of one film (the second of two calls: the base operator built): the LCP and
    its tangent; with the fit; with the fit moving only a band (:class:`BandFit`)."""
    out = []
    for ld, S in BAND_ROWS:
        b = bearing(ld)
        s = equilibrium(b, load_from_sommerfeld(b, S, OMEGA), OMEGA, "fem",
                        direction=LOAD_DIRECTION, **mesh(ld, 144, "P2")).state
        g = reference_grading(s)
        ref = films(b, s, REFERENCE, _nz(ld, REFERENCE), "P2", g)[0]["fitted"]
        for n in levels:
            row = []
            for band in (False, True):
                films(b, s, n, _nz(ld, n), "P2", g, band=band)
                f, _, _, dt = films(b, s, n, _nz(ld, n), "P2", g, band=band)
                row.append((_errors(f["fitted"], ref)[1], dt[1]))
            out.append((ld, S, n, (_errors(f["plain"], ref)[1], dt[0]), *row))
    return out


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true")
    p.add_argument("--band", action="store_true",
                   help="the band-fitted film's errors and cost beside the fitted one's")
    p.add_argument("--rows", type=int, nargs="*", help="the rows (0-9) shown; all by default")
    p.add_argument("--elements", nargs="*", default=["P2", "P1"])
    a = p.parse_args(argv)
    n_rows = sum(len(table) for table in TABLE.values())
    if a.rows and not all(0 <= r < n_rows for r in a.rows):
        p.error(f"--rows must lie in 0..{n_rows - 1}, got {a.rows}")
    if a.band:
        print("K, C error against the fitted P2 288 and CPU of one film: plain (LCP and "
              "tangent), fitted, band-fitted")
        for ld, S, n, plain, fitted, band in band_table():
            print(f"L/D {ld:g} S {S:<6g} {n:4d}  plain {plain[0]:.1e} {plain[1]:.3f} s  "
                  f"fitted {fitted[0]:.1e} {fitted[1]:.3f} s  band {band[0]:.1e} "
                  f"{band[1]:.3f} s")
        return
    levels = LEVELS[:3] if a.quick else LEVELS
    select = (4, 9) if a.quick else a.rows
    rows, refs = study(levels, ("P2",) if a.quick else tuple(a.elements), select)
    print("K, C error: the larger of K's and C's largest-entry error over the largest entry; "
          "(a) against P2 288 graded unfitted (the benchmark's reference), (b) against the "
          "fitted P2 288 (graded as the meshes); orders per doubling between levels")
    groups = {}
    for ld, S, eps, el, n, f, move, ncols, dt in rows:
        groups.setdefault((ld, S, eps, el), []).append((n, f, move, ncols, dt))
    worst = {}
    pairs = {"plain": [], "fitted": []}
    searches = {"plain": [], "fitted": []}
    for (ld, S, eps, el), g in groups.items():
        ref = refs[(ld, S)]
        ns = [x[0] for x in g]
        kind = "graded" if eps >= GRADED_FROM_EPS else "uniform"
        bf, bk = _errors(ref["benchmark"], ref["fitted"])
        print(f"\nL/D {ld:g}, S {S:g} (eps {eps:.3f}), {el} {kind}: cells around {ns}, "
              f"fitted columns {[x[3] for x in g]}, last fit move [deg] "
              f"{' '.join(f'{math.degrees(x[2]):.0e}' for x in g)}; (a) from (b): force "
              f"{bf:.1e}, K, C {bk:.1e}")
        for film in ("plain", "fitted"):
            for q, name in ((0, "force"), (1, "K, C")):
                for against in ("benchmark", "fitted"):
                    e = [_errors(x[1][film], ref[against])[q] for x in g]
                    o = _orders(e, ns)
                    tag = "(a)" if against == "benchmark" else "(b)"
                    print(f"  {film:6s} {name:5s} {tag} " + " ".join(f"{v:8.1e}" for v in e)
                          + "   orders " + " ".join(f"{v:5.2f}" for v in o))
                    if against == "fitted":
                        for n, v in zip(ns, e):
                            key = (el, film, name, n)
                            worst[key] = max(worst.get(key, 0.0), v)
            # h/2h pairs within the levels: estimate against the true error (b)
            by_n = {x[0]: x[1][film] for x in g}
            cost = {x[0]: x[4][0 if film == "plain" else 1] for x in g}
            accepted = None
            for n in ns:
                if 2 * n in by_n:
                    fine, coarse = by_n[2 * n], by_n[n]
                    est = SAFETY * _errors(fine, coarse)[1] / (2.0 ** PAIR_ORDER[film] - 1.0)
                    true = _errors(fine, ref["fitted"])[1]
                    pairs[film].append((el, ld, S, 2 * n, est, true))
                    if accepted is None and est <= SEARCH_RTOL:
                        accepted = (2 * n, est, true, cost[n] + cost[2 * n])
            searches[film].append((el, ld, S, accepted))
        print("  seconds, LCP + tangent " + " ".join(f"{x[4][0]:.3f}" for x in g)
              + "; with the fit " + " ".join(f"{x[4][1]:.3f}" for x in g))
    print("\nlargest error over the rows against (b), per level")
    for el in sorted({k[0] for k in worst}):
        for film in ("plain", "fitted"):
            for name in ("force", "K, C"):
                e = [worst[(el, film, name, n)] for n in levels if (el, film, name, n) in worst]
                print(f"  {el} {film:6s} {name:5s} " + " ".join(f"{v:8.1e}" for v in e))
    print("\nh/2h pairs (n / 2n cells around) of K, C: estimate SAFETY |d| / (2^p - 1), "
          "p = 1 (plain, the search's) and 2 (fitted), against the true error (b)")
    for film, ps in pairs.items():
        if not ps:
            continue
        eff = np.array([est / true for *_, est, true in ps if true > 2e-5])
        low = [(el, ld, S, n, est, true) for el, ld, S, n, est, true in ps
               if true > 2e-5 and est < true]
        print(f"  {film:6s}: {len(eff)} pairs (true error > 2e-5), effectivity least "
              f"{eff.min():.2f}, median {np.median(eff):.2f}, largest {eff.max():.2f}; "
              f"below 1: {len(low)}")
        for el, ld, S, n, est, true in low:
            print(f"     {el} L/D {ld:g} S {S:g} {n} cells: estimate {est:.1e}, true {true:.1e}")
    print(f"\nthe first pair whose estimate is within {SEARCH_RTOL:g} (a search from 36 / 72 "
          "on these levels): fine mesh, estimate, true error (b), CPU of the pair's two films "
          "(plain: LCP + tangent; fitted: with the fit)")
    for film, ss in searches.items():
        total = {}
        for el, ld, S, acc in sorted(ss, key=lambda r: r[0], reverse=True):
            if acc is None:
                print(f"  {film:6s} {el} L/D {ld:g} S {S:<6g} none within the levels")
                continue
            n, est, true, dt = acc
            total[el] = total.get(el, 0.0) + dt
            print(f"  {film:6s} {el} L/D {ld:g} S {S:<6g} {n:4d} cells  estimate {est:.1e}  "
                  f"true {true:.1e}  {dt:.3f} s")
        for el, t in total.items():
            print(f"  {film:6s} {el}: the accepted pairs {t:.3f} s CPU")


if __name__ == "__main__":
    main()
