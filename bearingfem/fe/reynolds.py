"""Finite-element Reynolds solve: film -> mesh -> assembly -> cavitation solve -> forces."""
from __future__ import annotations

import numpy as np

from ..bearing import Bearing, JournalState
from ..film import film_thickness
from ..solution import FilmSolution, film_solution
from ..solvers.cavitation import LCPResult, active_set, psor
from ..solvers.linsolve import solve_spd
from ..validation import check_film_solve, check_grooves, check_jfo_supply
from .assembly import FilmOperator, fe_operator
from .jfo import jfo_force, solve_jfo
from .mesh import ELEMENTS
from .multilevel import coarse_guess

__all__ = ["solve_reynolds", "fe_operator", "fe_pressure", "fe_force"]

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
                factor=None, dirichlet: np.ndarray | None = None) -> LCPResult:
    """Dimensionless nodal pressure P (p = mu (R/c)^2 P) on all dofs, ambient on fixed ones.

    For "gumbel" the returned field is the unconstrained (full-Sommerfeld) solution; the
    half-Sommerfeld clip is applied where pressure is used. ``active0`` and ``factor``
    (from the result of a nearby state on the same operator) warm-start the solve.
    """
    free = op.mesh.free
    load = op.load(state.eps, state.eps_dot, state.wedge_speed)
    if dirichlet is not None:      # pressures held on fixed dofs (grooves) enter the load
        load = load - op.stiffness(state.eps) @ dirichlet
    b = load[free]
    K = op.free_stiffness(state.eps)
    P = np.zeros(op.mesh.ndofs) if dirichlet is None else dirichlet.copy()
    if not np.any(b):
        # No wedge and no squeeze: ambient everywhere (avoids 0/0 in residuals).
        return LCPResult(P, 0, 0.0, True, np.zeros(op.mesh.ndofs, bool), factor)
    if cavitation == "reynolds":
        if method == "psor":
            res = psor(K, b, tol=tol, colours=colours)
        else:
            # the coarse levels hold the grooves at their pressures too
            held = () if dirichlet is None else tuple(
                float(dirichlet[dofs[0]]) if len(dofs) else 0.0 for dofs in op.mesh.grooves)
            P0 = None if active0 is not None else coarse_guess(op, state, tol, held)
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


def fe_force(bearing: Bearing, state: JournalState, n_theta=60, n_z=10, element="P1",
             cavitation="gumbel", method="active-set", half=True, warm: LCPResult | None = None,
             grooves=(), ambient_pressure: float = 0.0):
    """(F_r, F_t) [N] and the :class:`LCPResult`: the light path used in time integration.

    Pass the previous call's result as ``warm`` (same mesh, nearby state): its cavitated
    set and factorisation start this solve. ``grooves`` (fixed in the inertial frame) move
    the mesh with the attitude angle, so the force stays smooth in it.
    """
    if cavitation == "jfo":     # steady JFO film; warm = previous call's cavitated set
        return jfo_force(bearing, state,
                         lambda nt, nz: fe_operator(bearing, state, nt, nz, "P1", None, half,
                                                    grooves),
                         n_theta, n_z, grooves, ambient_pressure,
                         None if warm is None else getattr(warm, "cavitated", None))
    op = fe_operator(bearing, state, n_theta, n_z, element, None, half, grooves)
    a0, factor = (None, None) if warm is None else (warm.active, warm.factor)
    if a0 is not None and (a0.shape != (op.mesh.ndofs,) or not a0.any()):
        a0 = None
    res = fe_pressure(op, state, cavitation, method, active0=a0, factor=factor,
                      dirichlet=groove_pressures(bearing, op, grooves))
    ic, is_ = _integrated_force(op, res.pressure, cavitation == "gumbel")
    k = bearing.force_scale * (2.0 if op.mesh.half else 1.0)
    return (k * ic, k * is_), res


