"""Newton solve of the EHD-JFO film (:class:`~bearingfem.ehd.jfo.JFOCoupling`) with load
continuation.

Unknowns: one universal variable u per free volume, P = max(u, 0), phi = 1 + min(u, 0)
(Giacopini et al. 2010; the rigid solver's variable, :mod:`bearingfem.solvers.jfo`). R(u)
is semismooth; its generalised Jacobian is exact: the columns of dR/dP (K, the viscosity
slopes and the bush through K and T: sparse plus the compliance's dense or low-rank part)
where u > 0 and of dR/dphi = T + S where u <= 0. Newton steps are damped by a nonmonotone
backtracking on |R|_2 after a watchdog (:meth:`_Newton.run`); converged when max |R| <=
tol x the largest size of the terms the residual sums (|K||P| + |T||phi| + |S phi|), the
EHD film's test.

Load continuation as in :mod:`bearingfem.ehd.newton`: the coupling s in [0, 1] scales the
deflection (s C p) and the pressure the lubricant sees (s p); s = 0 is the rigid JFO film,
solved by :func:`~bearingfem.fe.jfo_steady.solve_jfo`'s solver, the start. A failed
Newton run is retried with a quarter of the increment; below 1e-4 the solve raises
:class:`~bearingfem.errors.ConvergenceError`.

References: M. Giacopini, M.T. Fowell, D. Dini, A. Strozzi, A mass-conserving
complementarity formulation to study lubricant films in the presence of cavitation,
J. Tribol. 132 (2010) 041702; the watchdog: R.M. Chamberlain, M.J.D. Powell,
C. Lemarechal, H.C. Pedersen, The watchdog technique for forcing convergence in algorithms
for constrained optimization, Math. Programming Study 16 (1982) 1-17; the nonmonotone
line search: L. Grippo, F. Lampariello, S. Lucidi, A nonmonotone line search technique
for Newton's method, SIAM J. Numer. Anal. 23 (1986) 707-716.
"""
from __future__ import annotations

import logging
from collections import deque
from dataclasses import dataclass

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp

from ..fe.jfo_balance import JFOFlows
from ..solvers.continuation import Increments
from ..solvers.jfo import JFOResult
from .film_compliance import BushJacobian
from .newton import MEMORY, _block, _BlockLU, _KrylovLU

__all__ = ["solve_ehd_jfo", "EHDJFOSolve"]

LOG = logging.getLogger(__name__)

#: The load continuation's steps in the coupling s (as :mod:`bearingfem.ehd.newton`'s).
STEPS = Increments(1.0, 1e-4)
MAX_NEWTON = 40


@dataclass(frozen=True)
class EHDJFOSolve:
    """The converged EHD-JFO film: P, phi on all nodes, the solver's record (a
    :class:`~bearingfem.solvers.jfo.JFOResult`: Newton iterations over all continuation
    steps), continuation steps and rejected attempts, the flows, and whether the warm
    start converged by itself."""

    P: np.ndarray
    phi: np.ndarray
    result: JFOResult
    steps: int
    rejected: int
    flows: JFOFlows
    warm: bool = False      # the warm start converged (no load continuation was needed)


def _on_pattern(tables, A) -> np.ndarray:
    """The values of the sparse ``A`` on the Jacobian pattern of ``tables`` (the
    transport's couplings are between neighbouring nodes, so they lie in it)."""
    A = sp.csr_matrix(A)
    n, keys = A.shape[0], tables.keys
    wanted = np.repeat(np.arange(n), np.diff(A.indptr)) * n + A.indices
    at = np.searchsorted(keys, wanted)
    if not np.array_equal(keys[np.minimum(at, keys.size - 1)], wanted):
        raise ValueError("the balance's couplings must lie in the film's Jacobian pattern")
    return np.bincount(at, A.data, minlength=keys.size)


def _split(u, can):
    """(P, phi) of the universal variable on the free volumes."""
    P = np.where(can, np.maximum(u, 0.0), u)
    phi = np.where(can, 1.0 + np.minimum(u, 0.0), 1.0)
    return P, phi


