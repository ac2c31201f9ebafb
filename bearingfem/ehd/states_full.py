"""The EHD film with the bush's whole deflection as states of the time integration.

:class:`FullStateEHD` (``modes`` 0) integrates the whole deflection on the bush's grid
instead of the modal film's modes (:mod:`bearingfem.ehd.states_modal`, whose coupling
it shares: q = w, no modes chosen), w + tau dw/dt = C (p + p_a) with C the full
compliance applied per theta harmonic; its Newton carries the dense squeeze term
matrix-free (GMRES) and its tangent is dense (docs/ehd-states.md, "The whole deflection
integrated"). :func:`full_bush_setup` is what every film of the whole deflection holds
(this one and the implicit-step film, :mod:`bearingfem.ehd.implicit`).
"""
from __future__ import annotations

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp

from ..bearing import Bearing
from ..contract import StateTangent
from ..scales import force_factor
from .coupling import jacobian_tables
from .film_compliance import BushJacobian, CirculantCompliance
from .grid import FrameShift, node_grid
from .states_modal import ModalStateEHD, _Frame, hold_bush_inputs
from .transient import ehd_compliance

__all__ = ["FullStateEHD"]

#: Leading modes of the full compliance in the full-state film's preconditioner (the
#: sparse film plus their low-rank squeeze, by Woodbury): GMRES then resolves the rest.
PRECONDITIONER_MODES = 32


def full_bush_setup(film, name: str, bearing: Bearing, lubricant, bush, n_theta: int,
                    n_z: int, relaxation: float, roughness, profile) -> None:
    """What a film of the bush's whole deflection holds (:class:`FullStateEHD` and
    :class:`~.implicit.ImplicitStepEHD`): the inputs (:func:`hold_bush_inputs`), the whole
    compliance on the bush grid applied per theta harmonic (``film.compliance``) and its
    leading modes (the Newton step's preconditioner with the sparse film, ``film._low``)."""
    hold_bush_inputs(film, name, bearing, lubricant, bush, n_theta, n_z, relaxation,
                     roughness, profile)
    comp = ehd_compliance(bush, bearing.radius, bearing.length, film.n_theta, film.n_z, 0)
    n = comp.shape[0] * comp.shape[1]
    film.compliance = CirculantCompliance(comp.blocks, comp.shape, np.arange(n),
                                          np.arange(n))
    film._low = comp.reduced(min(PRECONDITIONER_MODES, n))
#: GMRES's relative residual for the full-state film's Newton and chord steps: an inexact
#: Newton, converged by the film's own residual test (TOL); 1e-3 took half the CPU of
#: 1e-12 on the seed pin's first 2 % of a turn (48 x 4), the results equal to 2e-7
STEP_TOLERANCE = 1e-3


class _GridCompliance:
    """The film nodes' pressure to the bush grid's quasi-static deflection, C T^T
    (:meth:`_FullFrame.comply` after the frame shift's transpose), for
    :class:`~.film_compliance.BushJacobian`."""

    def __init__(self, frame: "_FullFrame"):
        self.frame = frame

    def apply(self, x: np.ndarray) -> np.ndarray:
        return self.frame.comply(self.frame.shift.to_grid(x))

    @property
    def left(self) -> np.ndarray:
        """The dense (grid, nodes) matrix (checks and the tangent's dense solve)."""
        return self.apply(np.eye(self.frame.size))


class _FullFrame(_Frame):
    """:class:`_Frame` for the full deflection as the states (q = w on the bush grid, no
    modes): L is the frame shift to the film nodes (sparse, two entries a row) and S R^T
    the whole compliance, applied per theta harmonic (FFT, one (n_z + 1)^2 block each)."""

    def __init__(self, op, gamma: float, compliance: CirculantCompliance, low,
                 clearance: float):
        self.op, self.gamma, self.clearance = op, gamma, clearance
        self.compliance, self.modal, self._V = compliance, None, None
        self.low = low      # the compliance's leading singular triples (the preconditioner's)
        self.shift = FrameShift(node_grid(op.mesh), gamma)
        self.left = self.shift.matrix()                          # (nodes, grid), sparse
        self.size = self.left.shape[1]

    def deflection(self, q: np.ndarray) -> np.ndarray:
        return self.shift.to_nodes(q)

    def comply(self, p_grid: np.ndarray) -> np.ndarray:
        return self.compliance.on_grid(p_grid)

    def newton_part(self, G, scale: float, relaxation: float) -> tuple:
        """The bush part (scale / tau) G C T^T, matrix-free: a
        :class:`~.film_compliance.BushJacobian`, which the Newton step solves by GMRES
        preconditioned by the film's sparse LU."""
        if self._V is None:     # V_k of the low-rank part: the same at every pressure and q
            self._V = (scale / relaxation) * self.shift.to_nodes(self.low.right
                                                                 * self.low.singular)
        low = (np.asarray(G @ self.low.left), self._V)
        return BushJacobian((scale / relaxation) * G, _GridCompliance(self), low,
                            STEP_TOLERANCE), None

    def rates_factor(self, scale: float, relaxation: float) -> np.ndarray:
        raise ValueError("the full-state film has no low-rank rates factor")


