"""What the benchmarks share: one way to time, and the cases more than one of them runs.

Timing (:func:`best_of`): the best of ``repeat`` calls, wall time (``time.perf_counter``)
and CPU time (``time.process_time``: on a shared machine wall time carries other jobs'
load; the film is single-threaded with OMP_NUM_THREADS=1). "Cold" means the same in every
benchmark: :func:`bearingfem.clear_caches` before each call, so every mesh, operator and
table the call needs is built inside its time; "warm" keeps them as the last call left
them.

Cases: the plain bearing of benchmarks/design.py and ross31.py; Lund & Thomsen's (1978)
two-axial-groove bearing of benchmarks/grooved.py, chart_accuracy.py and ross31.py, with
its film-at-the-limit rows (:func:`two_groove_rows`, printed by grooved.py, compared with
ROSS by ross31.py); the seed pin's heavy EHD state of benchmarks/ehd*.py; the seed scene
with its options replaced (:func:`scene`) and the oils of benchmarks/ehd_step.py and
ehd_states.py.
"""
from __future__ import annotations

import dataclasses
import itertools
import math
import time
from dataclasses import dataclass

import numpy as np

from bearingfem import Bearing, Groove, JournalState, Lubricant, clear_caches, solve_reynolds
from bearingfem.design import coefficients, design_chart, equilibrium
from bearingfem.design.groups import load_from_sommerfeld
from bearingfem.fe.grooved import groove_operator_for
from bearingfem.fe.kernel import fe_operator, fe_pressure, groove_pressures
from bearingfem.routes import fe_force
from bearingfem.film import local_to_inertial
from bearingfem.scales import force_factor
from mechanism import load_scene


# -- timing ----------------------------------------------------------------------------

@dataclass(frozen=True)
class Timed:
    """``repeat`` calls: the best wall time [s], the best CPU time [s], the last result."""

    wall: float
    cpu: float
    out: object


def best_of(f, repeat: int = 1, cold: bool = False, before=None) -> Timed:
    """Time ``repeat`` calls of ``f()``. ``cold``: the library's caches cleared before each
    call (untimed); ``before()``: anything else undone before each call (untimed)."""
    wall = cpu = math.inf
    out = None
    for _ in range(repeat):
        if cold:
            clear_caches()
        if before is not None:
            before()
        c0, t0 = time.process_time(), time.perf_counter()
        out = f()
        wall = min(wall, time.perf_counter() - t0)
        cpu = min(cpu, time.process_time() - c0)
    return Timed(wall, cpu, out)


# -- design errors ---------------------------------------------------------------------

def design_error(out, ref) -> float:
    """The largest of |d eps| / eps, |d journal angle| [rad], max|dK| / max|K| and
    max|dC| / max|C| between two (eps, angle, K, C)."""
    (e, g, K, C), (e0, g0, K0, C0) = out, ref
    return max(abs(e - e0) / e0, abs(math.remainder(g - g0, 2 * math.pi)),
               np.abs(K - K0).max() / np.abs(K0).max(), np.abs(C - C0).max() / np.abs(C0).max())


def force_error(F, F0) -> float:
    return float(np.linalg.norm(np.subtract(F, F0)) / np.linalg.norm(F0))


# -- the plain bearing (benchmarks/design.py, ross31.py) -------------------------------

PLAIN_BEARING = Bearing(radius=0.05, length=0.03, clearance=0.1e-3, viscosity=0.1)
PLAIN_LOAD, PLAIN_OMEGA = (0.0, -525.0), 157.1


# -- Lund & Thomsen's two-groove bearing (benchmarks/grooved.py, chart_accuracy.py, ross31.py)

TWO_GROOVE_BEARING = Bearing(radius=0.05, length=0.1, clearance=100e-6, viscosity=0.02)
TWO_GROOVE_OMEGA = 3000.0 * 2.0 * math.pi / 60.0
TWO_GROOVE_LOAD = (0.0, -load_from_sommerfeld(TWO_GROOVE_BEARING, 0.635, TWO_GROOVE_OMEGA))
TWO_GROOVES = (Groove(angle=0.0, width=math.radians(20.0)),
               Groove(angle=math.pi, width=math.radians(20.0)))
