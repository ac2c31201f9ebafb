"""The isothermal, Newtonian EHL line contact: Reynolds film + elastic half-space.

A cylinder of reduced radius R rolls on a plane at mean surface speed u_m, carrying the
load w per unit length; the film obeys the steady 1-D Reynolds equation

    d/dx(rho h^3 / (12 mu) dp/dx) = u_m d(rho h)/dx,   h = h0 + x^2/(2R) + v(x),

with the Reynolds (Swift-Stieber) exit: p >= 0, and where p = 0 the flow may leave the
film (the residual r = -(Reynolds operator) >= 0, p r = 0). The load balance int p dx = w
closes the rigid approach h0. In Hertz units (X = x/b, P = p/p_h, H = h R/b^2, see
:mod:`bearingfem.ehl.halfspace`)

    d/dX(eps dP/dX) - lambda d(rho_r H)/dX = 0,   eps = rho_r H^3 / eta_r,
    lambda = 12 mu0 u_m R^2 / (b^3 p_h),   H = H0 + X^2/2 + V(P),   dX sum P = pi/2,

rho_r, eta_r the density and viscosity ratios of :class:`~bearingfem.lubricant.Lubricant`.
The Poiseuille term is central (second order); the wedge term is Venner & Lubrecht's
second-order upwind (1.5 q_i - 2 q_{i-1} + 0.5 q_{i-2})/dX, q = rho_r H, stable where the
film is stiff. All unknowns (P at the inner nodes, H0) are solved at once by a damped
semismooth Newton method on min(P_i, s_i r_i) = 0 (s_i > 0 a row scale), as Houpert &
Hamrock (J. Tribol. 108, 1986, 411-420) did; the residual is evaluated with the FFT
deflection. Each step is the dense LU of the Jacobian (the elastic block the full
influence matrix) on grids of up to DENSE_NODES nodes, and GMRES with a multilevel
preconditioner on finer ones (:mod:`bearingfem.ehl.multilevel`). Steps are projected on P >= 0 and damped by backtracking on |phi|_2; the
linear system is equilibrated by rows and columns. Starting guesses, mesh sequencing and
load continuation are in :mod:`bearingfem.ehl.contact`.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import scipy.linalg
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..errors import ConvergenceError
from .halfspace import LineCompliance
from .multilevel import (Level, distribution_1d, interpolation, multilevel_step, near_field,
                         restriction)

__all__ = ["DimensionlessLine", "NewtonRecord", "solve_dimensionless", "DENSE_NODES"]


@dataclass(frozen=True)
class DimensionlessLine:
    """One line-contact problem in Hertz units on a uniform grid X (inlet first)."""

    X: np.ndarray
    lam: float                 # lambda = 12 mu0 u_m R^2 / (b^3 p_h)
    eta: object                # P -> (eta_r, d eta_r / dP), arrays
    rho: object                # P -> (rho_r, d rho_r / dP), arrays


@dataclass(frozen=True)
class NewtonRecord:
    """Converged pressure (all nodes), film, H0 and the Newton record."""

    pressure: np.ndarray
    film: np.ndarray
    approach: float
    iterations: int
    residual: float


CAVITATION_GUARD = 0.01
#: Grids up to this many nodes take the dense Newton step (an LU of the whole Jacobian);
#: finer ones the multilevel Newton-Krylov step (:mod:`bearingfem.ehl.multilevel`). The
#: two agree to the solver's tolerance; the dense one is the faster below ~500 nodes.
DENSE_NODES = 500
#: The multilevel step: its near field spans this many cells either side; grids are
#: halved down to at most COARSE_NODES, solved there by a dense LU.
NEAR_WIDTH = 8
COARSE_NODES = 300
#: Where GMRES fails (seen near the rigid limit, M ~ 0.1) grids up to this many nodes take
#: the dense step instead (its matrix: 8 n^2 bytes).
DENSE_FALLBACK = 3000
UPWIND = (1.5, -2.0, 0.5)      # second-order upwind weights of q_i, q_{i-1}, q_{i-2}


def _cavitated(P, sr):
    """Nodes held at P = 0: the semismooth set {P <= s r}, less those still well pressurised
    (P > 1 % of the peak). Those cannot be cavitated at the solution, and a Newton step that
    zeroes them throws away the Hertz zone; the solution of the equations is unchanged."""
    return (P <= sr) & (P <= CAVITATION_GUARD * max(float(P.max()), 0.0))


def _complementarity(P, sr):
    """The function Newton drives to zero: P where cavitated, s r elsewhere."""
    return np.where(_cavitated(P, sr), P, sr)


def _shift(a: np.ndarray, k: int) -> np.ndarray:
    """a_{i-k} (zero past the inlet), as a vector over i."""
    out = np.zeros_like(a)
    out[k:] = a[: a.size - k] if k else a
    return out


class _System:
    """Residuals and the Jacobian of one dimensionless problem."""

    def __init__(self, prob: DimensionlessLine, load: float):
        self.prob = prob
        self.load = load
        self.n = prob.X.size
        self.dx = prob.X[1] - prob.X[0]
        self.compliance = LineCompliance(self.n, self.dx)
        self.K = None            # dense influence matrix, built on first Jacobian
        self.levels = None       # the multilevel step's KeptLevels
        self.geometry = prob.X**2 / 2
        k = self.compliance.kernel[:3]
        self.wedge_stiffness = (1.5 * k[0] - 2.0 * k[1] + 0.5 * k[2]) / self.dx

    def film(self, P, H0):
        return H0 + self.geometry + self.compliance.deflection(P)

    def reynolds(self, P, H):
        """r = -(Reynolds operator) at every node (inner rows are the equations)."""
        prob, dx = self.prob, self.dx
        eta, _ = prob.eta(P)
        rho, _ = prob.rho(P)
        eps = rho * H**3 / eta
        q = rho * H
        ef = 0.5 * (eps[1:] + eps[:-1])                 # eps at the faces i + 1/2
        flux = ef * np.diff(P) / dx**2
        r = np.zeros(self.n)
        r[1:-1] = -(flux[1:] - flux[:-1])
        wedge = sum(w * _shift(q, k) for k, w in enumerate(UPWIND))
        wedge[1] = q[1] - q[0]                          # first-order next to the inlet
        r[1:-1] += prob.lam * wedge[1:-1] / dx
        return r, ef

    def jacobian(self, P, H, ef):
        """d r / d(P, H) as banded sparse blocks; the caller adds the elastic coupling."""
        prob, dx, n = self.prob, self.dx, self.n
        eta, deta = prob.eta(P)
        rho, drho = prob.rho(P)
        eps = rho * H**3 / eta
        deps_dP = eps * (drho / rho - deta / eta)
        deps_dH = 3.0 * eps / H
        dq_dP, dq_dH = drho * H, rho
        dP = np.diff(P) / dx**2
        i = np.arange(1, n - 1)
        rows, cols, vp, vh = [], [], [], []

        def add(col, valp, valh):
            rows.append(i), cols.append(col), vp.append(valp), vh.append(valh)

        # Poiseuille: -(ef_{i+1/2}(P_{i+1}-P_i) - ef_{i-1/2}(P_i - P_{i-1}))/dx^2
        up, down = dP[i], dP[i - 1]                     # (P_{i+1}-P_i)/dx^2, (P_i-P_{i-1})/dx^2
        add(i + 1, -ef[i] / dx**2 - 0.5 * deps_dP[i + 1] * up, -0.5 * deps_dH[i + 1] * up)
        add(i, (ef[i] + ef[i - 1]) / dx**2 - 0.5 * deps_dP[i] * (up - down),
            -0.5 * deps_dH[i] * (up - down))
        add(i - 1, -ef[i - 1] / dx**2 + 0.5 * deps_dP[i - 1] * down,
            0.5 * deps_dH[i - 1] * down)
        # wedge: lam/dx * sum_k w_k q_{i-k}; first order at i = 1
        c = prob.lam / dx
        weights = np.array([UPWIND] * (n - 2))
        weights[0] = (1.0, -1.0, 0.0)
        for k in range(3):
            j = np.maximum(i - k, 0)
            add(j, c * weights[:, k] * dq_dP[j], c * weights[:, k] * dq_dH[j])
        rows, cols = np.concatenate(rows), np.concatenate(cols)
        JP = sp.csr_matrix((np.concatenate(vp), (rows, cols)), shape=(n, n))
        JH = sp.csr_matrix((np.concatenate(vh), (rows, cols)), shape=(n, n))
        return JP, JH

    def merit(self, P, H0, s=None):
        """Complementarity residual phi(P, s r) on inner nodes and the load balance; the
        row scale s is computed here unless given (a line search keeps its iterate's)."""
        H = self.film(P, H0)
        r, ef = self.reynolds(P, H)
        if s is not None:
            phi = _complementarity(P[1:-1], s * r[1:-1])
            return np.concatenate([phi, [self.dx * P.sum() - self.load * np.pi / 2]]), H, r, ef, s
        # row scale: 1 / (the Jacobian's diagonal, near enough): Poiseuille where the oil is
        # thin, the elastic wedge (lam/dx) rho (1.5 K_0 - 2 K_1 + 0.5 K_2) where it is stiff
        rho, _ = self.prob.rho(P[1:-1])
        s = 1.0 / ((ef[1:] + ef[:-1]) / self.dx**2 + self.prob.lam * rho * self.wedge_stiffness)
        phi = _complementarity(P[1:-1], s * r[1:-1])
        load = self.dx * P.sum() - self.load * np.pi / 2
        return np.concatenate([phi, [load]]), H, r, ef, s


def solve_dimensionless(prob: DimensionlessLine, P0: np.ndarray, H0: float, *,
                        tol: float = 1e-9, max_iter: int = 60, load: float = 1.0,
                        dense_nodes: int | None = None) -> NewtonRecord:
    """Damped semismooth Newton on (P, H0) for dX sum P = load pi/2; raises
    ConvergenceError if it stalls. Each step is solved densely on grids of up to
    ``dense_nodes`` nodes (default DENSE_NODES), by the multilevel Newton-Krylov step on
    finer ones."""
    dense_nodes = DENSE_NODES if dense_nodes is None else dense_nodes
    S = _System(prob, load)
    n = S.n
    P = np.asarray(P0, float).copy()
    P[0] = P[-1] = 0.0
    phi, H, r, ef, s = S.merit(P, H0)
    norm = np.linalg.norm(phi)              # the line search's merit; convergence in max-norm
    worst = float(np.abs(phi).max())
    inner = slice(1, n - 1)
    for it in range(1, max_iter + 1):
        if n <= dense_nodes:
            step = _dense_step(S, P, H, ef, r, s, phi)
        else:
            step = _krylov_step(S, P, H, ef, r, s, phi, tol)
        if step is None:
            break
        t = 1.0
        while t > 1e-4:
            P_try = P.copy()
            P_try[inner] = np.maximum(P[inner] + t * step[:-1], 0.0)   # projected: P >= 0
            H0_try = H0 + t * step[-1]
            with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
                trial = S.merit(P_try, H0_try)
            new_norm = np.linalg.norm(trial[0])
            if np.all(trial[1] > 0) and np.isfinite(new_norm) and \
                    new_norm < (1 - 1e-4 * t) * norm:
                break
            t /= 2
        else:
            break
        P, H0 = P_try, H0_try
        phi, H, r, ef, s = trial
        norm = new_norm
        # converged: the guarded function and the plain min(P, s r) both vanish
        worst = max(float(np.abs(phi).max()),
                    float(np.abs(np.minimum(P[inner], s * r[inner])).max()))
        if worst < tol:
            return NewtonRecord(np.maximum(P, 0.0), H, float(H0), it, worst)
    raise ConvergenceError("EHL line contact Newton (complementarity residual)", it, worst,
                           f"lambda = {prob.lam:.4g}, tolerance {tol:.0e}")


def _dense_step(S: _System, P, H, ef, r, s, phi):
    """The Newton step from the dense Jacobian (elastic block: the full influence matrix)."""
    n = S.n
    if S.K is None:
        S.K = S.compliance.matrix()
    JP, JH = S.jacobian(P, H, ef)
    inner = slice(1, n - 1)
    J = np.zeros((n - 1, n - 1))                   # unknowns: P_1..P_{n-2}, H0
    dense = (JH[inner] @ S.K)[:, inner] + JP[inner][:, inner].toarray()
    J[:-1, :-1] = s[:, None] * dense
    J[:-1, -1] = s * np.asarray(JH[inner].sum(axis=1)).ravel()
    active = _cavitated(P[inner], s * r[inner])
    J[:-1][active] = 0.0
    J[np.flatnonzero(active), np.flatnonzero(active)] = 1.0
    J[-1, :-1] = S.dx
    return _equilibrated_step(J, phi)


def _krylov_step(S: _System, P, H, ef, r, s, phi, tol):
    """The same step by GMRES on all nodes, preconditioned by a V-cycle
    (:mod:`bearingfem.ehl.multilevel`): boundary and cavitated rows are dP_i = -P_i.
    The V-cycle's grids are kept from the last step while its cavitated set holds and
    GMRES was quick; if GMRES fails with kept grids they are rebuilt, and if it fails on
    fresh ones the step is the dense one on grids up to DENSE_FALLBACK nodes (else None:
    Newton stops and raises)."""
    n = S.n
    fixed = np.ones(n, bool)
    fixed[1:-1] = _cavitated(P[1:-1], s * r[1:-1])
    rhs = np.append(np.where(fixed, -P, -r), -phi[-1])
    scale = np.ones(n + 1)
    scale[1:n - 1] = np.where(fixed[1:-1], 1.0, s)           # GMRES's residual is Newton's phi
    JP, JH = S.jacobian(P, H, ef)

    def block(dP):
        return np.where(fixed, dP, JP @ dP + JH @ S.compliance.deflection(dP))

    column = np.where(fixed, 0.0, np.asarray(JH.sum(axis=1)).ravel())
    x, S.levels = multilevel_step(block, column, np.full(n, S.dx), rhs, scale, 1e-3 * tol,
                                  S.levels, fixed,
                                  lambda: _levels(S.prob, S.load, P, H, fixed))
    if x is not None:
        return np.append(x[1:-2], x[-1])
    return _dense_step(S, P, H, ef, r, s, phi) if n <= DENSE_FALLBACK else None


def _levels(prob: DimensionlessLine, load: float, P, H, fixed) -> list[Level]:
    """The V-cycle's grids for the pressure block from ``prob``'s (state P, H; rows
    ``fixed`` held) down, each with half the cells, to at most COARSE_NODES nodes."""
    levels = []
    while True:
        S = _System(prob, load)
        free = ~fixed
        _, ef = S.reynolds(P, H)
        JP, JH = S.jacobian(P, H, ef)

        def matvec(dP, S=S, JP=JP, JH=JH, free=free):
            return np.where(free, JP @ dP + JH @ S.compliance.deflection(dP), dP)

        if S.n <= COARSE_NODES:
            A = free[:, None] * (JH @ S.compliance.matrix() + JP.toarray())
            A[np.flatnonzero(fixed), np.flatnonzero(fixed)] = 1.0
            lu = scipy.linalg.lu_factor(A, check_finite=False)
            levels.append(Level(matvec, lambda v, lu=lu: scipy.linalg.lu_solve(lu, v)))
            return levels
        T = distribution_1d(free)
        near = sp.diags(free.astype(float)) @ (JH @ near_field(S.compliance.kernel, T,
                                                               NEAR_WIDTH) + JP @ T) \
            + sp.diags(fixed.astype(float)) @ T
        lu = spla.splu(near.tocsc())
        Xc = np.linspace(prob.X[0], prob.X[-1], (S.n + 1) // 2)
        # corrections from the coarse grid leave held nodes alone
        prolong = (sp.diags(free.astype(float)) @ interpolation(prob.X, Xc)).tocsr()
        levels.append(Level(matvec, lambda v, lu=lu, T=T: T @ lu.solve(v), prolong,
                            restriction(prolong)))
        fixed = np.interp(Xc, prob.X, fixed.astype(float)) > 0.5
        fixed[0] = fixed[-1] = True
        P, H = np.interp(Xc, prob.X, P), np.interp(Xc, prob.X, H)
        prob = DimensionlessLine(Xc, prob.lam, prob.eta, prob.rho)


def _equilibrated_step(J: np.ndarray, phi: np.ndarray):
    """Newton step -J^-1 phi of a dense Jacobian (scaled in place), or None if singular.
    Rows then columns are equilibrated: in the rigid limit the H0 column is many orders
    of magnitude off the pressure columns."""
    try:
        row = 1.0 / np.maximum(np.abs(J).max(axis=1), np.finfo(float).tiny)
        J *= row[:, None]
        col = 1.0 / np.maximum(np.abs(J).max(axis=0), np.finfo(float).tiny)
        J *= col[None, :]
        with warnings.catch_warnings():   # a poor step is caught by the line search
            warnings.simplefilter("ignore", scipy.linalg.LinAlgWarning)
            return -col * scipy.linalg.solve(J, row * phi, check_finite=False)
    except (scipy.linalg.LinAlgError, ValueError):
        return None
