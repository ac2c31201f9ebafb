"""The mass-conserving (JFO) grooved film on the mesh fixed in the bearing: a new journal
angle changes the gap, not the mesh or the operator.

The mesh is the one of :mod:`bearingfem.fe.grooved`: its angle is phi = theta + gamma
(the film angle of a journal at gamma = 0), the grooves' edges are grid lines on any
n_theta, and the Poiseuille stiffness of -div(H^3 grad P) at (eps, gamma) is a
combination of its seven harmonic tables. The JFO balance (:mod:`bearingfem.fe.jfo`)
takes, per control volume, the content int H, the Couette face int H dzeta and the
squeeze int dH/dt of the gap H = 1 + eps cos(phi - gamma); these are the rigid cylinder's
exact integrals with the volumes' theta limits shifted by -gamma, so a new journal angle
costs a few vector operations (:func:`grooved_balance_film`).

As on the grooves' moving mesh, the steady film is the one steady in the frame of the
line of centres (content carried at w/2, a squeeze eps_dot cos(theta)) with the grooves
where they are at this instant; the transient film on this mesh is
:class:`~bearingfem.fe.jfo_grooved_transient.GroovedJFOFilm`. The grooves may be flooded (``Groove.pressure`` held, fraction 1) or
starved (``Groove.fraction`` < 1: what the groove supplies is the flow the film draws at
that fraction, reported as ``flow_in``).

On nodes, this film is the grooves' moving-mesh film turned by gamma (the same volumes and
quadrature points): the two agree to the solver's tolerance (tests/test_jfo_grooved.py).
"""
from __future__ import annotations

import numpy as np

from ..bearing import Bearing, JournalState
from ..errors import ConvergenceError
from ..film import film_thickness, film_thickness_integral
from ..scales import force_factor
from ..solution import FilmSolution, film_solution
from .assembly import FilmOperator
from .grooved import GroovedOperator, rotated, groove_operator_for, grooved_operator
from .jfo_balance import solve_film_balance, film_volumes
from .jfo_fields import BalanceFilm
from .jfo_steady import COARSEST_FREE_NODES, coarser_mesh, prolonged_cavity, jfo_shear

__all__ = ["grooved_balance_film", "solve_grooved_jfo", "grooved_jfo_force",
           "grooved_jfo_solution"]


def grooved_balance_film(gop: GroovedOperator, state: JournalState) -> BalanceFilm:
    """The balance's film of ``state`` on the bearing-fixed mesh of ``gop`` (exact
    integrals of the gap 1 + eps cos(phi - gamma) over the volumes)."""
    cv = film_volumes(gop.op.mesh)
    e, g = state.eps, state.gamma
    content = cv.width * film_thickness_integral(cv.x_lo - g, cv.x_hi - g, e)
    cos_integral = cv.width * film_thickness_integral(cv.x_lo - g, cv.x_hi - g, 1.0) - cv.area
    return BalanceFilm(values=gop.values(e, g), content=content,
                       face=film_thickness(cv.face - g, e) * cv.width,
                       squeeze=state.eps_dot * cos_integral)


def grooved_films(state: JournalState):
    """op -> the balance film of ``state`` on that bearing-fixed mesh (tables cached)."""
    return lambda op: grooved_balance_film(grooved_operator(op), state)


def _operator(bearing: Bearing, grooves):
    return lambda nt, nz: groove_operator_for(bearing, nt, nz, "P1", grooves).op


def _steady(bearing, state, n_theta, n_z, grooves, ambient, cavitated0=None):
    """(BalanceSolve, op) of the steady film; a cold start takes its first cavitated set
    from the same film on a mesh half as fine (recursively), as the moving mesh's does."""
    op = _operator(bearing, grooves)(n_theta, n_z)
    f = grooved_films(state)(op)
    cv = film_volumes(op.mesh)
    warm = 3
    if cavitated0 is None and len(op.mesh.free) > COARSEST_FREE_NODES:
        bc, opc = _steady(bearing, state, *coarser_mesh(n_theta, n_z), grooves, ambient)
        cavitated0 = prolonged_cavity(opc, op, bc.P, bc.phi)
        warm = 12
    try:
        b = solve_film_balance(bearing, op, state.eps, f.transport(cv, state.wedge_speed),
                               12.0 * f.squeeze, np.zeros(op.mesh.ndofs), grooves, ambient,
                               cavitated0, warm, values=f.values)
    except ConvergenceError as e:
        raise e.at(f"steady grooved JFO film {n_theta}x{n_z}, eps = {state.eps:.6g}") \
            from None
    return b, op


def grooved_jfo_force_of(bearing: Bearing, op: FilmOperator, P: np.ndarray,
                         gamma: float) -> tuple:
    """(F_r, F_t) [N]: the integrals in phi rotated into the line of centres."""
    F = force_factor(bearing, True) * rotated(op.force_integrals(P), gamma)
    return float(F[0]), float(F[1])


def grooved_jfo_force(bearing: Bearing, state: JournalState, n_theta: int, n_z: int,
                      grooves, ambient_pressure: float = 0.0, cavitated0=None):
    """(F_r, F_t) [N] of the steady grooved JFO film and its solve record (light path);
    ``cavitated0``: a nearby state's cavitated set on this mesh."""
    b, op = _steady(bearing, state, n_theta, n_z, grooves, ambient_pressure, cavitated0)
    return grooved_jfo_force_of(bearing, op, b.P, state.gamma), b.result


def grooved_jfo_solution(bearing: Bearing, state: JournalState, op: FilmOperator, b,
                         method: str = "fem-P1/jfo") -> FilmSolution:
    """The whole film of the balance solve ``b`` on the bearing-fixed mesh ``op``, nodes
    reported at their film angles theta = phi - gamma."""
    P, phi = b.P, b.phi
    friction, cav_fraction = jfo_shear(bearing, state.omega, op, P, phi,
                                       film_thickness(op.qp_theta - state.gamma, state.eps))
    return film_solution(
        bearing, state, P, op.mesh.theta - state.gamma, op.mesh.zeta,
        grooved_jfo_force_of(bearing, op, P, state.gamma), friction=friction,
        leakage=b.flows.side_leakage, side_outflow=b.flows.side_outflow,
        flow_in=b.flows.flow_in,
        cavitated_fraction=cav_fraction, record=b.result, method=method, cavitation="jfo",
        half=True, mesh=op.mesh, fraction=phi, mass_balance=b.flows.balance)


def solve_grooved_jfo(bearing: Bearing, state: JournalState, n_theta: int, n_z: int,
                      grooves, ambient_pressure: float = 0.0) -> FilmSolution:
    """The steady grooved JFO film (half length, arguments checked by
    :func:`~bearingfem.solve_reynolds`)."""
    b, op = _steady(bearing, state, n_theta, n_z, grooves, ambient_pressure)
    return grooved_jfo_solution(bearing, state, op, b)

