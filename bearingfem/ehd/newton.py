"""Newton solve of the EHD film (:mod:`bearingfem.ehd.coupling`) with load continuation.

Unknown: the nodal pressure P on the free dofs. Full films ("none", and "gumbel", whose
clip is applied afterwards as on the rigid film) solve R(P) = 0. Swift-Stieber films
("reynolds") solve the complementarity problem P >= 0, R >= 0, P R = 0 by a semismooth
(primal-dual active-set) Newton method on Phi = min(d P, R), d the stiffness diagonal,
so both arguments are in the residual's units (Hintermueller, Ito & Kunisch, SIAM J.
Optim. 13 (2002) 865-888): rows with d P < R are held cavitated (step -P), the others take
the Newton row of R. Every step is damped by a nonmonotone backtracking on |Phi|_2 (a
step is accepted below the largest |Phi|_2 of the last :data:`MEMORY` iterates, less
1e-4 of its share: L. Grippo, F. Lampariello, S. Lucidi, SIAM J. Numer. Anal. 23 (1986)
707-716) and rejected where the gap would close.

Convergence test: max |Phi| <= tol * max_i (|K| |P| + |load|)_i over the free dofs, the
size of the terms the residual sums (so tol is relative to round-off of the assembly).

Progress: each Newton iteration is logged at DEBUG and each continuation step at INFO on
the ``bearingfem.ehd.newton`` logger (``logging.basicConfig(level=logging.INFO)`` shows a
long solve's course; nothing is printed).

Load continuation: the coupling is scaled by s in [0, 1] (fields at s p, deflection
s C p; s = 0 is the isoviscous rigid film). Newton first tries s = 1 from the rigid film;
a failed step is retried from the last converged s with a quarter of the increment, a
converged one doubles it. Below an increment of 1e-4 the solve raises ConvergenceError.
"""
from __future__ import annotations

import logging
import warnings
from collections import deque
from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from ..errors import ConvergenceError
from ..solvers.continuation import Increments
from .coupling import jacobian_tables
from .film_compliance import BushJacobian

__all__ = ["EHDResult", "solve_ehd", "ConvergenceError"]

LOG = logging.getLogger(__name__)

MIN_INCREMENT = 1e-4
MAX_NEWTON = 30
#: The floor of the weight d in the semismooth residual Phi = min(d P, R), relative to the
#: largest d (the film's stiffness diagonal, ~ h^3 / mu); any positive weight has the same
#: solutions. Why: where the gap nearly closes under the summits d falls to ~1e-7 of its
#: largest, so at a start 0.35 % from the solution R > d P held nodes of 7e4 (scaled)
#: pressure at P = 0 in the step: Newton stalled and the continuation took 646
#: evaluations at the seed pin's closure (eps 1.15), 3 Newton steps with the floor
#: (tests/test_ehd_implicit: the doubled step).
NCP_FLOOR = 1e-3
#: A step is measured against the largest |Phi|_2 of this many last iterates (a
#: nonmonotone line search, Grippo et al. 1986): a path that rises for a few steps where
#: nodes leave or join the cavity is not cut short.
MEMORY = 10


@dataclass(frozen=True, eq=False)
class EHDResult:
    """The converged EHD pressure with its record.

    pressure : dimensionless nodal pressure P; active : dofs held cavitated
    iterations : Newton iterations over all continuation attempts, rejected ones included;
    steps : continuation steps taken (1: s = 1 reached directly); rejected : attempts
    retried with a smaller increment; residual : final max |Phi| relative to the
    residual's term size; converged : always True (a failed solve raises)
    """

    pressure: np.ndarray
    iterations: int
    residual: float
    converged: bool
    active: np.ndarray
    steps: int
    rejected: int
    factor: object = None
    factorisations: int = 0


