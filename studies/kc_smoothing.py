"""Two ways to make K and C of a cavitated film regular in the mesh, measured (neither kept).

    python -m studies.kc_smoothing            # ~3 min (run it with no other heavy job on the machine)
    python -m studies.kc_smoothing --window   # the eps-window table alone, ~1 min

The FE film's K and C are the exact tangent of the discrete film with its cavitated set
held; their error jumps when a node joins or leaves the film (studies/kc_phase.py). Both
tables are on Lund & Thomsen's ten rows (studies/lund_thomsen.py) at the states of P2 144
equilibria, P2, Reynolds' condition, against the benchmark's reference (P2 288 cells
around graded toward the least film), errors as the larger of K's and C's largest-entry
error relative to the matrix's largest entry, uniform and graded meshes:

1. ``differences_table``: K and C from central differences of the film force over a step
   that spans switching events, with Richardson in the step. The force is continuous in
   the state, so its difference over a step is the tangent averaged over the step. eps
   moves by d, gamma by d / eps (the same displacement), eps_dot by omega d / 2 (the same
   change of the source); the wedge partial is W = F / w exactly (the film's LCP is
   positively homogeneous in its source, at eps_dot = 0). Steps d = 0.005 .. 0.04 and the
   Richardson value (4 K(d) - K(2 d)) / 3.
2. ``window_table``: the held set's tangent at 2 k + 1 states eps (1 + w x), x in [-1, 1],
   their mean and a quadratic fit's value at eps (the window's curvature removed).
"""
from __future__ import annotations

import argparse
import itertools
import math
import time
from dataclasses import replace

import numpy as np

from bearingfem.design import coefficients, equilibrium
from bearingfem.design.groups import load_from_sommerfeld
from bearingfem.design.tolerance import GRADING_STRENGTH
from bearingfem.models import film_model

from .lund_thomsen import GROOVES, LOAD_DIRECTION, OMEGA, TABLE, bearing, mesh

FILM = dict(grooves=GROOVES, cavitation="reynolds", element="P2")
#: cells around of the meshes compared (multiples of 18: nodes on the grooves' edges)
LEVELS = (36, 54, 72, 108)
#: the difference steps in eps
STEPS = (0.005, 0.01, 0.02, 0.04)
#: the eps windows' half-widths relative to eps, and the states per window
WINDOWS = (0.03, 0.08, 0.15)
WINDOW_STATES = 9


def _error(K, C, ref) -> float:
    K0, C0 = ref
    return float(max(np.abs(K - K0).max() / np.abs(K0).max(),
                     np.abs(C - C0).max() / np.abs(C0).max()))


def rows():
    """[(L/D, S, state, (K, C) of the reference)] at the ten rows' P2 144 equilibria."""
    out = []
    for ld, table in TABLE.items():
        for S, *_ in table:
            b = bearing(ld)
            s = equilibrium(b, load_from_sommerfeld(b, S, OMEGA), OMEGA, "fem",
                            direction=LOAD_DIRECTION, **mesh(ld, 144, "P2")).state
            ref = coefficients(b, s, "fem", **mesh(ld, 288, "P2"),
                               grading=(s.gamma, GRADING_STRENGTH))
            out.append((ld, S, s, (np.asarray(ref.K), np.asarray(ref.C))))
    return out


def meshes(ld, state):
    """[(label, options)]: uniform and graded (as the search grades: the angle on its
    15 deg grid) P2 meshes of :data:`LEVELS` cells around."""
    step = math.pi / 12.0
    grading = (step * round(state.gamma / step), GRADING_STRENGTH)
    out = []
    for graded, n in itertools.product((False, True), LEVELS):
        n_z = max(4, 2 * round(n * ld / math.pi / 2.0))
        o = dict(FILM, n_theta=n, n_z=n_z, **({"grading": grading} if graded else {}))
        out.append((f"{'graded' if graded else 'uniform'} {n}x{n_z}", o))
    return out


def differenced(bearing_, state, options, d):
    """(K, C) in the inertial frame from central differences of the force over step d
    (module docstring)."""
    m = film_model("fem")

    def force(s):
        return np.asarray(m.film_force(bearing_, s, **options), float)

    F = force(state)
    A = (force(replace(state, eps=state.eps + d)) - force(replace(state, eps=state.eps - d))) / (2 * d)
    dg = d / state.eps
    G = (force(replace(state, gamma=state.gamma + dg))
         - force(replace(state, gamma=state.gamma - dg))) / (2 * dg)
    de = 0.5 * state.omega * d
    B = (force(replace(state, eps_dot=de)) - force(replace(state, eps_dot=-de))) / (2 * de)
    W = F / state.wedge_speed
    c, e = bearing_.clearance, state.eps
    JF = np.array([-F[1], F[0]]) + G
    K = -np.column_stack([A, JF / e]) / c
    C = -np.column_stack([B, -2.0 * W / e]) / c
    g = state.gamma
    R = np.array([[math.cos(g), -math.sin(g)], [math.sin(g), math.cos(g)]])
    return R @ K @ R.T, R @ C @ R.T


