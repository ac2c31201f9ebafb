"""Equilibrium + K/C of a grooved bearing: Newton on the exact partials against the root
search it replaced (Brent on the periodic film's |F(eps)|, then Powell's hybrid method in
the journal position), film solves and wall time at the same accuracy.

    python -m benchmarks.design --grooved [--quick] [--repeat N]

Bearing: Lund & Thomsen's (1978) two-axial-groove bearing, 20 deg grooves across the load
(at 0 and 180 deg, load downward), L/D 1, D 0.1 m, c 100 um, mu 0.02 Pa s, 3000 rpm,
S 0.635, Reynolds' condition. Reference: Newton on FE P2 192x32 (eps and attitude against
the root search there agree to 1e-10). Error = the largest of |d eps| / eps, |d attitude|
[rad], max|dK| / max|K|, max|dC| / max|C|. "periodic" is the same bearing without grooves
(a load it carries at the same Sommerfeld number). Film solves are counted at the FE
pressure solve (a grooved partial costs three: its d/dgamma is a central difference).
Times: best of ``repeat`` with the operator caches cleared (grooved operators are built per
journal angle, so every equilibrium builds them anew anyway).
"""
from __future__ import annotations

import math
import time

import numpy as np
from scipy.optimize import brentq, root

import bearingfem.fe.reynolds as fe_reynolds
import bearingfem.fe.sensitivity as fe_sensitivity
from bearingfem import Bearing, Groove, JournalState
from bearingfem.design import coefficients, equilibrium
from bearingfem.design.groups import load_from_sommerfeld
from bearingfem.fe.assembly import film_operator
from bearingfem.fe.mesh import film_mesh
from bearingfem.film import local_to_inertial
from bearingfem.models import film_model

BEARING = Bearing(radius=0.05, length=0.1, clearance=100e-6, viscosity=0.02)
OMEGA = 3000.0 * 2.0 * math.pi / 60.0
LOAD = (0.0, -load_from_sommerfeld(BEARING, 0.635, OMEGA))
GROOVES = (Groove(angle=0.0, width=math.radians(20.0)),
           Groove(angle=math.pi, width=math.radians(20.0)))
MESHES = [(48, 8), (72, 12), (96, 16)]
REFERENCE = (192, 32)


class SolveCounter:
    """Counts FE pressure solves (every force, solution and partial goes through one)."""

    def __init__(self):
        self.n = 0
        self._orig = fe_reynolds.fe_pressure

    def __enter__(self):
        def counted(*a, **k):
            self.n += 1
            return self._orig(*a, **k)
        fe_reynolds.fe_pressure = fe_sensitivity.fe_pressure = counted
        return self

    def __exit__(self, *exc):
        fe_reynolds.fe_pressure = fe_sensitivity.fe_pressure = self._orig


def root_search(opts):
    """The route before Newton: Brent on the periodic |F(eps)|, then the 2-D hybrid root."""
    m = film_model("fem")
    o = m.options(opts)
    periodic = {**o, "grooves": ()}
    W = math.hypot(*LOAD)

    def force(eps, gamma, oo):
        return m.force(BEARING, JournalState(eps, omega=OMEGA, gamma=gamma), **oo)

    math.hypot(*force(0.99, 0.0, periodic))         # the capacity check it made
    eps = brentq(lambda e: math.hypot(*force(e, 0.0, periodic)) - W, 0.0, 0.99,
                 xtol=1e-300, rtol=1e-13)
    f_r, f_t = force(eps, 0.0, periodic)
    gamma = math.atan2(-LOAD[1], -LOAD[0]) - math.atan2(f_t, f_r)
    if o["grooves"]:
        def residual(q):
            e, g = math.hypot(*q), math.atan2(q[1], q[0])
            return np.add(local_to_inertial(*force(e, g, o), g), LOAD) / W
        sol = root(residual, [eps * math.cos(gamma), eps * math.sin(gamma)], method="hybr",
                   options=dict(xtol=1e-12))
        eps, gamma = math.hypot(*sol.x), math.atan2(sol.x[1], sol.x[0])
    state = JournalState(eps, omega=OMEGA, gamma=gamma)
    f_r, f_t = force(eps, gamma, o)
    film_model("fem").film_solution(BEARING, state, **opts)      # the solution it returned
    return state, math.atan2(f_t, -f_r)


def newton(opts):
    eq = equilibrium(BEARING, LOAD, OMEGA, "fem", **opts)
    return eq.state, eq.attitude


def design_numbers(route, opts):
    state, attitude = route(opts)
    kc = coefficients(BEARING, state, "fem", **opts)
    return state.eps, attitude, kc.K, kc.C


def error(out, ref):
    (e, a, K, C), (e0, a0, K0, C0) = out, ref
    return max(abs(e - e0) / e0, abs(math.remainder(a - a0, 2 * math.pi)),
               np.abs(K - K0).max() / np.abs(K0).max(), np.abs(C - C0).max() / np.abs(C0).max())


def run(route, opts, repeat):
    best = math.inf
    for _ in range(repeat):
        film_operator.cache_clear()
        film_mesh.cache_clear()
        with SolveCounter() as count:
            t0 = time.perf_counter()
            out = design_numbers(route, opts)
            best = min(best, time.perf_counter() - t0)
    return out, count.n, best


def grooved_table(repeat=2, quick=False):
    meshes = MESHES[:2] if quick else MESHES
    ref_mesh = (96, 16) if quick else REFERENCE
    rows = []
    print(f"Lund & Thomsen two-groove bearing, L/D 1, S 0.635, W = {-LOAD[1]:.1f} N; "
          f"reference P2 {ref_mesh[0]}x{ref_mesh[1]}")
    print(f"{'film':9s} {'mesh':10s} {'route':12s} {'eps':>9s} {'att [deg]':>9s} "
          f"{'error':>9s} {'solves':>6s} {'time [ms]':>10s} {'ratio':>6s}")
    for film, grooves in (("grooved", GROOVES), ("periodic", ())):
        base = dict(element="P2", cavitation="reynolds", grooves=grooves)
        ref = design_numbers(newton, dict(base, n_theta=ref_mesh[0], n_z=ref_mesh[1]))
        for n, z in meshes:
            opts = dict(base, n_theta=n, n_z=z)
            timing = {}
            for name, route in (("root search", root_search), ("Newton", newton)):
                out, solves, t = run(route, opts, repeat)
                timing[name] = t
                row = dict(film=film, mesh=f"P2 {n}x{z}", route=name, eps=out[0],
                           attitude=math.degrees(out[1]), error=error(out, ref),
                           solves=solves, time_s=t)
                rows.append(row)
                ratio = timing["root search"] / t
                print(f"{film:9s} {row['mesh']:10s} {name:12s} {out[0]:9.6f} "
                      f"{row['attitude']:9.4f} {row['error']:9.2e} {solves:6d} "
                      f"{1e3 * t:10.1f} {ratio:6.2f}")
    return rows