STATIC = (0.6, -0.25 * math.pi)          # eps, journal angle [rad] of the static film
STATIC_MESHES = [(18, 4), (24, 4), (36, 6), (48, 8)]
DESIGN_MESHES = [(14, 4), (16, 6), (18, 4), (20, 4), (24, 4), (30, 6), (36, 6), (48, 8)]
CHART_MESHES = [(24, 4), (36, 6), (48, 8)]
CHART_REFERENCE = (144, 24)
TWO_GROOVE_REFERENCE = (192, 32)


def fe_options(mesh, grooves=TWO_GROOVES) -> dict:
    """The P2 Reynolds-condition film on ``mesh`` (n_theta, n_z)."""
    return dict(n_theta=mesh[0], n_z=mesh[1], element="P2", cavitation="reynolds",
                grooves=grooves)


def design_numbers(bearing, load, omega, mesh, grooves) -> tuple:
    """eps, journal angle [rad], K, C (inertial) at equilibrium on the P2 film ``mesh``."""
    opts = fe_options(mesh, grooves)
    eq = equilibrium(bearing, load, omega, "fem", **opts)
    kc = coefficients(bearing, eq.state, "fem", **opts)
    return eq.eps, eq.state.gamma, np.asarray(kc.K), np.asarray(kc.C)


def inertial_design(mesh) -> tuple:
    """The two-groove bearing's :func:`design_numbers`."""
    return design_numbers(TWO_GROOVE_BEARING, TWO_GROOVE_LOAD, TWO_GROOVE_OMEGA, mesh,
                          TWO_GROOVES)


def two_groove_chart(mesh, **options):
    """The two-groove bearing's design chart (S 10..0.01, 20 points) on ``mesh``."""
    return design_chart(TWO_GROOVE_BEARING, TWO_GROOVE_OMEGA, model="fem", **options,
                        **fe_options(mesh))


_NEW_ANGLES = itertools.count(1)


def _state(new=False):
    """The static state, or (``new``) a journal angle near it not solved before in this
    run (no cache holds it)."""
    gamma = STATIC[1] + (1e-4 * next(_NEW_ANGLES) if new else 0.0)
    return JournalState(STATIC[0], omega=TWO_GROOVE_OMEGA, gamma=gamma)


def static_force(mesh, state=None):
    """(F_x, F_y) [N] of the two-groove film (solve_reynolds: a cold solve)."""
    return np.asarray(solve_reynolds(TWO_GROOVE_BEARING, state or _state(),
                                     **fe_options(mesh)).force)


def moving_mesh_force(mesh, state):
    """The route before the bearing-fixed mesh: the grooves' mesh and operator built for
    this journal angle, then the film solve (fe_operator caches per angle)."""
    b = TWO_GROOVE_BEARING
    op = fe_operator(b, state, mesh[0], mesh[1], "P2", None, True, TWO_GROOVES)
    res = fe_pressure(op, state, "reynolds", dirichlet=groove_pressures(b, op, TWO_GROOVES))
    f_r, f_t = force_factor(b, True) * op.force_integrals(res.pressure)
    return np.asarray(local_to_inertial(f_r, f_t, state.gamma))


def chart_error(ch, ref):
    """The largest over the chart's points of the design error (eps, attitude, K, B)."""
    return max(design_error((p.eps, p.attitude, p.K, p.B), (q.eps, q.attitude, q.K, q.B))
               for p, q in zip(ch.points, ref.points))