def differences_table(progress=print):
    """Per row and mesh: the held set's error, each step's, and Richardson's."""
    progress(f"{'L/D':>4} {'S':>6} {'mesh':>16} {'held set':>9} "
             + " ".join(f"{'d ' + format(d, 'g'):>9}" for d in STEPS)
             + " " + " ".join(f"{'R ' + format(d, 'g'):>9}" for d in STEPS if 2 * d in STEPS)
             + f" {'CPU s/step':>10}")
    out = []
    for ld, S, s, ref in rows():
        b = bearing(ld)
        for label, o in meshes(ld, s):
            kc = coefficients(b, s, "fem", **o)
            held = _error(np.asarray(kc.K), np.asarray(kc.C), ref)
            t = time.process_time()
            by_step = {d: differenced(b, s, o, d) for d in STEPS}
            cpu = (time.process_time() - t) / len(STEPS)
            plain = [_error(*by_step[d], ref) for d in STEPS]
            rich = [_error((4 * by_step[d][0] - by_step[2 * d][0]) / 3,
                           (4 * by_step[d][1] - by_step[2 * d][1]) / 3, ref)
                    for d in STEPS if 2 * d in STEPS]
            out.append((ld, S, label, held, plain, rich))
            progress(f"{ld:4g} {S:6g} {label:>16} {held:9.1e} "
                     + " ".join(f"{e:9.1e}" for e in plain) + " "
                     + " ".join(f"{e:9.1e}" for e in rich) + f" {cpu:10.3f}")
    return out


def window_table(progress=print, levels=(54, 72, 108)):
    """Per row and graded mesh: the held set's error, and per window the mean's and the
    quadratic fit's."""
    progress(f"{'L/D':>4} {'S':>6} {'mesh':>16} {'held set':>9} "
             + " ".join(f"{'mean ' + format(w, 'g'):>10} {'fit ' + format(w, 'g'):>9}"
                        for w in WINDOWS))
    out = []
    x = np.linspace(-1.0, 1.0, WINDOW_STATES)
    for ld, S, s, ref in rows():
        b = bearing(ld)
        for label, o in meshes(ld, s):
            if "grading" not in o or o["n_theta"] not in levels:
                continue
            kc = coefficients(b, s, "fem", **o)
            held = _error(np.asarray(kc.K), np.asarray(kc.C), ref)
            cols = []
            for w in WINDOWS:
                dx = x * w * s.eps
                KC = [coefficients(b, replace(s, eps=s.eps + v), "fem", **o) for v in dx]
                K = np.array([k.K for k in KC])
                C = np.array([k.C for k in KC])
                V = np.vander(dx, 3)
                fit = [np.linalg.lstsq(V, M.reshape(len(dx), -1), rcond=None)[0][-1]
                       .reshape(2, 2) for M in (K, C)]
                cols += [_error(K.mean(0), C.mean(0), ref), _error(*fit, ref)]
            out.append((ld, S, label, held, cols))
            progress(f"{ld:4g} {S:6g} {label:>16} {held:9.1e} "
                     + " ".join(f"{cols[2 * i]:10.1e} {cols[2 * i + 1]:9.1e}"
                                for i in range(len(WINDOWS))))
    return out


def _largest(rows_, column):
    """The largest error per mesh label of ``column(row)``."""
    worst = {}
    for r in rows_:
        worst[r[2]] = max(worst.get(r[2], 0.0), column(r))
    return worst


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--window", action="store_true", help="the eps-window table alone")
    a = p.parse_args(argv)
    if not a.window:
        table = differences_table()
        held = _largest(table, lambda r: r[3])
        rich = _largest(table, lambda r: r[5][STEPS.index(0.02)])
        print("\nlargest over the rows: mesh, held set, Richardson 0.02 / 0.04")
        for label in held:
            print(f"{label:>16} {held[label]:9.1e} {rich[label]:9.1e}")
    window_table()


if __name__ == "__main__":
    main()
