"""The plain (ungrooved) film searched to a tolerance on meshes graded toward its least film
against uniform meshes: the true error within the request and the estimate, effectivity,
meshes, solves and CPU time.

    python -m studies.plain_graded            # ~4 min (run it with no other heavy job on the machine)
    python -m studies.plain_graded --quick    # two states (smoke)

For each state (L/D 0.25, 0.5, 1; eps 0.3, 0.6, 0.9; Reynolds' condition and Gumbel's
film) ``solve_reynolds(rtol=)`` cold (memo cleared) at rtol 1e-3 and 1e-4, as the search
grades it (``graded``) and on uniform meshes (``grading=0.0``, the search before plain
films were graded), the true force error against P2 384 x 64 graded toward the least film
(its distance to P2 384 x 64 uniform printed beside). Then, at Reynolds' condition,
``equilibrium(rtol=2e-3)`` under the reference film's load at that eps (true error of the
journal position against the reference mesh's equilibrium, relative to |q|) and
``coefficients(rtol=1e-2)`` at the reference equilibrium (K and C against the reference
mesh's, each relative to its largest entry). CPU times of cold searches, one process.
"""
from __future__ import annotations

import argparse
import math
import time

import numpy as np

from bearingfem import Bearing, JournalState, coefficients, equilibrium, solve_reynolds
from bearingfem.accuracy import clear_memo, force_difference

REFERENCE = (384, 64)
STATES = [(ld, eps) for ld in (0.25, 0.5, 1.0) for eps in (0.3, 0.6, 0.9)]
OMEGA = 250.0
VARIANTS = (("graded", {}), ("uniform", dict(grading=0.0)))


def bearing(ld: float) -> Bearing:
    return Bearing(radius=0.01, length=0.02 * ld, clearance=20e-6, viscosity=0.0117)


def _cpu(fn):
    clear_memo()
    t = time.process_time()
    out = fn()
    return time.process_time() - t, out


def _kc_error(kc, ref) -> float:
    return float(max(np.abs(kc.K - ref.K).max() / np.abs(ref.K).max(),
                     np.abs(kc.C - ref.C).max() / np.abs(ref.C).max()))


def _judged(estimate: float, true: float, rtol: float) -> str:
    """The row's estimate, true error and effectivity, marked where the true error is
    outside the estimate or the request."""
    eff = estimate / true if true > 0 else math.inf
    ok = "" if true <= estimate <= rtol else "  <-- outside"
    return f"{estimate:9.2e} {true:9.2e} {eff:7.2f}{ok}"


def _mesh(acc) -> str:
    g = "" if acc.grading is None else f" g{acc.grading:g}"
    return f"{acc.mesh[0]}x{acc.mesh[1]}{g}"


def force_rows(states, cavitations, tolerances):
    """One row per (state, cavitation, rtol, variant)."""
    print(f"{'L/D':>5s} {'eps':>4s} {'cav':>8s} {'rtol':>6s} {'variant':>8s} {'mesh':>13s} "
          f"{'solves':>6s} {'CPU s':>7s} {'estimate':>9s} {'true':>9s} {'effect.':>7s}")
    worst = {}
    for (ld, eps), cav in ((s, c) for s in states for c in cavitations):
        b, s = bearing(ld), JournalState(eps=eps, omega=OMEGA)
        ref = solve_reynolds(b, s, *REFERENCE, "P2", cav, grading=0.6)
        ref_u = solve_reynolds(b, s, *REFERENCE, "P2", cav)
        print(f"# L/D {ld}, eps {eps}, {cav}: reference graded vs uniform "
              f"{force_difference(ref, ref_u):.1e}")
        for rtol in tolerances:
            for name, o in VARIANTS:
                t, sol = _cpu(lambda: solve_reynolds(b, s, rtol=rtol, cavitation=cav, **o))
                true = force_difference(ref, sol)
                eff = sol.force_error / true if true > 0 else math.inf
                key = (name, rtol)
                worst[key] = min(worst.get(key, math.inf), eff)
                print(f"{ld:5.2f} {eps:4.1f} {cav:>8s} {rtol:6.0e} {name:>8s} "
                      f"{_mesh(sol.accuracy):>13s} {sol.accuracy.solves:6d} {t:7.3f} "
                      f"{_judged(sol.force_error, true, rtol)}")
    for (name, rtol), eff in sorted(worst.items()):
        print(f"least effectivity, {name}, rtol {rtol:g}: {eff:.2f}")


def design_rows(states, eq_rtol=2e-3, kc_rtol=1e-2):
    """equilibrium(rtol) and coefficients(rtol) at Reynolds' condition, graded and uniform."""
    print(f"{'L/D':>5s} {'eps':>4s} {'what':>5s} {'variant':>8s} {'mesh':>13s} {'solves':>6s} "
          f"{'CPU s':>7s} {'estimate':>9s} {'true':>9s} {'effect.':>7s}")
    for ld, eps in states:
        b, s = bearing(ld), JournalState(eps=eps, omega=OMEGA)
        film = dict(cavitation="reynolds")
        W = math.hypot(*solve_reynolds(b, s, *REFERENCE, "P2", grading=0.6, **film).force)
        load = (0.0, -W)
        ref_opts = dict(n_theta=REFERENCE[0], n_z=REFERENCE[1], element="P2", grading=0.6,
                        **film)
        ref_eq = equilibrium(b, load, OMEGA, "fem", **ref_opts)
        q_ref = ref_eq.eps * np.array([math.cos(ref_eq.state.gamma),
                                       math.sin(ref_eq.state.gamma)])
        ref_kc = coefficients(b, ref_eq.state, "fem", **ref_opts)
        for name, o in VARIANTS:
            t, eq = _cpu(lambda: equilibrium(b, load, OMEGA, "fem", rtol=eq_rtol, **film, **o))
            q = eq.eps * np.array([math.cos(eq.state.gamma), math.sin(eq.state.gamma)])
            true = float(np.linalg.norm(q - q_ref) / np.linalg.norm(q_ref))
            est = eq.eps_error / eq.eps
            print(f"{ld:5.2f} {eps:4.1f} {'eq':>5s} {name:>8s} {_mesh(eq.accuracy):>13s} "
                  f"{eq.accuracy.solves:6d} {t:7.3f} {_judged(est, true, eq_rtol)}")
            t, kc = _cpu(lambda: coefficients(b, ref_eq.state, "fem", rtol=kc_rtol, **film,
                                              **o))
            true = _kc_error(kc, ref_kc)
            print(f"{ld:5.2f} {eps:4.1f} {'K, C':>5s} {name:>8s} {_mesh(kc.accuracy):>13s} "
                  f"{kc.accuracy.solves:6d} {t:7.3f} {_judged(kc.error, true, kc_rtol)}")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true")
    a = p.parse_args(argv)
    states = [(1.0, 0.6), (0.25, 0.9)] if a.quick else STATES
    force_rows(states, ("reynolds",) if a.quick else ("reynolds", "gumbel"),
               (1e-3,) if a.quick else (1e-3, 1e-4))
    design_rows(states)


if __name__ == "__main__":
    main()
