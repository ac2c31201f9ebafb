"""The bush's rate in the implicit-step film's Newton matrix, and the film frame it sees.

The implicit-step film (:mod:`~bearingfem.ehd.implicit`) advances the bush's deflection by
backward Euler, (tau + dt) v + w_n = C (p + p_a(w_n + dt v)); the rate's derivative in the
pressure, dv/dP = scale S^-1 C T^T with S = (tau + dt) I + dt C T^T K T (C the bush's
compliance, T the frame shift from the bush grid to the film's nodes, K the summits'
stiffness -dp_a/dh at the nodes), is the bush's part of the film's Newton matrix, applied
matrix-free. :class:`_RateInverse` solves S (Woodbury on the summits' nodes, GMRES past
it), :class:`_RateCompliance` applies dv/dP, :class:`_Frame` is the frame shift at one
journal angle with what the Woodbury gathers from it.
"""
from __future__ import annotations

from functools import cached_property

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp

from .grid import FrameShift, node_grid

#: The GMRES tolerance of S^-1 inside the Newton matrix's products (those solved to
#: STEP_TOLERANCE: an inexact Newton, converged by the film's residual test)
PRODUCT_KRYLOV = 1e-6
#: The most nodes :class:`_RateInverse` takes in its Woodbury set (a gathered (m, m)
#: matrix and its LU per Newton matrix: 8 ms at 546 nodes, 42 ms at 1024); past it, GMRES
#: on S. The seed pin's sets reach 546 nodes at 192 x 16
WOODBURY_NODES = 1024


class _RateInverse:
    """S^-1, S = (tau + dt) I + dt C T^T K T, by Woodbury on the nodes whose summits'
    stiffness counts at ``rtol``: the set A = {i : dt |C| k_i / (tau + dt) > rtol / 10}
    (|C| the compliance's 2-norm, T a blend of two shifts: |T| <= 1), so
    S_A^-1 = (I - U (tau' I + V^T U)^-1 V^T) / tau' with U = dt C T^T E_A K_A and
    V^T = E_A^T T. The (m, m) matrix V^T U = dt (T C T^T)[A, A] K_A is gathered from the
    node-to-node compliance, circulant in theta (:meth:`~.implicit._StepFilm.node_compliance`: no
    compliance product), and U is applied as one compliance product (U z = dt C T^T of
    K_A z on A). The nodes left out leave the residual r = -dt C T^T K_r T y,
    |r| <= dt |C| max(k_r) |y|: where that bound passes ``rtol`` |b| the solve is
    y = S_A^-1 b, else GMRES on S from it. Past :data:`WOODBURY_NODES` nodes in the set
    no Woodbury is built: GMRES on S from b / (tau + dt).
    Why: GMRES on S inside every Newton-matrix product (about 4 compliance products and
    the Krylov method's overhead) took half the implicit film's run at 48 x 4; the Woodbury
    solve is a small LU's back substitution and one compliance product. Its build was m
    compliance columns, one batched product (37 ms at 546 nodes on 192 x 16, hence a cap of
    128 and GMRES on S past it); the gather costs 3 ms there and the LU 8 ms."""

    def __init__(self, step, stiffness, rtol: float, s: float = 1.0):
        self.step, self.stiffness, self.rtol, self.s = step, stiffness, rtol, s
        self.tau, dt = step.tau, s * step.dt
        self.trivial = stiffness is None or dt == 0.0 or not np.any(stiffness)
        if self.trivial:
            return
        gain = dt * step.run.compliance_norm / self.tau
        k = np.asarray(stiffness, float)
        active = k * gain > 0.1 * rtol
        self.active = np.flatnonzero(active)
        self.left_out = gain * float(np.max(k[~active], initial=0.0))
        m = self.active.size
        self.capped = m > WOODBURY_NODES
        self.lu = None
        if m == 0 or self.capped:
            return
        self.dk = dt * k[self.active]                       # dt K_A
        small = (self.tau * np.eye(m)
                 + step.node_compliance(self.active) * self.dk[None, :])
        self.lu = la.lu_factor(small, check_finite=False)

    def woodbury(self, b: np.ndarray) -> np.ndarray:
        """S_A^-1 b (the Woodbury set's inverse, unchecked: a preconditioner's)."""
        if self.trivial or self.lu is None:
            return b / self.tau
        z = la.lu_solve(self.lu, self.step.shift.to_nodes(b)[self.active],
                        check_finite=False)
        nodes = np.zeros((self.stiffness.size,) + z.shape[1:])
        nodes[self.active] = self.dk.reshape((-1,) + (1,) * (z.ndim - 1)) * z
        return (b - self.step.comply(nodes)) / self.tau

    def solve(self, b: np.ndarray) -> np.ndarray:
        """y with S y = b to ``rtol`` (|S y - b| <= rtol |b| where the Woodbury set holds
        or GMRES converges in its restarts; else its last iterate: a preconditioner's, the
        film's own residual test judges the solve); b (grid,) or (grid, k)."""
        if self.trivial:
            return b / self.tau
        y = self.woodbury(b)
        if b.ndim == 2:
            return np.column_stack([self._checked(b[:, j], y[:, j]) for j in range(b.shape[1])])
        return self._checked(b, y)

    def _checked(self, b, y):
        if self.capped:
            return self.step.solve_rate(b, self.stiffness, self.rtol, self.s)
        if self.left_out * self.tau * np.linalg.norm(y) <= self.rtol * np.linalg.norm(b):
            return y
        self.step.run.rate_fallbacks += 1
        return self.step.solve_rate(b, self.stiffness, self.rtol, self.s, x0=y)


