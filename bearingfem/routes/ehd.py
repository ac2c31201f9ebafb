"""The elastohydrodynamic films: a pressure-dependent oil or an elastic bush, solved by
Newton (:mod:`bearingfem.ehd`), with Reynolds' condition or the JFO film."""
from __future__ import annotations

from dataclasses import replace

from ..ehd.film import check_ehd, solve_elastic_film
from ..ehd.jfo import check_ehd_jfo, solve_elastic_jfo_film
from .base import Route, film_and_summits
from .problem import FilmProblem

__all__ = ["ElasticFilm", "ElasticJFOFilm"]


class _ElasticRoute(Route):
    """The EHD routes' light path: the whole film, its summits solved with it."""

    def total_force(self, p: FilmProblem, warm=None):
        """The film and its summits, solved together; ``warm``: the last call's film on
        the same mesh, which starts Newton (the same answer to ``tol``)."""
        if warm is not None and p.start is None:
            p = replace(p, start=warm)
        sol = self.solve(p)
        return film_and_summits(sol), sol


class ElasticFilm(_ElasticRoute):
    name = "ehd"
    summary = "a lubricant (pressure-viscosity/density law) or a bush, cavitation 'none' " \
              "or 'reynolds', P1, whole length"
    uses = frozenset({"element", "method", "tol", "cavitated_shear", "supply_angle", "half",
                      "grooves", "fields", "tilt", "tilt_rate", "profile", "lubricant", "bush",
                      "roughness", "start"})
    rough_flow = True

    def check_options(self, p: FilmProblem) -> None:
        check_ehd(p.lubricant, p.bush, p.fields, p.element, p.cavitation)

    def solve(self, p: FilmProblem):
        return solve_elastic_film(
            p.bearing, p.state, p.n_theta, p.n_z, p.cavitation, element=p.element,
            method=p.method, tol=p.tol, supply_angle=p.supply_angle,
            cavitated_shear=p.cavitated_shear, grooves=p.grooves, fields=p.fields,
            tilt=p.tilt, tilt_rate=p.tilt_rate, profile=p.profile, lubricant=p.lubricant,
            bush=p.bush,
            roughness=p.roughness, start=p.start)


class ElasticJFOFilm(_ElasticRoute):
    name = "ehd-jfo"
    summary = "the JFO film with a bush or a pressure-viscosity law, whole length"
    uses = frozenset({"element", "tol", "supply_angle", "half", "grooves",
                      "ambient_pressure", "lubricant", "bush", "roughness", "start"})

    def check_options(self, p: FilmProblem) -> None:
        check_ehd_jfo(p.lubricant, p.fields, p.tilt, p.tilt_rate)

    def solve(self, p: FilmProblem):
        return solve_elastic_jfo_film(
            p.bearing, p.state, p.n_theta, p.n_z, lubricant=p.lubricant, bush=p.bush,
            grooves=p.grooves, ambient_pressure=p.ambient_pressure, tol=p.tol,
            supply_angle=p.supply_angle, start=p.start, roughness=p.roughness)