def _merit(film, P, s, free, cavitation):
    """(Phi on the free dofs, its scale, active rows, the evaluated film) or Nones (gap
    closed): active rows are those where Phi = min(d P, R) takes d P (held cavitated)."""
    with np.errstate(over="ignore", invalid="ignore"):   # a trial step may overflow mu
        ev = film.evaluate(P, s)
    if ev is None or not np.all(np.isfinite(ev.residual)):
        return None, None, None, None
    R, size, values = ev.residual, ev.size, ev.values
    scale = float(np.max(size[free], initial=0.0)) or 1.0
    if cavitation != "reynolds":
        return R[free], scale, np.zeros(free.size, bool), ev
    # the stiffness diagonal: the pattern's diagonal entries, floored at NCP_FLOOR of
    # their largest (any positive weight has the same solutions P >= 0, R >= 0, P R = 0)
    d = values[jacobian_tables(film.op).stiffness_diagonal][free]
    dP, Rf = np.maximum(d, NCP_FLOOR * np.max(d, initial=0.0)) * P[free], R[free]
    return np.minimum(dP, Rf), scale, dP < Rf, ev


class _Factor:
    """The semismooth Newton system at one pressure, factorised: rows held cavitated
    (``held``, over the free dofs) step to P = 0, the others take the Newton row of R.
    :meth:`step` gives the step for a residual Phi; at another pressure of a nearby film
    it is a chord step (the old Jacobian, :func:`_chord`), and :meth:`with_held` factorises
    the same Jacobian with other held rows."""

    def __init__(self, J, U, V, tables, free, held):
        self.held, self.J, self.U, self.V = held, J, U, V
        self.tables, self.free = tables, free
        self.I, self.A = free[~held], free[held]
        I = self.I
        block = _block(tables, J.data, I, J.shape[0])       # J[I][:, I], transposed
        self.lu = (_BlockLU(block) if U is None else
                   _KrylovLU(block, U, I, J.shape[0]) if isinstance(U, BushJacobian) else
                   _BlockLU(block, U[np.ix_(I, I)]) if V is None else
                   _BlockLU(block, U[I], V[I]))

    @classmethod
    def at(cls, film, P, s, free, held, ev):
        """The factorised system of ``film`` at P (``ev`` its evaluation). A local
        compliance's T_H C (the liner's) is sparse on the film's own pattern: it is added
        to J, and the Newton matrix factorised whole (no GMRES)."""
        J, U, V = film.jacobian(P, s, ev)
        tables = jacobian_tables(film.op)
        own = U.local() if isinstance(U, BushJacobian) else None
        if own is not None:
            T = U.coupling
            if (sp.isspmatrix_csr(T) and np.array_equal(T.indptr, J.indptr)
                    and np.array_equal(T.indices, J.indices)):
                J, U = tables.pattern.matrix(J.data + T.data * own[T.indices]), None
        return cls(J, U, V, tables, free, held)

    def with_held(self, held):
        """The same Jacobian with other held rows (no Jacobian built)."""
        return _Factor(self.J, self.U, self.V, self.tables, self.free, held)

    def step(self, P, phi):
        """The step on all dofs (zero on fixed dofs) for Phi ``phi`` at ``P``."""
        I, A, U, V = self.I, self.A, self.U, self.V
        dA = -P[A]
        known = np.zeros_like(P)
        known[A] = dA
        rhs = -phi[~self.held] - (self.J @ known)[I]
        if isinstance(U, BushJacobian):  # the held rows' known step through the bush
            rhs = rhs - U.apply(known)[I]
        elif U is not None:
            rhs = rhs - (U[np.ix_(I, A)] @ dA if V is None else U[I] @ (V[A].T @ dA))
        dI = self.lu.solve(rhs)
        step = np.zeros_like(P)
        step[I], step[A] = dI, dA
        return step


#: SuperLU's column ordering of the film's Newton block: the minimum degree of B^T + B
#: (the block is structurally symmetric: the film's FE pattern), measured on the seed pin's
#: heavy state at 480 x 80 against SuperLU's default COLAMD: 36 % less fill, factorisation
#: 0.094 against 0.117 s, each triangular solve 0.0026 against 0.0042 s
#: (benchmarks/bush_build.py, docs/ehd.md); the LU is the same matrix's, so the step is
#: the same to round-off.
ORDERING = "MMD_AT_PLUS_A"