class _RateCompliance:
    """dv/dP x = scale S^-1 C T^T x (S = (tau + dt) I + dt C T^T K T): the bush's part of
    the Newton matrix after the coupling, for :class:`~.film_compliance.BushJacobian`."""

    def __init__(self, step, stiffness, s: float):
        self.step, self.stiffness, self.s = step, stiffness, s
        self.inverse = _RateInverse(step, stiffness, PRODUCT_KRYLOV, s)

    def apply(self, x: np.ndarray) -> np.ndarray:
        f = self.step
        return self.inverse.solve(f.comply(f.scale * x))


class _Frame:
    """The frame shift at one journal angle (kept while gamma holds); its sparse matrix
    and the nodes' grid indices built when first asked (a Newton matrix, the summits'
    Woodbury): gamma moves at every trial state, and built with each frame they took 6 %
    of a run (96 x 8)."""

    def __init__(self, op, gamma: float):
        self.op, self.gamma = op, gamma
        self.shift = FrameShift(node_grid(op.mesh), gamma)
        self._table = None

    @cached_property
    def left(self) -> sp.csr_matrix:
        """T, the frame shift to the nodes (nodes x grid)."""
        return self.shift.matrix()

    @cached_property
    def indices(self) -> tuple:
        """(j, k): each film node's angle and axial index on the grid."""
        node = node_grid(self.op.mesh)
        j, k = np.empty(node.size, int), np.empty(node.size, int)
        j[node.ravel()] = np.repeat(np.arange(node.shape[0]), node.shape[1])
        k[node.ravel()] = np.tile(np.arange(node.shape[1]), node.shape[0])
        return j, k

    def blended(self, columns: np.ndarray, a: float) -> np.ndarray:
        """((1 - a)^2 + a^2) c(d) + a (1 - a) (c(d - 1) + c(d + 1)) of the grid's columns
        c (n_theta, n_z + 1, n_z + 1), raveled (:meth:`~.implicit._StepFilm.node_compliance`)."""
        if self._table is None or self._table[0] != a:   # kept per fraction a
            self._table = (a, (((1 - a) ** 2 + a * a) * columns
                               + a * (1 - a) * (np.roll(columns, 1, axis=0)
                                                + np.roll(columns, -1, axis=0))).ravel())
        return self._table[1]
