"""Static equilibrium of a journal under a steady load, for any film model.

A periodic film's steady force in the local frame depends on eps alone (gamma only turns
it), and its magnitude grows monotonically from 0 at eps = 0 to the wall. So equilibrium
is one bracketed root, |F(eps)| = W (Brent's method), followed by the turn gamma that puts
the film force opposite the load. Grooves fixed in space make the force depend on gamma
too: from that periodic equilibrium a 2-D root in the journal position finishes the job.
The attitude angle phi = atan2(F_t, -F_r) is the angle from the load line to the line of
centres, in the sense of rotation.

Models with exact partials (the FE film, the closed forms) instead take Newton's method in
the journal position q = e/c: the Jacobian dF/dq is the stiffness the partials give
(:mod:`bearingfem.design.coefficients`, grooves' d/dgamma included), so each step costs one
film evaluation with its partials, and the iteration starts from a closed form
(:mod:`bearingfem.design.newton`) or a nearby equilibrium (``start=``). A misaligned FE
film (``tilt``) takes the same iteration on its exact 4x4 stiffness, whose position
columns are the derivative of the film as it is solved (its mesh turning with the journal).
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from scipy.optimize import brentq, root

from ..accuracy import check_estimate, check_rtol, refuse_rtol
from ..bearing import Bearing, JournalState, check_finite, check_surface_speed
from ..errors import ConvergenceError, LoadCapacityError
from ..reynolds import solve_reynolds
from ..fe.sensitivity import fe_tilt_coefficients
from ..fields import check_tilt
from ..film import local_to_inertial
from ..models import film_model, solve_film
from .groups import petroff_friction, sommerfeld_number
from .records import EPS_MAX, Equilibrium, least_film, load_vector
from .thermal import thd_equilibrium
from .newton import (closed_form_start, film_mesh, newton_position, polar_linearisation,
                     shrink_inside)
from .tolerance import answer_to_tolerance

__all__ = ["Equilibrium", "equilibrium", "EPS_MAX", "ConvergenceError", "LoadCapacityError"]


def equilibrium(bearing: Bearing, load, omega: float, model: str = "fem", *,
                direction: float | None = None, eps_max: float = EPS_MAX,
                xtol: float | None = None, start=None, rtol: float | None = None,
                estimate: bool = False, **options) -> Equilibrium:
    """Where the journal sits under a steady ``load`` at speed ``omega``.

    Parameters
    ----------
    bearing : :class:`Bearing`
    load : (W_x, W_y) [N], the external force on the journal the film carries (inertial
        frame); or its magnitude [N] with ``direction`` [rad]
    omega : journal speed relative to the bearing [rad/s], non-zero
    model : film model name (:data:`bearingfem.models.FILM_MODELS`); ``options`` its
        options, e.g. ``n_theta=120, n_z=20, element="P2", cavitation="reynolds"``
    eps_max : largest eccentricity ratio searched, in (0, 1)
    xtol : relative tolerance of the root on eps (relative, so light loads, eps ~ 1e-8,
        stay exact): the iteration's, not the film's (None: 1e-13; 1e-4 rtol with
        ``rtol``; a thermal film's, the force residual relative to the load at which its
        Broyden iteration stops, 1e-8: :func:`~bearingfem.design.thermal.thd_equilibrium`)
    rtol : a requested relative accuracy of the journal position q = e/c against the mesh
        limit, in [1e-6, 0.1] (mesh models): the mesh (and element, P2 unless given) is
        chosen to reach it and ``eps_error`` reports the estimate; n_theta and n_z are
        then refused (an ``element`` given is kept). Successive calls with the same bearing and options start at the
        mesh that sufficed last (:mod:`bearingfem.accuracy`)
    estimate : on the mesh given, also estimate ``eps_error`` (one more equilibrium on the
        half mesh)
    start : an :class:`Equilibrium` or :class:`JournalState` near the answer (e.g. the
        previous load of a sweep), where Newton's method starts (models with exact
        partials only; default: the closed-form equilibrium). Newton's method raises
        :class:`ConvergenceError` if it does not converge from there.
    tilt : (tilt_x, tilt_y) [rad], a prescribed misalignment (model "fem"; no grooves
        or roughness): the journal centre at the mid-plane is placed where the tilted film
        balances the load, by Newton's method on the tilted film's exact stiffness
        (:func:`bearingfem.fe.sensitivity.fe_tilt_coefficients`) with both journal ends
        kept inside ``eps_max``; ``solution.moment`` is the moment the film then exerts
        (the bearing's reaction to the misalignment), ``film_min`` / ``film_min_angle``
        the least gap over the length (at an end) and its angle, and the friction the
        film's own shear integral
    thermal, lubricant : a :class:`~bearingfem.thermal.Thermal` and its oil: the thermal
        film's equilibrium (:func:`bearingfem.design.thermal.thd_equilibrium`); with
        ``rtol`` or ``estimate`` its mesh is searched, or its error estimated, as the
        isothermal film's (P1 unless an ``element`` is given); ``start`` is refused
    """
    check_surface_speed(bearing.radius, check_finite("omega", omega))
    estimate = check_estimate(estimate, rtol)
    if options.get("thermal") is not None:     # the thermal film (bearingfem.design.thermal)
        if model != "fem":     # named before the search's own "no mesh" refusal of rtol
            raise ValueError(f"a thermal film needs model 'fem', got {model!r}")
        if start is not None:
            raise ValueError("start: not taken with thermal= (the thermal equilibrium starts "
                             "from the supply temperature's isothermal one)")
        if rtol is not None or estimate:
            # the same search on the thermal equilibrium, P1 unless given (the thermal
            # film's element, as solve_reynolds' search takes it), no warm start (its
            # iteration starts from the isothermal position)
            xtol = 1e-4 * check_rtol(rtol) if xtol is None and rtol is not None else xtol
            return _equilibrium_with_error(bearing, load, omega, model, rtol, dict(
                direction=direction, eps_max=eps_max, xtol=xtol, start=None), options)
        return thd_equilibrium(bearing, load, omega, model, direction=direction,
                               eps_max=eps_max, isothermal=isothermal_position,
                               **({} if xtol is None else {"xtol": xtol}), **options)
    if rtol is not None or estimate:
        if options.get("tilt") is not None:
            # the search's meshes are the aligned film's (a tilt was refused there as
            # "not an option of film model 'fem'", which it is without rtol)
            raise ValueError(f"tilt: not taken with {'rtol' if rtol is not None else 'estimate'}"
                             " (the tilted equilibrium is solved on the mesh given: n_theta, "
                             "n_z)")
        if rtol is not None and xtol is None:
            # the root to 1e-4 of the accuracy asked: its error then leaves the mesh
            # pairs' differences alone, and Newton takes a step fewer
            xtol = 1e-4 * check_rtol(rtol)
        return _equilibrium_with_error(bearing, load, omega, model, rtol, dict(
            direction=direction, eps_max=eps_max, xtol=xtol, start=start), options)
    xtol = 1e-13 if xtol is None else xtol
    tilt = check_tilt("tilt", options.pop("tilt", (0.0, 0.0)))
    m = film_model(model)
    if any(tilt) and not m.tilts:
        raise ValueError(f"tilt needs a model that solves a tilted journal (model 'fem'), "
                         f"got model={model!r}")
    opts = m.options(options)
    if any(tilt) and opts.get("roughness") is not None:
        raise ValueError("tilt with roughness is not supported: give one of them")
    if any(tilt) and opts.get("grooves"):
        # grooves fixed in space do not turn with the film: no exact tilted partials yet
        raise ValueError("tilt with grooves is not supported: give one of them")
    wx, wy = load_vector(load, direction)
    W = math.hypot(wx, wy)
    omega = check_finite("omega", omega)
    if omega == 0.0 and opts.get("roughness") is None:   # rough surfaces carry a dry load
        raise ValueError("omega must be non-zero [rad/s]: without rotation a film carries "
                         "no steady load")
    eps_max = check_finite("eps_max", eps_max)
    if not 0.0 < eps_max < 1.0:
        raise ValueError(f"eps_max must lie in (0, 1), got {eps_max!r}")
    # the dry limit (omega = 0, asperities alone) has no closed-form start: Brent's route
    newton = m.exact_derivatives and not m.memory and omega != 0.0
    if start is not None and not newton:
        raise ValueError(f"start needs a model with exact partials (Newton's method) and "
                         f"omega != 0, got model={model!r}, omega={omega!r}")
    q0 = _start_position(start, eps_max) if start is not None else None
    if newton:
        return _newton_equilibrium(m, bearing, omega, (wx, wy), opts, q0, eps_max, xtol,
                                   model, tilt)
    calls = [0]
    grooves = opts.get("grooves", ())
    periodic = {**opts, "grooves": ()} if grooves else opts

    def force(eps, gamma=0.0, o=periodic):
        calls[0] += 1
        return m.film_force(bearing, JournalState(eps, omega=omega, gamma=gamma), **o)

    f_max = math.hypot(*force(eps_max))
    if not f_max >= W:
        raise LoadCapacityError(W, f_max, eps_max, model, film_mesh(opts))
    eps = brentq(lambda e: math.hypot(*force(e)) - W, 0.0, eps_max, xtol=1e-300, rtol=xtol)
    f_r, f_t = force(eps)
    # turn the eccentricity so that the film force points opposite the load
    gamma = math.atan2(-wy, -wx) - math.atan2(f_t, f_r)
    gamma = math.atan2(math.sin(gamma), math.cos(gamma))
    if grooves:   # grooves fixed in space: the force depends on gamma too - a 2-D root
        eps, gamma = _grooved_equilibrium(lambda e, g: force(e, g, opts), (wx, wy), eps,
                                          gamma, eps_max, model)
        f_r, f_t = force(eps, gamma, opts)
    state = JournalState(eps, omega=omega, gamma=gamma)
    sol = solve_film(model, bearing, state, opts)
    return _result(bearing, omega, (wx, wy), state, (f_r, f_t), sol, model, calls[0])


def _position(eq: Equilibrium) -> np.ndarray:
    return eq.eps * np.array([math.cos(eq.state.gamma), math.sin(eq.state.gamma)])


def _equilibrium_with_error(bearing, load, omega, model, rtol, how, options):
    """The equilibrium on the mesh that reaches ``rtol`` (or on the mesh given, with its
    error), each mesh's Newton started from the last mesh's answer."""
    m = film_model(model)
    # a thermal equilibrium starts from its own isothermal position, never from a start
    newton = m.exact_derivatives and not m.memory and options.get("thermal") is None
    last = []

    def evaluate(opts):
        start = last[-1] if newton and last else how["start"]
        eq = equilibrium(bearing, load, omega, model, **{**how, "start": start}, **opts)
        last.append(eq)
        return eq

    def difference(fine, coarse):     # relative change of the journal position
        qf = _position(fine)
        return float(np.linalg.norm(qf - _position(coarse)) / np.linalg.norm(qf))

    toward = None
    if rtol is not None and "grading" in m.defaults and omega != 0.0:
        # the mesh is graded toward where the closed form puts the journal (a grooved
        # film's angle; whether eps calls for a grading at all)
        q = closed_form_start(bearing, omega, load_vector(load, how["direction"]))
        toward = (math.atan2(q[1], q[0]), math.hypot(*q))
    # the memo (a design loop's next load starts at the mesh that sufficed) is keyed on
    # the bearing's shape and the film options, not the load
    eq, _, record = answer_to_tolerance(m, "equilibrium", round(bearing.length_ratio, 12),
                                        options, evaluate, difference, rtol,
                                        bearing.length_ratio, toward=toward)
    return replace(eq, eps_error=record.error * eq.eps, accuracy=record)


def _result(bearing, omega, load, state, force_local, sol, model, calls, tilt=(0.0, 0.0)):
    """The :class:`Equilibrium` at ``state``, the film force there (local) and solution."""
    (wx, wy), W = load, math.hypot(*load)
    (f_r, f_t), eps, gamma = force_local, state.eps, state.gamma
    film_force = tuple(float(f) for f in local_to_inertial(f_r, f_t, gamma))
    # Petroff's closed Couette integral and the by-parts Poiseuille term hold for the
    # cylindrical gap only: a tilted film's friction is its own shear integral
    friction = sol.friction_force if any(tilt) else petroff_friction(bearing, eps, omega, f_t)
    contact = (0.0, 0.0) if sol is None else sol.asperity_force
    if sol is not None:
        friction += sol.asperity_friction_torque / bearing.radius
    friction = float(friction)     # plain floats: the record prints as numbers, not np.float64
    film_min, film_min_angle = least_film(bearing, state, tilt)
    return Equilibrium(
        eps=eps, attitude=math.atan2(f_t, -f_r), state=state, load=(wx, wy),
        film_force=film_force,
        sommerfeld=sommerfeld_number(bearing, W, omega) if omega else 0.0,   # dry: S = 0
        film_min=film_min, film_min_angle=film_min_angle,
        friction_force=friction, friction_coefficient=friction / W,
        power_loss=abs(friction * bearing.radius * omega),
        pressure_max=None if sol is None else sol.pressure_max,
        side_leakage=None if sol is None else sol.side_leakage,
        flow_in=None if sol is None else _plain(sol.flow_in),
        solution=sol, model=model, iterations=calls,
        asperity_load_share=-(contact[0] * wx + contact[1] * wy) / W ** 2)


def _plain(v):
    """A flow as a plain float (-0.0 as 0.0), None kept."""
    return None if v is None else float(v) + 0.0


def _start_position(start, eps_max):
    """The journal position q = e/c of ``start`` (an Equilibrium or JournalState)."""
    state = start.state if isinstance(start, Equilibrium) else start
    if not isinstance(state, JournalState):
        raise ValueError(f"start must be an Equilibrium or a JournalState, got "
                         f"{type(start).__name__}")
    if not 0.0 < state.eps < eps_max:
        raise ValueError(f"start.eps must lie in (0, eps_max = {eps_max:g}), got "
                         f"{state.eps!r}")
    return np.array([state.eps * math.cos(state.gamma), state.eps * math.sin(state.gamma)])


#: Newton's iteration goes on from where it stopped this many times when the force there
#: is off the load by more than its limit (a cavitated set changing near the root)
NEWTON_RESTARTS = 2


def isothermal_position(bearing: Bearing, load, omega: float, model: str, *,
                        eps_max: float = EPS_MAX, xtol: float = 1e-13, rtol=None,
                        **options) -> tuple:
    """(eps, gamma) of :func:`equilibrium` (aligned journal, default tolerance) without
    the film's outputs there: Newton's position alone for models with exact partials,
    else the whole equilibrium's. Why: a search that only starts from it (the thermal
    film's, :func:`~bearingfem.design.thermal.thd_equilibrium`) needs no solution record,
    whose film and partials cost a quarter of the isothermal equilibrium at 48 x 8.
    ``xtol`` (formerly ``rtol``; Newton's models only): Newton stops on a step below
    sqrt(xtol) |q| and takes it, the force then off by ~xtol of the load; the default is
    the equilibrium's, a start may take a looser one. ``rtol`` (a film accuracy) is
    refused: the start is found on the mesh given."""
    refuse_rtol(rtol, "Newton's tolerance is xtol (the position is found on the mesh given)")
    m = film_model(model)
    if not 0.0 < check_finite("eps_max", eps_max) < 1.0:
        raise ValueError(f"eps_max must lie in (0, 1), got {eps_max!r}")
    if not 0.0 < check_finite("xtol", xtol) < 1.0:
        raise ValueError(f"xtol must lie in (0, 1), got {xtol!r}")
    if not (m.exact_derivatives and not m.memory and omega != 0.0):
        eq = equilibrium(bearing, load, omega, model, eps_max=eps_max, **options)
        return eq.eps, eq.state.gamma
    eps, gamma, _, _ = _newton_position(m, bearing, omega, tuple(load),
                                        m.options(options), None, eps_max, xtol, model,
                                        (0.0, 0.0))
    return eps, gamma


def _newton_position(m, bearing, omega, load, opts, q0, eps_max, rtol, model, tilt):
    """(eps, gamma, partials, calls) by Newton's method on the model's exact partials
    (module docstring); a tilted FE film's from its exact 4x4 stiffness, with both
    journal ends inside eps_max."""
    calls = [0]
    c = bearing.clearance
    d_end = 0.5 * bearing.length / c * np.array([tilt[1], -tilt[0]])   # end centre - q
    if not math.hypot(*d_end) < eps_max:
        raise ValueError(f"tilt {tilt} [rad] puts the journal's ends {math.hypot(*d_end):.3g} "
                         f"c off its mid-plane centre: |tilt| L / (2 c) must be < eps_max = "
                         f"{eps_max:g}")

    def partials(eps, gamma):
        calls[0] += 1
        return m.force_derivatives(bearing, JournalState(eps, omega=omega, gamma=gamma),
                                   **opts)

    def tilted(q):
        calls[0] += 1
        state = JournalState(math.hypot(*q), omega=omega, gamma=math.atan2(q[1], q[0]))
        kc = fe_tilt_coefficients(bearing, state, tilt, opts["n_theta"], opts["n_z"],
                                  opts["element"], opts["cavitation"])
        return kc.force[:2], -c * kc.K[:2, :2]          # dF/dq = -c K, q = e/c

    film = tilted if any(tilt) else polar_linearisation(partials)
    if q0 is None:
        q0 = closed_form_start(bearing, omega, load)

    def capacity():     # what the (periodic) film carries at eps_max, for the error message
        calls[0] += 1
        if any(tilt):   # the tilted film with its nearer end at eps_max, along the start
            return math.hypot(*film(shrink_inside(q0 / math.hypot(*q0) * 2.0, d_end,
                                                  eps_max))[0])
        o = {**opts, "grooves": ()} if opts.get("grooves") else opts
        return math.hypot(*m.film_force(bearing, JournalState(eps_max, omega=omega), **o))

    eps, gamma = newton_position(film, load, q0, eps_max, rtol, capacity, model, d_end,
                                 film_mesh(opts))
    return eps, gamma, partials, calls


def _newton_equilibrium(m, bearing, omega, load, opts, q0, eps_max, rtol, model, tilt):
    """Equilibrium by Newton's method on the model's exact partials (module docstring); a
    tilted FE film's from its exact 4x4 stiffness, with both journal ends inside eps_max."""
    # Newton stops on a step below sqrt(rtol) |q|: the force is then off by about rtol
    limit = max(1e-8, 10.0 * rtol)
    solves = 0
    for restart in range(NEWTON_RESTARTS + 1):
        eps, gamma, partials, calls = _newton_position(m, bearing, omega, load, opts, q0,
                                                       eps_max, rtol, model, tilt)
        state = JournalState(eps, omega=omega, gamma=gamma)
        if opts.get("grooves") and not any(tilt):
            # the film there with its partials, warm from Newton's last cavitated set: the
            # grooved operator keeps both, so the solution below and coefficients() at this
            # state take them instead of a cold solve (bearingfem.fe.grooved)
            partials(eps, gamma)
        sol = (solve_reynolds(bearing, state, opts["n_theta"], opts["n_z"], opts["element"],
                              opts["cavitation"], tilt=tilt) if any(tilt)
               else solve_film(model, bearing, state, opts))
        solves += calls[0] + 1
        # the model's force: the film's and, with roughness, the asperities' (mixed
        # lubrication)
        f_loc = m.film_force(bearing, state, **opts) if sol is None else tuple(
            np.add(sol.force_local, sol.asperity_force_local))
        residual = (np.hypot(*(np.add(local_to_inertial(*f_loc, gamma), load)))
                    / math.hypot(*load))
        if residual <= limit:
            return _result(bearing, omega, load, state, f_loc, sol, model, solves, tilt)
        # the partials hold the cavitated set: where it changes near the root the last
        # step is not quadratically small, and Newton goes on from where it stopped
        q0 = eps * np.array([math.cos(gamma), math.sin(gamma)])
    raise ConvergenceError(f"Newton's equilibrium ({model} model)", solves, residual,
                           f"eps = {eps:.6g} (film force off the load by more than "
                           f"{limit:.0e} of it)")


def _grooved_equilibrium(force, load, eps0, gamma0, eps_max, model):
    """(eps, gamma) where the film force balances ``load``, the journal position found by
    Powell's hybrid method from the periodic film's equilibrium (eps0, gamma0)."""
    W = math.hypot(*load)

    def residual(q):
        eps = min(math.hypot(*q), eps_max)
        gamma = math.atan2(q[1], q[0])
        f_r, f_t = force(eps, gamma)
        fx, fy = local_to_inertial(f_r, f_t, gamma)
        return [(fx + load[0]) / W, (fy + load[1]) / W]

    q0 = [eps0 * math.cos(gamma0), eps0 * math.sin(gamma0)]
    sol = root(residual, q0, method="hybr", options=dict(xtol=1e-12))
    eps = math.hypot(*sol.x)
    if not sol.success or np.max(np.abs(residual(sol.x))) > 1e-8 or eps >= eps_max:
        raise ValueError(f"no equilibrium with these grooves below eps_max = {eps_max:g} "
                         f"({model} model): {sol.message}")
    return eps, math.atan2(sol.x[1], sol.x[0])

