"""Planar films on a P1 mesh: Reynolds-family and mass-conserving (JFO), steady and transient.

Dimensional form on the rectangle (x along the sliding, y across):

    div(h^3 / (12 mu) grad p) = (U/2) d(phi h)/dx + d(phi h)/dt,
    p >= 0, 0 <= phi <= 1, p (1 - phi) = 0,

the same balance as the journal film (:mod:`bearingfem.fe.jfo`) with the gap from the
film's callable: the Poiseuille operator is assembled with h^3 at the quadrature points,
the content is balanced on the nodes' control volumes (:mod:`bearingfem.fe.volumes`).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp
from skfem import Basis, BilinearForm, ElementTriP1, MeshTri1, MeshTri1DG
from skfem.helpers import dot, grad

from ..bearing import check_positive
from ..caches import cached
from ..errors import ConvergenceError
from ..planar import PlanarFilm
from ..solvers.jfo import FirstSet, JFOResult, solve_balance
from ..validation import check_int
from .mesh import quiet_skfem
from .multilevel import free_interpolation
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


@cached(maxsize=16)
def planar_mesh(length: float, width: float, n_x: int, n_y: int, sides: str) -> PlanarMesh:
    """Tensor P1 mesh of the rectangle with its inlet/outlet nodes and control volumes."""
    xa = np.linspace(0.0, length, n_x + 1)
    ya = np.linspace(0.0, width, n_y + 1)
    with quiet_skfem():
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
    the area with phi < 1; t: the time [s] of the film; iterations and factorisations
    of its solve (of all its substeps and the coarser meshes that placed their first
    sets); substeps: the backward-Euler steps the step was cut into to converge (1: not
    cut; the flows are those of the last).
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
    factorisations: int = 0
    substeps: int = 1

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
        self.t = t
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
        t=float(t), iterations=res.iterations, converged=res.converged,
        factorisations=res.factorisations)


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
    try:
        P, phi, res, inflow = solve_balance(d.K, d.T, zero, zero, m.free, P_fix, phi_fix)
    except ConvergenceError as e:
        raise e.at(f"steady planar film, t = {t:.6g} s") from None
    return _solution(m, P, phi, res, inflow, zero, zero, t)


#: A transient step that does not converge is cut in halves up to this many times.
MAX_CUTS = 3

#: Coarser meshes for a step's first set stop at this many cells along x.
COARSEST_CELLS = 25


@cached(maxsize=64)
def _interpolation(length: float, width: float, n_x: int, n_y: int, sides: str,
                   fine_x: int, fine_y: int) -> sp.csr_matrix:
    """Bilinear interpolation from the nodes of the (n_x, n_y) planar mesh to those of
    the (fine_x, fine_y) one (either may be the finer)."""
    periodic = sides == "periodic"
    src = planar_mesh(length, width, n_x, n_y, sides)
    dst = planar_mesh(length, width, fine_x, fine_y, sides)
    i = np.rint(src.x / length * n_x).astype(int)
    j = np.rint(src.y / width * n_y).astype(int)
    cols = n_y if periodic else n_y + 1
    dof_at = np.full((n_x + 1, cols), -1)
    dof_at[i, np.mod(j, cols)] = np.arange(len(src.x))
    if periodic:          # close the loop across y = width
        dof_at = np.hstack([dof_at, dof_at[:, :1]])
    u, v = dst.x / length * n_x, dst.y / width * n_y
    i0 = np.clip(np.floor(u).astype(int), 0, n_x - 1)
    j0 = np.clip(np.floor(v).astype(int), 0, n_y - 1)
    s, r = np.clip(u - i0, 0.0, 1.0), np.clip(v - j0, 0.0, 1.0)
    rows = np.repeat(np.arange(len(dst.x)), 4)
    idx = np.column_stack([dof_at[i0, j0], dof_at[i0 + 1, j0], dof_at[i0, j0 + 1],
                           dof_at[i0 + 1, j0 + 1]]).ravel()
    w = np.column_stack([(1 - s) * (1 - r), s * (1 - r), (1 - s) * r, s * r]).ravel()
    return sp.csr_matrix((w, (rows, idx)), shape=(len(dst.x), len(src.x)))


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
        self._levels = [(n_x, n_y)]      # the film's mesh, then the coarser ones
        while self._levels[-1][0] // 2 >= COARSEST_CELLS:
            c_x, c_y = self._levels[-1]
            self._levels.append((c_x // 2, max(1, c_y // 2)))

    def step(self, dt: float) -> PlanarSolution:
        """Advance by ``dt`` [s] and keep the new film. A step whose solve does not
        converge is cut in two (up to ``MAX_CUTS`` times, the result's ``substeps`` says
        into how many); if it still does not, :class:`~bearingfem.errors.ConvergenceError`
        is raised and the film stays at its last converged step."""
        dt = check_positive("dt", dt)
        try:
            sol = self._advance(dt, MAX_CUTS)
        except ConvergenceError as e:
            raise e.at(f"planar film step {self.steps + 1} to t = {self.t + dt:.6g} s "
                       f"(cut {MAX_CUTS} times)") from None
        self.steps += 1
        return sol

    def _advance(self, dt: float, cuts: int) -> PlanarSolution:
        kept = (self.t, self.fraction, self.content, self.cavitated)
        try:
            return self._solve_step(dt)
        except ConvergenceError:
            if cuts == 0:
                raise
        try:
            first = self._advance(0.5 * dt, cuts - 1)
            last = self._advance(0.5 * dt, cuts - 1)
        except ConvergenceError:
            self.t, self.fraction, self.content, self.cavitated = kept
            raise
        return replace(last, iterations=first.iterations + last.iterations,
                       factorisations=first.factorisations + last.factorisations,
                       substeps=first.substeps + last.substeps)

    def _solve_step(self, dt: float) -> PlanarSolution:
        m = self.mesh
        t = self.t + dt
        d = _Discretisation(self.film, m, t)
        storage, source = d.content / dt, self.content / dt
        P, phi, res, inflow = self._balance(0, d, dt, source, self.cavitated)
        sol = _solution(m, P, phi, res, inflow, storage, source, t)
        self.t, self.fraction, self.content = t, phi, phi * d.content
        cav = np.zeros(m.basis.N, bool)
        cav[m.free] = res.cavitated
        self.cavitated = cav
        return sol

    def _balance(self, level: int, d: _Discretisation, dt: float, source, cavitated):
        """The step's balance on mesh ``level`` (0: the film's, then each half as fine).
        When the previous set does not settle, its first set comes from the same step on
        the next coarser mesh (recursively): a front that jumps many cells in one step
        is then placed within a cell or two whatever the mesh, where the active set alone
        moves it about a cell per iteration."""
        f = self.film
        n_x, n_y = self._levels[level]
        m = planar_mesh(f.length, f.width, n_x, n_y, f.sides)
        storage = d.content / dt
        start = None
        if level + 1 < len(self._levels):
            def start():
                c_x, c_y = self._levels[level + 1]
                down = _interpolation(f.length, f.width, n_x, n_y, f.sides, c_x, c_y)
                mc = planar_mesh(f.length, f.width, c_x, c_y, f.sides)
                up = free_interpolation(
                    _interpolation(f.length, f.width, c_x, c_y, f.sides, n_x, n_y), mc.free)
                dc = _Discretisation(f, mc, d.t)
                fill = down @ (source / storage)      # content relative to the new gap
                try:
                    # no first set there: the previous one already failed on this mesh
                    P, phi, res, _ = self._balance(level + 1, dc, dt, fill * dc.content / dt,
                                                   None)
                except ConvergenceError:
                    return None
                return FirstSet(up @ (P - (1.0 - phi)) < 0.0, res.iterations,
                                res.factorisations)
        return solve_balance(d.K, d.T, storage, source, m.free, *_held(f, m), cavitated,
                             start=start)
