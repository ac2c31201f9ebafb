"""Mass-conserving (JFO) cavitation: pressure and film fraction as a complementarity pair.

A discretised Jakobsson-Floberg-Olsson film balances, at every free control volume j,

    R_j = (K P)_j + (A phi)_j - b_j = 0,   P >= 0,  phi <= 1,  P (1 - phi) = 0,

with K the (symmetric) Poiseuille operator, A the transport and storage of the film
content phi h (Couette upwinding, and the time derivative) and b what the fixed control
volumes and the previous step give. One universal variable u per volume carries both
(Giacopini et al. 2010, Almqvist et al. 2014): P = max(u, 0), phi = 1 + min(u, 0).
R(u) is piecewise linear, so semismooth Newton on it is an active-set method: for a set
C of cavitated volumes the unknowns are P off C and phi on C, one sparse solve gives the
exact answer of that set, and the set changes where P < 0 or phi > 1. From a good set (the
previous time step's, a coarser mesh's, or that of the Reynolds-condition problem of the
same balance) one to four iterations finish. Sets differ only in the columns of the volumes
that changed, so after the first factorisation a set a few volumes away is solved exactly
by a low-rank (Woodbury) correction of it: a solve costs about one factorisation.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
import scipy.sparse as sp

from ..errors import ConvergenceError
from .cavitation import active_set_iterations
from .jfo_sets import SetSolver, set_lu, set_matrix  # noqa: F401 (tests import them here)
from .linsolve import principal_block

__all__ = ["JFOResult", "FirstSet", "jfo_solve", "solve_balance", "upwind_transport"]


@dataclass(frozen=True)
class JFOResult:
    """Solution of one JFO balance with its convergence record.

    pressure, fraction : P >= 0 and phi in [0, 1] on the free volumes
    cavitated : the set C (phi solved, P = 0)
    iterations : the Newton iterations and those of the Reynolds-condition problem that
        placed the first set
    residual : max |R| / max |b| at the returned (P, phi)
    converged : the set repeated and the residual is at round-off (always True: a solve
        that does not converge raises :class:`~bearingfem.errors.ConvergenceError`)
    factorisations : sparse LU factorisations among the iterations (the others were
        low-rank corrections of one), with those of the problem that placed the first set
    """

    pressure: np.ndarray
    fraction: np.ndarray
    cavitated: np.ndarray
    iterations: int
    residual: float
    converged: bool
    factorisations: int = 0


@dataclass(frozen=True)
class FirstSet:
    """A first cavitated set for :func:`jfo_solve` and the work it took to find it
    (e.g. the same balance solved on a coarser mesh)."""

    cavitated: np.ndarray
    iterations: int = 0
    factorisations: int = 0


#: A warm first set is near the answer when its first iteration changes fewer volumes
#: than this many layers along its fronts (see ``_active_set``).
NEAR_LAYERS = 4

#: Largest residual (relative to max |b|) a converged JFO solve may leave.
RESIDUAL_LIMIT = 1e-8


def _fischer_burmeister(K: sp.csc_matrix, A: sp.csc_matrix, b: np.ndarray, P: np.ndarray,
                        phi: np.ndarray, tol: float, max_iter: int):
    """Fischer-Burmeister-Newton-Schur (Woloszynski et al. 2015): Newton on
    K P + A phi = b and FB(P / s, 1 - phi) = 0 with FB(a, c) = a + c - sqrt(a^2 + c^2),
    the second set eliminated per volume (Schur complement) so each iteration is one
    sparse solve in one unknown per volume; Armijo line search on the squared residual.
    Smooth where the active set's jumps cycle (fronts where P and 1 - phi both vanish)."""
    s = max(float(np.abs(b).max(initial=0.0)) / max(float(K.diagonal().mean()), 1e-300),
            1e-300)
    b_scale = max(float(np.abs(b).max(initial=0.0)), np.finfo(float).tiny)

    def residuals(P, phi):
        a, c = P / s, 1.0 - phi
        return (K @ P + A @ phi - b) / b_scale, a + c - np.hypot(a, c)

    def merit(F1, F2):
        return 0.5 * (float(F1 @ F1) + float(F2 @ F2))

    F1, F2 = residuals(P, phi)
    m = merit(F1, F2)
    it = 0
    for it in range(1, max_iter + 1):
        a, c = P / s, 1.0 - phi
        r = np.hypot(a, c)
        deg = r < 1e-300
        ra = np.where(deg, 1.0, r)
        alpha = np.where(deg, 1.0 - 1.0 / np.sqrt(2.0), 1.0 - a / ra) / s   # dFB/dP
        beta = np.where(deg, 1.0 - 1.0 / np.sqrt(2.0), 1.0 - c / ra)        # -dFB/dphi
        p_type = beta >= alpha * s          # unknown dP (dphi eliminated) on these
        # columns of the reduced matrix: K + A alpha/beta on p-type, A + K beta/alpha else
        wk = np.where(p_type, 1.0, beta / np.where(p_type, 1.0, alpha))
        wa = np.where(p_type, alpha / np.where(p_type, beta, 1.0), 1.0)
        J = (K @ sp.diags(wk) + A @ sp.diags(wa)).tocsc()
        rhs = -F1 * b_scale \
            - A @ np.where(p_type, F2 / np.where(p_type, beta, 1.0), 0.0) \
            + K @ np.where(p_type, 0.0, F2 / np.where(p_type, 1.0, alpha))
        x = set_lu(J).solve(rhs)
        dP = np.where(p_type, x, (beta * x - F2) / np.where(p_type, 1.0, alpha))
        dphi = np.where(p_type, (alpha * x + F2) / np.where(p_type, beta, 1.0), x)
        step = 1.0
        while True:
            P1, phi1 = P + step * dP, phi + step * dphi
            G1, G2 = residuals(P1, phi1)
            m1 = merit(G1, G2)
            if m1 <= (1.0 - 1e-4 * step) * m or step < 1e-6:
                break
            step *= 0.5
        P, phi, F1, F2, m = P1, phi1, G1, G2, m1
        if np.sqrt(2.0 * m) < tol:
            break
    return P, phi, it, bool(np.sqrt(2.0 * m) < tol)


