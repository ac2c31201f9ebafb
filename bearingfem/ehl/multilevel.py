"""The Newton step of the EHL contacts in O(N log N): GMRES with a multilevel preconditioner.

Each Newton step of :mod:`bearingfem.ehl.line` and :mod:`bearingfem.ehl.point` solves

    [ JP + JH K   JH 1 ] [dP ]     [f]
    [ dX^d 1^T     0   ] [dH0]  =  [g]

(cavitated and boundary rows replaced by dP_i = f_i), JP and JH the film's sparse
Jacobian blocks and K the dense half-space influence matrix. Here K is applied by the
zero-padded FFT (:mod:`~bearingfem.ehl.halfspace`, :mod:`~bearingfem.ehl.pointspace`),
so a product costs N log N, and the step is found by right-preconditioned GMRES. The
preconditioner is one V-cycle for the pressure block over grids halved down to a dense
solve (<= 300 nodes on a line, <= 1000 on a plane; rediscretised: each grid's Jacobian
at the finer grid's state interpolated onto it, linear interpolation and its
row-normalised transpose between grids), with H0 by the Schur complement:

* the smoother solves the near field exactly: J T with the elastic part truncated to
  offsets <= w cells, by a sparse LU, and steps T y. T distributes each change of a free
  node's pressure as the pattern (-1/2, 1, -1/2) along a line (-1/4 to each of the four
  neighbours on a plane): Venner & Lubrecht's distributive relaxation (Multilevel methods
  in lubrication, Elsevier 2000, Ch. 4 and 9). The log (1/r) kernel does not decay, so its
  truncation to a band changes the operator's low-frequency part and even its sign (a
  banded preconditioner of K itself weakens as the grid refines); the kernel of K T is
  its second difference (Laplacian), which falls as 1/j^2 (1/r^3), so the truncated near
  field stays close to J T at every frequency and the smoother is stable;
* the coarse grid takes what the near field misses, the long-range part of the
  deflection, exactly at the coarsest grid (dense LU).

The products per step then stay near constant as the grid refines (1-6 on 250 ... 12000
nodes, docs/ehl.md), so a step costs O(N log N).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

__all__ = ["Level", "KeptLevels", "vcycle", "krylov_step", "multilevel_step",
           "interpolation", "restriction",
           "distribution_1d", "distribution_2d", "near_field"]

#: A V-cycle's grids are kept for the next Newton step while its cavitated set holds and
#: GMRES took at most this many products (rebuilding them is most of a step's cost).
REUSE_PRODUCTS = 12
#: GMRES stops at this fraction of the Newton residual (an inexact Newton step: Newton
#: converges at least linearly by this factor; its own test on the residual decides).
RELATIVE = 1e-5
#: A step whose true residual is above this fraction is refused. Near a fine grid's
#: rounding floor GMRES's recurrence runs on below the true residual; a step that halves
#: it still moves Newton on (and its line search judges).
ACCEPT = 0.5
MAX_PRODUCTS = 300
#: Smoothing steps either side of each coarse-grid correction: V(2, 2). V(1, 1) serves as
#: well on most contacts but stalls (300 products) on the finest grids of a sharp outlet
#: spike (24000 nodes at M 7.4, L 10.9, Roelands oil), where V(2, 2) converges.
SWEEPS = 2


@dataclass(frozen=True)
class Level:
    """One grid of the V-cycle, for the pressure block (H0 held). ``matvec`` applies the
    block to dP and ``smooth`` solves its near field; ``prolong`` (fine x coarse nodes) and
    ``restrict`` lead to the next coarser grid (None on the coarsest, where ``smooth`` is
    exact)."""

    matvec: Callable[[np.ndarray], np.ndarray]
    smooth: Callable[[np.ndarray], np.ndarray]
    prolong: sp.csr_matrix | None = None
    restrict: sp.csr_matrix | None = None


@dataclass(frozen=True, eq=False)
class KeptLevels:
    """A V-cycle's grids kept from the last Newton step: the GMRES products the step took
    on them, the held set they were built for and the sweeps they ran with."""

    levels: list
    products: int
    fixed: np.ndarray
    sweeps: int


def multilevel_step(block, column, weights, rhs, scale, tol: float,
                    kept: KeptLevels | None, fixed: np.ndarray,
                    build: Callable[[], list]) -> tuple:
    """(x or None, the grids to keep or None): :func:`krylov_step` on the ``kept`` grids
    while they serve (the same held set, at most :data:`REUSE_PRODUCTS` products last
    time), else, or if that fails, on fresh ones from ``build()``."""
    if kept is not None and (kept.products > REUSE_PRODUCTS
                             or not np.array_equal(kept.fixed, fixed)):
        kept = None
    attempts = ([(kept.levels, kept.sweeps)] if kept else []) + [(None, SWEEPS)]
    for levels, sweeps in attempts:
        if levels is None:
            levels = build()
        x, products = krylov_step(block, levels, column, weights, rhs, scale, tol, sweeps)
        if x is not None:
            return x, KeptLevels(levels, products, fixed, sweeps)
    return None, None


def vcycle(levels: list[Level], r: np.ndarray, k: int = 0, sweeps: int = 1) -> np.ndarray:
    """One V(sweeps, sweeps) cycle from grid ``k`` on the pressure rows' right-hand side r."""
    level = levels[k]
    x = level.smooth(r)
    if level.prolong is None:
        return x
    for _ in range(sweeps - 1):
        x = x + level.smooth(r - level.matvec(x))
    x = x + level.prolong @ vcycle(levels, level.restrict @ (r - level.matvec(x)), k + 1,
                                   sweeps)
    for _ in range(sweeps):
        x = x + level.smooth(r - level.matvec(x))
    return x


