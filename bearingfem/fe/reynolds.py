"""Finite-element Reynolds solve: film -> mesh -> assembly -> cavitation solve -> forces."""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..bearing import Bearing, JournalState, check_inside_clearance
from ..film import film_thickness
from ..solution import FilmSolution, film_solution
from ..solvers.cavitation import LCPResult, active_set, psor
from ..solvers.linsolve import solve_spd
from ..validation import check_film_solve, check_grooves, check_jfo_supply
from ..fields import FilmFields, check_tilt
from ..scales import flow_factor, force_factor, shear_friction
from .assembly import FilmOperator, fe_operator
from .general import film_moment, film_system, general_film
from .jfo import jfo_force, solve_jfo
from .jfo_compressible import check_elrod, is_elrod, solve_compressible_jfo
from .jfo_fields import balance_films
from .mesh import ELEMENTS
from .mixed import check_roughness, film_contact, with_contact
from .multilevel import coarse_guess

__all__ = ["solve_reynolds", "fe_operator", "fe_pressure", "fe_force", "general_film",
           "film_moment"]

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
                system=None) -> LCPResult:
    """Dimensionless nodal pressure P (p = mu (R/c)^2 P) on all dofs, ambient on fixed ones.

    For "gumbel" the returned field is the unconstrained (full-Sommerfeld) solution; the
    half-Sommerfeld clip is applied where pressure is used. ``active0`` and ``factor``
    (from the result of a nearby state on the same operator) warm-start the solve.
    ``system`` = (stiffness values on the operator's pattern, load) of a film on general
    fields (:func:`bearingfem.fe.general.film_system`); None is the rigid cylinder of
    ``state``, combined from the operator's terms.
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
    set and factorisation start this solve. ``grooves`` (fixed in the inertial frame) are
    solved on the bearing-fixed mesh of :mod:`bearingfem.fe.grooved` (no rebuild for a
    new journal angle; ``warm`` gives its cavitated set only), the JFO film's too
    (:mod:`bearingfem.fe.jfo_grooved`).
    """
    if cavitation == "jfo" and grooves and half:     # the bearing-fixed mesh
        from .jfo_grooved import grooved_jfo_force
        return grooved_jfo_force(bearing, state, n_theta, n_z, grooves, ambient_pressure,
                                 None if warm is None else getattr(warm, "cavitated", None))
    if cavitation == "jfo":     # steady JFO film; warm = previous call's cavitated set
        return jfo_force(bearing, state,
                         lambda nt, nz: fe_operator(bearing, state, nt, nz, "P1", None, half,
                                                    grooves),
                         n_theta, n_z, grooves, ambient_pressure,
                         None if warm is None else getattr(warm, "cavitated", None))
    if grooves and half:    # the bearing-fixed mesh: a new journal angle rebuilds nothing
        from .grooved import groove_operator_for, grooved_force
        return grooved_force(bearing, state,
                             groove_operator_for(bearing, n_theta, n_z, element, grooves),
                             grooves, cavitation, method, warm)
    op = fe_operator(bearing, state, n_theta, n_z, element, None, half, grooves)
    a0, factor = (None, None) if warm is None else (warm.active, warm.factor)
    if a0 is not None and (a0.shape != (op.mesh.ndofs,) or not a0.any()):
        a0 = None
    res = fe_pressure(op, state, cavitation, method, active0=a0, factor=factor,
                      dirichlet=groove_pressures(bearing, op, grooves))
    ic, is_ = _integrated_force(op, res.pressure, cavitation == "gumbel")
    k = force_factor(bearing, op.mesh.half)
    return (k * ic, k * is_), res


