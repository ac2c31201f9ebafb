"""The steady mass-conserving (JFO) journal film on the finite-element mesh (the model and
its variables: :mod:`bearingfem.fe.jfo`): steady in the frame of the line of centres, where
the content moves at w/2 = (omega - 2 gamma_dot)/2 and a squeeze eps_dot changes the local
film at the rate eps_dot cos(theta); and the film solution every JFO solve reports.
"""
from __future__ import annotations

import numpy as np

from ..bearing import Bearing, JournalState
from ..errors import ConvergenceError
from ..film import film_thickness
from ..scales import force_factor, shear_friction
from ..solution import FilmSolution, film_solution
from ..solvers.jfo import JFOResult
from .assembly import FilmOperator
from .general import film_moment
from .jfo_balance import (JFOFlows, cos_integral, mesh_prolongation, solve_film_balance, transport,
                          film_volumes)

__all__ = ["solve_jfo", "jfo_force"]


def jfo_shear(bearing, omega: float, op: FilmOperator, P, phi, gap, viscosity=1.0):
    """(friction, cavitated area fraction) of a JFO film: ``gap`` H and ``viscosity`` (ratio)
    at the quadrature points. The Couette shear acts on the oil present (the fraction phi
    of the gap, as streamers), the Poiseuille part where the film is full."""
    Pq = op.at_quadrature(P)
    dPq = np.asarray(op.mesh.basis.interpolate(P).grad[0])
    friction = shear_friction(bearing, omega, op.qp_weight, gap, dPq,
                              couette_share=np.clip(op.at_quadrature(phi), 0.0, 1.0),
                              poiseuille_share=Pq > 0.0, viscosity=viscosity,
                              half=op.mesh.half)
    area = film_volumes(op.mesh).area
    return friction, float(np.sum(area * (1.0 - phi > 1e-12)) / np.sum(area))


def jfo_film_solution(bearing, state, op: FilmOperator, P, phi, res: JFOResult,
                   flows: JFOFlows, method: str, film=None) -> FilmSolution:
    """Forces, friction and the rest of a JFO film (P >= 0 is the pressure everywhere);
    ``film``: its :class:`~bearingfem.fe.jfo_fields.BalanceFilm` on fields (None: the
    rigid cylinder): a whole-length film on fields also gets its moment."""
    k = force_factor(bearing, op.mesh.half)
    ic, is_ = op.force_integrals(P)
    f_r, f_t = k * float(ic), k * float(is_)
    fields = None if film is None else film.fields
    Hq = film_thickness(op.qp_theta, state.eps) if fields is None else fields.gap
    friction, cav_fraction = jfo_shear(bearing, state.omega, op, P, phi, Hq,
                                       1.0 if fields is None else fields.viscosity)
    return film_solution(
        bearing, state, P, op.mesh.theta, op.mesh.zeta, (f_r, f_t), friction=friction,
        leakage=flows.side_leakage, side_outflow=flows.side_outflow, flow_in=flows.flow_in, cavitated_fraction=cav_fraction,
        record=res, method=method, cavitation="jfo", half=op.mesh.half, mesh=op.mesh,
        fraction=phi, mass_balance=flows.balance,
        moment=(0.0, 0.0) if op.mesh.half else film_moment(bearing, op, P, state.gamma),
        gap=None if film is None else film.gap)


#: Below this many free nodes a steady film starts cold instead of from a coarser mesh.
COARSEST_FREE_NODES = 500


def coarser_mesh(n_theta: int, n_z: int) -> tuple:
    """(n_theta, n_z) of the mesh half as fine a cold start takes its cavity from."""
    return max(8, n_theta // 2), max(2, n_z // 2)


def prolonged_cavity(coarse: FilmOperator, fine: FilmOperator, P, phi):
    """Cavitated set (bool per node) on ``fine`` from the film (P, phi) solved on
    ``coarse``: where the prolonged universal variable P - (1 - phi) is < 0."""
    return (mesh_prolongation(coarse.mesh, fine.mesh) @ (P - (1.0 - phi))) < 0.0


def steady_jfo(bearing: Bearing, state: JournalState, operator, n_theta, n_z, grooves,
            ambient, cavitated0=None, film=None):
    """Steady film on the mesh ``operator(n_theta, n_z)``. A cold start takes its first
    cavitated set from the same film on a mesh half as fine (recursively): the fronts then
    sit within a node of their place and one or two iterations finish. ``film``: a
    function of the operator giving its :class:`~bearingfem.fe.jfo_fields.BalanceFilm`
    (None: the rigid cylinder's); the last value returned is the fine mesh's (or None)."""
    op = operator(n_theta, n_z)
    cv = film_volumes(op.mesh)
    f = None if film is None else film(op)
    if f is None:
        T = transport(cv, state.eps, state.wedge_speed)
        storage = 12.0 * state.eps_dot * cos_integral(cv)
    else:
        T, storage = f.transport(cv, state.wedge_speed), 12.0 * f.squeeze
    warm = 3
    if cavitated0 is None and len(op.mesh.free) > COARSEST_FREE_NODES:
        Pc, phic, _, _, opc, _ = steady_jfo(bearing, state, operator, *coarser_mesh(n_theta, n_z),
                                         grooves, ambient, film=film)
        cavitated0 = prolonged_cavity(opc, op, Pc, phic)
        warm = 12
    try:
        b = solve_film_balance(bearing, op, state.eps, T, storage, np.zeros(op.mesh.ndofs), grooves,
                   ambient, cavitated0, warm, values=None if f is None else f.values)
    except ConvergenceError as e:
        raise e.at(f"steady JFO film {n_theta}x{n_z}, eps = {state.eps:.6g}") from None
    return b.P, b.phi, b.result, b.flows, op, f


def solve_jfo(bearing: Bearing, state: JournalState, operator, n_theta: int, n_z: int,
              grooves=(), ambient_pressure: float = 0.0, film=None) -> FilmSolution:
    """Steady JFO film on the mesh ``operator(n_theta, n_z)`` (a callable that builds the
    film operator of a mesh; arguments checked by ``solve_reynolds``); ``film``: a
    function of the operator giving the film on fields
    (:func:`~bearingfem.fe.jfo_fields.field_balance_film`), None the rigid cylinder."""
    P, phi, res, flows, op, f = steady_jfo(bearing, state, operator, n_theta, n_z, grooves,
                                        ambient_pressure, film=film)
    return jfo_film_solution(bearing, state, op, P, phi, res, flows, "fem-P1/jfo", f)


def jfo_force(bearing: Bearing, state: JournalState, operator, n_theta: int, n_z: int,
              grooves=(), ambient_pressure: float = 0.0, cavitated0=None):
    """(F_r, F_t) [N] of the steady JFO film and its solve record (light path)."""
    P, _, res, _, op, _ = steady_jfo(bearing, state, operator, n_theta, n_z, grooves,
                                  ambient_pressure, cavitated0)
    ic, is_ = op.force_integrals(P)
    k = force_factor(bearing, op.mesh.half)
    return (k * float(ic), k * float(is_)), res


#: A transient step that does not converge is cut in halves up to this many times.