def krylov_step(block: Callable[[np.ndarray], np.ndarray], levels: list[Level],
                column: np.ndarray, row: np.ndarray, rhs: np.ndarray, row_scale: np.ndarray,
                atol: float, sweeps: int = 1) -> tuple[np.ndarray | None, int]:
    """(x, GMRES products) for the bordered system [[A, column], [row, 0]] x = rhs, A the
    pressure block (applied by ``block``), to RELATIVE of |row_scale rhs| (or ``atol``); x
    is None when GMRES does not get there in MAX_PRODUCTS. ``levels`` may be those of an
    earlier Newton iterate (a preconditioner needs only be near A); ``sweeps`` smoothing
    steps either side of each coarse-grid correction.

    Right-preconditioned: A^-1 by one V-cycle, and H0 by the Schur complement
    row . A^-1 column with A^-1 column by one V-cycle too (H0 kept off the grids: its
    column is weak against the pressures' where the film is near rigid, and a coarse
    grid's error in it would be amplified)."""
    n = rhs.size
    z = vcycle(levels, column, sweeps=sweeps)
    schur = float(row @ z)

    def precondition(v):
        x1 = vcycle(levels, v[:-1], sweeps=sweeps)
        y = (row @ x1 - v[-1]) / schur
        return np.append(x1 - y * z, y)

    def apply(x):
        return np.append(block(x[:-1]) + column * x[-1], row @ x[:-1])

    AM = spla.LinearOperator((n, n), dtype=float,
                             matvec=lambda v: row_scale * apply(precondition(v / row_scale)))
    count = [0]

    def tally(_):
        count[0] += 1

    y, info = spla.gmres(AM, row_scale * rhs, rtol=RELATIVE, atol=atol, restart=50,
                         maxiter=MAX_PRODUCTS // 50, callback=tally, callback_type="pr_norm")
    x = precondition(y / row_scale)
    # GMRES may stall short of RELATIVE in rounding (its residual recurrence drifts from the
    # true one); an inexact Newton step to ACCEPT still converges, and the line search
    # guards it
    residual = np.linalg.norm(row_scale * (apply(x) - rhs))
    good = np.isfinite(residual) and residual <= max(ACCEPT * np.linalg.norm(row_scale * rhs),
                                                     atol)
    return (x if good else None), count[0]


def interpolation(fine: np.ndarray, coarse: np.ndarray) -> sp.csr_matrix:
    """Linear interpolation from the nodes ``coarse`` to ``fine`` (both increasing, same
    ends), as a (fine x coarse) sparse matrix."""
    j = np.clip(np.searchsorted(coarse, fine, side="right") - 1, 0, coarse.size - 2)
    t = (fine - coarse[j]) / (coarse[j + 1] - coarse[j])
    rows = np.arange(fine.size)
    return sp.csr_matrix((np.concatenate([1 - t, t]),
                          (np.concatenate([rows, rows]), np.concatenate([j, j + 1]))),
                         shape=(fine.size, coarse.size))


def restriction(prolong: sp.csr_matrix) -> sp.csr_matrix:
    """The transpose of ``prolong`` with rows summing to one (full weighting)."""
    R = prolong.T.tocsr()
    total = np.asarray(R.sum(axis=1)).ravel()
    return (sp.diags(np.divide(1.0, total, out=np.zeros_like(total), where=total > 0)) @ R).tocsr()


def distribution_1d(free: np.ndarray) -> sp.csr_matrix:
    """T: the identity, with each free node whose neighbours are free too distributing as
    (-1/2, 1, -1/2)."""
    n = free.size
    d = free.copy()
    d[0] = d[-1] = False
    d[1:-1] &= free[:-2] & free[2:]
    i = np.flatnonzero(d)
    cols = np.arange(n)
    return sp.csr_matrix((np.concatenate([np.ones(n), np.full(2 * i.size, -0.5)]),
                          (np.concatenate([cols, i - 1, i + 1]), np.concatenate([cols, i, i]))),
                         shape=(n, n))


def distribution_2d(free: np.ndarray) -> sp.csr_matrix:
    """T on an (nx, ny) grid (C order): a free node with four free neighbours distributes
    -1/4 to each of them."""
    nx, ny = free.shape
    d = free.copy()
    d[0, :] = d[-1, :] = d[:, 0] = d[:, -1] = False
    d[1:-1, 1:-1] &= free[:-2, 1:-1] & free[2:, 1:-1] & free[1:-1, :-2] & free[1:-1, 2:]
    i = np.flatnonzero(d)
    n = nx * ny
    cols = np.arange(n)
    nb = np.concatenate([i - ny, i + ny, i - 1, i + 1])
    return sp.csr_matrix((np.concatenate([np.ones(n), np.full(nb.size, -0.25)]),
                          (np.concatenate([cols, nb]), np.concatenate([cols, np.tile(i, 4)]))),
                         shape=(n, n))


def near_field(kernel: np.ndarray, T: sp.csr_matrix, width: int) -> sp.csr_matrix:
    """K T kept to offsets <= ``width`` cells (each axis), K the Toeplitz (block-Toeplitz
    for a 2-D ``kernel[k, l]``) influence matrix of ``kernel``: the near field of the
    distributed influence."""
    k = np.atleast_2d(kernel.T).T if kernel.ndim == 1 else kernel
    nx, ny = k.shape
    reach = width + 1                       # T reaches one node further
    di = np.arange(-min(reach, nx - 1), min(reach, nx - 1) + 1)
    dj = np.arange(-min(reach, ny - 1), min(reach, ny - 1) + 1)
    node = np.arange(nx * ny)
    ix, jy = np.divmod(node, ny)
    rows, cols, vals = [], [], []
    for a in di:
        for b in dj:
            ok = (ix + a >= 0) & (ix + a < nx) & (jy + b >= 0) & (jy + b < ny)
            rows.append(node[ok])
            cols.append(node[ok] + a * ny + b)
            vals.append(np.full(ok.sum(), k[abs(a), abs(b)]))
    K = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(nx * ny, nx * ny))
    KT = (K @ T).tocoo()
    ri, rj = np.divmod(KT.row, ny)
    ci, cj = np.divmod(KT.col, ny)
    keep = (np.abs(ri - ci) <= width) & (np.abs(rj - cj) <= width)
    return sp.csr_matrix((KT.data[keep], (KT.row[keep], KT.col[keep])), shape=KT.shape)
