"""The linear solves of the JFO active set (:mod:`bearingfem.solvers.jfo`): for a set C of
cavitated volumes, J(C) has the columns of the Poiseuille operator K off C and of the
transport and storage A on C. Sets a few volumes apart share factors through a low-rank
(Woodbury) correction; the volumes' adjacency gives the sets' fronts.
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .blocksolve import BORDERED_MAX_CHANGES

__all__: list = []


def set_lu(J: sp.csc_matrix):
    """LU of a set's matrix. Its columns are those of K (an M-matrix) or of the transport
    and storage (positive diagonal, column sums >= 0): diagonally dominant by columns, so
    diagonal pivots are stable and the symmetric fill-reducing ordering of the film
    stiffness serves (the cost of one factorisation of K)."""
    return spla.splu(J, permc_spec="MMD_AT_PLUS_A",
                     options=dict(SymmetricMode=True, DiagPivotThresh=0.1))


def set_matrix(K: sp.csc_matrix, A: sp.csc_matrix, cavitated: np.ndarray,
                stacked=None) -> sp.csc_matrix:
    """Columns of K off the set and of A on it: the Jacobian of R for that set, gathered
    from the CSC arrays directly (no sparse products or format conversions).
    ``stacked``: (data, indices) of K and A concatenated, when the caller keeps them."""
    data, indices = stacked if stacked is not None else _stacked(K, A)
    count = np.where(cavitated, np.diff(A.indptr), np.diff(K.indptr))
    indptr = np.zeros(len(count) + 1, dtype=K.indptr.dtype)
    np.cumsum(count, out=indptr[1:])
    start = np.where(cavitated, A.indptr[:-1] + K.nnz, K.indptr[:-1])
    pos = np.repeat(start - indptr[:-1], count) + np.arange(indptr[-1])
    return sp.csc_matrix((data[pos], indices[pos], indptr), shape=K.shape)


def _stacked(K: sp.csc_matrix, A: sp.csc_matrix):
    return np.concatenate([K.data, A.data]), np.concatenate([K.indices, A.indices])


class SetSolver:
    """Solves J(C) x = r for the sets C of one balance. J(C) has the columns of K off C
    and of A on C, so the matrices of two sets differ only in the k columns of the volumes
    where the sets differ: J(C) = J(C0) + U E^T with U those columns' differences and E
    their unit vectors. For k <= ``BORDERED_MAX_CHANGES`` (as for the Reynolds film's
    bordered solves, a fixed count keeps every run reproducible) the Woodbury identity
    solves it exactly with the factors of J(C0): one solve with k + 1 right-hand sides and
    a k x k dense system, instead of a new factorisation."""

    def __init__(self, K: sp.spmatrix, A: sp.spmatrix):
        self.K, self.A = sp.csc_matrix(K), sp.csc_matrix(A)
        self.stacked = _stacked(self.K, self.A)
        self.base: np.ndarray | None = None      # the set C0 of the factors
        self.lu = None
        self.factorisations = 0
        self._neighbours = None

    @property
    def neighbours(self) -> sp.csr_matrix:
        """Adjacency of the volumes (the pattern of K off its diagonal), 0/1."""
        if self._neighbours is None:
            G = sp.csr_matrix(self.K, copy=True)
            G.data[:] = 1.0
            G.setdiag(0.0)
            G.eliminate_zeros()
            self._neighbours = G
        return self._neighbours

    def front(self, cavitated: np.ndarray) -> int:
        """How many volumes have a neighbour on the other side of the set's boundary."""
        c = cavitated.astype(float)
        G = self.neighbours
        return int(np.count_nonzero(np.where(cavitated, G @ (1.0 - c), G @ c)))

    def solve(self, cavitated: np.ndarray, rhs: np.ndarray) -> np.ndarray:
        if self.base is not None:
            changed = np.flatnonzero(cavitated != self.base)
            if len(changed) <= BORDERED_MAX_CHANGES:
                x = self._corrected(cavitated, changed, rhs)
                if x is not None:
                    return x
        self.lu = set_lu(set_matrix(self.K, self.A, cavitated, self.stacked))
        self.base = cavitated.copy()
        self.factorisations += 1
        return self.lu.solve(rhs)

    def _corrected(self, cavitated, changed, rhs):
        """The Woodbury solve, or None when its k x k system is near singular (then the
        caller factorises)."""
        if len(changed) == 0:
            return self.lu.solve(rhs)
        # new column minus old: A_j - K_j where j joined the set, K_j - A_j where it left
        sign = np.where(cavitated[changed], 1.0, -1.0)
        U = (self.A[:, changed] - self.K[:, changed]).toarray() * sign
        Y = self.lu.solve(np.column_stack([rhs, U]))
        y, Z = Y[:, 0], Y[:, 1:]
        S = np.eye(len(changed)) + Z[changed]
        if np.linalg.cond(S) > 1e10:
            return None
        return y - Z @ np.linalg.solve(S, y[changed])