def solve_reynolds(bearing: Bearing, state: JournalState, n_theta: int = 120, n_z: int = 20,
                   element: str = "P1", cavitation: str = "reynolds", *,
                   method: str = "active-set", supply_angle=None, half: bool = True,
                   tol: float = 1e-10, cavitated_shear: str = "full",
                   grooves=(), ambient_pressure: float = 0.0) -> FilmSolution:
    """Solve the Reynolds equation on a finite-element mesh of the unwrapped film.

    Parameters
    ----------
    bearing, state : :class:`Bearing`, :class:`JournalState`
    n_theta : cells around the circumference (>= 8)
    n_z : cells along the length (>= 2); with ``half=True`` only z >= 0 is meshed,
        with ceil(n_z/2) cells, which the symmetry of an aligned journal allows
    element : "P1" or "P2" triangles
    cavitation : "none" (full Sommerfeld), "gumbel" (negative pressure set to ambient after
        the solve), "reynolds" (Swift-Stieber complementarity, projected iteration), "jfo"
        (mass-conserving Jakobsson-Floberg-Olsson film, :mod:`bearingfem.fe.jfo`; P1 only;
        needs a supply: grooves, supply_angle or ambient_pressure > 0)
    method : "active-set" (default) or "psor" for ``cavitation="reynolds"``
    supply_angle : inertial angle [rad] of an axial supply line at ambient pressure, or None
        for a fully periodic film
    tol : tolerance of the projected iteration
    cavitated_shear : "full" - Couette shear mu omega R / h acts over the whole cavitated
        area (a full film of oil that carries no pressure); "none" - no shear there
    grooves : axial supply grooves (:class:`~bearingfem.bearing.Groove`), fixed in the
        inertial frame and flooded at their pressure; with ``cavitation="none"``
        ``flow_in`` is the flow they feed [m^3/s] (equal to the side leakage); with
        ``cavitation="jfo"`` a groove may be starved (``fraction`` < 1)
    ambient_pressure : JFO films: pressure at the axial ends and a supply line above the
        cavitation pressure [Pa] (>= 0)

    Returns
    -------
    FilmSolution
    """
    n_theta, n_z, supply_angle = check_film_solve(
        bearing, state, n_theta, n_z, cavitation, method, supply_angle, tol,
        element=(element, tuple(ELEMENTS)), cavitated_shear=(cavitated_shear, SHEAR))
    grooves = check_grooves(grooves, supply_angle, mass_conserving=cavitation == "jfo")
    ambient_pressure = check_jfo_supply(cavitation, grooves, supply_angle, ambient_pressure,
                                        element)

    if cavitation == "jfo":
        return solve_jfo(bearing, state,
                         lambda nt, nz: fe_operator(bearing, state, nt, nz, "P1", supply_angle,
                                                    half, grooves),
                         n_theta, n_z, grooves, ambient_pressure)
    op = fe_operator(bearing, state, n_theta, n_z, element, supply_angle, half, grooves)
    dirichlet = groove_pressures(bearing, op, grooves)
    res = fe_pressure(op, state, cavitation, method, tol, dirichlet=dirichlet)
    P = res.pressure
    clip = cavitation != "none"
    Pn = np.maximum(P, 0.0) if clip else P
    mult = 2.0 if op.mesh.half else 1.0
    ic, is_ = _integrated_force(op, P, cavitation == "gumbel")
    f_r, f_t = bearing.force_scale * mult * ic, bearing.force_scale * mult * is_

    # Diagnostics at quadrature points of the film.
    Pq, dPq = _qp_fields(op, Pn)
    wq, th = op.qp_weight, op.qp_theta
    Hq = film_thickness(th, state.eps)
    pmax = float(np.max(np.abs(Pn), initial=0.0))
    wet = Pq > 1e-12 * pmax if clip else np.ones_like(Pq, bool)
    area = float(np.sum(wq))
    cav_fraction = float(np.sum(wq[~wet]) / area) if clip else 0.0
    shear_cav = 1.0 if cavitated_shear == "full" else 0.0
    couette = state.omega / Hq * np.where(wet, 1.0, shear_cav)
    poiseuille = np.where(wet, 0.5 * Hq * dPq, 0.0)
    mu, R, c = bearing.viscosity, bearing.radius, bearing.clearance
    friction = mu * R ** 3 / c * mult * float(np.sum(wq * (couette + poiseuille)))
    # Side leakage: the consistent boundary flux is the residual at the end dofs. With
    # cavitation, positive residuals there are complementarity multipliers of the
    # cavitated zone, not flow, so only outflow (negative residual) counts.
    r = op.stiffness(state.eps) @ Pn - op.load(state.eps, state.eps_dot, state.wedge_speed)
    r_end = r[op.mesh.end]
    if clip:
        r_end = np.minimum(r_end, 0.0)
    leakage = -c * R ** 2 / 12.0 * mult * float(np.sum(r_end))
    # What the grooves feed: the same consistent flux at their dofs (into the film > 0;
    # groove dofs on the axial ends carry leakage, counted above). The Reynolds-condition
    # films do not conserve mass (their multipliers create and destroy oil), so a feed is
    # defined for the full film only.
    flow_in = None
    if grooves and not clip:
        r_in = r[np.setdiff1d(np.concatenate(op.mesh.grooves), op.mesh.end)]
        flow_in = c * R ** 2 / 12.0 * mult * float(np.sum(r_in))

    return film_solution(
        bearing, state, Pn, op.mesh.theta, op.mesh.zeta, (f_r, f_t), friction=friction,
        leakage=leakage, flow_in=flow_in, cavitated_fraction=cav_fraction, record=res,
        method=f"fem-{element}" + (f"/{method}" if cavitation == "reynolds" else ""),
        cavitation=cavitation, half=op.mesh.half, mesh=op.mesh)
