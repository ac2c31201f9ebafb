"""The EHD film with mass-conserving (JFO) cavitation: the JFO balance on the elastic gap.

The steady JFO balance of :mod:`bearingfem.fe.jfo` on the nodes' control volumes,

    R_j = (K(p, H) P)_j + (T(H) phi)_j + S_j phi_j = 0   on the free volumes,
    P >= 0,  phi <= 1,  P (1 - phi) = 0,

with the gap of the elastic bush H = H_rigid + w / c, w = C p (C its compliance,
:func:`~bearingfem.ehd.coupling.dof_compliance`), and a pressure-viscosity law of a
:class:`~bearingfem.lubricant.Lubricant` in the Poiseuille operator K (the EHD film's
own, :class:`~bearingfem.ehd.coupling.EHDFilm`, at zero wedge speed). T is the upwind
Couette transport across the volumes' downstream faces, whose flux 6 w int H dzeta
takes the deflection by the Gauss rule of :mod:`bearingfem.fe.jfo_fields` on each face
(w bilinear between the nodes there, as that module reads a nodal field; P1 at the
element quadrature points in K, as the Reynolds EHD film does). S is the squeeze storage
12 eps_dot int cos(theta) of the rigid cylinder: quasi-static, the deflection's rate is
left out, as in the Reynolds EHD film.

Unknowns: one universal variable u per free volume, P = max(u, 0), phi = 1 + min(u, 0)
(Giacopini et al. 2010; the rigid solver's variable, :mod:`bearingfem.solvers.jfo`). R(u)
is semismooth; its generalised Jacobian is exact: the columns of dR/dP (K, the viscosity
slopes and the bush through K and T: sparse plus the compliance's dense or low-rank part)
where u > 0 and of dR/dphi = T + S where u <= 0. Newton steps are damped by backtracking
on |R|_2 after a watchdog (:meth:`_Newton.run`); converged when max |R| <= tol x the
largest size of the terms the residual sums (|K||P| + |T||phi| + |S phi|), the EHD
film's test.

Load continuation as in :mod:`bearingfem.ehd.newton`: the coupling s in [0, 1] scales the
deflection (s C p) and the pressure the lubricant sees (s p); s = 0 is the rigid JFO film,
solved by :func:`~bearingfem.fe.jfo_steady.solve_jfo`'s solver, the start. A failed
Newton run is retried with a quarter of the increment; below 1e-4 the solve raises
:class:`~bearingfem.errors.ConvergenceError`.

References: M. Giacopini, M.T. Fowell, D. Dini, A. Strozzi, A mass-conserving
complementarity formulation to study lubricant films in the presence of cavitation,
J. Tribol. 132 (2010) 041702; C. Bertocchi, D. Dini, M. Giacopini, M.T. Fowell,
A. Baldini, Fluid film lubrication in the presence of cavitation: a mass-conserving
two-dimensional formulation for compressible, piezoviscous and non-Newtonian fluids,
Tribol. Int. 67 (2013) 61-71; the watchdog: R.M. Chamberlain, M.J.D. Powell,
C. Lemarechal, H.C. Pedersen, The watchdog technique for forcing convergence in algorithms
for constrained optimization, Math. Programming Study 16 (1982) 1-17.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from ..errors import ConvergenceError
from ..fe.jfo_balance import JFOFlows, _boundary_values, _cos_integral, film_volumes
from ..fe.jfo_fields import BalanceFilm, _halves, _zeta_extent, rigid_balance_film
from ..fe.multilevel import prolongation
from ..fields import FilmFields
from ..lubricant import Lubricant
from ..scales import flow_factor
from ..solvers.jfo import JFOResult
from ..fe.volumes import transport_matrix
from .coupling import EHDFilm, ehd_film
from .newton import _block

__all__ = ["JFOCoupling", "FaceMaps", "jfo_coupling", "solve_ehd_jfo", "check_ehd_jfo",
           "EHDJFOSolve"]

MIN_INCREMENT = 1e-4
MAX_NEWTON = 40


def check_ehd_jfo(lubricant, fields, tilt, tilt_rate):
    """ValueError for what the EHD-JFO film does not model, before any work."""
    if lubricant is not None:
        if not isinstance(lubricant, Lubricant):
            raise ValueError(f"lubricant must be a bearingfem.Lubricant or None, "
                             f"got {type(lubricant).__name__}")
        if lubricant.density is not None or lubricant.bulk_modulus is not None:
            # the content rho phi H would need the density of the cavity's streamers
            raise ValueError("cavitation='jfo' with a bush takes a lubricant with a "
                             "pressure-viscosity law only: give density=None and "
                             "bulk_modulus=None")
    if fields is not None or any(tilt) or any(tilt_rate):
        raise ValueError("cavitation='jfo' with a bush or lubricant takes no fields, tilt "
                         "or tilt_rate yet")


@dataclass(frozen=True, eq=False)
class FaceMaps:
    """Linear maps from the nodal gap departure (H - H_rigid, dimensionless) to each
    control volume's downstream-face integral int dH dzeta (``face``) and content
    int dH dA (``content``), by the Gauss rule of :mod:`bearingfem.fe.jfo_fields`."""

    face: sp.csr_matrix
    content: sp.csr_matrix


@lru_cache(maxsize=16)
def face_maps(op) -> FaceMaps:
    mesh = op.mesh
    cv = film_volumes(mesh)
    n = len(cv.down)
    ys, wy = _halves(*_zeta_extent(op, cv))
    th = np.broadcast_to(cv.face[:, None], ys.shape)
    rows = np.repeat(np.arange(n), ys.shape[1])
    face = sp.csr_matrix((wy.ravel(), (rows, np.arange(rows.size))), shape=(n, rows.size)) \
        @ prolongation(mesh, th.ravel(), ys.ravel())
    xs, wx = _halves(cv.x_lo, mesh.axes[0][cv.column], cv.x_hi)
    TH = np.broadcast_to(xs[:, :, None], xs.shape + (ys.shape[1],))
    ZE = np.broadcast_to(ys[:, None, :], TH.shape)
    W = wx[:, :, None] * wy[:, None, :]
    rows = np.repeat(np.arange(n), W[0].size)
    content = sp.csr_matrix((W.ravel(), (rows, np.arange(rows.size))), shape=(n, rows.size)) \
        @ prolongation(mesh, TH.ravel(), ZE.ravel())
    return FaceMaps(face.tocsr(), content.tocsr())


@dataclass(frozen=True, eq=False)
class BalanceState:
    """The balance at one (P, phi): its film (K values, faces), residual on all nodes
    and the size of its terms."""

    ev: object
    K: sp.csr_matrix
    T: sp.csr_matrix
    face: np.ndarray
    residual: np.ndarray
    size: np.ndarray


@dataclass(frozen=True, eq=False)
class JFOCoupling:
    """One steady EHD-JFO problem on one P1 film operator (module docstring).

    poiseuille : the EHD film at zero wedge speed and no squeeze (its residual is K P);
    speed : the wedge speed w [rad/s] (6 x speed x face is the Couette flux);
    storage : the squeeze storage S per volume; P_fixed, phi_fixed : held values
    """

    poiseuille: EHDFilm
    speed: float
    storage: np.ndarray
    P_fixed: np.ndarray
    phi_fixed: np.ndarray
    maps: FaceMaps
    face0: np.ndarray
    content0: np.ndarray

    @property
    def op(self):
        return self.poiseuille.op

    def gap_departure(self, P: np.ndarray, s: float = 1.0) -> np.ndarray:
        """Nodal w / c (dimensionless) of the bush under s p."""
        f = self.poiseuille
        return f.deflection(P, s) / f.clearance

    def evaluate(self, P: np.ndarray, phi: np.ndarray, s: float = 1.0) -> BalanceState | None:
        """The balance at (P, phi) on all nodes, or None where the gap closes."""
        ev = self.poiseuille.evaluate(P, s)
        if ev is None:
            return None
        face = self.face0 + self.maps.face @ self.gap_departure(P, s)
        cv = film_volumes(self.op.mesh)
        T = transport_matrix(cv, 6.0 * self.speed * face)
        K = sp.csr_matrix((ev.values, self.op.indices, self.op.indptr), shape=self.op.shape)
        flow = T @ phi + self.storage * phi
        size = np.abs(K) @ np.abs(P) + np.abs(T) @ np.abs(phi) + np.abs(self.storage * phi)
        return BalanceState(ev, K, T, face, K @ P + flow, size)

    def content_slope(self, phi):
        """d(residual)/d(gap departure) beyond the faces' (None: the steady balance has
        no content term; the transient step's, :mod:`bearingfem.ehd.jfo_transient`)."""
        return None

    def jacobian(self, P, phi, s, state: BalanceState):
        """(dR/dP sparse, U, V, dR/dphi) with dR/dP = sparse + U V^T (U, V None without a
        bush; V None: U is the dense full product)."""
        J, U, V = self.poiseuille.jacobian(P, s, state.ev)
        A = state.T + sp.diags(self.storage, format="csr")
        f = self.poiseuille
        if f.compliance is None:
            return J, None, None, A
        cv = film_volumes(self.op.mesh)
        k = np.flatnonzero(cv.down >= 0)
        flux = 6.0 * self.speed * state.face[k]
        up = np.where(flux >= 0.0, k, cv.down[k])
        # d(T phi)/d(face_k) = 6 speed phi_up (e_k - e_down): the face flux leaves k
        g = 6.0 * self.speed * phi[up]
        n = len(cv.down)
        DT = sp.csr_matrix((np.concatenate([g, -g]),
                            (np.concatenate([k, cv.down[k]]), np.concatenate([k, k]))),
                           shape=(n, n))
        TH = DT @ self.maps.face
        slope = self.content_slope(phi)
        if slope is not None:
            TH = TH + slope
        scale = s * f.scale / f.clearance
        c = f.compliance
        if c.right is None:
            return J, U + scale * (TH @ c.left), None, A
        return J, U + scale * (TH @ (c.left * c.singular)), V, A