class FullStateEHD(ModalStateEHD):
    """The "fem-ehd" film with the bush's whole deflection on its grid as integration
    states (``modes`` 0: no truncation): q = w, N = n_theta (n_z + 1) states,
    q + tau dq/dt = C (p + p_a) with C the full compliance applied per theta harmonic
    (the bush is axisymmetric: FFT in theta, one (n_z + 1)^2 block per harmonic).

    The film's Newton carries the squeeze term G (C p - q) / tau through GMRES
    preconditioned by the film's sparse LU (:class:`~.newton._KrylovLU`); the tangent
    (contract rule 17) is dense, N x N, from one dense LU of the Newton matrix. With all
    n_theta (n_z + 1) modes the modal film is this one in another basis (q_modal = L^T w,
    L orthogonal; tests/test_ehd_states_full.py).

    Parameters: as :class:`ModalStateEHD` without ``modes``.
    """

    def __init__(self, bearing: Bearing, lubricant=None, bush=None, n_theta: int = 48,
                 n_z: int = 8, relaxation: float = 1e-5, roughness=None, profile=None):
        full_bush_setup(self, "full-state", bearing, lubricant, bush, n_theta, n_z,
                        relaxation, roughness, profile)
        n = self.compliance.shape[0] * self.compliance.shape[1]
        self.left = self.modal = None
        self.state_size = n
        self.steps = 0
        self._P, self._factor, self._frame, self._rated = None, [], None, None

    def _new_frame(self, op, gamma: float) -> _FullFrame:
        return _FullFrame(op, gamma, self.compliance, self._low, self.bearing.clearance)

    def tangent(self) -> StateTangent:
        """As :meth:`ModalStateEHD.tangent`, with L the (sparse) frame shift and the
        pressure's response dP/dq = -M^-1 dR/dq from a dense LU of the Newton matrix M on
        the rows not held cavitated (N columns: one dense factorisation, cost N^3 / 3)."""
        if self._rated is None:
            raise ValueError("tangent() differentiates the last rates() call: call rates first")
        coupled, res = self._rated
        op, frame, film = coupled.op, coupled.frame, coupled.film
        c, P, n = self.bearing.clearance, res.pressure, self.state_size
        ev = coupled.evaluate(P)
        T = frame.left                                              # (nodes, grid) sparse
        whole = ev if ev.flow is None or film.lubricant is not None else coupled.film_state(P)
        dR = film.gap_slope(P, 1.0, whole, coupled.moving) @ (T / c)
        if coupled.gamma_dot:
            # the whirl's squeeze gamma_dot dw/dalpha / c at the points, as a sparse map
            t = jacobian_tables(op)
            dofs = op.mesh.basis.element_dofs                        # (j, e)
            E, Q = t.dx.shape
            rows = np.broadcast_to((np.arange(E)[:, None] * Q + np.arange(Q))[None],
                                   t.dphi[:, 0].shape)
            cols = np.broadcast_to(dofs[:, :, None], t.dphi[:, 0].shape)
            D = sp.csr_matrix(((t.dphi[:, 0] / t.dx[None]).ravel(),
                               (rows.ravel(), cols.ravel())), shape=(E * Q, T.shape[0]))
            rho = np.broadcast_to(ev.fields.density, op.qp_weight.shape)
            if ev.flow is not None:
                rho = rho * ev.flow.gap_slope
            w = sp.diags((12.0 * rho * op.qp_weight).ravel())
            dR = dR + op.qp_interp.T @ (w @ (D @ T)) * (coupled.gamma_dot / c)
        dR = dR.toarray()
        # K = C T^T (grid x nodes): the grid's quasi-static deflection per nodal pressure,
        # formed once (one FFT of N columns); every dense product below is K's
        K = frame.comply(T.T.toarray())
        dpa = (sp.csr_matrix(T.shape) if coupled.contact is None else
               sp.diags(self.roughness.pressure_derivative(c * coupled.gap)) @ T)   # [Pa/m]
        rates_q = np.asarray((dpa.T @ K.T).T)
        rates_q[np.diag_indices(n)] -= 1.0
        rates_q /= self.tau
        G = coupled.squeeze_load(ev)
        dR += G @ rates_q
        free = op.mesh.free
        J, U, _ = coupled.jacobian(P, 1.0, ev)
        I = free[~res.active[free]]
        M = J[I][:, I].toarray() + np.asarray(U.coupling[I] @ K[:, I])
        dP = np.zeros_like(dR)
        dP[I] = la.lu_solve(la.lu_factor(M, overwrite_a=True, check_finite=False), -dR[I],
                            overwrite_b=True, check_finite=False)
        k = force_factor(self.bearing, False)
        ic, is_ = op.force_integrals((dP + dpa.toarray() / film.scale).T)
        rates = rates_q + (film.scale / self.tau) * (K[:, I] @ dP[I])
        return StateTangent(force_local=k * np.vstack([ic, is_]), rates=rates)