def jfo_solve(K: sp.spmatrix, A: sp.spmatrix, b: np.ndarray, *,
              cavitated0: np.ndarray | None = None, max_iter: int = 12,
              warm_iterations: int = 3, tol: float = 1e-11,
              start: Callable[[], FirstSet | None] | None = None) -> JFOResult:
    """Solve the JFO complementarity balance K P + A phi = b (see the module text).

    Parameters
    ----------
    K, A : free-volume operators (square, sparse); A must have a positive diagonal on
        every volume that may cavitate (a cavity keeps or sheds its own content)
    b : right-hand side
    cavitated0 : initial set (e.g. the previous time step's, or a coarser mesh's), or a
        tuple of them tried in turn, each for ``warm_iterations`` (and on, up to twice
        that, while its set changes fewer volumes at every iteration)
    start : called (once) when there is no ``cavitated0`` or it did not settle: a
        :class:`FirstSet` near the answer (the same balance on a coarser mesh), tried for
        ``max_iter``; None or returning None: skipped. Last, the set of this balance's
        Reynolds-condition problem is tried for ``max_iter``.
    max_iter : active-set iterations per first set; after the last, the
        Fischer-Burmeister-Newton fallback takes over from the last iterate
    tol : residual (relative to max |b|) both methods must reach

    Raises :class:`~bearingfem.errors.ConvergenceError` when none of them converges.
    """
    K = sp.csc_matrix(K)
    A = sp.csc_matrix(A)
    n = b.shape[0]
    scale = max(float(np.abs(b).max(initial=0.0)), np.finfo(float).tiny)
    # Volumes that can hold a cavity: those whose own content leaves or changes (A_jj > 0).
    can_cavitate = A.diagonal() > 0.0
    # (first set, iterations, iterations while near the answer: warm sets only)
    tries = [(lambda c=c: FirstSet(c), warm_iterations, 2 * warm_iterations)
             for c in _first_sets(cavitated0)]
    if start is not None:
        tries.append((start, max_iter, None))
    # the Reynolds-condition set takes its transport from the last iterate's fraction
    tries.append((lambda: _reynolds_set(K, A, b, phi, can_cavitate), max_iter, None))
    it = lus = 0
    P, phi = np.zeros(n), np.ones(n)
    converged = warm_near = False
    sets = SetSolver(K, A)
    for first, limit, near_limit in tries:
        if near_limit is not None and warm_near:
            continue
        guess = first()
        if guess is None:
            continue
        it, lus = it + guess.iterations, lus + guess.factorisations
        cav = np.asarray(guess.cavitated, bool) & can_cavitate
        P, phi, cav, k, converged = _active_set(sets, A, b, cav, can_cavitate, limit,
                                                near_limit)
        it += k
        if converged:
            break
        # a warm set that was near the answer (a far one stops after one iteration) and
        # did not settle: its fronts travel farther than iterations move them, and the
        # other warm sets are farther still; the coarse meshes place them
        warm_near = near_limit is not None and k > 1
    lus += sets.factorisations
    if not converged:
        P, phi, fb_it, converged = _fischer_burmeister(
            K, A, b, np.maximum(P, 0.0), np.minimum(phi, 1.0), tol, 40)
        it, lus = it + fb_it, lus + fb_it
        cav = phi < 1.0
    P = np.maximum(P, 0.0)
    phi = np.clip(phi, 0.0, 1.0)
    r = K @ P + A @ phi - b
    residual = float(np.abs(r).max(initial=0.0)) / scale
    if not (converged and residual < RESIDUAL_LIMIT):
        raise ConvergenceError("JFO balance (active set, then Fischer-Burmeister Newton)",
                               it, residual)
    return JFOResult(pressure=P, fraction=phi, cavitated=cav, iterations=it,
                     residual=residual, converged=True, factorisations=lus)


