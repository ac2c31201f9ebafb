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
pressure solve (a grooved partial costs one: its d/dgamma is exact on the bearing-fixed
mesh, :mod:`bearingfem.fe.grooved`). Times: best of ``repeat`` with the operator caches
cleared.

    python -m benchmarks.grooved [--quick] [--repeat N]

The film at the limit (one run, best of ``repeat``): one static film at eps 0.6, journal
angle -45 deg (as benchmarks/ross31.py) - "build" the first solve on a mesh (mesh, operator
and the seven harmonic tables), "new angle" a cold solve at a journal angle not seen before
(tables reused, the cavitated set from the coarser levels), "warm" a new angle started from
the previous angle's cavitated set (fe_force's ``warm``, as in time integration), "moving mesh" the route before: a mesh and
operator built per journal angle; equilibrium + K/C at S 0.635 (cold: caches cleared;
warm: tables built); the design chart (S 10..0.01, 20 points). Errors against P2 192x32
(the chart: the largest over its points, against P2 144x24). :func:`ours_rows` gives the
same numbers to benchmarks/ross31.py.
"""
from __future__ import annotations

import argparse
import itertools
import math
import time

import numpy as np
from scipy.optimize import brentq, root

import bearingfem.fe.grooved as fe_grooved
import bearingfem.fe.kernel as fe_kernel
from bearingfem.routes import fe_force
import bearingfem.fe.sensitivity as fe_sensitivity
from bearingfem import Bearing, Groove, JournalState
from bearingfem.design import coefficients, equilibrium
from bearingfem.design.groups import load_from_sommerfeld
from bearingfem.fe.assembly import film_operator
from bearingfem.fe.grooved import _mesh_arcs, bearing_fixed_operator, groove_operator_for
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
        self._orig = fe_kernel.fe_pressure

    def __enter__(self):
        def counted(*a, **k):
            self.n += 1
            return self._orig(*a, **k)
        # every module that calls the kernel's pressure solve by name
        fe_kernel.fe_pressure = fe_grooved.fe_pressure = fe_sensitivity.fe_pressure = counted
        return self

    def __exit__(self, *exc):
        fe_kernel.fe_pressure = fe_grooved.fe_pressure = fe_sensitivity.fe_pressure = \
            self._orig


def root_search(opts):
    """The route before Newton: Brent on the periodic |F(eps)|, then the 2-D hybrid root."""
    m = film_model("fem")
    o = m.options(opts)
    periodic = {**o, "grooves": ()}
    W = math.hypot(*LOAD)

    def force(eps, gamma, oo):
        return m.film_force(BEARING, JournalState(eps, omega=OMEGA, gamma=gamma), **oo)

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
        clear_caches()
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


STATIC = (0.6, -0.25 * math.pi)          # eps, journal angle [rad]: as benchmarks/ross31.py
STATIC_MESHES = [(18, 4), (24, 4), (36, 6), (48, 8)]
DESIGN_MESHES = [(14, 4), (16, 6), (18, 4), (20, 4), (24, 4), (30, 6), (36, 6), (48, 8)]
CHART_MESHES = [(24, 4), (36, 6), (48, 8)]
CHART_REFERENCE = (144, 24)


def fe_options(mesh):
    return dict(n_theta=mesh[0], n_z=mesh[1], element="P2", cavitation="reynolds",
                grooves=GROOVES)


def clear_caches():
    film_operator.cache_clear()
    film_mesh.cache_clear()
    bearing_fixed_operator.cache_clear()
    _mesh_arcs.cache_clear()


def best(f, repeat, before=None, cpu=None):
    """(best wall time [s] of ``repeat`` calls of f(k), k the call's index, the last
    output); ``before()`` runs untimed before each call; a list ``cpu`` gets the best
    process time [s] appended (on a shared machine wall time carries the others' load)."""
    t, c, out = math.inf, math.inf, None
    for k in range(repeat):
        if before:
            before()
        c0, t0 = time.process_time(), time.perf_counter()
        out = f(k)
        t = min(t, time.perf_counter() - t0)
        c = min(c, time.process_time() - c0)
    if cpu is not None:
        cpu.append(c)
    return t, out


_NEW_ANGLES = itertools.count(1)


def _state(new=False):
    """The static state, or (``new``) a journal angle near it not solved before in this
    run (no cache holds it)."""
    gamma = STATIC[1] + (1e-4 * next(_NEW_ANGLES) if new else 0.0)
    return JournalState(STATIC[0], omega=OMEGA, gamma=gamma)


def static_force(mesh, state=None):
    """(F_x, F_y) [N] of the two-groove film (solve_reynolds: a cold solve)."""
    from bearingfem import solve_reynolds
    return np.asarray(solve_reynolds(BEARING, state or _state(), **fe_options(mesh)).force)


def moving_mesh_force(mesh, state):
    """The route before the bearing-fixed mesh: the grooves' mesh and operator built for
    this journal angle, then the film solve (fe_operator caches per angle)."""
    from bearingfem.fe.kernel import fe_operator, fe_pressure, groove_pressures
    from bearingfem.scales import force_factor
    op = fe_operator(BEARING, state, mesh[0], mesh[1], "P2", None, True, GROOVES)
    res = fe_pressure(op, state, "reynolds", dirichlet=groove_pressures(BEARING, op, GROOVES))
    f_r, f_t = force_factor(BEARING, True) * op.force_integrals(res.pressure)
    return np.asarray(local_to_inertial(f_r, f_t, state.gamma))


def force_error(F, F0):
    return float(np.linalg.norm(np.subtract(F, F0)) / np.linalg.norm(F0))


def inertial_design(mesh):
    """eps, journal angle [rad], K, C (inertial) at equilibrium (benchmarks/ross31.py's)."""
    opts = fe_options(mesh)
    eq = equilibrium(BEARING, LOAD, OMEGA, "fem", **opts)
    kc = coefficients(BEARING, eq.state, "fem", **opts)
    return eq.eps, eq.state.gamma, np.asarray(kc.K), np.asarray(kc.C)


def chart(mesh):
    from bearingfem.design import design_chart
    return design_chart(BEARING, OMEGA, model="fem", **fe_options(mesh))


def chart_error(ch, ref):
    """The largest over the chart's points of the design error (eps, attitude, K, B)."""
    return max(error((p.eps, p.attitude, p.K, p.B), (q.eps, q.attitude, q.K, q.B))
               for p, q in zip(ch.points, ref.points))


def ours_rows(quick=False, repeat=3):
    """(rows, references) of the film at the limit: rows are dicts with case ("two-groove
    static", "two-groove design", "two-groove chart"), code, mesh, error, time_s (static:
    a new journal angle, cold; design and chart: caches cleared), warm_s, build_s (static:
    the first solve on the mesh), before_s (static: the moving mesh). references: "static"
    (F_x, F_y) [N] and "two_groove" (eps, gamma, K, C) on P2 192x32 (96x16 quick).
    cpu_s: the process time of the run time_s times (best of ``repeat``); warm_cpu_s
    that of the warm design and chart."""
    ref_mesh = (96, 16) if quick else REFERENCE
    refs = dict(static=static_force(ref_mesh), two_groove=inertial_design(ref_mesh))
    rows = []
    for mesh in STATIC_MESHES[:2] if quick else STATIC_MESHES:
        gop = groove_operator_for(BEARING, mesh[0], mesh[1], "P2", GROOVES)

        last = [None]

        def force(state, warm=False):
            (f_r, f_t), res = fe_force(BEARING, state, mesh[0], mesh[1], "P2", "reynolds",
                                       grooves=GROOVES, warm=last[0] if warm else None)
            last[0] = res
            return np.asarray(local_to_inertial(f_r, f_t, state.gamma))

        def cold():     # the operator rebuilt on its first use, no cavitated set kept
            clear_caches()

        build, F = best(lambda k: force(_state()), repeat, cold)
        gop = groove_operator_for(BEARING, mesh[0], mesh[1], "P2", GROOVES)
        cpu = []
        new, _ = best(lambda k: force(_state(True)), repeat, gop.last.clear, cpu)
        warm, _ = best(lambda k: force(_state(True), warm=True), repeat)
        full, _ = best(lambda k: static_force(mesh, _state(True)), repeat)
        moving, _ = best(lambda k: moving_mesh_force(mesh, _state(True)), repeat)
        rows.append(dict(case="two-groove static", code="bearingfem",
                         mesh=f"P2 {mesh[0]}x{mesh[1]}", error=force_error(F, refs["static"]),
                         time_s=new, warm_s=warm, build_s=build, solution_s=full,
                         before_s=moving, cpu_s=cpu[0]))
    for mesh in DESIGN_MESHES[:2] if quick else DESIGN_MESHES:
        cpu = []
        cold, out = best(lambda k: inertial_design(mesh), repeat, clear_caches, cpu)
        warm, _ = best(lambda k: inertial_design(mesh), repeat, cpu=cpu)
        e, g, K, C = out
        e0, g0, K0, C0 = refs["two_groove"]
        rows.append(dict(case="two-groove design", code="bearingfem",
                         mesh=f"P2 {mesh[0]}x{mesh[1]}", error=error((e, g, K, C),
                                                                     (e0, g0, K0, C0)),
                         time_s=cold, warm_s=warm, cpu_s=cpu[0], warm_cpu_s=cpu[1]))
    ref_chart = chart((48, 8) if quick else CHART_REFERENCE)
    for mesh in CHART_MESHES[:1] if quick else CHART_MESHES:
        cpu = []
        cold, out = best(lambda k: chart(mesh), max(1, repeat - 1), clear_caches, cpu)
        warm, _ = best(lambda k: chart(mesh), max(1, repeat - 1), cpu=cpu)
        rows.append(dict(case="two-groove chart", code="bearingfem",
                         mesh=f"P2 {mesh[0]}x{mesh[1]}", error=chart_error(out, ref_chart),
                         error_position=max(max(abs(p.eps - q.eps) / q.eps,
                                                abs(p.attitude - q.attitude))
                                            for p, q in zip(out.points, ref_chart.points)),
                         time_s=cold, warm_s=warm, cpu_s=cpu[0], warm_cpu_s=cpu[1],
                         evaluations=out.evaluations))
    return rows, refs


def print_rows(rows):
    print(f"{'case':18s} {'mesh':10s} {'error':>9s} {'time [ms]':>10s} {'warm [ms]':>10s} "
          f"{'cpu [ms]':>10s} {'build [ms]':>10s} {'film [ms]':>10s} {'before [ms]':>10s}")
    for r in rows:
        extra = "".join(f" {1e3 * r[k]:10.2f}" if k in r else f" {'':10s}"
                        for k in ("cpu_s", "build_s", "solution_s", "before_s"))
        print(f"{r['case']:18s} {r['mesh']:10s} {r['error']:9.2e} {1e3 * r['time_s']:10.2f} "
              f"{1e3 * r['warm_s']:10.2f}{extra}")


def main(argv=None):
    ap = argparse.ArgumentParser(description="grooved films at the limit")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="fewer meshes, coarse reference")
    args = ap.parse_args(argv)
    rows, _ = ours_rows(args.quick, args.repeat)
    print(f"Lund & Thomsen two-groove bearing, L/D 1, 3000 rpm; static film at eps "
          f"{STATIC[0]}, journal angle {math.degrees(STATIC[1]):g} deg; equilibrium at "
          f"S 0.635; chart S 10..0.01, 20 points")
    print_rows(rows)
    return rows


if __name__ == "__main__":
    main()
