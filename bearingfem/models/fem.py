"""The finite-element film with Reynolds-family cavitation ("fem"): the film of
:func:`bearingfem.solve_reynolds`, plus the asperity contact with roughness (film and
summits carry the load together), with its exact partials (discrete sensitivities). With
a ``lubricant`` or a ``bush`` it is the steady EHD film (inside the clearance circle; the
"fem-ehd" model goes beyond it and along a run), its partials by central differences."""
from __future__ import annotations

from dataclasses import replace

from ..contract import SteadyRun
from ..differentiate import central_differences
from ..elastic import ElasticBush
from ..lubricant import Lubricant
from ..fe.mixed import contact_partial_eps
from ..routes import FilmProblem, route_for, solve
from ..solution import ForceDerivatives
from .registry import FilmModel, register

__all__ = ["FEModel"]


def _problem(bearing, state, n_theta, n_z, element, cavitation, grooves, roughness,
             grading, lubricant=None, bush=None) -> FilmProblem:
    """The model's film problem (its options come checked from the registry)."""
    return FilmProblem(bearing, state, n_theta, n_z, element, cavitation, grooves=grooves,
                       roughness=roughness, grading=grading, lubricant=lubricant, bush=bush)


class FEModel(FilmModel):
    name = "fem"
    defaults = dict(n_theta=48, n_z=8, element="P1", cavitation="gumbel", grooves=(),
                    roughness=None, grading=None, lubricant=None, bush=None)
    #: a pressure-dependent oil or an elastic bush makes the film the steady EHD film
    rules = {"lubricant": ("instance", (Lubricant,)), "bush": ("instance", (ElasticBush,))}
    numeric = True
    tilts = True

    def _film_force(self, bearing, state, **options):
        """A cold solve's force, film plus asperity contact."""
        p = _problem(bearing, state, **options)
        return route_for(p).total_force(p)[0]

    def _film_solution(self, bearing, state, **options):
        return solve(_problem(bearing, state, **options))

    def _force_derivatives(self, bearing, state, **options) -> ForceDerivatives:
        """The film's exact partials plus the asperity force and its exact partial in eps
        (it has none in eps_dot or w; its gamma partial with grooves, the mesh moving with
        them, is a quadrature error and is left out)."""
        p = _problem(bearing, state, **options)
        route = route_for(p)
        d = route.derivatives(p)
        if d is None:       # a film without exact partials (the EHD film): differences
            return central_differences(lambda s: self._film_force(bearing, s, **options),
                                       state)
        contact = route.contact(p)
        if contact is None:
            return d
        f = contact.force_local
        de = contact_partial_eps(bearing, state, route.contact_operator(p), p.roughness)
        return replace(d, force=(d.force[0] + f[0], d.force[1] + f[1]),
                       d_eps=(d.d_eps[0] + de[0], d.d_eps[1] + de[1]))

    def _along_run(self, bearing, **options):
        """Each solve of the run starts from the previous one's cavitated set and
        factorisation (consecutive states of an integration are close): the same answer
        as a cold solve to the solver tolerance; only the cost changes (rule 7)."""
        last = {}

        def warm_force(bearing, state, **options):
            p = _problem(bearing, state, **options)
            route = route_for(p)
            key = (bearing.length_ratio, p.n_theta, p.n_z, p.element, p.cavitation,
                   p.grooves, p.grading, p.kind)
            force, last[key] = route.total_force(p, last.get(key))
            return force
        return SteadyRun(bearing, warm_force, options)


register(FEModel())