def _splu(block):
    """SuperLU of the CSC ``block`` with the film's ordering (:data:`ORDERING`)."""
    return splu(block, permc_spec=ORDERING)


class _BlockLU:
    """A Newton matrix on the free rows and columns, M = B + U V^T, factorised: B sparse,
    given as the CSC of its transpose (:func:`_block`), and the bush's part U V^T (none
    without U; V None: U is the dense product). One sparse LU, with Woodbury for a low
    rank, or one dense LU for the full compliance; a singular M raises LinAlgError (or
    splu's RuntimeError)."""

    def __init__(self, block, U=None, V=None):
        self.V = V
        if U is not None and V is None:
            self.dense = _lu(block.toarray().T + U)
            return
        self.dense, self.lu = None, _splu(block)
        if V is not None:
            self.Z = self.lu.solve(U, trans="T")
            self.small = _lu(np.eye(V.shape[1]) + V.T @ self.Z)

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        if self.dense is not None:
            return la.lu_solve(self.dense, rhs, check_finite=False)
        y = self.lu.solve(rhs, trans="T")
        if self.V is None:
            return y
        return y - self.Z @ la.lu_solve(self.small, self.V.T @ y, check_finite=False)


#: GMRES of the Newton step: converged at |r| <= KRYLOV_TOL |rhs| (true residual, right
#: preconditioning), so the step is the direct solve's to about round-off times the
#: preconditioned system's condition; a solve that ends above KRYLOV_ACCEPT |rhs| raises.
KRYLOV_TOL = 1e-12
KRYLOV_ACCEPT = 1e-8
KRYLOV_RESTART = 60
KRYLOV_MAXITER = 10
_EPS = float(np.finfo(float).eps)


class _KrylovLU:
    """The Newton matrix on the rows I, M = B + (T_H C)[I][:, I] diag(columns), with the
    bush's part matrix-free (a :class:`~.film_compliance.BushJacobian`: the compliance by FFT):
    GMRES on M P^-1 y = rhs, x = P^-1 y, P = B by its sparse LU (the film's own Jacobian
    with the deflection held; right preconditioning, so GMRES measures the true residual),
    plus the bush's low-rank part by Woodbury where it gives one (``bush.low_rank``).
    ``block`` is the CSC of B's transpose (:func:`_block`); ``columns`` (over I, or None)
    scales M's bush columns (the JFO's columns taken from dR/dP). Same interface as
    :class:`_BlockLU`; a singular B raises splu's RuntimeError, a GMRES solve that does not
    converge LinAlgError (a stall to the Newton callers)."""

    def __init__(self, block, bush: BushJacobian, index, n: int, columns=None):
        low = bush.low_rank if columns is None else None
        # P = B, or B + U_k V_k^T (Woodbury) where the bush gives a low-rank part of itself
        self.lu = _BlockLU(block) if low is None else _BlockLU(block, low[0][index],
                                                               low[1][index])
        self.B = block.T.tocsr()
        self.bush, self.index, self.n, self.columns = bush, index, n, columns
        self.products = 0          # matrix-vector products so far (the benchmark's record)

    def matvec(self, x: np.ndarray) -> np.ndarray:
        full = np.zeros(self.n)
        full[self.index] = x if self.columns is None else x * self.columns
        self.products += 1
        return self.B @ x + self.bush.apply(full)[self.index]

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        if rhs.ndim == 2:
            return np.column_stack([self.solve(r) for r in rhs.T])
        norm = float(np.linalg.norm(rhs))
        if norm == 0.0:
            return np.zeros_like(rhs)
        inverse = self.lu.solve
        tol = KRYLOV_TOL if self.bush.tolerance is None else self.bush.tolerance
        y, estimate = _gmres(lambda v: self.matvec(inverse(v)), rhs, tol, KRYLOV_RESTART,
                             KRYLOV_MAXITER)
        x = inverse(y)
        if estimate <= tol:
            return x
        residual = float(np.linalg.norm(rhs - self.matvec(x)))
        if not residual <= max(KRYLOV_ACCEPT, 10.0 * tol) * norm:
            raise la.LinAlgError(f"GMRES of the EHD Newton step stopped at a relative "
                                 f"residual {residual / norm:.3g}")
        return x