def jfo_coupling(bearing, state, op, lubricant, bush, grooves, ambient: float) -> JFOCoupling:
    """The EHD-JFO problem of ``op`` (a whole-length P1 film operator)."""
    rigid = FilmFields().on(op, state)
    base = replace(rigid, gap_rate=np.zeros_like(rigid.gap))
    gap0 = FilmFields().nodal_gap(op, state)
    poiseuille = replace(ehd_film(bearing, state, op, base, gap0, lubricant, bush),
                         wedge=0.0, eps=0.0)
    cv = film_volumes(op.mesh)
    P_fix, phi_fix = _boundary_values(bearing, op.mesh, grooves, ambient)
    rb = rigid_balance_film(op, state)
    return JFOCoupling(poiseuille, state.wedge_speed,
                       12.0 * state.eps_dot * _cos_integral(cv), P_fix, phi_fix,
                       face_maps(op), rb.face, rb.content)


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

    def __init__(self, film: JFOCoupling, free, can):
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
        block = _block(t, data, free, n)        # the free block, transposed (solve "T")
        if U is None:
            return splu(block).solve(-R, trans="T")
        if V is None:
            return la.solve(block.toarray().T + U[np.ix_(free, free)] * pos, -R,
                            check_finite=False)
        Uf, Vf = U[free], V[free] * pos[:, None]
        lu = splu(block)
        y, Z = lu.solve(-R, trans="T"), lu.solve(Uf, trans="T")
        small = np.eye(Vf.shape[1]) + Vf.T @ Z
        return y - Z @ la.solve(small, Vf.T @ y, check_finite=False)

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

        Each step is damped by backtracking on |R|_2, after a watchdog (Chamberlain et
        al. 1982): a full step that fails the decrease but moves a cavity's boundary is
        followed by one more Newton step, kept if that point decreases |R|_2 from u
        (:meth:`lookahead`; the pair counts as two iterations)."""
        R, scale, st = self.merit(u, s)
        if R is None:
            return None, 0
        it = 0
        while True:
            res = float(np.max(np.abs(R), initial=0.0)) / scale
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
            t = u + du
            trial = self.merit(t, s)
            if trial[0] is not None and np.linalg.norm(trial[0]) < (1 - 1e-4) * norm:
                u, (R, scale, st) = t, trial
                continue
            ahead = self.lookahead(u, t, s, trial) if it < MAX_NEWTON else None
            if ahead is not None:
                it += 1
                t2, trial2 = ahead
                if trial2[0] is not None and np.linalg.norm(trial2[0]) < (1 - 1e-4) * norm:
                    u, (R, scale, st) = t2, trial2
                    continue
            alpha = 0.5
            while alpha >= 1.0 / 256:
                t = u + alpha * du
                tR, tscale, tst = self.merit(t, s)
                if tR is not None and np.linalg.norm(tR) < (1 - 1e-4 * alpha) * norm:
                    u, R, scale, st = t, tR, tscale, tst
                    break
                alpha *= 0.5
            else:
                return None, it


def solve_ehd_jfo(bearing, film: JFOCoupling, P0, phi0=None, tol: float = 1e-10,
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
    done, increment, iterations, steps, rejected = 0.0, 1.0, 0, 0, 0
    residual, warm = 0.0, False
    if start is not None:
        Ps, phis = start
        out, iterations = newton.run(np.where(phis[free] < 1.0, phis[free] - 1.0,
                                              Ps[free]), 1.0, tol)
        if out is not None:
            done, (u, residual) = 1.0, out
            steps, warm = 1, True
    if done < 1.0:
        if callable(P0):
            P0, phi0 = P0()
        u = np.where(phi0[free] < 1.0, phi0[free] - 1.0, P0[free])
    while done < 1.0:
        s = min(1.0, done + increment)
        out, its = newton.run(u, s, tol)
        iterations += its
        if out is None:
            rejected += 1
            increment *= 0.25
            if increment < MIN_INCREMENT:
                raise ConvergenceError("EHD-JFO Newton (load continuation)", iterations,
                                       None, f"coupling s = {done:.4g}, increment below "
                                       f"{MIN_INCREMENT}: refine the mesh or reduce the load")
            continue
        u, residual = out
        steps += 1
        done, increment = s, min(1.0, 2.0 * increment)
    P, phi = newton.nodal(u)
    st = film.evaluate(P, phi, 1.0)
    inflow = -(st.K @ P + st.T @ phi)
    res = JFOResult(P[free], phi[free], phi[free] < 1.0, iterations, residual, True, 0)
    feed = np.setdiff1d(op.mesh.fixed, op.mesh.end)
    k = flow_factor(bearing, op.mesh.half)
    flows = JFOFlows(flow_in=-k * float(np.sum(inflow[feed])),
                     side_leakage=k * float(np.sum(inflow[op.mesh.end])),
                     storage=k * float(np.sum(film.storage[free] * phi[free])))
    return EHDJFOSolve(P, phi, res, steps, rejected, flows, warm)


def balance_film(film: JFOCoupling, P: np.ndarray) -> BalanceFilm:
    """The :class:`BalanceFilm` of the converged deformed film (its outputs' fields)."""
    fields, _ = film.poiseuille.fields(P)
    dH = film.gap_departure(P)
    values = film.poiseuille.evaluate(P).values
    return BalanceFilm(values=values, content=film.content0 + film.maps.content @ dH,
                       face=film.face0 + film.maps.face @ dH,
                       squeeze=film.storage / 12.0, fields=fields,
                       gap=film.poiseuille.gap0 + dH)


def solve_ehd_jfo_film(bearing, state, operator, n_theta: int, n_z: int, lubricant, bush,
                       grooves, ambient: float, tol: float, start=None):
    """The route of ``solve_reynolds(..., cavitation="jfo", bush=, lubricant=)``: the rigid
    JFO film on ``operator(n_theta, n_z)`` (whole length), then the EHD-JFO Newton; a
    :class:`FilmSolution` with ``fraction``, ``deformation`` [m] and the deformed ``gap``.
    ``start``: a previous EHD-JFO FilmSolution on the same mesh (warm start)."""
    from ..fe.jfo_steady import _film_solution, _steady
    op = operator(n_theta, n_z)
    film = jfo_coupling(bearing, state, op, lubricant, bush, grooves, ambient)

    def rigid():
        return _steady(bearing, state, operator, n_theta, n_z, grooves, ambient)[:2]
    warm = None
    if start is not None:
        P, phi = getattr(start, "pressure", None), getattr(start, "fraction", None)
        if P is None or phi is None or np.shape(P) != (op.mesh.ndofs,):
            raise ValueError(f"start must be a JFO FilmSolution of the same film mesh "
                             f"({op.mesh.ndofs} nodes) or None")
        warm = (np.asarray(P, float) / bearing.pressure_scale, np.asarray(phi, float))
    try:
        out = solve_ehd_jfo(bearing, film, rigid, None, tol, warm)
    except ConvergenceError as e:
        raise e.at(f"steady EHD-JFO film {n_theta}x{n_z}, eps = {state.eps:.6g}") from None
    sol = _film_solution(bearing, state, op, out.P, out.phi, out.result, out.flows,
                         "fem-P1/jfo-ehd-newton", balance_film(film, out.P))
    return replace(sol, deformation=film.poiseuille.deflection(out.P))