def two_groove_rows(quick=False, repeat=3):
    """(rows, references) of the two-groove film at the limit: rows are dicts with case
    ("two-groove static", "two-groove design", "two-groove chart"), code, mesh, error,
    time_s (static: a new journal angle, cold; design and chart: cold), warm_s, build_s
    (static: the first solve on the mesh), before_s (static: the moving mesh).
    references: "static" (F_x, F_y) [N] and "two_groove" (eps, gamma, K, C) on P2 192x32
    (96x16 quick). cpu_s: the CPU time of the run time_s times (best of ``repeat``);
    warm_cpu_s that of the warm design and chart."""
    ref_mesh = (96, 16) if quick else TWO_GROOVE_REFERENCE
    refs = dict(static=static_force(ref_mesh), two_groove=inertial_design(ref_mesh))
    rows = []
    for mesh in STATIC_MESHES[:2] if quick else STATIC_MESHES:
        last = [None]

        def force(state, warm=False):
            (f_r, f_t), res = fe_force(TWO_GROOVE_BEARING, state, mesh[0], mesh[1],
                                                   "P2", "reynolds", grooves=TWO_GROOVES,
                                                   warm=last[0] if warm else None)
            last[0] = res
            return np.asarray(local_to_inertial(f_r, f_t, state.gamma))

        # build: the operator rebuilt on its first use, no cavitated set kept
        build = best_of(lambda: force(_state()), repeat, cold=True)
        gop = groove_operator_for(TWO_GROOVE_BEARING, mesh[0], mesh[1], "P2", TWO_GROOVES)
        new = best_of(lambda: force(_state(True)), repeat, before=gop.last.clear)
        warm = best_of(lambda: force(_state(True), warm=True), repeat)
        full = best_of(lambda: static_force(mesh, _state(True)), repeat)
        moving = best_of(lambda: moving_mesh_force(mesh, _state(True)), repeat)
        rows.append(dict(case="two-groove static", code="bearingfem",
                         mesh=f"P2 {mesh[0]}x{mesh[1]}",
                         error=force_error(build.out, refs["static"]), time_s=new.wall,
                         warm_s=warm.wall, build_s=build.wall, solution_s=full.wall,
                         before_s=moving.wall, cpu_s=new.cpu))
    for mesh in DESIGN_MESHES[:2] if quick else DESIGN_MESHES:
        cold = best_of(lambda: inertial_design(mesh), repeat, cold=True)
        warm = best_of(lambda: inertial_design(mesh), repeat)
        rows.append(dict(case="two-groove design", code="bearingfem",
                         mesh=f"P2 {mesh[0]}x{mesh[1]}",
                         error=design_error(cold.out, refs["two_groove"]),
                         time_s=cold.wall, warm_s=warm.wall, cpu_s=cold.cpu,
                         warm_cpu_s=warm.cpu))
    ref_chart = two_groove_chart((48, 8) if quick else CHART_REFERENCE)
    for mesh in CHART_MESHES[:1] if quick else CHART_MESHES:
        cold = best_of(lambda: two_groove_chart(mesh), max(1, repeat - 1), cold=True)
        warm = best_of(lambda: two_groove_chart(mesh), max(1, repeat - 1))
        out = cold.out
        rows.append(dict(case="two-groove chart", code="bearingfem",
                         mesh=f"P2 {mesh[0]}x{mesh[1]}", error=chart_error(out, ref_chart),
                         error_position=max(max(abs(p.eps - q.eps) / q.eps,
                                                abs(p.attitude - q.attitude))
                                            for p, q in zip(out.points, ref_chart.points)),
                         time_s=cold.wall, warm_s=warm.wall, cpu_s=cold.cpu,
                         warm_cpu_s=warm.cpu, evaluations=out.evaluations))
    return rows, refs


# -- the seed pin's EHD film (benchmarks/ehd.py, ehd_jfo.py, ehd_mixed.py) --------------

BRONZE = dict(outer_radius=0.016, modulus=110e9, poisson=0.34)
HEAVY = JournalState(eps=0.995, gamma=0.0, omega=250.0)
NEAR = JournalState(eps=0.9955, gamma=-0.01, omega=250.0)


def mid_film(sol):
    """Least film thickness at the mid-plane [m]."""
    return float(np.min(sol.film_thickness[np.abs(sol.z) < 1e-12]))


# -- the seed scene (benchmarks/ehd_run.py, ehd_step.py, ehd_states.py) ---------------

MU0 = 0.0117
OILS = {"barus": Lubricant(viscosity=MU0, barus=2e-8, density="dowson-higginson"),
        "roelands": Lubricant(viscosity=MU0, roelands=0.751, density="dowson-higginson"),
        "iso": Lubricant(viscosity=MU0, density="dowson-higginson")}


def scene(name, speed, turns, **options):
    """The scene ``name`` at crank speed ``speed`` [rad/s] for ``turns`` from top dead
    centre, recorded throughout, its film options updated with ``options``."""
    sc = load_scene(name)
    lub = dataclasses.replace(sc.lubrication, options=dict(sc.lubrication.options, **options))
    return dataclasses.replace(sc, lubrication=lub, crank_speed=speed,
                               run=dataclasses.replace(sc.run, turns=turns,
                                                       record_from_turn=0.0))