def _gmres(apply, b: np.ndarray, tol: float, restart: int, maxiter: int) -> tuple:
    """GMRES (Saad & Schultz, SIAM J. Sci. Stat. Comput. 7 (1986) 856-869) on A y = b from
    y = 0, A applied by ``apply``: restarted every ``restart`` products, at most
    ``maxiter`` cycles, stopped where |b - A y| <= ``tol`` |b|; the Arnoldi basis by
    classical Gram-Schmidt done twice (BLAS products), the least squares by Givens
    rotations. (y, |b - A y| / |b|) with the residual's norm as the rotations give it
    (exact in exact arithmetic: no product is taken to check it), except where the Krylov
    space turns invariant (the new basis vector's norm within round-off of its product's):
    there the rotations' residual is that of a basis no longer orthogonal, or of a
    singular A on the space, so the solve ends with the true residual (one product), as
    does a cycle whose basis came within 1e-8 of it; a product not finite ends the solve
    at the last cycle's y with residual inf.
    Why not scipy's gmres: its Python loop cost 0.6 ms a solve beside 0.45 ms a product,
    and it takes one product more a cycle for the residual (the implicit-step film's chord
    steps, 96 x 8: 6 products a solve)."""
    norm_b = float(np.linalg.norm(b))
    if norm_b == 0.0:
        return np.zeros_like(b), 0.0
    y, r, beta = np.zeros_like(b), b, norm_b
    residual = beta
    for cycle in range(maxiter):
        suspect = False                               # a basis vector near the span
        V = np.empty((restart + 1, b.size))
        R = np.zeros((restart, restart))              # the rotated Hessenberg matrix
        g = np.zeros(restart + 1)
        cs, sn = np.zeros(restart), np.zeros(restart)
        V[0], g[0] = r / beta, beta
        for j in range(restart):
            w = apply(V[j])
            size = float(np.linalg.norm(w))
            basis = V[:j + 1]
            h = basis @ w
            w = w - h @ basis
            again = basis @ w
            w -= again @ basis
            h += again
            below = float(np.linalg.norm(w))
            if not np.isfinite(below + size):
                return y, np.inf
            invariant = below <= 16.0 * _EPS * size
            suspect = suspect or below <= 1e-8 * size
            if invariant:
                below = 0.0
            for i in range(j):                        # the earlier rotations
                h[i], h[i + 1] = cs[i] * h[i] + sn[i] * h[i + 1], cs[i] * h[i + 1] - sn[i] * h[i]
            rho = float(np.hypot(h[j], below))
            cs[j], sn[j] = (h[j] / rho, below / rho) if rho > 0.0 else (1.0, 0.0)
            h[j] = rho
            R[:j + 1, j] = h
            g[j + 1], g[j] = -sn[j] * g[j], cs[j] * g[j]
            residual = abs(g[j + 1])
            if invariant:
                break
            V[j + 1] = w / below
            if residual <= tol * norm_b:
                break
        k = j + 1 if R[j, j] != 0.0 else j           # a zero pivot: A singular on the space
        y = y + la.solve_triangular(R[:k, :k], g[:k], check_finite=False) @ V[:k]
        if not suspect and (residual <= tol * norm_b or cycle == maxiter - 1):
            break
        r = b - apply(y)
        beta = float(np.linalg.norm(r))
        if invariant or beta <= tol * norm_b or cycle == maxiter - 1:
            return y, beta / norm_b
    return y, residual / norm_b


