"""The mass-conserving (JFO) films: rigid in the film frame (on any fields), grooved on
the bearing-fixed mesh, and compressible (Elrod-type, a lubricant with a bulk modulus)."""
from __future__ import annotations

from ..fe.assembly import fe_operator
from ..fe.jfo_compressible import check_elrod, solve_compressible_jfo
from ..fe.jfo_fields import balance_films
from ..fe.jfo_grooved import grooved_jfo_force, solve_grooved_jfo
from ..fe.jfo_steady import jfo_force, solve_jfo
from .base import Route
from .problem import FilmProblem

__all__ = ["JFOFilm", "GroovedJFOFilm", "CompressibleJFOFilm"]


def _operators(p: FilmProblem):
    """The function (n_theta, n_z) -> film operator of the nested JFO solve."""
    half = p.half and not p.general

    def operator(nt, nz):
        return fe_operator(p.bearing, p.state, nt, nz, "P1", p.supply_angle, half, p.grooves)
    return operator


def _cavitated(warm):
    return None if warm is None else getattr(warm, "cavitated", None)


class JFOFilm(Route):
    name = "jfo"
    summary = "the mass-conserving JFO film meshed in the film frame, rigid or on fields " \
              "(a tilt, a bush edge profile)"
    uses = frozenset({"element", "supply_angle", "half", "grooves", "ambient_pressure",
                      "fields", "tilt", "tilt_rate", "profile", "roughness"})

    def solve(self, p: FilmProblem):
        operator = _operators(p)
        film = gap = None
        if p.general:
            fine = operator(p.n_theta, p.n_z)
            film = balance_films(p.bearing, p.state, fine, p.fields, p.tilt, p.tilt_rate,
                                 p.profile)
            gap = film(fine).fields.gap                 # bad fields raised above
            if film(fine).fields.is_rigid(fine, p.state):
                film = None                 # the rigid data takes the fast path
        sol = solve_jfo(p.bearing, p.state, operator, p.n_theta, p.n_z, p.grooves,
                        p.ambient_pressure, film)
        if p.roughness is None:
            return sol
        return self.with_contact(p, sol, operator(p.n_theta, p.n_z), gap)

    def force(self, p: FilmProblem, warm=None):
        if p.general or p.roughness is not None:
            return super().force(p, warm)
        return jfo_force(p.bearing, p.state, _operators(p), p.n_theta, p.n_z, p.grooves,
                         p.ambient_pressure, _cavitated(warm))


class GroovedJFOFilm(Route):
    name = "jfo-grooved"
    summary = "the JFO film with axial grooves on the bearing-fixed mesh (half length)"
    uses = frozenset({"element", "grooves", "ambient_pressure", "half"})

    def solve(self, p: FilmProblem):
        return solve_grooved_jfo(p.bearing, p.state, p.n_theta, p.n_z, p.grooves,
                                 p.ambient_pressure)

    def force(self, p: FilmProblem, warm=None):
        return grooved_jfo_force(p.bearing, p.state, p.n_theta, p.n_z, p.grooves,
                                 p.ambient_pressure, _cavitated(warm))


class CompressibleJFOFilm(Route):
    name = "jfo-compressible"
    summary = "the compressible (Elrod-type) JFO film of a lubricant with a bulk_modulus"
    uses = frozenset({"element", "supply_angle", "half", "grooves", "ambient_pressure",
                      "lubricant", "roughness"})

    def check_options(self, p: FilmProblem) -> None:
        check_elrod(p.bearing, p.lubricant)

    def solve(self, p: FilmProblem):
        operator = _operators(p)
        sol = solve_compressible_jfo(p.bearing, p.state, operator, p.n_theta, p.n_z,
                                     float(p.lubricant.bulk_modulus), p.grooves,
                                     p.ambient_pressure)
        if p.roughness is None:
            return sol
        return self.with_contact(p, sol, operator(p.n_theta, p.n_z))
