"""The finite-element film with Reynolds-family cavitation ("fem"): the film of
:func:`bearingfem.solve_reynolds`, plus the asperity contact with roughness (film and
summits carry the load together), with its exact partials (discrete sensitivities)."""
from __future__ import annotations

from dataclasses import replace

from ..contract import SteadyRun
from ..fe.mixed import contact_partial_eps
from ..routes import FilmProblem, route_for, solve
from ..solution import ForceDerivatives
from .registry import FilmModel, register

__all__ = ["FEModel"]


def _problem(bearing, state, n_theta, n_z, element, cavitation, grooves, roughness,
             grading) -> FilmProblem:
    """The model's film problem (its options come checked from the registry)."""
    return FilmProblem(bearing, state, n_theta, n_z, element, cavitation, grooves=grooves,
                       roughness=roughness, grading=grading)


def _total(route, p: FilmProblem, force) -> tuple:
    """The film's force plus the summits' (the film's alone without roughness)."""
    contact = route.contact(p)
    if contact is None:
        return force
    c = contact.force_local
    return force[0] + c[0], force[1] + c[1]


class FEModel(FilmModel):
    name = "fem"
    defaults = dict(n_theta=48, n_z=8, element="P1", cavitation="gumbel", grooves=(),
                    roughness=None, grading=None)
    numeric = True
    tilts = True

    def _film_force(self, bearing, state, **options):
        """A cold solve's force, film plus asperity contact."""
        p = _problem(bearing, state, **options)
        route = route_for(p)
        return _total(route, p, route.force(p)[0])

    def _film_solution(self, bearing, state, **options):
        return solve(_problem(bearing, state, **options))

    def _force_derivatives(self, bearing, state, **options) -> ForceDerivatives:
        """The film's exact partials plus the asperity force and its exact partial in eps
        (it has none in eps_dot or w; its gamma partial with grooves, the mesh moving with
        them, is a quadrature error and is left out)."""
        p = _problem(bearing, state, **options)
        route = route_for(p)
        d = route.derivatives(p)
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
                   p.grooves, p.grading)
            force, last[key] = route.force(p, last.get(key))
            return _total(route, p, force)
        return SteadyRun(bearing, warm_force, options)


register(FEModel())