def _reynolds_set(K, A, b, phi_guess, can_cavitate) -> FirstSet:
    """A starting set from the Reynolds-condition problem of this balance: with the
    transport between volumes taken from ``phi_guess``, each volume's own storage term
    D (1 - phi) is the multiplier of P >= 0, a symmetric complementarity problem that
    :func:`~bearingfem.solvers.cavitation.active_set` solves robustly. It is exact where
    the content does not move between volumes (pure squeeze) and for rupture (where JFO
    and Reynolds agree); the active set then moves the reformation fronts. Returns the
    set and the work it took (its iterations are capped: it only places a first set)."""
    D = A.diagonal()
    q = b - (A @ phi_guess - D * phi_guess) - D
    res = active_set_iterations(sp.csr_matrix(K), q)
    w = K @ res.pressure - q
    return FirstSet((res.pressure <= 0.0) & (w > 0.0) & can_cavitate, res.iterations,
                    res.factorisations)


def _first_sets(cavitated0) -> list:
    """``cavitated0`` of :func:`jfo_solve` as a list of boolean sets."""
    if cavitated0 is None:
        return []
    if isinstance(cavitated0, tuple):
        return [np.asarray(c, bool) for c in cavitated0]
    return [np.asarray(cavitated0, bool)]


def _active_set(sets: SetSolver, A, b, cav, can_cavitate, max_iter, near_iter=None):
    """Semismooth Newton on the universal variable from the set ``cav`` (module text):
    ``max_iter`` iterations. With ``near_iter`` (a warm set: the kept or extrapolated
    one) the set must be near the answer: its first iteration changes fewer volumes than
    ``NEAR_LAYERS`` layers along its fronts (a set off by a jump of the squeeze differs
    on an area: on the journal film of benchmarks/jfo_iterations.py at 480x80, 9086
    volumes at the jump against 8-75 in the other steps), or the try ends there (the
    caller's next first set is better than fronts moved a layer per iteration); near, it
    goes on up to ``near_iter`` while each iteration changes fewer volumes than the one
    before (measured 7, 2, 1, 0 at 240x40; 33, 26, 10, ... at 480x80)."""
    n = b.shape[0]
    P, phi = np.zeros(n), np.ones(n)
    seen = set()
    near, last_changes = True, n
    band = NEAR_LAYERS * sets.front(cav) if near_iter is not None else n
    it = 0
    while it < max(max_iter, near_iter or 0):
        it += 1
        rhs = b - A @ np.where(cav, 0.0, 1.0)
        x = sets.solve(cav, rhs)
        P = np.where(cav, 0.0, x)
        phi = np.where(cav, x, 1.0)
        # Newton step on min/max: pressurised volumes with P < 0 cavitate, cavities whose
        # content would exceed a full film (phi > 1) fill.
        new = np.where(cav, phi < 1.0, (P < 0.0) & can_cavitate)
        if np.array_equal(new, cav):
            P, phi = _refined(sets, A, b, cav, P, phi)
            return P, phi, cav, it, True
        new &= ~_filled_ahead(sets.neighbours, A, cav, phi)
        key = new.tobytes()
        if key in seen:        # the sets cycle: let the caller take over
            return P, phi, cav, it, False
        seen.add(key)
        changes = int(np.count_nonzero(new != cav))
        cav = new
        near = near and (it > 1 or changes < band)
        if near_iter is not None and not near:
            break
        if it >= max_iter and not (near and changes < last_changes):
            break
        last_changes = changes
    return P, phi, cav, it, False


