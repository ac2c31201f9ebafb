"""Planar films on a P1 mesh: Reynolds-family and mass-conserving (JFO), steady and transient.

Dimensional form on the rectangle (x along the sliding, y across):

    div(h^3 / (12 mu) grad p) = (U/2) d(phi h)/dx + d(phi h)/dt,
    p >= 0, 0 <= phi <= 1, p (1 - phi) = 0,

the same balance as the journal film (:mod:`bearingfem.fe.jfo`) with the gap from the
film's callable: the Poiseuille operator is assembled with h^3 at the quadrature points,
the content is balanced on the nodes' control volumes (:mod:`bearingfem.fe.volumes`).
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import scipy.sparse as sp
from skfem import Basis, BilinearForm, ElementTriP1, MeshTri1, MeshTri1DG
from skfem.helpers import dot, grad

from ..bearing import check_positive
from ..planar import PlanarFilm
from ..solvers.jfo import JFOResult, solve_balance
from ..validation import check_int
from .mesh import _quiet_skfem
from .volumes import ControlVolumes, control_volumes, transport_matrix

__all__ = ["PlanarSolution", "PlanarJFO", "solve_planar", "planar_mesh"]


@BilinearForm
def _poiseuille(u, v, w):
    return w.k * dot(grad(u), grad(v))


@dataclass(frozen=True, eq=False)
class PlanarMesh:
    basis: object
    x: np.ndarray
    y: np.ndarray
    inlet: np.ndarray
    outlet: np.ndarray
    free: np.ndarray
    volumes: ControlVolumes
    qp: tuple                 # (x, y) at the quadrature points


@lru_cache(maxsize=16)
def planar_mesh(length: float, width: float, n_x: int, n_y: int, sides: str) -> PlanarMesh:
    """Tensor P1 mesh of the rectangle with its inlet/outlet nodes and control volumes."""
    xa = np.linspace(0.0, length, n_x + 1)
    ya = np.linspace(0.0, width, n_y + 1)
    with _quiet_skfem():
        if sides == "periodic":
            mesh = MeshTri1DG.init_tensor(xa, ya, periodic=[1])
        else:
            mesh = MeshTri1.init_tensor(xa, ya)
        basis = Basis(mesh, ElementTriP1(), intorder=4)
    x, y = (np.array(c) for c in basis.doflocs)
    tol = 1e-9 * length
    inlet = np.flatnonzero(np.abs(x) < tol)
    outlet = np.flatnonzero(np.abs(x - length) < tol)
    free = np.setdiff1d(np.arange(basis.N), np.union1d(inlet, outlet))
    cv = control_volumes(x, y, xa, ya, False, periodic_y=sides == "periodic")
    qp = tuple(np.array(c) for c in basis.global_coordinates())
    return PlanarMesh(basis, x, y, inlet, outlet, free, cv, qp)


@dataclass(frozen=True)
class PlanarSolution:
    """A solved planar film.

    pressure [Pa] and fraction (film fraction) at the nodes x, y [m]; load: the integral
    of p over the film [N]; flow_in: through the inlet [m^3/s]; flow_out: through the
    outlet; storage: rate of change of the content of the free volumes [m^3/s];
    mass_balance = flow_in - flow_out - storage (round-off); cavitated_fraction: share of
    the area with phi < 1; t: the time [s] of the film.
    """

    x: np.ndarray
    y: np.ndarray
    pressure: np.ndarray
    fraction: np.ndarray
    load: float
    flow_in: float
    flow_out: float
    storage: float
    cavitated_fraction: float
    t: float
    iterations: int
    converged: bool

    @property
    def mass_balance(self) -> float:
        return self.flow_in - self.flow_out - self.storage

    def cavity_start(self, y: float | None = None) -> float:
        """x [m] where the first cavitated volume (phi < 1) along the node row at ``y``
        [m] (default: the first row) begins (its volume's upstream face), or the end of
        the row when there is none."""
        sel = np.isclose(self.y, self.y.min() if y is None else y)
        xs, ph = self.x[sel], self.fraction[sel]
        o = np.argsort(xs)
        xs, ph = xs[o], ph[o]
        cav = np.flatnonzero(ph < 1.0 - 1e-12)
        if not len(cav):
            return float(xs[-1])
        i = cav[0]
        return float(0.5 * (xs[i - 1] + xs[i])) if i > 0 else float(xs[0])


class _Discretisation:
    """Operators of the planar film at one time: Poiseuille K, transport T, content."""

    def __init__(self, film: PlanarFilm, m: PlanarMesh, t: float):
        cv = m.volumes
        k = film.film(*m.qp, t) ** 3 / (12.0 * film.viscosity)
        self.K = _poiseuille.assemble(m.basis, k=k).tocsr()
        h_face = film.film(cv.face, m.y, t)
        self.T = transport_matrix(cv, 0.5 * film.speed * h_face * cv.width)
        # content: Simpson's rule across each volume (exact for gaps linear or quadratic in x)
        mid = 0.5 * (cv.x_lo + cv.x_hi)
        self.content = cv.area / 6.0 * (film.film(cv.x_lo, m.y, t)
                                        + 4.0 * film.film(mid, m.y, t)
                                        + film.film(cv.x_hi, m.y, t))


def _held(film: PlanarFilm, m: PlanarMesh):
    n = m.basis.N
    P, phi = np.zeros(n), np.ones(n)
    P[m.inlet], phi[m.inlet] = film.inlet_pressure, film.inlet_fraction
    P[m.outlet] = film.outlet_pressure
    return P, phi


def _solution(m: PlanarMesh, P, phi, res, inflow, storage, source, t):
    free = m.free
    load = float(np.sum(m.basis.interpolate(P) * m.basis.dx))
    area = m.volumes.area
    return PlanarSolution(
        x=m.x, y=m.y, pressure=P, fraction=phi, load=load,
        flow_in=-float(np.sum(inflow[m.inlet])), flow_out=float(np.sum(inflow[m.outlet])),
        storage=float(np.sum(storage[free] * phi[free] - source[free])),
        cavitated_fraction=float(np.sum(area * (phi < 1.0 - 1e-12)) / np.sum(area)),
        t=float(t), iterations=res.iterations, converged=res.converged)


def _check_mesh(n_x, n_y):
    return check_int("n_x", n_x, 2), check_int("n_y", n_y, 1)


def solve_planar(film: PlanarFilm, n_x: int = 200, n_y: int = 4, t: float = 0.0,
                 cavitation: str = "jfo") -> PlanarSolution:
    """Steady planar film at time ``t`` (the gap's time derivative is not used).

    cavitation : "jfo" (mass-conserving) or "none" (full film, p may go negative)
    """
    n_x, n_y = _check_mesh(n_x, n_y)
    if cavitation not in ("jfo", "none"):
        raise ValueError(f"cavitation must be 'jfo' or 'none' for a planar film, "
                         f"got {cavitation!r}")
    m = planar_mesh(film.length, film.width, n_x, n_y, film.sides)
    d = _Discretisation(film, m, t)
    P_fix, phi_fix = _held(film, m)
    zero = np.zeros(m.basis.N)
    if cavitation == "none":   # phi = 1 everywhere: the transport is a known source
        P_fix_b = np.where(np.isin(np.arange(m.basis.N), m.free), 0.0, P_fix)
        b = -(d.K @ P_fix_b) - d.T @ np.ones(m.basis.N)
        Kf = d.K[m.free][:, m.free].tocsc()
        P = P_fix_b.copy()
        P[m.free] = sp.linalg.spsolve(Kf, b[m.free])
        phi = np.ones(m.basis.N)
        inflow = -(d.K @ P + d.T @ phi)
        n = len(m.free)
        res = JFOResult(P[m.free], phi[m.free], np.zeros(n, bool), 1, 0.0, True)
        return _solution(m, P, phi, res, inflow, zero, zero, t)
    P, phi, res, inflow = solve_balance(d.K, d.T, zero, zero, m.free, P_fix, phi_fix)
    return _solution(m, P, phi, res, inflow, zero, zero, t)


class PlanarJFO:
    """Transient mass-conserving planar film (backward Euler on the content phi h).

    ``film = PlanarJFO(PlanarFilm(...), n_x, n_y, t0=0.0, fraction=1.0)``;
    ``film.step(dt)`` advances by dt [s] and returns the :class:`PlanarSolution`. The
    state is the film fraction (``film.fraction``) and the content per volume.
    """

    def __init__(self, film: PlanarFilm, n_x: int = 200, n_y: int = 4, t0: float = 0.0,
                 fraction=1.0):
        n_x, n_y = _check_mesh(n_x, n_y)
        self.film = film
        self.mesh = planar_mesh(film.length, film.width, n_x, n_y, film.sides)
        n = self.mesh.basis.N
        phi = np.broadcast_to(np.asarray(fraction, float), (n,)).copy()
        if np.any(phi < 0.0) or np.any(phi > 1.0):
            raise ValueError("fraction must lie in [0, 1]")
        self.t = float(t0)
        self.fraction = phi
        self.content = phi * _Discretisation(film, self.mesh, self.t).content
        self.cavitated = phi < 1.0
        self.steps = 0

    def step(self, dt: float) -> PlanarSolution:
        dt = check_positive("dt", dt)
        m = self.mesh
        t = self.t + dt
        d = _Discretisation(self.film, m, t)
        P_fix, phi_fix = _held(self.film, m)
        storage, source = d.content / dt, self.content / dt
        P, phi, res, inflow = solve_balance(d.K, d.T, storage, source, m.free, P_fix,
                                            phi_fix, self.cavitated)
        sol = _solution(m, P, phi, res, inflow, storage, source, t)
        self.t, self.fraction, self.content = t, phi, phi * d.content
        cav = np.zeros(m.basis.N, bool)
        cav[m.free] = res.cavitated
        self.cavitated = cav
        self.steps += 1
        return sol
