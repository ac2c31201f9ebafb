"""The Reynolds-condition film of a thermal (THD) film: on the bearing-fixed mesh, with a
viscosity field at its quadrature points (the fixed point's and the coupled Newton's film,
:mod:`bearingfem.routes.thd`, :mod:`bearingfem.routes.thd_newton`)."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..fe.general import film_moment, general_assembly
from ..fe.kernel import fe_pressure, film_outputs, groove_pressures
from ..fe.multilevel import descend
from ..solvers.blocksolve import inactive_solve
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


def turned_guess(op, state, tol: float, held: tuple = ()) -> np.ndarray | None:
    """:func:`~bearingfem.fe.multilevel.coarse_guess` for the bearing-fixed mesh: the
    coarser levels' rigid film of ``state`` turned by gamma (its stiffness on the gap
    h(phi - gamma) at the level's quadrature points, its load turned), interpolated to
    ``op``'s free dofs; None when ``op`` is the coarsest level. Why: the operator's own
    rigid film is the journal at gamma = 0, whose cavity lies gamma away from this one's
    (a cold 96 x 16 film at gamma = -1 took 6 active-set solves from it, 2 from this)."""
    def film(level):
        values = general_assembly(level).stiffness_values(
            film_thickness(level.qp_theta - state.gamma, state.eps) ** 3)
        return (_turned_load(level, state), level.free_stiffness(state.eps, values),
                lambda: level.matrix(values))

    return descend(op, film, tol, held)


class ReynoldsFieldFilm:
    """The Reynolds-condition film of a journal ``state`` on the bearing-fixed mesh of
    :func:`thermal_operator` with a viscosity field: the stiffness of -div(H^3/m grad P)
    by :func:`~bearingfem.fe.general.general_assembly`'s products (no form re-run), the
    load fixed (the viscosity does not enter it), and each solve started from the last
    one's cavitated set and factors (``warm``: an earlier film on the same operator, e.g.
    the last thermal step's or a neighbouring state's, or an :class:`LCPResult`; a warm
    film of the same state on the same operator lends its gap and load too). Without a
    warm start the first set comes from the coarser levels' film turned to the state
    (:func:`turned_guess`)."""

    def __init__(self, bearing, state, op, element, grooves, tol, warm=None):
        self.bearing, self.state, self.op, self.tol = bearing, state, op, tol
        self.element, self.grooves = element, grooves
        if isinstance(warm, ReynoldsFieldFilm) and warm.op is op and warm.state == state \
                and warm.grooves == grooves:
            self.fields, self.cubed, self.load, self.held = \
                warm.fields, warm.cubed, warm.load, warm.held
        else:
            theta = op.qp_theta - state.gamma
            self.fields = FilmFields(gap=film_thickness(theta, state.eps),
                                     gap_rate=state.eps_dot * np.cos(theta))
            self.cubed = self.fields.gap ** 3
            self.load = _turned_load(op, state)
            self.held = groove_pressures(bearing, op, grooves)
        self.last = warm.last if isinstance(warm, ReynoldsFieldFilm) else warm

    def forget_factors(self) -> None:
        """Start the next solve from the warm cavitated set alone, without its factors
        (a new factorisation instead of CG preconditioned by them)."""
        if self.last is not None and self.last.factor is not None:
            self.last = replace(self.last, factor=None)

    def solve(self, ratio: np.ndarray):
        """(nodal pressure [Pa], nodal fraction) on the viscosity ``ratio`` mu/mu_ref at
        the quadrature points."""
        self.values = general_assembly(self.op).stiffness_values(self.cubed / ratio)
        warm = self.last
        guess = None
        if warm is None:
            held = () if self.held is None else tuple(
                float(self.held[d[0]]) if len(d) else 0.0 for d in self.op.mesh.grooves)
            guess = turned_guess(self.op, self.state, self.tol, held)
        self.last = fe_pressure(self.op, self.state, "reynolds", tol=self.tol,
                                active0=None if warm is None else warm.active,
                                factor=None if warm is None else warm.factor,
                                dirichlet=self.held, system=(self.values, self.load),
                                guess=guess)
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

    def force_partials(self) -> tuple:
        """(dF/dq, dF/dv) [N] of the last solve's film with its viscosity field held: the
        inertial force's derivatives in the journal position q = e/c and its rate
        v = (de/dt)/c [1/s], (2, 2) each (column j: the j-th component), exact at the
        solve's cavitated set. On the bearing-fixed mesh the gap is
        H = 1 + q_x cos(phi) + q_y sin(phi) and the source's load
        (6 omega q_x - 12 v_y) b_sin - (6 omega q_y + 12 v_x) b_cos (the turned wedge and
        squeeze of :func:`_turned_load`, linear in q and v); the inertial force is
        k (P . b_cos, P . b_sin) whatever gamma. So dP solves the film's inactive block
        with the load's partial less dK/dq P, dK/dq the stiffness of 3 H^2 dH/dq / m:
        four right-hand sides on one factorisation, where central differences take
        eight films."""
        op, res, omega = self.op, self.last, self.state.omega
        if self.state.eps_dot != 0.0 or self.state.gamma_dot != 0.0:
            raise ValueError("force_partials: the film must be steady (eps_dot = "
                             "gamma_dot = 0)")
        P, free = res.pressure, op.mesh.free
        assembly = general_assembly(op)
        slope = 3.0 * self.fields.gap ** 2 / self.ratio
        rhs = np.column_stack([
            6.0 * omega * op.b_sin - op.matrix(assembly.stiffness_values(
                slope * np.cos(op.qp_theta))) @ P,
            -6.0 * omega * op.b_cos - op.matrix(assembly.stiffness_values(
                slope * np.sin(op.qp_theta))) @ P,
            -12.0 * op.b_cos, -12.0 * op.b_sin])
        inactive = ~res.active[free]
        K = op.free_stiffness(self.state.eps, self.values)
        # the solve's factors when it made them (CG preconditioned by another film's
        # factors leaves those, not this K's: then a factorisation here)
        dP = np.zeros((op.mesh.ndofs, 4))
        dP[free] = inactive_solve(K, res.factor if res.factorisations else None, inactive,
                                  rhs[free])
        k = force_factor(self.bearing, False)
        J = k * np.stack([dP.T @ op.b_cos, dP.T @ op.b_sin])        # (2, 4)
        return J[:, :2], J[:, 2:]

    def solution(self) -> FilmSolution:
        """The last solve's :class:`FilmSolution` (the general film's outputs), nodes
        reported at their film angles."""
        mesh = self.op.mesh
        # the mesh's angle is already inertial: the moment's lever turns by 0, not gamma
        return film_outputs(self.bearing, self.state, self.op, self.last, self.values,
                            self.load, FilmFields(gap=self.fields.gap, viscosity=self.ratio),
                            "reynolds", "full", self.grooves,
                            f"fem-{self.element}/active-set",
                            film_thickness(mesh.theta - self.state.gamma, self.state.eps),
                            force=self.force_local(), theta=mesh.theta - self.state.gamma,
                            moment=film_moment(self.bearing, self.op, self.last.pressure,
                                               0.0))
