"""The transient EHD film with JFO cavitation: the film fraction as memory on the elastic bush.

One backward-Euler step of the content, as the rigid transient JFO film
(:class:`~bearingfem.fe.jfo.JFOFilm`), on the gap of the elastic bush
H = H_rigid + w / c, w = C p:

    R_j = (K(p, H) P)_j + (T(H) phi)_j + 12 (Q_j(H) phi_j - Q_j^n) / dt = 0,

on the free control volumes, with Q(H) = int H dA the full content of a volume at
t_{n+1} and Q^n = phi_n Q(H_n) the content kept at t_n (carried to the new mesh position
as the rigid film carries it, :func:`~bearingfem.fe.volumes.shift_rows`). The content
change holds the deflection's rate (w_{n+1} - w_n) / (c dt) through Q: the squeeze of
the bush, which the steady and the Reynolds EHD films leave out. The Couette content
moves at omega/2 relative to the bearing (transport 6 omega, the rigid step's).

Solved by the steady EHD-JFO film's Newton (:func:`~bearingfem.ehd.jfo_newton.solve_ehd_jfo`:
universal variable, exact Jacobian, load continuation from the rigid step), warm started
from the kept (P, phi). Its content term 12 Q(H) phi / dt enters the Jacobian by the
storage 12 Q / dt (dR/dphi) and 12 phi / dt dQ/dH (dR/dP through the compliance).

Reference: M. Giacopini, M.T. Fowell, D. Dini, A. Strozzi, J. Tribol. 132 (2010) 041702.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp

from ..bearing import Bearing, JournalState, check_positive
from ..errors import ConvergenceError
from ..fe.assembly import fe_operator
from ..fe.jfo_balance import step_balance, film_volumes
from ..fe.volumes import shift_rows
from ..scales import force_factor
from .jfo import JFOCoupling, check_ehd_jfo, jfo_coupling
from .jfo_newton import solve_ehd_jfo

__all__ = ["StepCoupling", "EHDJFOFilm", "EHDJFOStep"]


@dataclass(frozen=True, eq=False)
class StepCoupling(JFOCoupling):
    """The balance of one backward-Euler step (module docstring): ``storage`` is
    12 Q(H_rigid) / dt, ``rate`` 12 / dt [1/s] and ``old`` 12 Q^n / dt per volume."""

    rate: float = 0.0
    old: np.ndarray | None = None

    def content(self, P: np.ndarray, s: float = 1.0) -> np.ndarray:
        """Q(H) per volume: the full content of the deformed gap."""
        return self.content0 + self.maps.content @ self.gap_departure(P, s)

    def evaluate(self, P, phi, s: float = 1.0):
        st = super().evaluate(P, phi, s)
        if st is None:
            return None
        extra = self.rate * (self.maps.content @ self.gap_departure(P, s)) * phi
        return replace(st, residual=st.residual + extra - self.old,
                       size=st.size + np.abs(extra) + np.abs(self.old))

    def content_slope(self, phi):
        return sp.diags(self.rate * phi) @ self.maps.content

    def jacobian(self, P, phi, s, state):
        J, U, V, A = super().jacobian(P, phi, s, state)
        dQ = self.rate * (self.maps.content @ self.gap_departure(P, s))
        return J, U, V, A + sp.diags(dQ, format="csr")


@dataclass(frozen=True)
class EHDJFOStep:
    """One converged step: P (dimensionless, all nodes), fraction phi, content phi Q(H)
    per volume, nodal deflection [m], force (F_r, F_t) [N] in the line-of-centres frame,
    Newton iterations and the oil balance: ``inflow`` (net flow into the free volumes
    from the fixed nodes, from K P + T phi there) and ``content_rate`` (the change of
    their content over dt), both dimensionless x 12."""

    P: np.ndarray
    fraction: np.ndarray
    content: np.ndarray
    deformation: np.ndarray
    force: tuple
    iterations: int
    inflow: float
    content_rate: float
    result: object = None           # the solver's JFOResult


class EHDJFOFilm:
    """A transient EHD-JFO film on the whole-length P1 mesh: its memory is the content
    phi Q(H) per volume (fraction and deflection together).

    Parameters: bearing, state (start, full film of the steady EHD-JFO solve or ``fraction``
    1 on the undeformed gap), n_theta, n_z, lubricant, bush (as for
    :func:`~bearingfem.solve_reynolds`), ambient_pressure [Pa], tol (Newton).
    """

    def __init__(self, bearing: Bearing, state: JournalState, n_theta: int, n_z: int,
                 bush, lubricant=None, ambient_pressure: float = 0.0, tol: float = 1e-10):
        check_ehd_jfo(lubricant, None, (0.0, 0.0), (0.0, 0.0))
        self.bearing, self.bush, self.lubricant = bearing, bush, lubricant
        self.ambient, self.tol = float(ambient_pressure), float(tol)
        self._operator = lambda s: fe_operator(bearing, s, n_theta, n_z, "P1", None, False)
        op = self._operator(state)
        self.state = state
        self.P = np.zeros(op.mesh.ndofs)
        self.fraction = np.ones(op.mesh.ndofs)
        self.content = jfo_coupling(bearing, state, op, lubricant, bush, (),
                                    self.ambient).content0.copy()
        self.steps = 0

    def _turn(self, state: JournalState) -> float:
        return float(np.mod(state.gamma - self.state.gamma + np.pi, 2 * np.pi) - np.pi)

    def coupling(self, state: JournalState, dt: float):
        """(StepCoupling, kept content on the new mesh) of the step to ``state`` after
        ``dt`` [s]."""
        op = self._operator(state)
        cv = film_volumes(op.mesh)
        old = shift_rows(cv, self.content[None], self._turn(state) / (2 * np.pi / cv.n_columns))[0]
        film = jfo_coupling(self.bearing, state, op, self.lubricant, self.bush, (),
                            self.ambient)
        kept = {f: getattr(film, f) for f in ("poiseuille", "P_fixed", "phi_fixed", "maps",
                                             "face0", "content0")}
        return StepCoupling(speed=state.omega, storage=12.0 * film.content0 / dt,
                            rate=12.0 / dt, old=12.0 * old / dt, **kept), old

    def advance(self, state: JournalState, dt: float) -> EHDJFOStep:
        """Advance by ``dt`` [s] to ``state`` and keep the new film; raises
        ConvergenceError (keeping the film as it was) when Newton does not converge."""
        dt = check_positive("dt", dt)
        film, old = self.coupling(state, dt)
        op = film.op
        cv = film_volumes(op.mesh)
        cells = self._turn(state) / (2 * np.pi / cv.n_columns)
        P0, phi0 = shift_rows(cv, np.stack([self.P, self.fraction]), cells)

        def rigid():
            b = step_balance(self.bearing, op, state, dt, old, None, (), self.ambient).solve
            return b.P, b.phi
        try:
            out = solve_ehd_jfo(self.bearing, film, rigid, None, self.tol,
                                (P0, np.clip(phi0, 0.0, 1.0)))
        except ConvergenceError as e:
            raise e.at(f"EHD-JFO film step {self.steps + 1}, dt = {dt:.6g} s") from None
        P, phi = out.P, out.phi
        st = film.evaluate(P, phi)
        Q = film.content(P)
        free = op.mesh.free
        flux = np.asarray(st.K @ P + st.T @ phi)
        ic, is_ = op.force_integrals(P)
        k = force_factor(self.bearing, op.mesh.half)
        self.state, self.P, self.fraction, self.content = state, P, phi, phi * Q
        self.steps += 1
        return EHDJFOStep(P, phi, phi * Q, film.poiseuille.deflection(P),
                          (k * float(ic), k * float(is_)), out.result.iterations,
                          inflow=float(np.sum(flux[op.mesh.fixed])),
                          content_rate=float(np.sum((12.0 * phi * Q - 12.0 * old)[free]))
                          / dt, result=out.result)