def _filled_ahead(G: sp.csr_matrix, A: sp.csc_matrix, cav: np.ndarray, phi: np.ndarray,
                  layers: int = 64) -> np.ndarray:
    """Cavities the overfill of a reformation front fills beyond its first layer: a
    cavity with phi > 1 holds (phi - 1) A_jj more content than it can; shared equally
    among its cavity neighbours (``G``: the adjacency of the volumes) it fills those
    whose deficit (1 - phi) A_kk it covers, and what is left goes on. The active set
    alone moves the front one layer per iteration (a cavity beyond the first sees no
    pressure), where a nearly full cavity takes many layers a step. Only where the
    first set was placed: the set's own iterations then confirm or undo each volume."""
    D = A.diagonal()
    over = cav & (phi > 1.0)
    filled = over.copy()
    excess = np.where(over, (phi - 1.0) * D, 0.0)
    deficit = np.where(cav & ~over, (1.0 - phi) * D, 0.0)
    for _ in range(layers):
        open_ = cav & ~filled
        takers = G @ open_.astype(float)                 # open cavity neighbours of each
        share = np.where((excess > 0.0) & (takers > 0.0),
                         excess / np.maximum(takers, 1.0), 0.0)
        received = np.where(open_, G @ share, 0.0)
        newly = open_ & (received > 0.0) & (received >= deficit)
        if not newly.any():
            break
        filled |= newly
        excess = np.where(newly, received - deficit, 0.0)
    return filled & ~over


def _refined(sets: SetSolver, A, b, cav, P, phi, passes: int = 4):
    """Iterative refinement on the same factors while it gains: the balance of flows to
    round-off. A corrected solve of a changed set reaches ~1e-10 of |b|, and |b| grows as
    1/dt with the storage of a short time step while the flows do not: on the squeeze film
    of 800 cells and 3200 steps a period one refinement left 1.5e-9 of a step's throughput."""
    r = b - sets.K @ P - A @ phi
    size = float(np.abs(r).max(initial=0.0))
    for _ in range(passes):
        dx = sets.solve(cav, r)
        P1, phi1 = P + np.where(cav, 0.0, dx), phi + np.where(cav, dx, 0.0)
        r1 = b - sets.K @ P1 - A @ phi1
        size1 = float(np.abs(r1).max(initial=0.0))
        if size1 >= size:
            break
        P, phi, r, gain, size = P1, phi1, r1, size / max(size1, 1e-300), size1
        if gain < 2.0:
            break
    return P, phi


def solve_balance(K: sp.csr_matrix, T: sp.csr_matrix, storage: np.ndarray,
                  source: np.ndarray, free: np.ndarray, P_fixed: np.ndarray,
                  phi_fixed: np.ndarray, cavitated0=None, K_free=None,
                  warm_iterations: int = 3, start=None):
    """Solve the JFO balance K P + T phi + storage phi = source on the ``free`` volumes,
    the others holding (P_fixed, phi_fixed) (arrays over all nodes).

    Returns (P, phi, result, inflow): P and phi on all nodes and the net flow each fixed
    node receives from its neighbours, -(K P + T phi) (zero on free nodes to round-off).
    The sum of ``inflow`` over the fixed nodes equals the storage of the free volumes,
    sum(storage phi - source), exactly: that is the discrete mass balance.
    ``start``: as for :func:`jfo_solve`, its set given on all nodes.
    """
    fixed_only = np.ones(len(source), bool)
    fixed_only[free] = False
    Pb = np.where(fixed_only, P_fixed, 0.0)
    phib = np.where(fixed_only, phi_fixed, 0.0)
    b = source[free] - (K @ Pb)[free] - (T @ phib)[free]
    A = (principal_block(T, free) + sp.diags(storage[free])).tocsr()
    Kf = principal_block(K, free) if K_free is None else K_free
    c0 = tuple(c[free] for c in _first_sets(cavitated0))
    n = len(free)
    if not np.any(b) and not np.any(A.diagonal()):
        res = JFOResult(np.zeros(n), np.ones(n), np.zeros(n, bool), 0, 0.0, True)
    else:
        first = None if start is None else lambda: _on_free(start(), free)
        res = jfo_solve(Kf, A, b, cavitated0=c0, warm_iterations=warm_iterations,
                        start=first)
    P, phi = Pb, np.where(fixed_only, phi_fixed, 0.0)
    P[free], phi[free] = res.pressure, res.fraction
    return P, phi, res, -(K @ P + T @ phi)


def _on_free(guess: FirstSet | None, free: np.ndarray) -> FirstSet | None:
    if guess is None:
        return None
    return FirstSet(np.asarray(guess.cavitated, bool)[free], guess.iterations,
                    guess.factorisations)


def upwind_transport(k: np.ndarray, d: np.ndarray, flux: np.ndarray, n: int) -> sp.csr_matrix:
    """(T phi)_i = net outflow of volume i when ``flux`` (signed, along k -> d) crosses
    the face from volume k to volume d carrying phi from the upwind one: every face flux
    leaves one volume and enters the other, so T's columns sum to zero (mass is kept)."""
    fwd = flux >= 0.0
    up = np.where(fwd, k, d)
    a = np.abs(flux)
    out_v, in_v = np.where(fwd, k, d), np.where(fwd, d, k)
    return sp.csr_matrix((np.concatenate([a, -a]),
                          (np.concatenate([out_v, in_v]), np.concatenate([up, up]))),
                         shape=(n, n))
