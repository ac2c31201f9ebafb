"""The finite-element Reynolds-family films (cavitation "none", "gumbel", "reynolds"):
the rigid cylinder in the film frame, the grooved film on the bearing-fixed mesh, and the
film on general fields (fields, tilt)."""
from __future__ import annotations

from ..fe.assembly import fe_operator
from ..fe.general import general_film
from ..fe.grooved import (groove_operator_for, grooved_derivatives, grooved_force,
                          grooved_solution)
from ..fe.kernel import rigid_force, solve_film
from ..fe.mixed import film_flow
from ..fe.sensitivity import fe_force_derivatives
from .base import Route, film_and_summits
from .problem import FilmProblem

__all__ = ["RigidFilm", "GroovedFilm", "GeneralFilm"]

_SOLVER = frozenset({"element", "method", "tol", "cavitated_shear", "roughness"})


def _film_frame_half(p: FilmProblem):
    """The half-length mesh in the film frame (the summits of a rigid aligned film)."""
    return fe_operator(p.bearing, p.state, p.n_theta, p.n_z, p.element, None, True,
                       p.grooves)


class RigidFilm(Route):
    name = "rigid"
    summary = "the rigid cylinder, cavitation 'none', 'gumbel' or 'reynolds', meshed in " \
              "the film frame (graded toward the least film with grading)"
    uses = _SOLVER | {"supply_angle", "half", "grooves", "grading"}

    @staticmethod
    def operator(p: FilmProblem):
        return fe_operator(p.bearing, p.state, p.n_theta, p.n_z, p.element, p.supply_angle,
                           p.half, p.grooves, p.grading)

    contact_operator = operator

    def solve(self, p: FilmProblem):
        op = self.operator(p)
        sol = solve_film(p.bearing, p.state, op, p.element, p.cavitation, p.method, p.tol,
                         p.cavitated_shear, p.grooves)
        return self.with_contact(p, sol, op)

    def force(self, p: FilmProblem, warm=None):
        return rigid_force(p.bearing, p.state, self.operator(p), p.cavitation, p.method,
                           warm, p.grooves, p.tol)

    def derivatives(self, p: FilmProblem):
        if p.supply_angle is not None or not p.half:
            return None
        return fe_force_derivatives(p.bearing, p.state, p.n_theta, p.n_z, p.element,
                                    p.cavitation, p.grooves, p.grading)


class GroovedFilm(Route):
    name = "grooved"
    summary = "flooded axial grooves on the bearing-fixed mesh (half length; graded in " \
              "theta with grading): a new journal angle rebuilds nothing"
    uses = _SOLVER | {"grooves", "half", "grading"}

    def check_options(self, p: FilmProblem) -> None:
        if p.grading is not None and not isinstance(p.grading, tuple):
            raise ValueError(f"grading on a grooved film is (angle [rad], strength in "
                             f"[0, 0.99]) of its bearing-fixed mesh, got {p.grading!r}")
        if p.grading is not None and p.roughness is not None:
            raise ValueError("grading is for grooved films on the bearing-fixed mesh "
                             "without roughness: give grooves, and no roughness")

    @staticmethod
    def operator(p: FilmProblem):
        return groove_operator_for(p.bearing, p.n_theta, p.n_z, p.element, p.grooves,
                                   p.grading)

    contact_operator = staticmethod(_film_frame_half)

    def solve(self, p: FilmProblem):
        sol = grooved_solution(p.bearing, p.state, self.operator(p), p.grooves, p.cavitation,
                               p.method, p.tol, p.cavitated_shear, p.element)
        return self.with_contact(p, sol)

    def force(self, p: FilmProblem, warm=None):
        return grooved_force(p.bearing, p.state, self.operator(p), p.grooves, p.cavitation,
                             p.method, warm)

    def derivatives(self, p: FilmProblem):
        return grooved_derivatives(p.bearing, p.state, self.operator(p), p.grooves,
                                   p.cavitation)


class GeneralFilm(Route):
    name = "general"
    summary = "a film on general fields (gap, viscosity, density), a tilted journal, a " \
              "bush edge profile or a rough gap's flow, whole length"
    uses = _SOLVER | {"supply_angle", "half", "grooves", "fields", "tilt", "tilt_rate",
                      "profile"}
    rough_flow = True

    def solve(self, p: FilmProblem):
        op = fe_operator(p.bearing, p.state, p.n_theta, p.n_z, p.element, p.supply_angle,
                         False, p.grooves)
        film, gap = general_film(p.bearing, p.state, op, p.fields, p.tilt, p.tilt_rate,
                                 p.profile)
        sol = solve_film(p.bearing, p.state, op, p.element, p.cavitation, p.method, p.tol,
                         p.cavitated_shear, p.grooves, film, gap,
                         film_flow(p.bearing, p.state, p.roughness, film.gap))
        return self.with_contact(p, sol, op, film.gap)

    def total_force(self, p: FilmProblem, warm=None):
        """The film's force plus the summits' on the film's own mesh and gap, from one
        whole solve (the general film has no separate contact mesh)."""
        return film_and_summits(self.solve(p)), None