def solve_reynolds(bearing: Bearing, state: JournalState, n_theta: int = 120, n_z: int = 20,
                   element: str = "P1", cavitation: str = "reynolds", *,
                   method: str = "active-set", supply_angle=None, half: bool = True,
                   tol: float = 1e-10, cavitated_shear: str = "full",
                   grooves=(), ambient_pressure: float = 0.0, fields: FilmFields | None = None,
                   tilt=(0.0, 0.0), tilt_rate=(0.0, 0.0), lubricant=None,
                   bush=None, roughness=None, start=None, thermal=None) -> FilmSolution:
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
    fields : :class:`~bearingfem.fields.FilmFields`: gap, its rate, viscosity and density
        fields of the film (every cavitation model; JFO: :mod:`bearingfem.fe.jfo_fields`);
        None is the rigid cylinder
    tilt : (tilt_x, tilt_y) [rad], the journal axis turned about the inertial x and y axes
        through the bearing centre (:func:`~bearingfem.fields.tilted_gap`); its gap is
        added to the fields' (every cavitation model)
    tilt_rate : their rates [rad/s] (squeeze)
    lubricant : :class:`~bearingfem.lubricant.Lubricant` whose viscosity and density follow
        the pressure (ratios to the bearing's viscosity), or None (cavitation "none" or
        "reynolds"; solved by Newton, :mod:`bearingfem.ehd`). With cavitation "jfo", a
        lubricant with a ``bulk_modulus`` (and constant viscosity) gives the compressible
        Elrod-type JFO film (:mod:`bearingfem.fe.jfo_compressible`; ``density`` rho/rho0)
    bush : :class:`~bearingfem.elastic.ElasticBush` (its compliance is built on the film
        grid) or a prebuilt full or reduced compliance on the (n_theta, n_z + 1) grid; the
        gap becomes c (1 + eps cos theta) + deformation (P1, cavitation "none",
        "reynolds" or "jfo" (:mod:`bearingfem.ehd.jfo`, with a pressure-viscosity law
        only); quasi-static: the deflection's rate is left out of the squeeze term).
        With a lubricant or a bush, ``method`` and ``tol`` serve the rigid start and the
        Newton test, and ``iterations`` counts Newton steps (:mod:`bearingfem.ehd`)
    roughness : :class:`~bearingfem.contact.Roughness` (mixed lubrication): the
        Greenwood-Tripp asperity contact of the gap at the film's quadrature points is
        added as ``asperity_force`` / ``asperity_friction_torque`` (the film's pressure is
        unchanged by it, :mod:`bearingfem.fe.mixed`); with a bush the summits' pressure
        deforms the bush too (mixed EHD, :mod:`bearingfem.ehd.asperity`); None: no contact
    start : with a lubricant or bush, a previous :class:`FilmSolution` of the same mesh
        whose pressure (and JFO fraction) starts Newton (a nearby state converges in a
        few steps; if that stalls, the cold route); None: a cold start. Same answer to ``tol``.
    thermal : :class:`~bearingfem.thermal.Thermal`: the thermal (THD) film of
        :func:`bearingfem.thermal.solve_thd` with this ``lubricant`` (its temperature law);
        ``start`` a previous thermal film of the same mesh

    With ``fields`` or a tilt the whole length is meshed (no mid-plane symmetry) and
    ``moment`` is the film's moment on the journal; fields that are the rigid cylinder's
    are solved by the rigid film's fast path (the same discrete problem).

    Returns
    -------
    FilmSolution
    """
    if thermal is not None:      # the thermal film (bearingfem.thermal), its own route
        from ..thermal.coupled import solve_thd
        return solve_thd(bearing, state, n_theta, n_z, lubricant=lubricant, thermal=thermal, grooves=grooves, cavitation=cavitation, element=element, supply_angle=supply_angle, tol=tol, start=start)
    n_theta, n_z, supply_angle = check_film_solve(
        bearing, state, n_theta, n_z, cavitation, method, supply_angle, tol,
        element=(element, tuple(ELEMENTS)), cavitated_shear=(cavitated_shear, SHEAR))
    grooves = check_grooves(grooves, supply_angle, mass_conserving=cavitation == "jfo")
    ambient_pressure = check_jfo_supply(cavitation, grooves, supply_angle, ambient_pressure,
                                        element)
    tilt, tilt_rate = check_tilt("tilt", tilt), check_tilt("tilt_rate", tilt_rate)
    if bush is None:
        check_inside_clearance(state, "solve_reynolds without a bush")
    if start is not None and not (lubricant is not None or bush is not None):
        raise ValueError("start is for the EHD film (a lubricant or a bush); got neither")
    if fields is not None and not isinstance(fields, FilmFields):
        raise ValueError(f"fields must be a FilmFields, got {type(fields).__name__}")
    # a lubricant with a bulk modulus and nothing else: the compressible (Elrod) JFO film
    compressible = cavitation == "jfo" and bush is None and is_elrod(lubricant)
    bulk_modulus = check_elrod(bearing, lubricant) if compressible else None
    ehd = not compressible and (lubricant is not None or bush is not None)
    if ehd and cavitation == "jfo":        # the EHD film with JFO cavitation
        from ..ehd.jfo import check_ehd_jfo, solve_ehd_jfo_film
        check_ehd_jfo(lubricant, fields, tilt, tilt_rate)
        if roughness is not None:
            raise ValueError("roughness with cavitation='jfo' and a bush or lubricant is "
                             "not supported yet")

        def whole(nt, nz):
            return fe_operator(bearing, state, nt, nz, "P1", supply_angle, False, grooves)
        return solve_ehd_jfo_film(bearing, state, whole, n_theta, n_z, lubricant, bush,
                                  grooves, ambient_pressure, tol, start)
    if ehd:
        from ..ehd.film import check_ehd, solve_ehd_film
        check_ehd(lubricant, bush, fields, element, cavitation)
    general = fields is not None or any(tilt) or any(tilt_rate) or ehd
    if compressible and general:
        raise ValueError("the compressible JFO film (a lubricant with bulk_modulus) takes no "
                         "fields, tilt or tilt_rate yet; give the incompressible film those")
    roughness = check_roughness(roughness)

    if cavitation == "jfo" and grooves and half and not general and not compressible \
            and roughness is None:     # the bearing-fixed mesh: a new angle rebuilds nothing
        from .jfo_grooved import solve_grooved_jfo
        return solve_grooved_jfo(bearing, state, n_theta, n_z, grooves, ambient_pressure)
    if cavitation == "jfo":
        def operator(nt, nz):
            return fe_operator(bearing, state, nt, nz, "P1", supply_angle,
                               half and not general, grooves)
        film = contact_gap = None
        if general:
            fine = operator(n_theta, n_z)
            film = balance_films(bearing, state, fine, fields, tilt, tilt_rate)
            contact_gap = film(fine).fields.gap            # bad fields raised above
            if film(fine).fields.is_rigid(fine, state):
                film = None                 # the rigid data takes the fast path
        sol = solve_compressible_jfo(bearing, state, operator, n_theta, n_z,
                                     bulk_modulus, grooves, ambient_pressure) \
            if compressible else solve_jfo(bearing, state, operator, n_theta, n_z, grooves,
                                           ambient_pressure, film)
        return sol if roughness is None else with_contact(
            sol, film_contact(bearing, state, operator(n_theta, n_z), roughness,
                              contact_gap))
    if grooves and half and not general and supply_angle is None:
        from .grooved import groove_operator_for, grooved_solution   # (imports this module)
        sol = grooved_solution(bearing, state,
                               groove_operator_for(bearing, n_theta, n_z, element, grooves),
                               grooves, cavitation, method, tol, cavitated_shear, element)
        return sol if roughness is None else with_contact(
            sol, film_contact(bearing, state, fe_operator(bearing, state, n_theta, n_z,
                                                          element, None, True, grooves),
                              roughness))
    op = fe_operator(bearing, state, n_theta, n_z, element, supply_angle,
                     half and not general, grooves)
    system = film = gap = None
    if general:
        film, gap = general_film(bearing, state, op, fields, tilt, tilt_rate)
        if ehd:
            return solve_ehd_film(bearing, state, op, film, gap, lubricant, bush, cavitation,
                                  method, tol, groove_pressures(bearing, op, grooves),
                                  cavitated_shear, grooves, start, roughness)
        if not film.is_rigid(op, state):      # the rigid data takes the fast path
            system = film_system(op, film, state.wedge_speed, state.eps)
    dirichlet = groove_pressures(bearing, op, grooves)
    res = fe_pressure(op, state, cavitation, method, tol, dirichlet=dirichlet, system=system)
    values, load = system if system is not None else (
        op.values(state.eps), op.load(state.eps, state.eps_dot, state.wedge_speed))
    sol = _film_outputs(bearing, state, op, res, values, load, film, cavitation,
                        cavitated_shear, grooves,
                        f"fem-{element}" + (f"/{method}" if cavitation == "reynolds" else ""),
                        gap)
    return sol if roughness is None else with_contact(
        sol, film_contact(bearing, state, op, roughness, None if film is None else film.gap))


def _film_outputs(bearing, state, op, res, values, load, film, cavitation, cavitated_shear,
                  grooves, method, gap=None, force=None, theta=None) -> FilmSolution:
    """Forces, moment, friction, leakage and feed of a solved film (rigid or on fields).
    ``force`` (F_r, F_t) [N] and the nodes' film angles ``theta`` of a mesh not in the film
    frame (grooved films, :mod:`bearingfem.fe.grooved`); None: integrated here, op's."""
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
    wet = Pq > 1e-12 * pmax if clip else np.ones_like(Pq, bool)
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
    # What the grooves feed: the same consistent flux at their dofs (into the film > 0;
    # groove dofs on the axial ends carry leakage, counted above). The Reynolds-condition
    # films do not conserve mass (their multipliers create and destroy oil), so a feed is
    # defined for the full film only.
    flow_in = None
    if grooves and not clip:
        r_in = r[np.setdiff1d(np.concatenate(op.mesh.grooves), op.mesh.end)]
        flow_in = flow_factor(bearing, half) * float(np.sum(r_in))
    moment = (0.0, 0.0) if half else film_moment(bearing, op, P, state.gamma,
                                                 cavitation == "gumbel")
    return film_solution(
        bearing, state, Pn, op.mesh.theta if theta is None else theta, op.mesh.zeta,
        (f_r, f_t), friction=friction,
        leakage=leakage, flow_in=flow_in, cavitated_fraction=cav_fraction, record=res,
        method=method, cavitation=cavitation, half=half, mesh=op.mesh, moment=moment,
        gap=gap)