class _Newton:
    """Damped semismooth Newton on the universal variable at one coupling s."""

    def __init__(self, film, free, can):     # film: a jfo.JFOCoupling (jfo.py imports us)
        self.film, self.free, self.can = film, free, can

    def nodal(self, u):
        P, phi = self.film.P_fixed.copy(), self.film.phi_fixed.copy()
        P[self.free], phi[self.free] = _split(u, self.can)
        return P, phi

    def merit(self, u, s):
        P, phi = self.nodal(u)
        with np.errstate(over="ignore", invalid="ignore"):
            st = self.film.evaluate(P, phi, s)
        if st is None or not np.all(np.isfinite(st.residual)):
            return None, None, None
        scale = float(np.max(st.size[self.free], initial=0.0)) or 1.0
        return st.residual[self.free], scale, st

    def step(self, u, s, R, st):
        """The Newton step on the free volumes: the columns of dR/dP where P is free
        (u > 0, or a volume whose content cannot change), of dR/dphi elsewhere."""
        free, film = self.free, self.film
        P, phi = self.nodal(u)
        J, U, V, A = film.jacobian(P, phi, s, st)
        pos = (u > 0.0) | ~self.can
        t = film.poiseuille.tables
        n = J.shape[0]
        from_P = np.ones(n, bool)
        from_P[free] = pos
        data = np.where(from_P[t.pattern.indices], J.data, _on_pattern(t, A))
        block = _block(t, data, free, n)        # the free block, transposed
        # the bush acts through dR/dP: only on the columns taken from it
        lu = (_BlockLU(block) if U is None else
              _KrylovLU(block, U, free, n, pos) if isinstance(U, BushJacobian) else
              _BlockLU(block, U[np.ix_(free, free)] * pos) if V is None else
              _BlockLU(block, U[free], V[free] * pos[:, None]))
        return lu.solve(-R)

    def lookahead(self, u, t, s, trial):
        """The watchdog's point: one more Newton step from the full step ``t`` when that
        step moved a cavity's boundary (None otherwise, or if it cannot be taken). Across
        the boundary the columns of the Jacobian at u no longer describe R, so |R| at t
        can rise by orders of magnitude while the step from t, on t's columns, lands
        close: backtracking alone then creeps (measured on the seed pin's heavy state,
        192 x 8: |R| 0.13 -> 0.065 -> 0.063 -> ... until the line search gives up)."""
        tR, _, tst = trial
        # a volume whose content cannot change keeps its dR/dP column (as in step)
        if tR is None or not np.any(((t > 0.0) != (u > 0.0)) & self.can):
            return None
        try:
            t2 = t + self.step(t, s, tR, tst)
        except (RuntimeError, la.LinAlgError):
            return None
        return t2, self.merit(t2, s)

    def run(self, u, s, tol):
        """((u, residual) or None when it stalls, iterations).

        Each step is damped by backtracking on |R|_2, measured against the largest |R|_2
        of the last :data:`~bearingfem.ehd.newton.MEMORY` iterates (Grippo et al. 1986),
        after a watchdog (Chamberlain et al. 1982): a full step that fails the decrease
        but moves a cavity's boundary is followed by one more Newton step, kept if that
        point passes the same test (:meth:`lookahead`; the pair counts as two
        iterations)."""
        R, scale, st = self.merit(u, s)
        if R is None:
            return None, 0
        it = 0
        recent = deque(maxlen=MEMORY)
        while True:
            res = float(np.max(np.abs(R), initial=0.0)) / scale
            LOG.debug("EHD-JFO Newton at s = %.4g: iteration %d, residual %.3g", s, it, res)
            if res <= tol:
                return (u, res), it
            if it >= MAX_NEWTON:
                return None, it
            try:
                du = self.step(u, s, R, st)
            except (RuntimeError, la.LinAlgError):
                return None, it
            it += 1
            norm = float(np.linalg.norm(R))
            recent.append(norm)
            ref = max(recent)
            t = u + du
            trial = self.merit(t, s)
            if trial[0] is not None and np.linalg.norm(trial[0]) < ref - 1e-4 * norm:
                u, (R, scale, st) = t, trial
                continue
            ahead = self.lookahead(u, t, s, trial) if it < MAX_NEWTON else None
            if ahead is not None:
                it += 1
                t2, trial2 = ahead
                if trial2[0] is not None and np.linalg.norm(trial2[0]) < ref - 1e-4 * norm:
                    u, (R, scale, st) = t2, trial2
                    continue
            alpha = 0.5
            while alpha >= 1.0 / 256:
                t = u + alpha * du
                tR, tscale, tst = self.merit(t, s)
                if tR is not None and np.linalg.norm(tR) < ref - 1e-4 * alpha * norm:
                    u, R, scale, st = t, tR, tscale, tst
                    break
                alpha *= 0.5
            else:
                return None, it


def solve_ehd_jfo(bearing, film, P0, phi0=None, tol: float = 1e-10,
                  start=None) -> EHDJFOSolve:
    """The EHD-JFO film from the rigid JFO film (P0, phi0 on all nodes; ``P0`` may be a
    function giving that pair, called only when needed) by load continuation (module
    docstring); raises ConvergenceError when it does not converge. ``start``: (P, phi)
    on all nodes of a nearby solved film: Newton at s = 1 from it first (a warm start),
    the cold route if that stalls."""
    op = film.op
    free = op.mesh.free
    st0 = film.evaluate(np.zeros(op.mesh.ndofs), np.ones(op.mesh.ndofs), 0.0)
    A = (st0.T + sp.diags(film.storage)).tocsc()
    can = A.diagonal()[free] > 0.0        # a volume whose content can leave or change
    newton = _Newton(film, free, can)
    iterations, steps, rejected, out = 0, 0, 0, None
    if start is not None:
        Ps, phis = start
        out, iterations = newton.run(np.where(phis[free] < 1.0, phis[free] - 1.0,
                                              Ps[free]), 1.0, tol)
    warm = out is not None
    if warm:
        (u, residual), steps = out, 1
    else:
        if callable(P0):
            P0, phi0 = P0()
        u = np.where(phi0[free] < 1.0, phi0[free] - 1.0, P0[free])
        walk = STEPS.walk(lambda s, out: newton.run(out[0], s, tol), (u, 0.0), 0.0, 1.0,
                          "EHD-JFO Newton (load continuation)", "coupling s",
                          "refine the mesh or reduce the load", LOG)
        (u, residual), steps, rejected = walk.state, walk.steps, walk.rejected
        iterations += walk.iterations
    P, phi = newton.nodal(u)
    st = film.evaluate(P, phi, 1.0)
    inflow = -(st.K @ P + st.T @ phi)
    res = JFOResult(P[free], phi[free], phi[free] < 1.0, iterations, residual, True, 0)
    flows = JFOFlows.from_inflow(bearing, op.mesh, inflow, film.storage[free] * phi[free])
    return EHDJFOSolve(P, phi, res, steps, rejected, flows, warm)