def _lu(M):
    """LAPACK's LU of the dense M; a singular M raises LinAlgError (as la.solve did), where
    lu_factor only warns."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", la.LinAlgWarning)
        lu = la.lu_factor(M, check_finite=False)
    if not np.all(np.isfinite(lu[0])) or np.any(np.diag(lu[0]) == 0.0):
        raise la.LinAlgError("singular Newton matrix")
    return lu


def _block(tables, data, I, n):
    """The block J[I][:, I] of the Jacobian with values ``data`` on ``tables``' pattern,
    as the CSC matrix of its transpose (the CSR rows taken as columns: splu takes it
    without conversion; solve with trans="T"). Built by masks on the pattern: scipy's
    fancy slicing cost more than the factorisation on a coupled run's meshes."""
    keep = np.zeros(n, bool)
    keep[I] = True
    number = np.cumsum(keep) - 1
    cols = tables.pattern.indices
    sel = keep[tables.rows] & keep[cols]
    indptr = np.zeros(I.size + 1, np.int64)
    np.cumsum(np.bincount(number[tables.rows[sel]], minlength=I.size), out=indptr[1:])
    return sp.csc_matrix((data[sel], number[cols[sel]], indptr), shape=(I.size, I.size))


def _newton(film, P, s, free, cavitation, tol, keep=None):
    """Damped (semismooth) Newton at coupling s from P: ((P, residual, active) or None
    when it stalls, the iterations it took). ``keep`` (a list): the last step's
    factorisation is put in it, for :func:`_chord` at a nearby film."""
    phi, scale, held, ev = _merit(film, P, s, free, cavitation)
    if phi is None:
        return None, 0
    recent = deque(maxlen=MEMORY)
    for it in range(MAX_NEWTON + 1):
        res = float(np.max(np.abs(phi), initial=0.0)) / scale
        LOG.debug("EHD Newton at s = %.4g: iteration %d, residual %.3g", s, it, res)
        if res <= tol:
            return (P, res, _held_nodes(P.size, free, held)), it
        if it == MAX_NEWTON:
            return None, it
        try:
            factor = _Factor.at(film, P, s, free, held, ev)
            step = factor.step(P, phi)
        except (RuntimeError, la.LinAlgError):       # singular Jacobian: treat as a stall
            return None, it
        if keep is not None:
            keep[:] = [factor]
        norm = float(np.linalg.norm(phi))
        recent.append(norm)
        ref = max(recent)
        alpha = 1.0
        while alpha >= 1.0 / 64:
            trial = P + alpha * step
            t_phi, t_scale, t_held, t_ev = _merit(film, trial, s, free, cavitation)
            with np.errstate(over="ignore"):
                better = (t_phi is not None
                          and np.linalg.norm(t_phi) < ref - 1e-4 * alpha * norm)
            if better:
                P, phi, scale, held, ev = trial, t_phi, t_scale, t_held, t_ev
                break
            alpha *= 0.5
        else:
            return None, it + 1
    return None, MAX_NEWTON


def _held_nodes(n, free, held):
    """The nodes held cavitated (over all n nodes) of the held rows over the free dofs."""
    active = np.zeros(n, bool)
    active[free[held]] = True
    return active


def _chord(film, P, s, free, tol, keep, max_steps=6, rate=0.3, slack=0):
    """Chord steps at coupling s from P with a kept factorisation (``keep``, a list holding
    it: the last right-hand side's in a run): ((P, residual, active), steps, P) when the
    residual test of :func:`_newton` passes; (None, steps, the iterate of least residual)
    as soon as a step fails to cut max |Phi| by ``rate`` (past the first ``slack`` such
    steps) or ``max_steps`` pass (then Newton takes over from that iterate). Where the
    held rows differ from the factor's, the same Jacobian is factorised again with them
    (kept in ``keep``); where that factorisation or a step's solve fails Newton takes over
    from the iterate of least residual. Swift-Stieber films ("reynolds") only."""
    factor = keep[0]
    phi, scale, held, _ = _merit(film, P, s, free, "reynolds")
    best, least, last = P, np.inf, np.inf
    for it in range(max_steps + 1):
        if phi is None:
            return None, it, best
        res = float(np.max(np.abs(phi), initial=0.0)) / scale
        if res <= tol:
            return (P, res, _held_nodes(P.size, free, held)), it, P
        if res < least:
            best, least = P, res
        if it == max_steps or (res > rate * last and slack == 0):
            return None, it, best
        if res > rate * last:
            slack -= 1
        try:
            if not np.array_equal(held, factor.held):
                factor = factor.with_held(held)
                keep[:] = [factor]
            step = factor.step(P, phi)
        except (RuntimeError, la.LinAlgError):  # singular or GMRES unconverged: Newton
            return None, it, best
        last = res
        P = P + step
        phi, scale, held, _ = _merit(film, P, s, free, "reynolds")
    return None, max_steps, best


