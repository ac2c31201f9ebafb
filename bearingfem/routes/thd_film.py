"""The Reynolds-condition film of a thermal (THD) film: on the bearing-fixed mesh, with a
viscosity field at its quadrature points (the fixed point's and the coupled Newton's film,
:mod:`bearingfem.routes.thd`, :mod:`bearingfem.routes.thd_newton`)."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..fe.general import film_moment, general_assembly
from ..fe.kernel import fe_pressure, film_outputs, groove_pressures
from ..fields import FilmFields
from ..film import film_thickness, local_to_inertial, source_coefficients
from ..scales import force_factor
from ..solution import FilmSolution

__all__ = ["ReynoldsFieldFilm"]


def _turned_load(op, state) -> np.ndarray:
    """The load of the source a_sin sin(theta) + a_cos cos(theta) on the bearing-fixed
    mesh, theta = phi - gamma: sin and cos of the difference on op's phi loads."""
    a_sin, a_cos = source_coefficients(state.eps, state.eps_dot, state.wedge_speed)
    c, s = math.cos(state.gamma), math.sin(state.gamma)
    return (a_sin * c + a_cos * s) * op.b_sin + (a_cos * c - a_sin * s) * op.b_cos


class ReynoldsFieldFilm:
    """The Reynolds-condition film of a journal ``state`` on the bearing-fixed mesh of
    :func:`thermal_operator` with a viscosity field: the stiffness of -div(H^3/m grad P)
    by :func:`~bearingfem.fe.general.general_assembly`'s products (no form re-run), the
    load fixed (the viscosity does not enter it), and each solve started from the last
    one's cavitated set and factors (``warm``: an earlier film on the same operator, e.g.
    the last thermal step's or a neighbouring state's, or an :class:`LCPResult`)."""

    def __init__(self, bearing, state, op, element, grooves, tol, warm=None):
        self.bearing, self.state, self.op, self.tol = bearing, state, op, tol
        self.element, self.grooves = element, grooves
        theta = op.qp_theta - state.gamma
        self.fields = FilmFields(gap=film_thickness(theta, state.eps),
                                 gap_rate=state.eps_dot * np.cos(theta))
        self.cubed = self.fields.gap ** 3
        self.load = _turned_load(op, state)
        self.held = groove_pressures(bearing, op, grooves)
        self.last = warm.last if isinstance(warm, ReynoldsFieldFilm) else warm

    def solve(self, ratio: np.ndarray):
        """(nodal pressure [Pa], nodal fraction) on the viscosity ``ratio`` mu/mu_ref at
        the quadrature points."""
        self.values = general_assembly(self.op).stiffness_values(self.cubed / ratio)
        warm = self.last
        self.last = fe_pressure(self.op, self.state, "reynolds", tol=self.tol,
                                active0=None if warm is None else warm.active,
                                factor=None if warm is None else warm.factor,
                                dirichlet=self.held, system=(self.values, self.load))
        self.ratio = ratio
        return self.last.pressure * self.bearing.pressure_scale, np.ones(self.op.mesh.ndofs)

    def force_local(self) -> tuple:
        """(F_r, F_t) [N] of the last solve: the integrals of P (cos, sin) phi turned into
        the journal's frame."""
        ic, is_ = self.op.force_integrals(self.last.pressure)
        k = force_factor(self.bearing, False)
        c, s = math.cos(self.state.gamma), math.sin(self.state.gamma)
        return (k * (ic * c + is_ * s), k * (is_ * c - ic * s))

    def force(self) -> np.ndarray:
        """The last solve's force on the journal [N], inertial (x, y)."""
        return np.array(local_to_inertial(*self.force_local(), self.state.gamma), float)

    def solution(self) -> FilmSolution:
        """The last solve's :class:`FilmSolution` (the general film's outputs), nodes
        reported at their film angles."""
        mesh = self.op.mesh
        sol = film_outputs(self.bearing, self.state, self.op, self.last, self.values,
                           self.load, FilmFields(gap=self.fields.gap, viscosity=self.ratio),
                           "reynolds", "full", self.grooves,
                           f"fem-{self.element}/active-set",
                           film_thickness(mesh.theta - self.state.gamma, self.state.eps),
                           force=self.force_local(), theta=mesh.theta - self.state.gamma)
        # the mesh's angle is already inertial: the moment's lever turns by 0, not gamma
        return replace(sol, moment=film_moment(self.bearing, self.op, self.last.pressure, 0.0))
