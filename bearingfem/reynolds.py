"""The film's public fronts: :func:`solve_reynolds` (finite elements) and
:func:`fvm_reynolds` (finite volumes), both over the route table of
:mod:`bearingfem.routes`."""
from __future__ import annotations

from dataclasses import replace

from .accuracy import check_no_mesh, film_to_tolerance, search_grading
from .bearing import Bearing, JournalState
from .fields import FilmFields
from .routes import film_problem, solve
from .solution import FilmSolution

__all__ = ["solve_reynolds", "fvm_reynolds"]


def solve_reynolds(bearing: Bearing, state: JournalState, n_theta: int | None = None,
                   n_z: int | None = None,
                   element: str | None = None, cavitation: str = "reynolds", *,
                   method: str = "active-set", supply_angle=None, half: bool = True,
                   tol: float = 1e-10, cavitated_shear: str = "full",
                   grooves=(), ambient_pressure: float = 0.0, fields: FilmFields | None = None,
                   tilt=(0.0, 0.0), tilt_rate=(0.0, 0.0), profile=None, lubricant=None,
                   bush=None, roughness=None, start=None, grading=None,
                   thermal=None, rtol: float | None = None) -> FilmSolution:
    """Solve the Reynolds equation on a finite-element mesh of the unwrapped film.

    The options make a :class:`~bearingfem.routes.FilmProblem`; its kind picks the route
    (:data:`bearingfem.routes.ROUTES`), which refuses by name any option it does not use.

    Parameters
    ----------
    bearing, state : :class:`Bearing`, :class:`JournalState`
    n_theta : cells around the circumference (>= 8; None: 120)
    n_z : cells along the length (>= 2; None: 20); with ``half=True`` only z >= 0 is meshed,
        with ceil(n_z/2) cells, which the symmetry of an aligned journal allows (films on
        fields, tilted or elastic are meshed over the whole length)
    element : "P1" or "P2" triangles (None: P1; with ``rtol``, P2 where the film takes it)
    cavitation : "none" (full Sommerfeld), "gumbel" (negative pressure set to ambient after
        the solve), "reynolds" (Swift-Stieber complementarity, projected iteration), "jfo"
        (mass-conserving Jakobsson-Floberg-Olsson film; P1 only; needs a supply: grooves,
        supply_angle or ambient_pressure > 0)
    method : "active-set" (default) or "psor", the projected iteration of "reynolds"
    supply_angle : inertial angle [rad] of an axial supply line at ambient pressure, or None
        for a fully periodic film
    tol : tolerance of the projected iteration (and of an EHD film's Newton test)
    cavitated_shear : "full" - Couette shear mu omega R / h acts over the whole cavitated
        area (a full film of oil that carries no pressure); "none" - no shear there
    grooves : axial supply grooves (:class:`~bearingfem.bearing.Groove`), fixed in the
        inertial frame and flooded at their pressure; with ``cavitation="none"``
        ``flow_in`` is the flow they feed [m^3/s]; with ``cavitation="jfo"`` a groove may
        be starved (``fraction`` < 1)
    ambient_pressure : JFO films: pressure at the axial ends and a supply line above the
        cavitation pressure [Pa] (>= 0)
    fields : :class:`~bearingfem.fields.FilmFields`: gap, its rate, viscosity and density
        fields of the film; None is the rigid cylinder
    tilt, tilt_rate : (tilt_x, tilt_y) [rad] and their rates [rad/s]: the journal axis
        turned about the inertial x and y axes through the bearing centre
        (:func:`~bearingfem.fields.tilted_gap`); ``moment`` is then the film's moment
    profile : :class:`~bearingfem.fields.EdgeProfile`: a crowned or chamfered bush bore,
        its gap h_p(z) [m] added to the film's, which is then meshed over its whole
        length (with fields, a tilt, grooves, a bush or a lubricant too; refused by the
        EHD-JFO film, a bush or lubricant with "jfo", the compressible JFO film and the
        thermal film)
    lubricant : :class:`~bearingfem.lubricant.Lubricant`: viscosity and density following
        the pressure (the EHD film, solved by Newton); with ``cavitation="jfo"`` a
        lubricant with a ``bulk_modulus`` (constant viscosity) is the compressible
        Elrod-type JFO film
    bush : :class:`~bearingfem.elastic.ElasticBush` or a prebuilt compliance on the
        (n_theta, n_z + 1) grid: the gap becomes c (1 + eps cos theta) + deformation
        (P1; cavitation "none", "reynolds" or "jfo"; quasi-static)
    roughness : :class:`~bearingfem.contact.Roughness`: the Greenwood-Tripp asperity
        contact of the gap is added as ``asperity_force`` / ``asperity_friction_torque``
        (with a bush the summits' pressure deforms the bush too); with ``flow``
        (:class:`~bearingfem.contact.FlowFactors`) the film's flow through the rough gap
        is Patir & Cheng's average flow model (the film is then meshed over its whole
        length; refused by the JFO and thermal films)
    start : the EHD and thermal films: a previous :class:`FilmSolution` of the same mesh to
        start from (the same answer to ``tol``); not with ``rtol`` (whose meshes it cannot
        know)
    grading : theta cells sized like 1 - strength cos(theta - focus)
        (:func:`~bearingfem.fe.mesh.film_mesh`); None: uniform cells. A strength in
        [0, 0.99] alone: plain films, meshed in the film frame, the focus their least film
        (one mesh for every state). (angle [rad], strength): the cells concentrate towards
        the inertial ``angle`` (where the film is thin): a grooved film's bearing-fixed
        mesh, or a plain film's at that angle's film angle
    thermal : :class:`~bearingfem.thermal.Thermal`: the thermal (THD) film, the energy
        equation coupled to the film through the ``lubricant``'s viscosity against
        temperature (:mod:`bearingfem.routes.thd`); ``temperature`` and
        ``temperature_max`` [K] are then given
    rtol : a requested relative accuracy of the film force, in [1e-6, 0.1]: the mesh (and,
        unless given, the element) is chosen to reach it and ``force_error`` reports the
        estimate (:mod:`bearingfem.accuracy`); n_theta and n_z are refused with it (the
        mesh is the search's), an ``element`` given is kept; without a ``grading`` of its
        own a plain or grooved film from eps 0.3 on is searched on meshes graded toward its
        least film (:func:`~bearingfem.accuracy.search_grading`; ``accuracy.grading``
        names it)

    Returns
    -------
    FilmSolution
    """
    options = dict(method=method, supply_angle=supply_angle, half=half, tol=tol,
                   cavitated_shear=cavitated_shear, grooves=grooves,
                   ambient_pressure=ambient_pressure, fields=fields, tilt=tilt,
                   tilt_rate=tilt_rate, profile=profile, lubricant=lubricant, bush=bush,
                   roughness=roughness,
                   start=start, grading=grading, thermal=thermal)
    if rtol is not None and start is not None:
        raise ValueError("start is not taken with rtol (the meshes of the search are not "
                         "known before it): give one of them")
    mesh = _mesh(n_theta, n_z, rtol)
    problem = film_problem(bearing, state, *mesh, cavitation,
                           element="P1" if element is None else element, **options)
    if rtol is None:
        return solve(problem)
    # accuracy on request: the problem is checked above, before any work; bearingfem.accuracy
    # chooses the mesh (and element), graded toward the least film where it pays
    graded = search_grading(problem, (state.gamma, state.eps))
    if graded is not None:
        options["grading"] = graded
    sol = film_to_tolerance(
        lambda nt, nz, el: solve(film_problem(bearing, state, nt, nz, cavitation, element=el,
                                              **options)),
        bearing, rtol, element, dict(options, cavitation=cavitation))
    return sol if graded is None else replace(sol, accuracy=replace(sol.accuracy,
                                                                    grading=graded))


