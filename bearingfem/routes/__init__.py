"""One way into the film: a problem record, a table of routes, a solve.

    problem = film_problem(bearing, state, 120, 20, "reynolds", grooves=G)
    route_for(problem).name          # "grooved"
    sol = solve(problem)             # the route's whole film

Each :class:`FilmProblem` names its route (:attr:`FilmProblem.kind`: decided in one
place); :data:`ROUTES` maps that name to the route, which checks the options it uses and
refuses the others (:mod:`bearingfem.routes.base` holds the rules every route keeps).
:func:`bearingfem.solve_reynolds` and :func:`bearingfem.fvm_reynolds` are fronts over
this table. A new kind of film adds one route module and one line in ``ROUTES``.

=================  ============================================================
route              problems
=================  ============================================================
rigid              the rigid cylinder, Reynolds family, meshed in the film frame
grooved            flooded axial grooves, Reynolds family, bearing-fixed mesh
general            fields (gap, viscosity, density) or a tilted journal
ehd                a pressure-dependent lubricant or an elastic bush
jfo                the mass-conserving film in the film frame, rigid or on fields
jfo-grooved        the mass-conserving film with grooves, bearing-fixed mesh
jfo-compressible   a lubricant with a bulk modulus: the compressible JFO film
ehd-jfo            the mass-conserving film with a bush or a pressure law
thd                the thermal film: energy equation and film coupled (Reynolds or JFO)
fv                 finite volumes, every cavitation model
=================  ============================================================
"""
from __future__ import annotations

from ..bearing import Bearing, JournalState
from .base import Route
from .ehd import ElasticFilm, ElasticJFOFilm
from .fe import GeneralFilm, GroovedFilm, RigidFilm
from .fv import FiniteVolumeFilm
from .jfo import CompressibleJFOFilm, GroovedJFOFilm, JFOFilm
from .problem import OPTION_DEFAULTS, FilmProblem, film_problem
from .thd import ThermalFilm, solve_thd

__all__ = ["ROUTES", "Route", "FilmProblem", "film_problem", "route_for", "solve",
           "film_force", "fe_force", "OPTION_DEFAULTS", "solve_thd"]

#: The film routes by the problem kind they solve.
ROUTES: dict = {r.name: r for r in (
    RigidFilm(), GroovedFilm(), GeneralFilm(), ElasticFilm(), JFOFilm(), GroovedJFOFilm(),
    CompressibleJFOFilm(), ElasticJFOFilm(), ThermalFilm(), FiniteVolumeFilm())}


def route_for(problem: FilmProblem) -> Route:
    """The route of ``problem``'s kind, its options checked (ValueError naming any the
    route does not use)."""
    route = ROUTES[problem.kind]
    route.check(problem)
    return route


def solve(problem: FilmProblem):
    """The whole film of ``problem`` (:class:`~bearingfem.solution.FilmSolution`)."""
    return route_for(problem).solve(problem)


def film_force(problem: FilmProblem, warm=None):
    """((F_r, F_t) [N], record): the light path of time integration. ``warm`` is the
    record of the previous call on the same problem's mesh at a nearby state."""
    return route_for(problem).force(problem, warm)


def fe_force(bearing: Bearing, state: JournalState, n_theta=60, n_z=10, element="P1",
             cavitation="gumbel", method="active-set", half=True, warm=None, grooves=(),
             ambient_pressure: float = 0.0):
    """(F_r, F_t) [N] and the solve's record of the finite-element film: the light path
    used in time integration (:func:`film_force` of the problem these arguments make).

    Pass the previous call's record as ``warm`` (same mesh, nearby state): its cavitated
    set and factorisation start this solve. ``grooves`` (fixed in the inertial frame) are
    solved on the bearing-fixed mesh (no rebuild for a new journal angle; ``warm`` gives
    its cavitated set only), the JFO film's too.
    """
    # the options come checked from the model registry: no film_problem checks on the hot
    # path (the route still refuses what it does not use)
    return film_force(FilmProblem(bearing, state, n_theta, n_z, element, cavitation, method,
                                  half=half, grooves=tuple(grooves),
                                  ambient_pressure=ambient_pressure), warm)
