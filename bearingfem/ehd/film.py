"""The EHD journal film (Reynolds' condition or no cavitation): what
``solve_reynolds(..., lubricant=, bush=)`` solves (:mod:`bearingfem.routes.ehd`)."""
from __future__ import annotations

import logging
from dataclasses import dataclass, replace

import numpy as np

from ..elastic import BushCompliance, ElasticBush
from ..errors import ConvergenceError
from ..fe.assembly import fe_operator
from ..fe.multilevel import prolongation
from ..fe.general import film_system, general_film
from ..fe.mixed import film_contact, friction_fields, with_contact
from ..fe.kernel import fe_pressure, film_outputs, groove_pressures
from ..lubricant import Lubricant
from .coupling import ehd_film
from .beyond import solve_beyond
from .newton import solve_ehd

__all__ = ["solve_elastic_film", "solve_ehd_film", "check_ehd", "NESTED_NODES"]

LOG = logging.getLogger(__name__)

#: A cold EHD solve on a film mesh of more nodes than this starts Newton from the film of
#: the mesh half as fine in theta and z, interpolated (nested iteration): on the seed pin's
#: heavy state the fine mesh then takes 4-5 Newton steps instead of the cold load
#: continuation's 17-28 (docs/ehd.md), and the answer is the same to the solver's
#: tolerance (Newton's own test decides it; a start that stalls falls back to the cold
#: route). Below it the cold route is cheap enough.
NESTED_NODES = 4000


@dataclass(frozen=True)
class _Start:
    """A start for :func:`warm_pressure`: a nodal pressure [Pa] on the film's mesh."""

    pressure: np.ndarray


def check_ehd(lubricant, bush, fields, element: str, cavitation: str):
    """ValueError for a lubricant or bush the EHD film cannot take, before any work."""
    if lubricant is not None and not isinstance(lubricant, Lubricant):
        raise ValueError(f"lubricant must be a bearingfem.Lubricant or None, "
                         f"got {type(lubricant).__name__}")
    if cavitation not in ("none", "reynolds"):
        # Gumbel's film clips after the solve: the fields and the bush would then follow a
        # suction the reported film does not have
        raise ValueError("lubricant and bush need cavitation 'none' or 'reynolds', got "
                         f"cavitation={cavitation!r}")
    if bush is not None and element != "P1":
        raise ValueError(f"bush needs element='P1' (the compliance acts on the film's "
                         f"vertex grid), got element={element!r}")
    if lubricant is not None and fields is not None and not (
            np.all(np.asarray(fields.viscosity) == 1.0)
            and np.all(np.asarray(fields.density) == 1.0)):
        raise ValueError("give the viscosity and density by the lubricant or by fields, "
                         "not both")


def warm_pressure(start, bearing, op, dirichlet) -> np.ndarray | None:
    """The dimensionless nodal pressure of a previous solution ``start`` on the same
    mesh (a :class:`FilmSolution`; None: a cold start), fixed dofs at their held values;
    ValueError when it is on another mesh."""
    if start is None:
        return None
    p = getattr(start, "pressure", None)
    if p is None or np.shape(p) != (op.mesh.ndofs,):
        raise ValueError(f"start must be a FilmSolution of the same film mesh "
                         f"({op.mesh.ndofs} nodes) or None")
    P = np.asarray(p, float) / bearing.pressure_scale
    fixed = np.setdiff1d(np.arange(op.mesh.ndofs), op.mesh.free)
    P[fixed] = 0.0 if dirichlet is None else dirichlet[fixed]
    return P


