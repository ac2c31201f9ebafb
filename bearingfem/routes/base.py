"""The contract every film route keeps, written once.

A route is one way to solve a :class:`~bearingfem.routes.problem.FilmProblem`: a mesh, a
discretisation and a solver for one kind of film. :data:`bearingfem.routes.ROUTES` maps
each problem's :attr:`~bearingfem.routes.problem.FilmProblem.kind` to its route, in the
manner of scipy's ``solve_ivp(method=...)`` and its ``METHODS``.

Rules for writing a route
-------------------------
1. ``name``: the problem kind it solves (the key in ``ROUTES``), and ``summary``: one
   line saying which problems those are.
2. ``uses``: every option (:data:`~bearingfem.routes.problem.OPTION_DEFAULTS`) the route
   reads; ``rough_flow``: True where it takes a rough gap's flow (Patir & Cheng's flow
   factors, given on the roughness: ``roughness.flow``, refused by that name elsewhere).
   An option set away from its default that the route does not use is refused by
   :meth:`Route.check` with a ValueError naming it and the route, before any work: no
   option is ever ignored in silence.
3. ``check_options(problem)``: what the route alone refuses (an element it cannot take,
   a lubricant law it does not model), before any work. The shared checks were made when
   the problem was built (:func:`~bearingfem.routes.problem.film_problem`).
4. ``solve(problem) -> FilmSolution``: the whole film, the problem's pressures, forces,
   friction and flows, with the asperity contact added by :meth:`Route.with_contact`
   where the route leaves the film's pressure unchanged by it (``contact_operator``
   names the mesh that carries it).
5. ``force(problem, warm) -> ((F_r, F_t), record)``: the light path of time integration
   (forces only). ``warm`` is the record of the previous call on the same mesh at a
   nearby state; the answer equals ``solve``'s to the solver's tolerance. A route without
   a light path inherits the whole solve.
6. ``derivatives(problem)``: the film force's exact partials where the route has them
   (None: the caller takes differences).
7. A solve that does not converge raises :class:`~bearingfem.errors.ConvergenceError`;
   nothing returns an unconverged film.
"""
from __future__ import annotations

from ..fe.assembly import FilmOperator
from ..contact import AsperityContact
from ..fe.mixed import film_contact, with_contact
from ..solution import FilmSolution, ForceDerivatives
from .problem import FilmProblem

__all__ = ["Route", "film_and_summits"]


def film_and_summits(sol: FilmSolution) -> tuple:
    """(F_r, F_t) [N]: a solution's film force plus its summits' (solved with the film)."""
    f, c = sol.force_local, sol.asperity_force_local
    return float(f[0] + c[0]), float(f[1] + c[1])


class Route:
    """Base class of the film routes (the module's rules)."""

    name: str = ""
    summary: str = ""
    uses: frozenset = frozenset()
    rough_flow: bool = False

    def check(self, problem: FilmProblem) -> FilmProblem:
        """``problem``, or a ValueError naming the options this route does not use (rule 2)
        or refuses (rule 3)."""
        unused = [k for k in problem.given() if k not in self.uses]
        if problem.rough_flow and not self.rough_flow:
            # the flow factors ride on the roughness: refused by their own name
            unused.append("roughness.flow")
        if unused:
            names = ", ".join(unused)
            raise ValueError(
                f"{names} {'is' if len(unused) == 1 else 'are'} not used by the "
                f"{self.name!r} film ({self.summary}); its options: "
                f"{', '.join(sorted(self.uses)) or 'none'}")
        self.check_options(problem)
        return problem

    def check_options(self, problem: FilmProblem) -> None:
        return None

    def solve(self, problem: FilmProblem) -> FilmSolution:
        raise NotImplementedError

    def force(self, problem: FilmProblem, warm=None):
        return self.solve(problem).force_local, None

    def total_force(self, problem: FilmProblem, warm=None):
        """((F_r, F_t) [N], record): the film's force plus the summits' (the film's alone
        without roughness), on the light path; ``warm`` as in :meth:`force`."""
        force, record = self.force(problem, warm)
        contact = self.contact(problem)
        if contact is None:
            return force, record
        c = contact.force_local
        return (force[0] + c[0], force[1] + c[1]), record

    def derivatives(self, problem: FilmProblem) -> ForceDerivatives | None:
        """The film force's exact partials in (eps, eps_dot, w) (gamma too where the
        route has it), or None where the route has none (the caller differences)."""
        return None

    def contact_operator(self, problem: FilmProblem) -> FilmOperator | None:
        """The mesh whose quadrature points carry the asperity contact of the rigid gap
        (rule 4), or None for a route that solves the contact with its film."""
        return None

    def contact(self, problem: FilmProblem, op: FilmOperator | None = None,
                gap=None) -> AsperityContact | None:
        """The Greenwood-Tripp contact of ``problem.roughness`` on ``op``'s quadrature
        points (default :meth:`contact_operator`; gap ``gap`` at them, None: the rigid
        cylinder's), or None without roughness: written once for every route."""
        if problem.roughness is None:
            return None
        op = self.contact_operator(problem) if op is None else op
        return film_contact(problem.bearing, problem.state, op, problem.roughness, gap)

    def with_contact(self, problem: FilmProblem, sol: FilmSolution,
                     op: FilmOperator | None = None, gap=None) -> FilmSolution:
        """``sol`` with :meth:`contact` added (``sol`` itself without roughness)."""
        contact = self.contact(problem, op, gap)
        return sol if contact is None else with_contact(sol, contact)
