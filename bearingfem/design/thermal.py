"""Equilibrium and dynamic coefficients of a thermal (THD) film.

Equilibrium: Broyden's method in the journal position q = e/c on the THD film's force,
each evaluation the thermal iteration (:class:`bearingfem.routes.thd.ThermalIteration`)
continued from the last position's temperatures and cavitated set to a temperature
tolerance that follows the force residual (inexact steps; an inexact step ends on the
film after an energy solve once the fixed point's measured contraction puts the next
change below that tolerance, without solving it): the thermal film's mesh is
fixed in the bearing, so one operator serves every position and the fields carry over
node by node. It starts at the isothermal equilibrium of the supply temperature, its
first Jacobian the thermal film's there with the viscosity field frozen (its exact
derivatives at the film just solved, cheap and smooth): the first step is the
frozen-viscosity Newton step, which takes in the oil's heating (a second isothermal
equilibrium at the viscosity that carries the thermal film's force there started
nearer, measured on the ROSS fixture at 48x8, but cost more than the two Broyden steps
it saved).
``Equilibrium.iterations`` counts the film solves.
Either way round: at omega < 0 the thermal film's oil enters at the grooves' leading
edges (:mod:`bearingfem.routes.thd`) and the attitude is negative, as the isothermal
equilibrium's; omega = 0 is refused (no Couette flow, no thermal film).

Coefficients: K and C of the film with its converged viscosity field frozen (its exact
derivatives in x, y and their rates at the film's cavitated set,
:meth:`~bearingfem.routes.thd_film.ReynoldsFieldFilm.force_partials`; the JFO film's by
central differences), the usual THD linearisation (the temperature field does not
follow a vibration at the rotor's frequencies); ROSS 3.1's fluid-film engine perturbs
its Reynolds equation about the converged film the same way.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..accuracy import refuse_estimate, refuse_rtol
from ..bearing import PLAUSIBLE, Bearing, JournalState, check_finite
from ..errors import ConvergenceError
from ..reynolds import solve_reynolds
from ..fields import FilmFields
from ..film import local_to_inertial
from ..solvers.cavitation import LCPResult
from ..routes.thd import (ReynoldsFieldFilm, ThermalIteration, check_thermal, solve_thd,
                          thermal_operator)
from .records import EPS_MAX, DynamicCoefficients, Equilibrium, least_film, load_vector
from .groups import sommerfeld_number

__all__ = ["thd_equilibrium", "thd_coefficients", "frozen_film", "thermal_mesh"]

STEP = 1e-5            # central-difference step in q = e/c (and v/(c omega))
MAX_STEPS = 40
PRESSURE_RTOL = 1e-8   # the film's last change, relative to its peak, at the answer


def thermal_mesh(options: dict) -> dict:
    """The thermal film's mesh options (n_theta, n_z, element, cavitation, grooves,
    supply_angle; tol where given) from ``options``, its defaults (48 x 8, P1, Reynolds'
    condition) where they are not given; ValueError naming an option it does not take."""
    known = ("n_theta", "n_z", "element", "cavitation", "grooves", "supply_angle", "tol")
    unknown = set(options) - set(known) - {"lubricant", "thermal", "temperature_tol",
                                           "relaxation", "max_iterations"}
    if unknown:
        raise ValueError(f"options not taken by the thermal film: {sorted(unknown)}")
    o = dict(n_theta=48, n_z=8, element="P1", cavitation="reynolds", grooves=(),
             supply_angle=None)
    o.update({k: v for k, v in options.items() if k in known})
    return o


def _solve_tol(mesh: dict) -> dict:
    """``tol`` for the thermal solve where it was given (its films' projected iteration)."""
    return {"tol": mesh["tol"]} if "tol" in mesh else {}


def frozen_film(bearing: Bearing, viscosity, mesh: dict):
    """A function state -> the film's inertial force [N]: the isothermal film with the
    ``viscosity`` field [Pa s] frozen at the thermal film's quadrature points (the same
    places in the bearing for every state; e.g. a thermal film's
    ``thermal.viscosity_quadrature``, with which it is that film at its state). The Reynolds film is
    solved on the thermal film's bearing-fixed mesh (one operator for every state, each
    solve started from the last one's cavitated set and factors); the JFO film by its
    route."""
    ratio = viscosity / bearing.viscosity
    if mesh["cavitation"] == "jfo":
        opts = {k: v for k, v in mesh.items() if k in ("grooves", "supply_angle")}

        def film(state):
            return np.array(solve_reynolds(
                bearing, state, mesh["n_theta"], mesh["n_z"], mesh["element"], "jfo",
                fields=FilmFields(viscosity=ratio), **opts).force, float)
        return film
    warm = []

    def film(state):
        op = thermal_operator(bearing, state, mesh["n_theta"], mesh["n_z"], mesh["element"],
                              mesh["supply_angle"], mesh["grooves"])
        f = ReynoldsFieldFilm(bearing, state, op, mesh["element"], tuple(mesh["grooves"]),
                              mesh.get("tol", 1e-10), warm[-1] if warm else None)
        f.solve(ratio)
        warm[:] = [f]
        return f.force()
    return film


def _warm(solution, op):
    """The cavitated set of a thermal film's solution on ``op`` (None if not on it)."""
    p = np.asarray(solution.pressure)
    if p.shape != (op.mesh.ndofs,):
        return None
    return LCPResult(p, 0, 0.0, True, p <= 0.0)


def _inertial_force(sol):
    return np.array(sol.force, float)


def _state(q, v, omega, clearance):
    return JournalState.from_eccentricity(q[0] * clearance, q[1] * clearance,
                                          v[0] * clearance, v[1] * clearance, clearance,
                                          omega)


def _jacobian(film, q, omega, clearance, velocity=False):
    """d F / d q (or d F / d (v/c)) [N] by central differences on ``film``."""
    J = np.empty((2, 2))
    for j in range(2):
        d = np.zeros(2)
        d[j] = STEP if not velocity else STEP * abs(omega)
        if velocity:
            fp = film(_state(q, d, omega, clearance))
            fm = film(_state(q, -d, omega, clearance))
        else:
            fp = film(_state(q + d, np.zeros(2), omega, clearance))
            fm = film(_state(q - d, np.zeros(2), omega, clearance))
        J[:, j] = (fp - fm) / (2.0 * d[j])
    return J


#: The margin on the fixed point's measured contraction when it predicts the next
#: temperature change of an inexact step (the largest of the last RATE_MEMORY rates)
RATE_SAFETY = 4.0
RATE_MEMORY = 3
#: The first position's temperature tolerance [K], and the largest of an inexact step's:
#: a 1 K error moves the force by ~3 %, below the first position's residual (the oil's
#: heating: 26 % of the load on ROSS's adiabatic fixture) and of the next steps' (5 %, 1 %)
FIRST_TOL = 1.0
#: The start's (the supply temperature's isothermal equilibrium) Newton tolerance: its
#: last step below 1e-2 |q| (the force then off by ~1e-4 of the load), where the first
#: thermal step moves eps by ~0.07 (ROSS's fixture); the equilibrium's 1e-13 took one or
#: two more isothermal films and partials for the same thermal search
START_XTOL = 1e-4


def _predicted_change(change: float, rates: list) -> float:
    """The next energy solve's change [K] after one of ``change`` [K], from the fixed
    point's contraction measured so far (the largest of its last RATE_MEMORY rates, times
    RATE_SAFETY; inf before a rate is known). Why: after a position step the first
    energy solve moves the temperatures by the step's effect and the next by ~1e-2 of
    that (the pressure's lag); an inexact step needs the film's temperatures within
    ``tol_t`` only, which the contraction tells without the second solve."""
    if not rates:
        return np.inf
    return RATE_SAFETY * max(rates[-RATE_MEMORY:]) * change


def thd_equilibrium(bearing: Bearing, load, omega: float, model: str = "fem", *,
                    direction=None, eps_max: float = EPS_MAX, xtol: float = 1e-8,
                    isothermal=None, rtol=None, estimate=None, **options) -> Equilibrium:
    """Where the journal sits under ``load`` with a thermal film (module docstring).

    Options: ``lubricant`` and ``thermal`` (required), the film's mesh options
    (``n_theta``, ``n_z``, ``element``, ``cavitation``, ``grooves``, ``supply_angle``)
    and the thermal solve's (``temperature_tol``, ``relaxation``, ``max_iterations``).
    ``xtol`` (formerly ``rtol``), in (0, 1): the film force's residual relative to
    the load at which Broyden's iteration stops (1e-8: the isothermal Newton
    equilibrium's own acceptance, and below what the temperature tolerance fixes, a 1e-6 K
    error moving the force by ~3e-8 of it; 1e-9 before took one more position on ROSS's
    fixture and moved eps by at most 2.6e-9, K and C by 1.1e-8). ``rtol`` (the toolkit's
    film accuracy) and ``estimate`` are refused here, on one mesh: ``equilibrium(...,
    thermal=, rtol=)`` chooses the mesh and estimates ``eps_error``. ``eq.solution`` is the THD
    film; ``friction_force`` and ``power_loss`` its own shear integral. ``isothermal``:
    (bearing, load, omega, model, eps_max=, xtol=, **mesh options) -> (eps, gamma) of
    the isothermal equilibrium that starts the search (to START_XTOL)
    (:func:`~bearingfem.design.equilibrium.isothermal_position`, passed in by
    :func:`~bearingfem.design.equilibrium`: this module lies below it).
    """
    refuse_rtol(rtol, "the thermal equilibrium's force tolerance is xtol (it is solved on "
                "the mesh given; equilibrium(..., thermal=, rtol=) chooses the mesh)")
    refuse_estimate(estimate, "thd_equilibrium solves one mesh; equilibrium(..., thermal=, "
                    "estimate=True) estimates eps_error")
    if model != "fem":
        raise ValueError(f"a thermal film needs model 'fem', got {model!r}")
    xtol = check_finite("xtol", xtol)
    if not 0.0 < xtol < 1.0:
        raise ValueError(f"xtol must lie in (0, 1), got {xtol!r}: the thermal "
                         "equilibrium's force residual relative to the load")
    lubricant, thermal = options.get("lubricant"), options.get("thermal")
    mesh = thermal_mesh(options)
    final_tol = options.get("temperature_tol", 1e-6)
    wx, wy = load_vector(load, direction)
    W = math.hypot(wx, wy)
    if omega == 0.0:
        # its sign says at which groove edges the oil enters (either way round)
        raise ValueError("omega must be nonzero for a thermal film (a journal at rest "
                         "carries no oil through: no Couette flow, no thermal film), got "
                         f"{omega!r}")
    check_thermal(lubricant, thermal, JournalState(0.5, omega=omega), mesh["cavitation"],
                  mesh["element"])
    # the isothermal equilibrium at the supply temperature starts the search: a Bearing at
    # the supply's viscosity, refused here by name above a Bearing's (a film at a given
    # position takes a colder start: Thermal.check_fluid)
    mu_supply = float(lubricant.viscosity_at(temperature=thermal.supply_temperature))
    most = PLAUSIBLE["viscosity"][1]
    if mu_supply > most:
        raise ValueError(f"supply_temperature {thermal.supply_temperature:g} K gives the "
                         f"lubricant a viscosity of {mu_supply:g} Pa s, more than the "
                         f"equilibrium's isothermal start takes (at most {most:g} Pa s, a "
                         "Bearing's); a thermal film at a given position solves it")
    cold = replace(bearing, viscosity=mu_supply)
    iso_model = "fem-jfo" if mesh["cavitation"] == "jfo" else "fem"
    iso_opts = dict(n_theta=mesh["n_theta"], n_z=mesh["n_z"], grooves=mesh["grooves"])
    if iso_model == "fem":
        iso_opts.update(element=mesh["element"], cavitation=mesh["cavitation"])
    eps0, gamma0 = isothermal(cold, (wx, wy), omega, iso_model, eps_max=eps_max,
                              xtol=START_XTOL, **iso_opts)
    q = eps0 * np.array([math.cos(gamma0), math.sin(gamma0)])
    c = bearing.clearance
    target = -np.array([wx, wy])
    relaxation = options.get("relaxation", 1.0)
    max_iterations = options.get("max_iterations", 200)
    it = ThermalIteration(bearing, _state(q, np.zeros(2), omega, c), mesh["n_theta"],
                          mesh["n_z"], lubricant=lubricant, thermal=thermal,
                          grooves=mesh["grooves"], cavitation=mesh["cavitation"],
                          element=mesh["element"], supply_angle=mesh["supply_angle"],
                          **_solve_tol(mesh))

    last = {"q": None, "film": None, "on_t": False}
    rates = []      # the fixed point's measured contractions (changes at one position)

    def balance(q, tol_t, p_rtol):
        """The film's force at q with the temperatures converged to ``tol_t`` [K] (the
        fixed point's steps from the last position's temperatures and cavitated set).
        At the final tolerance (``tol_t`` <= the thermal solve's) the film returned is
        on the temperatures the last energy solve moved by less than ``tol_t``, its
        pressure changed by less than ``p_rtol`` (the changes themselves:
        :func:`~bearingfem.routes.thd.solve_thd` tests its estimate of the error); at
        a looser one (an inexact step) the film before that energy solve, whose
        temperatures are as near (its pressure's change then follows theirs, ~1e-2
        of the peak per K), or the film after it when the fixed point's contraction
        (:func:`_predicted_change`) puts the next change below ``tol_t``. At the position
        of the last call the fixed point continues where it stopped."""
        state = _state(q, np.zeros(2), omega, c)
        same = last["q"] is not None and np.array_equal(q, last["q"])
        if same and last["on_t"]:
            film = last["film"]
        else:
            if not same:
                it.change = np.inf            # no energy solved at this position yet
            film = it.film(state)
        last["q"] = q.copy()
        for _ in range(max_iterations):
            if it.change < tol_t and it.pressure_change < p_rtol:
                last.update(film=film, on_t=True)
                return film
            before = it.change
            it.energy(state, relaxation)
            if np.isfinite(before) and before > 0.0:
                rates.append(it.change / before)
            if tol_t > final_tol and it.change < tol_t:
                last.update(film=film, on_t=False)
                return film
            film = it.film(state)
            if tol_t > final_tol and _predicted_change(it.change, rates) < tol_t:
                last.update(film=film, on_t=True)
                return film
        raise ConvergenceError("thermal film (temperature fixed point)", max_iterations,
                               it.change, f"eps = {state.eps:.6g}")

    film = balance(q, FIRST_TOL, 1e-2 * FIRST_TOL)
    # the later steps predict from their own contractions (~1e-2 after a position step),
    # not from those of the heating from the supply temperature (0.08 on ROSS's fixture)
    rates.clear()
    # the first Jacobian: the film just solved at q, its viscosity held (the JFO film's
    # by central differences)
    J = _jacobian(frozen_film(bearing, it.mu, mesh), q, omega, c) \
        if mesh["cavitation"] == "jfo" else film.force_partials()[0]
    r = film.force() - target
    tol_used = FIRST_TOL
    for _ in range(MAX_STEPS):
        if np.hypot(*r) <= xtol * W:
            if tol_used <= final_tol:
                break
            # balanced on loose temperatures: the same position with the final ones
            film = balance(q, final_tol, PRESSURE_RTOL)
            tol_used, r = final_tol, film.force() - target
            continue
        dq = -np.linalg.solve(J, r)
        # keep inside eps_max: shorten the step
        n = np.hypot(*(q + dq))
        t = 1.0 if n < eps_max else 0.5 * (eps_max - np.hypot(*q)) / max(np.hypot(*dq), 1e-300)
        dq = t * dq
        q = q + dq
        # inexact steps: far from the root the temperatures need not be exact (a 1 K
        # error moves the force by ~3 %, so |r|/W [K] leaves it ~30 times below the
        # residual), down to the final one
        tol_t = min(max(final_tol, float(np.hypot(*r)) / W), FIRST_TOL)
        tol_used = tol_t
        film = balance(q, tol_t, max(PRESSURE_RTOL, 1e-2 * tol_t))
        r_new = film.force() - target
        J = J + np.outer(r_new - r - J @ dq, dq) / float(dq @ dq)      # Broyden's update
        r = r_new
    else:
        raise ConvergenceError("thermal equilibrium (Broyden)", MAX_STEPS,
                               float(np.hypot(*r) / W), f"eps = {np.hypot(*q):.6g}")
    sol = it.solution()
    calls = it.iterations
    state = _state(q, np.zeros(2), omega, c)
    f_r, f_t = sol.force_local
    film_min, film_min_angle = least_film(bearing, state)
    friction = float(sol.friction_force)   # plain floats, as the isothermal record's
    return Equilibrium(
        eps=state.eps, attitude=math.atan2(f_t, -f_r), state=state, load=(wx, wy),
        film_force=tuple(float(f) for f in local_to_inertial(f_r, f_t, state.gamma)),
        sommerfeld=sommerfeld_number(replace(bearing, viscosity=mu_supply), W, omega),
        film_min=film_min, film_min_angle=film_min_angle, friction_force=friction,
        friction_coefficient=friction / W, power_loss=abs(sol.friction_torque * omega),
        pressure_max=sol.pressure_max, side_leakage=sol.side_leakage,
        flow_in=sol.flow_in, solution=sol, model="fem-thd", iterations=calls)


def thd_coefficients(bearing: Bearing, state: JournalState, frame: str = "inertial", *,
                     solution=None, rtol=None, estimate=None,
                     **options) -> DynamicCoefficients:
    """K [N/m] and C [N s/m] of the thermal film at ``state`` with its viscosity field
    frozen (module docstring); ``solution``: the THD film at ``state`` (e.g.
    ``eq.solution``), solved here when None. Options as :func:`thd_equilibrium`.
    ``rtol`` and ``estimate`` are refused here, on one mesh: ``coefficients(..., thermal=,
    rtol=)`` chooses the mesh and estimates ``error``."""
    refuse_rtol(rtol, "the thermal film's K and C are found here on the mesh given; "
                "coefficients(..., thermal=, rtol=) chooses the mesh")
    refuse_estimate(estimate, "thd_coefficients linearises one mesh; coefficients(..., "
                    "thermal=, estimate=True) estimates K and C's error")
    mesh = thermal_mesh(options)
    if solution is None:
        solve_opts = {k: options[k] for k in ("temperature_tol", "relaxation",
                                              "max_iterations") if k in options}
        solution = solve_thd(bearing, state, mesh["n_theta"], mesh["n_z"],
                             lubricant=options.get("lubricant"),
                             thermal=options.get("thermal"), grooves=mesh["grooves"],
                             cavitation=mesh["cavitation"], element=mesh["element"],
                             supply_angle=mesh["supply_angle"], **_solve_tol(mesh),
                             **solve_opts)
    viscosity = solution.thermal.viscosity_quadrature
    c, omega = bearing.clearance, state.omega
    if mesh["cavitation"] == "jfo":
        film = frozen_film(bearing, viscosity, mesh)
        q = np.array([state.eps * math.cos(state.gamma), state.eps * math.sin(state.gamma)])
        d_q, d_v = _jacobian(film, q, omega, c), _jacobian(film, q, omega, c, velocity=True)
    else:
        # exact at the film's cavitated set (ReynoldsFieldFilm.force_partials): the same
        # as central differences to their truncation (1e-9 measured at the step 1e-5 c)
        op = thermal_operator(bearing, state, mesh["n_theta"], mesh["n_z"], mesh["element"],
                              mesh["supply_angle"], mesh["grooves"])
        film = ReynoldsFieldFilm(bearing, state, op, mesh["element"], tuple(mesh["grooves"]),
                                 mesh.get("tol", 1e-10), _warm(solution, op))
        film.solve(viscosity / bearing.viscosity)
        d_q, d_v = film.force_partials()
    K, C = -d_q / c, -d_v / c
    force = tuple(float(f) for f in solution.force)
    method = "central-differences" if mesh["cavitation"] == "jfo" else "exact-sensitivity"
    out = DynamicCoefficients(K, C, "inertial", np.eye(2), state, force, "fem-thd",
                              f"{method} (viscosity frozen)", c, np.zeros((2, 2)))
    return out if frame == "inertial" else out.in_frame(frame)
