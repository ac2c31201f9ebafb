"""Solves on the inactive block of the film stiffness, the work inside an active-set step.

For a cavitated set, the pressure solves K_II P_I = b_I on the inactive (pressurised) dofs
I and is zero elsewhere. Three ways, cheapest first for their case:

* :func:`bordered_solve` - the factors of an earlier set's matrix, corrected exactly by
  Schur complements on the k dofs that changed (k + 1 triangular solves, no factorisation);
* factors of the :func:`pinned` matrix (K with identity rows and columns on the
  cavitated dofs: the size of K, so its factors serve every later set);
* :func:`dense_block_solve` for the tiny coarsest levels of nested iteration, where the
  set-up of sparse factors costs more than their arithmetic.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from .linsolve import factorise, pcg, solve_spd

__all__ = ["BlockSolver", "PinnedFactor", "pinned", "bordered_solve", "inactive_solve",
           "dense_block_solve", "DENSE_DOFS", "BORDERED_MAX_CHANGES"]

#: Up to this many dofs, dense LAPACK solves of the inactive block beat sparse factors.
DENSE_DOFS = 128

#: Most changed dofs for which a bordered solve beats a new factorisation. Measured on
#: 1200- and 19200-dof films: a factorisation costs 25-35 single solves, a (k+1)-column
#: solve about 0.7 (k + 1) of them plus ~0.1 ms of set-up. A fixed count (not timings)
#: keeps every solve, and so every time integration, reproducible to the last bit.
BORDERED_MAX_CHANGES = 20


@dataclass(frozen=True, eq=False)
class PinnedFactor:
    """Sparse LU factors of the pinned matrix of the cavitated set ``active``: the set is
    kept with them, so a later solve knows how far its own set is from theirs."""

    lu: object
    active: np.ndarray

    @property
    def shape(self):
        return self.lu.shape

    def solve(self, rhs):
        return self.lu.solve(rhs)


def pinned(K: sp.csr_matrix, inactive: np.ndarray) -> sp.csc_matrix:
    """K with the rows and columns of the cavitated dofs replaced by the identity.

    Solving it with the load zeroed on those dofs is the inactive-block solve, but the
    matrix keeps the size of K: its factors serve later sets, exactly through
    :func:`bordered_solve` or as a CG preconditioner. K is symmetric, so its CSR arrays are also the CSC arrays of the result.
    """
    n = K.shape[0]
    rows = np.repeat(np.arange(n), np.diff(K.indptr))
    coupled = inactive[rows] & inactive[K.indices]
    keep = coupled | (rows == K.indices)
    data = np.where(coupled, K.data, 1.0)[keep]
    indptr = np.zeros(n + 1, dtype=K.indptr.dtype)
    np.cumsum(np.bincount(rows[keep], minlength=n), out=indptr[1:])
    return sp.csc_matrix((data, K.indices[keep], indptr), shape=K.shape)


def bordered_solve(factor, K: sp.csr_matrix, b: np.ndarray, inactive0: np.ndarray,
                   inactive: np.ndarray) -> np.ndarray:
    """Inactive-block solve for ``inactive`` with the factors of the pinned matrix of
    ``inactive0``: exact, by Schur complements on the k dofs where the two sets differ.

    With J the dofs inactive in both, R those that left and G those that joined:
    K_JJ^-1 is the old inverse with x_R held at zero by multipliers, and x_G solves the
    (SPD) Schur complement K_GG - K_GJ K_JJ^-1 K_JG. One solve with k + m right-hand
    sides for ``b`` of shape (n,) (m = 1) or (n, m): the set-up serves every column.
    """
    b = np.asarray(b)
    B = b.reshape(len(b), -1)
    m = B.shape[1]
    R = np.flatnonzero(inactive0 & ~inactive)
    G = np.flatnonzero(inactive & ~inactive0)
    J = inactive0 & inactive
    nR, nG = len(R), len(G)
    rhs = np.zeros((len(b), nR + nG + m))
    rhs[R, np.arange(nR)] = 1.0
    KG = _dense_rows(K, G).T      # = K[:, G], K being symmetric
    rhs[:, nR:nR + nG] = np.where(J[:, None], KG, 0.0)
    rhs[:, nR + nG:] = np.where(J[:, None], B, 0.0)
    Y = factor.solve(rhs)
    if nR:   # hold x_R = 0: subtract the response to the multipliers on R
        Y[:, nR:] -= Y[:, :nR] @ np.linalg.solve(Y[R, :nR], Y[R, nR:])
    W, y = Y[:, nR:nR + nG], Y[:, nR + nG:]     # K_JJ^-1 K_JG and K_JJ^-1 b_J, zero off J
    x = y
    if nG:
        S = KG[G] - KG.T @ W
        x_G = np.linalg.solve(S, B[G] - KG.T @ y)
        x = y - W @ x_G
        x[G] = x_G
    x[~inactive] = 0.0   # exactly: x_R is zero only to round-off
    return x.reshape(b.shape)


def _dense_rows(K: sp.csr_matrix, rows: np.ndarray) -> np.ndarray:
    """K[rows] as a dense array, read straight off the CSR arrays (no sparse slicing)."""
    start, stop = K.indptr[rows], K.indptr[rows + 1]
    counts = stop - start
    where = np.repeat(stop - np.cumsum(counts), counts) + np.arange(counts.sum())
    out = np.zeros((len(rows), K.shape[1]))
    out[np.repeat(np.arange(len(rows)), counts), K.indices[where]] = K.data[where]
    return out


def dense_block_solve(K_dense: np.ndarray, b: np.ndarray, inactive: np.ndarray) -> np.ndarray:
    """Inactive-block solve with a dense K (small systems); zero on the cavitated dofs."""
    x = np.zeros(len(b))
    i = np.flatnonzero(inactive)
    x[i] = np.linalg.solve(K_dense[i][:, i], b[i])
    return x


class BlockSolver:
    """Inactive-block solves of one K and b for a sequence of cavitated sets, reusing
    factors; it keeps its own state (factors, the set they belong to, their count).

    For each set it takes the cheapest exact route it has:

    1. dense LAPACK, for systems of at most ``DENSE_DOFS`` dofs;
    2. :func:`bordered_solve` on its own factors of an earlier set of this K, while that
       set is within ``BORDERED_MAX_CHANGES`` dofs;
    3. CG preconditioned by ``factor``, factors of another K (the previous time step's),
       while the set is within ``few_changes`` dofs of theirs;
    4. a new factorisation of the set's :func:`pinned` matrix.

    ``factor``: a :class:`PinnedFactor` or LU factors of an unconstrained K, or None.
    """

    def __init__(self, K: sp.csr_matrix, b: np.ndarray, factor=None, few_changes: int = 8):
        self.K, self.b = K, b
        n = b.shape[0]
        self.dense = K.toarray() if n <= DENSE_DOFS else None
        lu = getattr(factor, "lu", factor)
        if lu is not None and (lu.shape != (n, n) or self.dense is not None):
            lu = factor = None
        self.lu = lu
        self.own = False        # whether ``lu`` factorises a pinned matrix of this very K
        self.factored = getattr(factor, "active", None)   # the set ``lu`` pins
        self.few_changes = few_changes
        self.factorisations = 0

    def unconstrained(self) -> np.ndarray:
        """The full-film solution of K P = b (no cavitated dof)."""
        if self.dense is not None:
            return np.linalg.solve(self.dense, self.b)
        P, self.lu, fresh = solve_spd(self.K, self.b, self.lu)
        if fresh:                       # factors of K itself, which pins no dof
            self.own, self.factored = True, None
            self.factorisations += 1
        if self.factored is None:
            self.factored = np.zeros(len(self.b), bool)
        return P

    def start(self, active: np.ndarray) -> None:
        """Take ``active`` as the set of factors that came without one."""
        if self.factored is None:
            self.factored = active.copy()

    def solve(self, active: np.ndarray, guess: np.ndarray) -> np.ndarray:
        """x with K_II x_I = b_I on the inactive dofs and x = 0 on ``active``; ``guess``
        starts CG."""
        inactive = ~active
        if self.dense is not None:
            return dense_block_solve(self.dense, self.b, inactive)
        k = len(self.b) if self.lu is None else np.count_nonzero(self.factored != active)
        if self.own and k <= BORDERED_MAX_CHANGES:
            return bordered_solve(self.lu, self.K, self.b, ~self.factored, inactive)
        rhs = np.where(inactive, self.b, 0.0)
        if self.lu is not None and not self.own and k <= self.few_changes:
            x, ok, _ = pcg(pinned(self.K, inactive), rhs, np.where(inactive, guess, 0.0),
                           self.lu.solve)
            if ok:
                return x
        self.lu = factorise(pinned(self.K, inactive))
        self.factored, self.own = active.copy(), True
        self.factorisations += 1
        return self.lu.solve(rhs)

    @property
    def factor(self):
        """The factors to hand to a later solve (with the set they pin), or None."""
        return None if self.lu is None else PinnedFactor(self.lu, self.factored)


def inactive_solve(K: sp.csr_matrix, factor, inactive: np.ndarray, rhs: np.ndarray):
    """Solve K_II X_I = rhs_I (X = 0 elsewhere) with the factors of the film solve.

    ``factor`` is LU of K itself (full film), a :class:`PinnedFactor` of some cavitated set
    (the Reynolds solve's last factorisation: exact bordered solves correct the few dofs
    where its set differs from the final one), or None for films small enough to be solved
    densely, which are factorised here.
    """
    rhs = np.where(inactive[:, None], rhs, 0.0)
    if isinstance(factor, PinnedFactor):
        if np.array_equal(~factor.active, inactive):
            X = factor.solve(rhs)
        else:
            X = np.column_stack([bordered_solve(factor.lu, K, rhs[:, j], ~factor.active,
                                                inactive) for j in range(rhs.shape[1])])
    elif factor is not None and inactive.all():
        X = factor.solve(rhs)
    else:
        X = factorise(pinned(sp.csr_matrix(K), inactive)).solve(rhs)
    X[~inactive] = 0.0
    return X
