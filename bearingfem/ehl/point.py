"""The isothermal, Newtonian EHL point contact: 2-D Reynolds film + elastic half-space.

A sphere of reduced radius R rolls on a plane at mean surface speed u_m along x, carrying
the load w; the film obeys the steady Reynolds equation

    div(rho h^3 / (12 mu) grad p) = u_m d(rho h)/dx,   h = h0 + (x^2 + y^2)/(2R) + v(x, y),

with p >= 0 and the complementarity of the line contact (where p = 0 the residual
r = -(Reynolds operator) >= 0, p r = 0). The load balance int int p = w closes h0. In
Hertz units (X = x/a, P = p/p_h, H = h R/a^2, :mod:`bearingfem.ehl.pointspace`)

    div(eps grad P) - lambda d(rho_r H)/dX = 0,   eps = rho_r H^3/eta_r,
    lambda = 12 mu0 u_m R^2/(a^3 p_h),   H = H0 + (X^2 + Y^2)/2 + V(P),  dX dY sum P = 2 pi/3

(Venner & Lubrecht, Multilevel methods in lubrication, Elsevier 2000, Ch. 9). Poiseuille
terms central (face coefficients the mean of the nodes'), the wedge second-order upwind
along X (first order next to the inlet), as in :mod:`bearingfem.ehl.line`; the same
damped, projected semismooth Newton method on (P, H0): each step by the dense Jacobian
(the elastic block the full influence matrix) on the y >= 0 half of the grid up to
DENSE_POINT_NODES nodes along x, by GMRES with a multilevel preconditioner on the whole
grid beyond (:mod:`bearingfem.ehl.multilevel`).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..errors import ConvergenceError
from .line import UPWIND, NewtonRecord, _cavitated, _complementarity, _equilibrated_step
from .multilevel import (Level, distribution_2d, interpolation, multilevel_step, near_field,
                         restriction)
from .pointspace import HERTZ_POINT_LOAD, PointCompliance

__all__ = ["DimensionlessPoint", "solve_point", "DENSE_POINT_NODES"]

#: Grids of up to this many nodes along x take the dense Newton step (an LU of the whole
#: Jacobian on the y >= 0 half); finer ones the multilevel Newton-Krylov step
#: (:mod:`bearingfem.ehl.multilevel`) on the whole grid. The two agree to the tolerance.
DENSE_POINT_NODES = 33
#: The multilevel step: near field to this many cells either way; grids halved down to at
#: most COARSE_POINTS nodes, solved there by a dense LU.
NEAR_WIDTH = 1
COARSE_POINTS = 1000
#: Where GMRES fails, grids up to this many nodes along x take the dense step instead.
DENSE_FALLBACK = 97


@dataclass(frozen=True)
class DimensionlessPoint:
    """One point-contact problem in Hertz units on a uniform grid X (inlet first) x Y."""

    X: np.ndarray
    Y: np.ndarray
    lam: float                 # lambda = 12 mu0 u_m R^2 / (a^3 p_h)
    eta: object                # P -> (eta_r, d eta_r / dP), arrays
    rho: object                # P -> (rho_r, d rho_r / dP), arrays


def _difference(n: int, d: float) -> sp.csr_matrix:
    """(n-1) x n forward difference / d: faces i + 1/2."""
    return sp.diags([-np.ones(n - 1), np.ones(n - 1)], [0, 1], shape=(n - 1, n)) / d


def _average(n: int) -> sp.csr_matrix:
    return sp.diags([np.full(n - 1, 0.5), np.full(n - 1, 0.5)], [0, 1], shape=(n - 1, n))


def _upwind(n: int, d: float) -> sp.csr_matrix:
    """d/dX second-order upwind (first order at node 1; node 0 is a boundary)."""
    D = sp.diags([np.full(n, UPWIND[0]), np.full(n - 1, UPWIND[1]), np.full(n - 2, UPWIND[2])],
                 [0, -1, -2], shape=(n, n)).tolil()
    D[1, :] = 0.0
    D[1, 0], D[1, 1] = -1.0, 1.0
    return D.tocsr() / d


class _PointSystem:
    """Residuals and Jacobian blocks of one dimensionless problem (nodes flat, C order)."""

    def __init__(self, prob: DimensionlessPoint, load: float):
        self.prob, self.load = prob, load
        nx, ny = prob.X.size, prob.Y.size
        self.shape = (nx, ny)
        self.d = prob.X[1] - prob.X[0]
        d = self.d
        Ix, Iy = sp.identity(nx), sp.identity(ny)
        self.Gx = sp.kron(_difference(nx, d), Iy).tocsr()
        self.Gy = sp.kron(Ix, _difference(ny, d)).tocsr()
        self.Ax = sp.kron(_average(nx), Iy).tocsr()
        self.Ay = sp.kron(Ix, _average(ny)).tocsr()
        self.Dx = sp.kron(_upwind(nx, d), Iy).tocsr()
        inner = np.zeros(self.shape, bool)
        inner[1:-1, 1:-1] = True
        # the film is symmetric about Y = 0: the unknowns are the inner nodes with Y >= 0,
        # each standing for itself and its mirror image (the dense solve ~8x cheaper)
        c = ny // 2
        half = inner.copy()
        half[:, :c] = False
        self.half = np.flatnonzero(half)
        jj = np.arange(ny)
        rep = np.arange(nx)[:, None] * ny + (c + np.abs(jj - c))[None, :]
        self.mirror = rep.ravel()                      # full node -> its Y >= 0 twin
        position = np.full(nx * ny, -1)
        position[self.half] = np.arange(self.half.size)
        cols = position[self.mirror]
        keep = inner.ravel()
        self.E = sp.csr_matrix((np.ones(keep.sum()), (np.flatnonzero(keep), cols[keep])),
                               shape=(nx * ny, self.half.size))
        self.inner = np.flatnonzero(inner)
        self.compliance = PointCompliance(nx, ny, d, d)
        self.spectrum = self.compliance.spectrum()
        self.K = None
        self.levels = None             # the last step's KeptLevels
        self.geometry = ((prob.X[:, None] ** 2 + prob.Y[None, :] ** 2) / 2).ravel()
        k = self.compliance.kernel[:3, 0]
        self.wedge_stiffness = (UPWIND[0] * k[0] + UPWIND[1] * k[1] + UPWIND[2] * k[2]) / d

    def film(self, P, H0):
        V = self.compliance.deflection(P.reshape(self.shape), self.spectrum).ravel()
        return H0 + self.geometry + V

    def reynolds(self, P, H):
        """r = -(Reynolds operator) at every node, and eps."""
        eta, _ = self.prob.eta(P)
        rho, _ = self.prob.rho(P)
        eps = rho * H**3 / eta
        r = (self.Gx.T @ ((self.Ax @ eps) * (self.Gx @ P))
             + self.Gy.T @ ((self.Ay @ eps) * (self.Gy @ P))
             + self.prob.lam * (self.Dx @ (rho * H)))
        return r, eps

    def jacobian(self, P, H):
        """d r / dP (at fixed H) and d r / dH, sparse."""
        eta, deta = self.prob.eta(P)
        rho, drho = self.prob.rho(P)
        eps = rho * H**3 / eta
        direct = (self.Gx.T @ sp.diags(self.Ax @ eps) @ self.Gx
                  + self.Gy.T @ sp.diags(self.Ay @ eps) @ self.Gy)
        dr_deps = (self.Gx.T @ sp.diags(self.Gx @ P) @ self.Ax
                   + self.Gy.T @ sp.diags(self.Gy @ P) @ self.Ay)
        deps_dP = eps * (drho / rho - deta / eta)
        JP = direct + dr_deps @ sp.diags(deps_dP) + self.prob.lam * self.Dx @ sp.diags(drho * H)
        JH = dr_deps @ sp.diags(3.0 * eps / H) + self.prob.lam * self.Dx @ sp.diags(rho)
        return JP.tocsr(), JH.tocsr()

    def merit(self, P, H0, s=None):
        H = self.film(P, H0)
        r, eps = self.reynolds(P, H)
        i = self.half
        if s is None:
            # row scale ~ 1 / the Jacobian's diagonal: Poiseuille where the oil is thin,
            # the elastic wedge lambda rho K' where it is stiff
            rho, _ = self.prob.rho(P[i])
            diag = (np.abs(self.Gx.T) @ (self.Ax @ eps) + np.abs(self.Gy.T) @ (self.Ay @ eps))
            s = 1.0 / (diag[i] / self.d + self.prob.lam * rho * abs(self.wedge_stiffness))
        phi = _complementarity(P[i], s * r[i])
        load = self.d**2 * P.sum() - self.load * HERTZ_POINT_LOAD
        return np.concatenate([phi, [load]]), H, r, s


def solve_point(prob: DimensionlessPoint, P0: np.ndarray, H0: float, *, tol: float = 1e-8,
                max_iter: int = 60, load: float = 1.0,
                dense_nodes: int | None = None) -> NewtonRecord:
    """Damped semismooth Newton on (P, H0) for dX dY sum P = load 2 pi/3; raises
    ConvergenceError if it stalls. P0 is (nx, ny); the record's pressure and film too.
    Each step is solved densely on grids of up to ``dense_nodes`` nodes along x (default
    DENSE_POINT_NODES), by the multilevel Newton-Krylov step on finer ones."""
    Y = np.asarray(prob.Y, float)
    if Y.size % 2 == 0 or not np.allclose(Y, -Y[::-1], rtol=0, atol=1e-12 * np.abs(Y).max()):
        raise ValueError("Y must be symmetric about 0 with an odd number of nodes")
    S = _PointSystem(prob, load)
    i = S.half
    P = np.zeros(S.shape)
    P[1:-1, 1:-1] = np.asarray(P0, float)[1:-1, 1:-1]
    P = P.ravel()[S.mirror]                  # symmetric in Y
    phi, H, r, s = S.merit(P, H0)
    norm, worst, it = np.linalg.norm(phi), float(np.abs(phi).max()), 0
    dense = S.shape[0] <= (DENSE_POINT_NODES if dense_nodes is None else dense_nodes)
    for it in range(1, max_iter + 1):
        step = (_dense_step if dense else _krylov_step)(S, P, H, r, s, phi, tol)
        if step is None:
            break
        t = 1.0
        while t > 1e-4:
            P_try = P.copy()
            P_try[i] = np.maximum(P[i] + t * step[:-1], 0.0)
            P_try = P_try[S.mirror]
            H0_try = H0 + t * step[-1]
            with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
                trial = S.merit(P_try, H0_try)
            new_norm = np.linalg.norm(trial[0])
            if np.all(trial[1] > 0) and np.isfinite(new_norm) and new_norm < (1 - 1e-4 * t) * norm:
                break
            t /= 2
        else:
            break
        P, H0 = P_try, H0_try
        phi, H, r, s = trial
        norm = new_norm
        worst = max(float(np.abs(phi).max()), float(np.abs(np.minimum(P[i], s * r[i])).max()))
        if worst < tol:
            return NewtonRecord(np.maximum(P, 0.0).reshape(S.shape), H.reshape(S.shape),
                                float(H0), it, worst)
    raise ConvergenceError("EHL point contact Newton (complementarity residual)", it, worst,
                           f"lambda = {prob.lam:.4g}, tolerance {tol:.0e}")


def _dense_step(S: _PointSystem, P, H, r, s, phi, tol):
    """The Newton step from the dense Jacobian on the y >= 0 half (each unknown's influence
    column plus its mirror's)."""
    i = S.half
    if S.K is None:
        Y_index = i % S.shape[1]
        off_axis = Y_index > S.shape[1] // 2
        K = S.compliance.matrix(None, i)
        K[:, off_axis] += S.compliance.matrix(
            None, i[off_axis] - 2 * (Y_index[off_axis] - S.shape[1] // 2))
        S.K = K
    weight = np.asarray(S.E.sum(axis=0)).ravel()       # 2 off the axis, 1 on it
    JP, JH = S.jacobian(P, H)
    m = i.size
    J = np.empty((m + 1, m + 1))
    J[:-1, :-1] = s[:, None] * (JH[i] @ S.K + (JP[i] @ S.E).toarray())
    J[:-1, -1] = s * np.asarray(JH[i].sum(axis=1)).ravel()
    active = _cavitated(P[i], s * r[i])
    J[:-1][active] = 0.0
    J[np.flatnonzero(active), np.flatnonzero(active)] = 1.0
    J[-1, :-1] = S.d**2 * weight
    J[-1, -1] = 0.0
    return _equilibrated_step(J, phi)


def _krylov_step(S: _PointSystem, P, H, r, s, phi, tol):
    """The same step by GMRES on the whole grid, preconditioned by a V-cycle
    (:mod:`bearingfem.ehl.multilevel`): boundary and cavitated rows are dP = -P. Grids
    kept and rebuilt as the line contact's (:func:`bearingfem.ehl.line._krylov_step`);
    where GMRES fails on fresh ones the step is the dense one up to DENSE_FALLBACK nodes
    along x (else None: Newton stops and raises)."""
    i = S.half
    n = P.size
    s_full = S.E @ s                                  # each inner node its y >= 0 twin's
    fixed = ~(S.E @ (~_cavitated(P[i], s * r[i])).astype(float)).astype(bool)
    rhs = np.append(np.where(fixed, -P, -r), -phi[-1])
    scale = np.append(np.where(fixed, 1.0, s_full), 1.0)
    JP, JH = S.jacobian(P, H)

    def block(dP):
        V = S.compliance.deflection(dP.reshape(S.shape), S.spectrum).ravel()
        return np.where(fixed, dP, JP @ dP + JH @ V)

    column = np.where(fixed, 0.0, np.asarray(JH.sum(axis=1)).ravel())
    x, S.levels = multilevel_step(block, column, np.full(n, S.d**2), rhs, scale, 1e-3 * tol,
                                  S.levels, fixed,
                                  lambda: _levels(S.prob, S.load, P, H, fixed.reshape(S.shape)))
    if x is not None:
        return np.append(x[i], x[-1])
    return _dense_step(S, P, H, r, s, phi, tol) if S.shape[0] <= DENSE_FALLBACK else None


def _levels(prob: DimensionlessPoint, load: float, P, H, fixed) -> list[Level]:
    """The V-cycle's grids for the pressure block from ``prob``'s (state P, H flat; nodes
    ``fixed`` (nx, ny) held) down, every other node kept, to at most COARSE_POINTS nodes."""
    levels = []
    while True:
        S = _PointSystem(prob, load)
        free = ~fixed.ravel()
        JP, JH = S.jacobian(P, H)

        def matvec(dP, S=S, JP=JP, JH=JH, free=free):
            V = S.compliance.deflection(dP.reshape(S.shape), S.spectrum).ravel()
            return np.where(free, JP @ dP + JH @ V, dP)

        if free.size <= COARSE_POINTS or min(S.shape) < 5:
            A = free[:, None] * (JH @ S.compliance.matrix() + JP.toarray())
            held = np.flatnonzero(~free)
            A[held, held] = 1.0
            lu = scipy.linalg.lu_factor(A, check_finite=False)
            levels.append(Level(matvec, lambda v, lu=lu: scipy.linalg.lu_solve(lu, v)))
            return levels
        T = distribution_2d(~fixed)
        near = sp.diags(free.astype(float)) @ (JH @ near_field(S.compliance.kernel, T,
                                                               NEAR_WIDTH) + JP @ T) \
            + sp.diags((~free).astype(float)) @ T
        lu = spla.splu(near.tocsc())
        Xc, Yc = prob.X[::2], prob.Y[(prob.Y.size // 2) % 2::2]     # Yc keeps Y = 0
        # bilinear interpolation; corrections from the coarse grid leave held nodes alone
        prolong = (sp.diags(free.astype(float))
                   @ sp.kron(interpolation(prob.X, Xc), interpolation(prob.Y, Yc))).tocsr()
        levels.append(Level(matvec, lambda v, lu=lu, T=T: T @ lu.solve(v), prolong,
                            restriction(prolong)))
        coarse = sp.kron(interpolation(prob.X, Xc), interpolation(prob.Y, Yc)).T.tocsr()
        inject = coarse.multiply(1.0 / np.maximum(np.asarray(coarse.sum(axis=1)), 1e-300)).tocsr()
        fixed = (inject @ (~free).astype(float) > 0.5).reshape(Xc.size, Yc.size)
        fixed[0, :] = fixed[-1, :] = fixed[:, 0] = fixed[:, -1] = True
        P, H = _bilinear(prob, P, Xc, Yc), _bilinear(prob, H, Xc, Yc)
        prob = DimensionlessPoint(Xc, Yc, prob.lam, prob.eta, prob.rho)


def _bilinear(prob, F, Xc, Yc):
    """F (flat on prob's grid) at the nodes Xc x Yc, a subset of prob's along each axis."""
    F = F.reshape(prob.X.size, prob.Y.size)
    return F[np.searchsorted(prob.X, Xc)][:, np.searchsorted(prob.Y, Yc)].ravel()
