"""Sparse symmetric positive-definite solves that reuse a factorisation.

The film stiffness K(eps) is symmetric positive definite and changes smoothly with the
state. Inside a time integration consecutive states are close, so the LU factors of an
earlier K precondition conjugate gradients on the new one well: a few triangular solves
(each ~30x cheaper than a factorisation at 20k dofs) replace a factorisation. When CG
does not converge quickly, the matrix is factorised afresh and that factor is returned
for the next call.
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

__all__ = ["factorise", "pcg", "solve_spd", "principal_block", "PCG_RTOL"]

#: Relative residual (2-norm) at which a preconditioned CG solve counts as exact.
PCG_RTOL = 1e-12


def factorise(A: sp.spmatrix):
    """SuperLU factors of a symmetric matrix (a symmetric ordering keeps the fill low)."""
    A = A if sp.isspmatrix_csc(A) else sp.csc_matrix(A)     # pinned() hands CSC already
    return spla.splu(A, permc_spec="MMD_AT_PLUS_A",
                     options=dict(SymmetricMode=True))


def pcg(A, b: np.ndarray, x: np.ndarray, precondition, rtol: float = PCG_RTOL,
        max_iter: int = 20):
    """Preconditioned conjugate gradients from ``x``; returns (x, converged, iterations)."""
    r = b - A @ x
    stop = rtol * max(float(np.linalg.norm(b)), np.finfo(float).tiny)
    if np.linalg.norm(r) <= stop:
        return x, True, 0
    z = precondition(r)
    d = z.copy()
    rz = float(r @ z)
    for it in range(1, max_iter + 1):
        Ad = A @ d
        alpha = rz / float(d @ Ad)
        x = x + alpha * d
        r = r - alpha * Ad
        if np.linalg.norm(r) <= stop:
            return x, True, it
        z = precondition(r)
        rz, rz_old = float(r @ z), rz
        d = z + (rz / rz_old) * d
    return x, False, max_iter


def solve_spd(A: sp.spmatrix, b: np.ndarray, factor=None, x0=None, max_iter: int = 20):
    """Solve A x = b; returns (x, factor used, factorised?).

    With ``factor`` (of a nearby matrix of the same size) CG is tried first from ``x0``.
    """
    n = b.shape[0]
    if factor is not None and factor.shape == (n, n):
        x, ok, _ = pcg(A, b, np.zeros(n) if x0 is None else x0, factor.solve,
                       max_iter=max_iter)
        if ok:
            return x, factor, False
    factor = factorise(A)
    return factor.solve(b), factor, True


def principal_block(M: sp.spmatrix, rows: np.ndarray) -> sp.csr_matrix:
    """M[rows][:, rows] (``rows``: sorted indices or a mask) from M's CSR arrays by one
    mask over its entries: scipy's fancy indexing validates and copies twice, most of the
    set-up of a small solve."""
    M = sp.csr_matrix(M)
    n = M.shape[0]
    index = np.full(n, -1)
    if np.asarray(rows).dtype == bool:
        rows = np.flatnonzero(rows)
    index[rows] = np.arange(len(rows))
    row_of = np.repeat(index, np.diff(M.indptr))
    col = index[M.indices]
    keep = (row_of >= 0) & (col >= 0)
    indptr = np.zeros(len(rows) + 1, dtype=M.indptr.dtype)
    np.cumsum(np.bincount(row_of[keep], minlength=len(rows)), out=indptr[1:])
    return sp.csr_matrix((M.data[keep], col[keep], indptr), shape=(len(rows), len(rows)))
