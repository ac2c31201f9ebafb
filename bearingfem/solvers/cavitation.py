"""Cavitation: the Swift-Stieber (Reynolds) condition as a linear complementarity problem.

Find P with  P >= 0,  r = K P - b >= 0,  P_i r_i = 0  for every free dof i.

K is the symmetric positive-definite film stiffness, so the problem has a unique solution.
Two solvers give the same discrete answer:

* :func:`active_set` - primal-dual active set (a semismooth Newton method on
  min(P, r / diag K) = 0): a few sparse solves, each on the inactive block.
* :func:`psor` - projected successive over-relaxation, the classical baseline. The sweep
  runs colour by colour over a colouring of the matrix graph: dofs of one colour do not
  couple, so each colour is one vectorised update and the sweep is an exact Gauss-Seidel.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from ..errors import ConvergenceError
from .blocksolve import BlockSolver

__all__ = ["LCPResult", "active_set", "active_set_iterations", "psor",
           "complementarity_residual", "graph_colouring"]


@dataclass(frozen=True)
class LCPResult:
    """Solution of the cavitation problem with its convergence record."""

    pressure: np.ndarray
    iterations: int
    residual: float           # complementarity residual, relative to max pressure
    converged: bool
    active: np.ndarray        # boolean mask: dofs held at P = 0 (cavitated)
    factor: object = field(default=None, repr=False, compare=False)  # reusable, see active_set
    factorisations: int = 0   # sparse LU factorisations the solve needed


def complementarity_residual(K: sp.spmatrix, b: np.ndarray, P: np.ndarray) -> float:
    """max_i |min(P_i, r_i / K_ii)| / max(P), r = K P - b: zero at the exact solution."""
    r = K @ P - b
    d = K.diagonal()
    scale = max(float(np.max(np.abs(P))), np.finfo(float).tiny)
    return float(np.max(np.abs(np.minimum(P, r / d)))) / scale


def active_set(K: sp.csr_matrix, b: np.ndarray, *, active0: np.ndarray | None = None,
               P0: np.ndarray | None = None, tol: float = 1e-10, max_iter: int = 100,
               factor=None, few_changes: int = 8) -> LCPResult:
    """Primal-dual active-set solve of the complementarity problem.

    Parameters
    ----------
    K, b : free-dof stiffness and load
    active0 : initial cavitated set (boolean).
    P0 : an approximate pressure (e.g. a coarser mesh's, interpolated), used when
        ``active0`` is not given: the first set is the semismooth Newton step from it,
        {P0 < r0 / diag K} with r0 = K P0 - b, which weighs the pressure against the
        multiplier estimate and so misplaces far fewer dofs near the front than {P0 <= 0}.
        Without either, the first set is where the unconstrained (full-Sommerfeld)
        solution is negative.
    factor : ``LCPResult.factor`` of an earlier call on a matrix of the same size (a
        :class:`~bearingfem.solvers.blocksolve.PinnedFactor`, or LU factors of an unconstrained
        K), e.g. the previous time step's. Its K differs from this one, so it only
        preconditions CG, and only while the set is within ``few_changes`` dofs of its own.

    Once this call has factorised a pinned matrix of its K, a set that moved by k <=
    ``BORDERED_MAX_CHANGES`` dofs from it is solved exactly with those factors
    (:func:`~bearingfem.solvers.blocksolve.bordered_solve`, k + 1 triangular solves) instead of
    a new factorisation. Systems of at most ``DENSE_DOFS`` dofs are solved densely.

    Raises :class:`~bearingfem.errors.ConvergenceError` when the set has not settled
    within ``max_iter`` solves.
    """
    res = active_set_iterations(K, b, active0=active0, P0=P0, tol=tol, max_iter=max_iter,
                                factor=factor, few_changes=few_changes)
    if not res.converged:
        raise ConvergenceError("Reynolds-condition active set", res.iterations, res.residual)
    return res


def active_set_iterations(K: sp.csr_matrix, b: np.ndarray, *,
                          active0: np.ndarray | None = None, P0: np.ndarray | None = None,
                          tol: float = 1e-10, max_iter: int = 100, factor=None,
                          few_changes: int = 8) -> LCPResult:
    """At most ``max_iter`` iterations of :func:`active_set` (same arguments), returned
    whether or not the set settled (``converged`` says which): a guess to start another
    solve from (a finer mesh's, a JFO balance's first set), never a solution."""
    K = K if sp.isspmatrix_csr(K) else sp.csr_matrix(K)     # no re-wrap of a CSR K
    r_scale = max(float(np.abs(b).max(initial=0.0)), np.finfo(float).tiny)
    block = BlockSolver(K, b, factor, few_changes)
    if active0 is not None:
        active = np.asarray(active0, bool).copy()
        P = np.zeros(b.shape[0])
        iterations = 0
        block.start(active)
    elif P0 is not None:
        P = np.maximum(np.asarray(P0, float), 0.0)
        active = P < (K @ P - b) / K.diagonal()
        iterations = 0
        block.start(active)
    else:
        P = block.unconstrained()
        active = P < 0.0
        iterations = 1
    converged = False
    while iterations < max_iter:
        P = block.solve(active, P)
        iterations += 1
        r = (K if block.dense is None else block.dense) @ P - b
        # Semismooth Newton step on min(P, r / diag K) = 0: an active dof stays while its
        # multiplier r is non-negative (to round-off), an inactive one joins when P < 0.
        new = np.where(active, r > -tol * r_scale, P < 0.0)
        if np.array_equal(new, active):
            converged = True
            break
        active = new
    P = np.maximum(P, 0.0)
    res = complementarity_residual(K, b, P) if P.any() else 0.0
    return LCPResult(pressure=P, iterations=iterations, residual=res, converged=converged,
                     active=P <= 0.0, factorisations=block.factorisations,
                     factor=block.factor)


def graph_colouring(K: sp.spmatrix, seed: int = 0) -> list[np.ndarray]:
    """Colour the graph of K so that no two dofs of one colour share a matrix entry.

    Jones-Plassmann with random priorities: every round, each uncoloured dof that
    outranks its uncoloured neighbours takes the current colour; vectorised over dofs.
    """
    n = K.shape[0]
    A = sp.csr_matrix(K, copy=True)
    A.data[:] = 1.0
    A.setdiag(0.0)
    A.eliminate_zeros()
    rng = np.random.default_rng(seed)
    prio = rng.permutation(n).astype(float) + 1.0
    colour = np.full(n, -1)
    c = 0
    while (colour < 0).any():
        eligible = colour < 0
        members = np.zeros(n, bool)
        while True:
            # Neighbours already in this colour exclude a dof for good.
            blocked = (A @ members.astype(float)) > 0
            cand = eligible & ~members & ~blocked
            if not cand.any():
                break
            w = np.where(cand, prio, 0.0)
            nb_max = A.multiply(w[None, :]).max(axis=1).toarray().ravel()
            members |= cand & (w > nb_max)
        colour[members] = c
        c += 1
    return [np.flatnonzero(colour == k) for k in range(c)]


def psor(K: sp.csr_matrix, b: np.ndarray, *, omega: float = 1.8, tol: float = 1e-10,
         max_iter: int = 200_000, P0: np.ndarray | None = None,
         colours: list[np.ndarray] | None = None) -> LCPResult:
    """Projected SOR on the complementarity problem (multicolour ordering).

    Stops when the largest update of a sweep is below ``tol`` times the largest pressure;
    raises :class:`~bearingfem.errors.ConvergenceError` when that takes over ``max_iter``
    sweeps.
    """
    if not 0.0 < omega < 2.0:
        raise ValueError(f"omega (relaxation) must lie in (0, 2), got {omega!r}")
    K = sp.csr_matrix(K)
    colours = graph_colouring(K) if colours is None else colours
    rows = [K[c] for c in colours]
    diag = [K.diagonal()[c] for c in colours]
    bs = [b[c] for c in colours]
    P = np.zeros_like(b) if P0 is None else np.maximum(np.asarray(P0, float), 0.0)
    converged = False
    it = 0
    for it in range(1, max_iter + 1):
        change = 0.0
        for c, Kc, dc, bc in zip(colours, rows, diag, bs):
            old = P[c]
            new = np.maximum(old + omega * (bc - Kc @ P) / dc, 0.0)
            P[c] = new
            change = max(change, float(np.max(np.abs(new - old), initial=0.0)))
        scale = max(float(P.max(initial=0.0)), np.finfo(float).tiny)
        if change <= tol * scale:
            converged = True
            break
    res = complementarity_residual(K, b, P) if P.any() else 0.0
    if not converged:
        raise ConvergenceError("projected SOR", it, res)
    return LCPResult(pressure=P, iterations=it, residual=res, converged=converged,
                     active=P <= 0.0)
