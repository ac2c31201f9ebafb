"""The finite-element film kernel: a mesh's pressure solve and what a solved film gives.

It knows meshes, not routes: which mesh and which film a problem asks for is chosen by
:mod:`bearingfem.routes`; this module imports none of them.
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..bearing import Bearing, JournalState
from ..film import film_thickness
from ..solution import FilmSolution, film_solution, undriven
from ..solvers.cavitation import LCPResult, active_set, psor
from ..solvers.linsolve import solve_spd
from ..scales import flow_factor, force_factor, shear_friction
from .assembly import FilmOperator, fe_operator
from .general import film_moment, film_system, general_film
from .multilevel import coarse_guess

__all__ = ["fe_operator", "fe_pressure", "rigid_force", "solve_film", "film_outputs",
           "groove_pressures", "general_film", "film_moment", "SHEAR"]

SHEAR = ("full", "none")


def groove_pressures(bearing: Bearing, op: FilmOperator, grooves) -> np.ndarray | None:
    """Dimensionless pressure held on the fixed dofs (the grooves'), or None without any."""
    if not grooves:
        return None
    G = np.zeros(op.mesh.ndofs)
    for g, dofs in zip(grooves, op.mesh.grooves):
        G[dofs] = g.pressure / bearing.pressure_scale
    return G


def fe_pressure(op: FilmOperator, state: JournalState, cavitation="reynolds",
                method="active-set", tol=1e-10, active0=None, colours=None,
                factor=None, dirichlet: np.ndarray | None = None,
                system=None, guess: np.ndarray | None = None) -> LCPResult:
    """Dimensionless nodal pressure P (p = mu (R/c)^2 P) on all dofs, ambient on fixed ones.

    For "gumbel" the returned field is the unconstrained (full-Sommerfeld) solution; the
    half-Sommerfeld clip is applied where pressure is used. ``active0`` and ``factor``
    (from the result of a nearby state on the same operator) warm-start the solve.
    ``system`` = (stiffness values on the operator's pattern, load) of a film on general
    fields (:func:`bearingfem.fe.general.film_system`); None is the rigid cylinder of
    ``state``, combined from the operator's terms. ``guess``: an approximate pressure on
    the free dofs that places the first cavitated set when ``active0`` is None, instead
    of the coarser levels' rigid film (:func:`~bearingfem.fe.multilevel.coarse_guess`).
    """
    free = op.mesh.free
    if system is None:
        values = op.values(state.eps)
        load = op.load(state.eps, state.eps_dot, state.wedge_speed)
    else:
        values, load = system
    if dirichlet is not None:      # pressures held on fixed dofs (grooves) enter the load
        K_all = op.matrix(values)
        load = load - K_all @ dirichlet
    b = load[free]
    K = op.free_stiffness(state.eps, values)
    P = np.zeros(op.mesh.ndofs) if dirichlet is None else dirichlet.copy()
    if not np.any(b):
        # No wedge and no squeeze: ambient everywhere (avoids 0/0 in residuals).
        return LCPResult(P, 0, 0.0, True, np.zeros(op.mesh.ndofs, bool), factor)
    if cavitation == "reynolds":
        if method == "psor":
            res = psor(K, b, tol=tol, colours=colours)
        else:
            # the coarse levels hold the grooves at their pressures too; on general fields
            # the rigid film's coarse levels only place the first set, the fine solve is exact
            held = () if dirichlet is None else tuple(
                float(dirichlet[dofs[0]]) if len(dofs) else 0.0 for dofs in op.mesh.grooves)
            P0 = None if active0 is not None else \
                guess if guess is not None else coarse_guess(op, state, tol, held)
            a0 = None if active0 is None else np.asarray(active0, bool)[free]
            res = active_set(K, b, active0=a0, P0=P0, tol=tol, factor=factor)
        P[free] = res.pressure
        active = np.zeros(op.mesh.ndofs, bool)
        active[free] = res.active
        return LCPResult(P, res.iterations, res.residual, res.converged, active, res.factor,
                         res.factorisations)
    P[free], factor, fresh = solve_spd(K, b, factor)
    return LCPResult(P, 1, 0.0, True, np.zeros(op.mesh.ndofs, bool), factor, int(fresh))


def _qp_fields(op: FilmOperator, P: np.ndarray):
    """Pressure and its theta-derivative at the quadrature points (elements x points)."""
    f = op.mesh.basis.interpolate(P)
    return np.asarray(f), np.asarray(f.grad[0])


def _integrated_force(op: FilmOperator, P: np.ndarray, clip: bool):
    """(integral of P cos theta, integral of P sin theta) over the meshed film."""
    ic, is_ = op.force_integrals(P, clip)
    return float(ic), float(is_)


def rigid_force(bearing: Bearing, state: JournalState, op: FilmOperator, cavitation: str,
                method: str = "active-set", warm: LCPResult | None = None, grooves=(),
                tol: float = 1e-10):
    """(F_r, F_t) [N] and the :class:`LCPResult` of the rigid film on ``op`` (a mesh in the
    film frame): the light path of time integration, no other outputs. ``warm``, the
    previous call's result on the same mesh at a nearby state, starts the solve from its
    cavitated set and factorisation."""
    a0, factor = (None, None) if warm is None else (warm.active, warm.factor)
    if a0 is not None and (a0.shape != (op.mesh.ndofs,) or not a0.any()):
        a0 = None
    res = fe_pressure(op, state, cavitation, method, tol, active0=a0, factor=factor,
                      dirichlet=groove_pressures(bearing, op, grooves))
    ic, is_ = _integrated_force(op, res.pressure, cavitation == "gumbel")
    k = force_factor(bearing, op.mesh.half)
    return (k * ic, k * is_), res


def solve_film(bearing: Bearing, state: JournalState, op: FilmOperator, element: str,
               cavitation: str, method: str = "active-set", tol: float = 1e-10,
               cavitated_shear: str = "full", grooves=(), film=None,
               gap=None, flow=None) -> FilmSolution:
    """The whole film on ``op`` (a mesh in the film frame): the rigid cylinder of ``state``
    when ``film`` is None, else a film on general fields (:func:`general_film`, with its
    ``gap``) and a rough gap's flow ``flow`` (:class:`~bearingfem.contact.FlowFields` at
    the quadrature points, None: the smooth film's); grooves held at their pressures."""
    system = None
    if film is not None and (flow is not None or not film.is_rigid(op, state)):
        system = film_system(op, film, state.wedge_speed, state.eps, flow)
    res = fe_pressure(op, state, cavitation, method, tol,
                      dirichlet=groove_pressures(bearing, op, grooves), system=system)
    values, load = system if system is not None else (
        op.values(state.eps), op.load(state.eps, state.eps_dot, state.wedge_speed))
    return film_outputs(bearing, state, op, res, values, load, film, cavitation,
                        cavitated_shear, grooves,
                        f"fem-{element}" + (f"/{method}" if cavitation == "reynolds" else ""),
                        gap)


def film_outputs(bearing, state, op, res, values, load, film, cavitation, cavitated_shear,
                 grooves, method, gap=None, force=None, theta=None,
                 moment=None) -> FilmSolution:
    """Forces, moment, friction, leakage and feed of a solved film (rigid or on fields).
    ``force`` (F_r, F_t) [N], ``moment`` (M_x, M_y) [N m] and the nodes' film angles
    ``theta`` of a mesh not in the film frame (grooved films, :mod:`bearingfem.fe.grooved`;
    the thermal film's bearing-fixed mesh); None: integrated here, op's."""
    P = res.pressure
    half = op.mesh.half
    clip = cavitation != "none"
    Pn = np.maximum(P, 0.0) if clip else P
    if force is None:
        ic, is_ = _integrated_force(op, P, cavitation == "gumbel")
        k = force_factor(bearing, half)
        force = (k * ic, k * is_)
    f_r, f_t = force

    # Diagnostics at quadrature points of the film.
    Pq, dPq = _qp_fields(op, Pn)
    wq, th = op.qp_weight, op.qp_theta
    Hq = film_thickness(th, state.eps) if film is None else film.gap
    pmax = float(np.max(np.abs(Pn), initial=0.0))
    # a film nothing drives is at ambient, not ruptured: all of it wet, no cavity
    wet = Pq > 1e-12 * pmax if clip and not (pmax == 0.0 and undriven(state, film)) \
        else np.ones_like(Pq, bool)
    area = float(np.sum(wq))
    cav_fraction = float(np.sum(wq[~wet]) / area) if clip else 0.0
    shear_cav = 1.0 if cavitated_shear == "full" else 0.0
    friction = shear_friction(bearing, state.omega, wq, Hq, dPq,
                              couette_share=np.where(wet, 1.0, shear_cav),
                              poiseuille_share=wet,
                              viscosity=1.0 if film is None else film.viscosity, half=half)
    # Side leakage: the consistent boundary flux is the residual at the end dofs. With
    # cavitation, positive residuals there are complementarity multipliers of the
    # cavitated zone, not flow, so only outflow (negative residual) counts.
    K = sp.csr_matrix((values, op.indices, op.indptr), shape=op.shape)
    r = K @ Pn - load
    r_end = r[op.mesh.end]
    if clip:
        r_end = np.minimum(r_end, 0.0)
    leakage = -flow_factor(bearing, half) * float(np.sum(r_end))
    # what leaves alone (the full film draws oil in at its ends where p < 0)
    outflow = -flow_factor(bearing, half) * float(np.sum(np.minimum(r_end, 0.0)))
    # What the grooves feed: the same consistent flux at their dofs (into the film > 0;
    # groove dofs on the axial ends carry leakage, counted above). The Reynolds-condition
    # films do not conserve mass (their multipliers create and destroy oil), so a feed is
    # defined for the full film only.
    flow_in = None
    if grooves and not clip:
        r_in = r[np.setdiff1d(np.concatenate(op.mesh.grooves), op.mesh.end)]
        flow_in = flow_factor(bearing, half) * float(np.sum(r_in))
    if moment is None:
        moment = (0.0, 0.0) if half else film_moment(bearing, op, P, state.gamma,
                                                     cavitation == "gumbel")
    return film_solution(
        bearing, state, Pn, op.mesh.theta if theta is None else theta, op.mesh.zeta,
        (f_r, f_t), friction=friction,
        leakage=leakage, side_outflow=outflow, flow_in=flow_in,
        cavitated_fraction=cav_fraction, record=res,
        method=method, cavitation=cavitation, half=half, mesh=op.mesh, moment=moment,
        gap=gap)