def solve_ehd_film(bearing, state, op, base, gap0, lubricant, bush, cavitation, method,
                   tol, dirichlet, cavitated_shear, grooves, start=None, roughness=None):
    """Solve the film of ``op`` with pressure-dependent fields and elastic gap; the base
    fields ``base`` (quadrature) and nodal gap ``gap0`` are the film's without them.
    ``start``: a previous solution on the same mesh to start Newton from (warm).
    ``roughness``: the asperity contact of the deformed gap is added
    (:func:`~bearingfem.fe.mixed.with_contact`); with a bush its pressure deforms the bush
    too (:mod:`bearingfem.ehd.asperity`), so ``deformation`` includes the summits' share;
    its ``flow`` factors, when given, carry the film's flow through the rough gap."""
    film = ehd_film(bearing, state, op, base, gap0, lubricant, bush, roughness)

    def rigid(film=film):                       # the isoviscous rigid film (s = 0)
        film0, _ = film.fields(np.zeros(op.mesh.ndofs), 0.0)
        return fe_pressure(op, replace(state, eps=film.eps), cavitation, method, tol,
                           dirichlet=dirichlet,
                           system=film_system(op, film0, state.wedge_speed, film.eps,
                                              film.flow_fields(film0))).pressure
    # beyond the clearance circle the rigid film does not exist: continue in eps instead
    solve = solve_beyond if state.eps >= 1.0 else solve_ehd
    res = solve(film, rigid, "reynolds" if cavitation == "reynolds" else "none", tol,
                start=warm_pressure(start, bearing, op, dirichlet))
    P = res.pressure
    fields, values, load = film.system(P)
    deformation = film.deflection(P)
    sol = film_outputs(bearing, state, op, res, values, load,
                       friction_fields(fields, roughness, bearing.clearance), cavitation,
                        cavitated_shear, grooves, "fem-P1/ehd-newton"
                        if op.mesh.basis.Nbfun == 3 else "fem-P2/ehd-newton",
                        gap0 + deformation / bearing.clearance)
    sol = replace(sol, deformation=deformation)
    if roughness is None:
        return sol
    # the summits on the deformed gap, at the quadrature points (the rigid mixed film's rule)
    return with_contact(sol, film_contact(bearing, state, op, roughness, fields.gap))


def solve_elastic_film(bearing, state, n_theta: int, n_z: int, cavitation: str = "reynolds",
                       *, element: str = "P1", method: str = "active-set", tol: float = 1e-10,
                       supply_angle=None, cavitated_shear: str = "full", grooves=(),
                       fields=None, tilt=(0.0, 0.0), tilt_rate=(0.0, 0.0), profile=None,
                       lubricant=None, bush=None, roughness=None, start=None):
    """The EHD film on an (n_theta, n_z) mesh of the whole length (arguments as
    :func:`bearingfem.solve_reynolds`'s, checked there): the film on its fields, then
    :func:`solve_ehd_film`."""
    check_ehd(lubricant, bush, fields, element, cavitation)
    op = fe_operator(bearing, state, n_theta, n_z, element, supply_angle, False, grooves)
    if (start is None and op.mesh.ndofs > NESTED_NODES and n_theta % 2 == 0
            and n_z % 2 == 0 and element == "P1" and supply_angle is None and not grooves
            and fields is None and roughness is None and state.eps < 1.0
            and isinstance(bush, (ElasticBush, BushCompliance))):
        start = nested_start(bearing, state, op, n_theta // 2, n_z // 2, cavitation,
                             method, tol, tilt, tilt_rate, profile, lubricant,
                             bush if isinstance(bush, ElasticBush) else bush.bush,
                             cavitated_shear)
    film, gap = general_film(bearing, state, op, fields, tilt, tilt_rate, profile)
    return solve_ehd_film(bearing, state, op, film, gap, lubricant, bush, cavitation, method,
                          tol, groove_pressures(bearing, op, grooves), cavitated_shear,
                          grooves, start, roughness)


def nested_start(bearing, state, op, n_theta, n_z, cavitation, method, tol, tilt,
                 tilt_rate, profile, lubricant, bush, cavitated_shear) -> _Start | None:
    """The EHD film on the (n_theta, n_z) mesh (itself nested where it is fine enough; the
    compliance of ``bush`` built on it), its pressure interpolated bilinearly to ``op``'s
    nodes: the start of ``op``'s Newton; None (the cold route) when that film does not
    converge."""
    LOG.info("EHD film %d x %d: Newton starts from the %d x %d film", op.mesh.n_theta,
             op.mesh.n_z, n_theta, n_z)
    try:
        coarse = solve_elastic_film(bearing, state, n_theta, n_z, cavitation, method=method,
                                    tol=tol, tilt=tilt, tilt_rate=tilt_rate,
                                    profile=profile, lubricant=lubricant, bush=bush,
                                    cavitated_shear=cavitated_shear)
    except ConvergenceError:
        return None
    mesh = fe_operator(bearing, state, n_theta, n_z, "P1", None, False, ()).mesh
    return _Start(prolongation(mesh, op.mesh.theta, op.mesh.zeta) @ coarse.pressure)