def warm_solve(film, P, free, tol, keep, max_steps: int = 6, rate: float = 0.3,
               slack: int = 0) -> tuple:
    """A Swift-Stieber film at s = 1 from the last solve's pressure ``P`` (of the film's
    size): chord steps on the kept factorisation (``keep``, ``max_steps``, ``rate`` and
    ``slack`` as :func:`_chord`; none when it is empty), then Newton from where the chord
    got to.
    (EHDResult, None) when either passes the residual test, else (None, its) with its
    Newton's iterations."""
    start, chord_steps = P.copy(), 0
    if keep:
        out, chord_steps, start = _chord(film, start, 1.0, free, tol, keep, max_steps, rate,
                                         slack)
        if out is not None:
            return EHDResult(out[0], chord_steps, out[1], True, out[2], 1, 0), None
    out, its = _newton(film, start, 1.0, free, "reynolds", tol, keep)
    if out is not None:
        return EHDResult(out[0], chord_steps + its, out[1], True, out[2], 1, 0), None
    return None, its


def solve_ehd(film, P0, cavitation: str, tol: float = 1e-10,
              start: np.ndarray | None = None) -> EHDResult:
    """The EHD pressure from the rigid film's P0 (fixed dofs keep P0's values), with the
    load continuation of the module docstring. ``P0`` may be a function giving it (called
    only when needed). ``start`` (nodal P, fixed dofs at their held values): a warm start,
    Newton at s = 1 from it first (a nearby state converges in a few steps); if that
    stalls, the cold route from P0."""
    free = film.op.mesh.free
    iterations = 0
    if start is not None:
        out, iterations = _newton(film, np.array(start, float), 1.0, free, cavitation, tol)
        if out is not None:
            P, residual, active = out
            return EHDResult(P, iterations, residual, True, active, 1, 0)
    P0 = P0() if callable(P0) else P0
    res = continuation(lambda s, P: _newton(film, P, s, free, cavitation, tol), P0.copy(),
                       0.0, 1.0, 1.0, MIN_INCREMENT, "EHD Newton (load continuation)",
                       "coupling s", "refine the mesh, reduce the load or stiffen the bush "
                       "(its deflection under the load may pass the clearance)")
    return replace(res, iterations=res.iterations + iterations)


def continuation(newton, P, done: float, target: float, max_increment: float,
                 min_increment: float, what: str, parameter: str, hint: str) -> EHDResult:
    """Walk a parameter from ``done`` to ``target`` by :class:`~bearingfem.solvers.
    continuation.Increments` (``max_increment`` the first and largest, ``min_increment``
    the smallest): ``newton(x, P)`` solves at x from P (((P, residual, active) or None when
    it stalls, its iterations)); ConvergenceError names ``what``, the ``parameter``
    reached and the ``hint``. Each attempt is logged at INFO (:data:`LOG`)."""
    walk = Increments(max_increment, min_increment).walk(
        lambda x, out: newton(x, out[0]), (P, None, None), done, target, what, parameter, hint,
        LOG)
    P, residual, active = walk.state
    return EHDResult(P, walk.iterations, residual, True, active, walk.steps, walk.rejected)