def _mesh(n_theta, n_z, rtol) -> tuple:
    """The (n_theta, n_z) a problem is checked on: the one given (None: 120 x 20); with
    ``rtol`` the search's own, so a mesh given beside it is refused by name rather than
    dropped (the default mesh then only checks the other options before any work)."""
    if rtol is not None:
        check_no_mesh(n_theta, n_z)
        return 120, 20
    return (120 if n_theta is None else n_theta), (20 if n_z is None else n_z)


def fvm_reynolds(bearing: Bearing, state: JournalState, n_theta: int | None = None,
                 n_z: int | None = None,
                 cavitation: str = "reynolds", *, method: str = "active-set",
                 supply_angle=None, tol: float = 1e-10, grooves=(),
                 ambient_pressure: float = 0.0, tilt=(0.0, 0.0),
                 tilt_rate=(0.0, 0.0), profile=None,
                 rtol: float | None = None) -> FilmSolution:
    """Finite-volume Reynolds solution: the same inputs (those it takes) and result type
    as :func:`solve_reynolds` (:mod:`bearingfem.fv`; forces are the midpoint sums of seed
    Eq. 16, second order). ``rtol``: the grid chosen to reach a requested relative
    accuracy of the force, ``force_error`` its estimate (second order, as P1); n_theta and
    n_z (None: 120 x 20) are then refused.
    ``profile``: a bush edge profile (:class:`~bearingfem.fields.EdgeProfile`)."""
    options = dict(method=method, supply_angle=supply_angle, tol=tol, grooves=grooves,
                   ambient_pressure=ambient_pressure, tilt=tilt, tilt_rate=tilt_rate,
                   profile=profile)
    mesh = _mesh(n_theta, n_z, rtol)
    problem = film_problem(bearing, state, *mesh, cavitation, discretisation="fv",
                           **options)
    if rtol is None:
        return solve(problem)
    return film_to_tolerance(
        lambda nt, nz, el: solve(film_problem(bearing, state, nt, nz, cavitation,
                                              discretisation="fv", **options)),
        bearing, rtol, "P1", dict(options, cavitation=cavitation, discretisation="fv"))
