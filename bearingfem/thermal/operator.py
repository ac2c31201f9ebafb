"""The energy equation's discretisation on the film's mesh: the arcs between grooves and
their edges, the film's heat-carrying flow, the element tables and the stabilised system.

Discretised by Galerkin with streamline-upwind Petrov-Galerkin stabilisation (Brooks &
Hughes 1982): the test function v gains tau beta . grad v, beta = rho cp q, with
tau = h_e / (2 |beta|) (coth Pe - 1/Pe), Pe = |beta| h_e / (2 k h), h_e the element's
length along the flow. The film is convection-dominated (Pe ~ 1e3 .. 1e5), so the
scheme is close to a pure upwind transport; its order on smooth fields is shown by a
manufactured solution (tests/test_thermal_energy.py).

Assembled by array products on element tables built once per mesh
(:class:`EnergyOperator`: the arcs' basis values and gradients at the quadrature points;
the coefficients change at every thermal step, the mesh does not); the dofs along theta
then zeta give the system a half-bandwidth of about n_z, which the banded LU of
:mod:`bearingfem.thermal.energy` uses.

The equation itself, its walls, groove mixing and balance: :mod:`bearingfem.thermal.energy`.

References: A.N. Brooks and T.J.R. Hughes, Comput. Methods Appl. Mech. Eng. 32 (1982)
199-259 (SUPG); P.G. Ciarlet and P.-A. Raviart, The combined effect of curved boundaries
and numerical integration in isoparametric finite element methods, in A.K. Aziz (ed.),
The Mathematical Foundations of the Finite Element Method, Academic Press (1972) 409-474
(the quadrature's degree, :data:`ARC_DEGREE`).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.linalg import solve_banded
from scipy.linalg.lapack import dgbtrf, dgbtrs
from skfem import Basis

from ..caches import cached
from ..film import film_thickness

__all__ = ["EnergyFlow", "film_flow", "EnergyOperator", "energy_operator", "energy_system",
           "film_edges", "FilmEdges", "arc_basis", "arc_degree"]


@dataclass(frozen=True, eq=False)
class EnergyFlow:
    """The film's flow at the quadrature points of the arcs' elements (elements x points),
    dimensional: beta = rho cp q [W/(m K)] in (theta, zeta) components, diffusivity k h
    [W/K], dissipation Phi [W/m^2]."""

    beta_theta: np.ndarray
    beta_zeta: np.ndarray
    diffusivity: np.ndarray
    dissipation: np.ndarray
    shear: np.ndarray | None = None    # its Couette part F mu U^2/h [W/m^2]
    gap: np.ndarray | None = None      # the film thickness h [m]
    fraction: np.ndarray | None = None  # the film fraction F


@dataclass(frozen=True, eq=False)
class FilmEdges:
    """The arcs' elements and the grooves' edges on one film mesh (a supply line is a
    groove of zero width).

    elements : indices of the elements outside every groove
    inflow, outflow : per groove, the dofs of its trailing edge (the next arc's inlet,
        held) and of its leading edge (the upstream arc's exit, free)
    interior : per groove, its dofs on no arc element (held)
    column_theta, column_groove : the theta of each grid column of arc dofs and the
        groove at the downstream end of its arc (an arc's carry-over flow is its least
        column flow)
    column_dofs, column_index, column_weight : the arc dofs, the column of each and its
        trapezoidal weight in zeta within the column (int q dzeta = sum of weight * q)
    """

    elements: np.ndarray
    inflow: tuple
    outflow: tuple
    interior: tuple
    column_theta: np.ndarray
    column_groove: np.ndarray
    column_dofs: np.ndarray
    column_index: np.ndarray
    column_weight: np.ndarray

    @property
    def held(self) -> np.ndarray:
        return np.unique(np.concatenate([*self.inflow, *self.interior]))


def _same_angle(a, b, tol=1e-9):
    d = np.mod(np.asarray(a) - b, 2.0 * np.pi)
    return (d < tol) | (d > 2.0 * np.pi - tol)


@cached(maxsize=16)
def film_edges(mesh, reverse: bool = False) -> FilmEdges:
    """The :class:`FilmEdges` of a film mesh with grooves or a supply line (not periodic:
    a thermal film needs fresh oil); cached per mesh (the meshes are cached).
    ``reverse``: the journal turns the other way (omega < 0), so the oil runs towards
    decreasing angle: each groove's leading edge is the inlet of the arc before it and its
    trailing edge that arc's exit, and an arc runs into the groove at its start."""
    if mesh.periodic:
        raise ValueError("a thermal film needs an oil supply: give grooves or a "
                         "supply_angle")
    basis = mesh.basis
    m = basis.mesh
    turn = 2.0 * np.pi
    t_lo, t_hi = float(np.min(mesh.theta)), float(np.max(mesh.theta))
    centre = m.p[0, m.t].mean(axis=0)
    arcs = mesh.arcs if mesh.arcs else ((mesh.theta0, mesh.theta0),)
    inside = np.zeros(m.t.shape[1], bool)
    for lo, hi in mesh.arcs:
        inside |= np.mod(centre - lo, turn) < np.mod(hi - lo, turn)
    elements = np.flatnonzero(~inside)
    on_arc = np.zeros(basis.N, bool)
    on_arc[basis.element_dofs[:, elements].ravel()] = True
    th = mesh.theta
    inflow, outflow, interior = [], [], []
    for k, (lo, hi) in enumerate(arcs):
        if mesh.arcs:
            enter, leave = (lo, hi) if reverse else (hi, lo)
            inflow.append(np.flatnonzero(on_arc & _same_angle(th, enter)))
            outflow.append(np.flatnonzero(on_arc & _same_angle(th, leave)))
            interior.append(np.setdiff1d(mesh.grooves[k], np.flatnonzero(on_arc)))
        else:          # the supply line: the mesh's first and last lines
            enter, leave = (t_hi, t_lo) if reverse else (t_lo, t_hi)
            inflow.append(np.flatnonzero(np.isclose(th, enter, rtol=0.0, atol=1e-9)))
            outflow.append(np.flatnonzero(np.isclose(th, leave, rtol=0.0, atol=1e-9)))
            interior.append(np.zeros(0, int))
    # the arc columns and the groove each arc runs into (relative position from the
    # mesh's first line; the first groove's leading edge is the last line)
    arc_dofs = np.flatnonzero(on_arc)
    key = np.round(th[arc_dofs], 10)
    column_theta, where = np.unique(key, return_inverse=True)
    # trapezoidal weights in zeta along each column: sort by (column, zeta)
    order = np.lexsort((mesh.zeta[arc_dofs], where))
    dofs, col, z = arc_dofs[order], where[order], mesh.zeta[arc_dofs[order]]
    same = col[1:] == col[:-1]
    half = np.where(same, 0.5 * np.diff(z), 0.0)
    weight = np.zeros(len(dofs))
    weight[:-1] += half
    weight[1:] += half
    rel_col = column_theta - t_lo
    if reverse:
        # the groove at the arc's start: the last trailing edge at or before the column
        rel_hi = np.array([np.mod(hi - t_lo, turn) for _, hi in arcs])
        order = np.argsort(rel_hi)
        pos = np.searchsorted(rel_hi[order], rel_col + 1e-9, side="right") - 1
        column_groove = order[np.mod(pos, len(order))]
    else:
        rel_lo = np.array([np.mod(lo - t_lo, turn) for lo, _ in arcs])
        rel_lo = np.where(rel_lo < 1e-9, t_hi - t_lo, rel_lo)
        order = np.argsort(rel_lo)
        pos = np.searchsorted(rel_lo[order], rel_col - 1e-9)
        column_groove = order[np.minimum(pos, len(order) - 1)]
    return FilmEdges(elements=elements, inflow=tuple(inflow), outflow=tuple(outflow),
                     interior=tuple(interior), column_theta=column_theta,
                     column_groove=column_groove, column_dofs=dofs, column_index=col,
                     column_weight=weight)


def _flow(bearing, state, theta, dP, F, mu, lubricant, gap=None) -> EnergyFlow:
    """:class:`EnergyFlow` from the dimensionless pressure's gradient ``dP`` (2, ...) in
    (theta, zeta), the film fraction and viscosity [Pa s] at the same points (``gap``:
    the film thickness [m] there, if already known)."""
    R, c = bearing.radius, bearing.clearance
    U = state.omega * R
    h = c * film_thickness(np.asarray(theta), state.eps) if gap is None else gap
    scale = bearing.pressure_scale / R                 # dp/dx = scale dP/dtheta
    dpx, dpz = scale * dP[0], scale * dP[1]
    k3 = h ** 3 / (12.0 * mu)
    rho_cp = lubricant.mass_density * lubricant.specific_heat
    shear = F * mu * U ** 2 / h
    return EnergyFlow(beta_theta=rho_cp * (0.5 * U * F * h - k3 * dpx),
                      beta_zeta=-rho_cp * k3 * dpz,
                      diffusivity=lubricant.conductivity * h,
                      dissipation=shear + k3 * (dpx ** 2 + dpz ** 2),
                      shear=shear, gap=h,
                      fraction=np.broadcast_to(F, np.shape(h)))


@cached(maxsize=4)
def _gap(op, clearance, eps, gamma) -> np.ndarray:
    """The film thickness [m] at ``op``'s points for a journal at (eps, gamma): the same
    at every thermal step of one position (kept for the last few)."""
    h = clearance * film_thickness(op.theta - gamma, eps)
    h.flags.writeable = False
    return h


def film_flow(bearing, state, basis, P, fraction, viscosity, lubricant) -> EnergyFlow:
    """:class:`EnergyFlow` at ``basis``'s quadrature points from the nodal dimensionless
    pressure ``P`` (p = mu0 (R/c)^2 P), nodal film ``fraction`` (1 outside a JFO cavity)
    and the viscosity ``viscosity`` [Pa s] at the quadrature points (elements x points);
    ``basis`` on a mesh fixed in the bearing (its angle phi = theta + gamma, as the
    thermal film's: :func:`bearingfem.routes.thd.thermal_operator`)."""
    f = basis.interpolate(P)
    return _flow(bearing, state, basis.global_coordinates()[0] - state.gamma,
                 np.asarray(f.grad),
                 np.asarray(basis.interpolate(fraction)), np.asarray(viscosity), lubricant)


#: The degree the arcs' quadrature integrates exactly, per element order k (P1, P2): 2k.
#: Why 2k: with the coefficients (beta, tau, k h, the reaction and the source) constant on
#: an element, every term of the system is a polynomial of degree at most 2k (the
#: reaction's v T, 2k; the convection's v beta.grad T, 2k - 1; SUPG's and the diffusion's
#: grad v . grad T, 2k - 2), so the rule is exact on them and its error is the
#: coefficients' variation over the element, O(h^2) relative; Strang's lemma then keeps
#: the scheme's order, as a rule exact for degree 2k - 1 does for the L2 error of a
#: P_k Galerkin scheme (Ciarlet & Raviart 1972). The film's own rule (degree 4, 6 points on
#: P1) integrates h^3/mu more closely than the energy equation needs: half its points
#: here halve the energy step's work at the points (flow, viscosity, tau, assembly).
ARC_DEGREE = {3: 2, 6: 4}

#: The film's own rule (degree 4 on P1, 6 on P2), which the arcs keep when a conducting
#: bush is coupled. Why: the bush's inner nodes take the film's heat at the arcs' points
#: (:func:`bearingfem.thermal.bush.wall_transfer`), and a bush up to twice as fine as the
#: film (allowed) is sampled too thinly by 3 points a triangle: on ROSS's conducting
#: fixture at 48 x 8 with the bush at 96 x 16 its hottest node moved by 0.28 K against
#: 4e-3 K with 6 points (the film's T_max by 5e-3 K).
BUSH_DEGREE = {3: 4, 6: 6}


def arc_degree(mesh, bush: bool = False) -> int:
    """The arcs' quadrature degree on ``mesh``: :data:`ARC_DEGREE`, or
    :data:`BUSH_DEGREE` with a conducting ``bush``."""
    return (BUSH_DEGREE if bush else ARC_DEGREE)[mesh.basis.Nbfun]


@cached(maxsize=16)
def arc_basis(mesh, edges: FilmEdges, degree: int | None = None):
    """The film's basis restricted to the arcs' elements, with the film's dof numbering,
    and a quadrature rule exact for ``degree`` (default :func:`arc_degree`: 3 points on a
    P1 triangle, 6 on P2; cached per mesh)."""
    b = mesh.basis
    return Basis(b.mesh, b.elem, intorder=arc_degree(mesh) if degree is None else degree,
                 elements=edges.elements, dofs=b.dofs)


@dataclass(frozen=True, eq=False)
class EnergyOperator:
    """The energy equation's tables on one film mesh, built once (:func:`energy_operator`):
    the arcs' basis functions and gradients at the quadrature points, the maps from nodal
    values to those points, and where each element entry lands in the matrix. A solve
    assembles by array products on these tables (no form is re-run): the coefficients
    change at every thermal iteration, the mesh does not."""

    basis: object              # the arcs' basis (:func:`arc_basis`)
    edges: FilmEdges
    theta: np.ndarray          # (elements, points) the mesh's angle at the quadrature points
    dx: np.ndarray             # (elements, points) quadrature weight times |det J|
    phi: np.ndarray            # (nb, elements, points) basis values
    grad: np.ndarray           # (nb, 2, elements, points) basis gradients (theta, zeta)
    cell: np.ndarray           # (2, elements, 1) the element's extent in theta and zeta
    value: sp.csr_matrix       # nodal -> values at the points (flattened)
    d_theta: sp.csr_matrix     # nodal -> d/dtheta at the points
    d_zeta: sp.csr_matrix      # nodal -> d/dzeta at the points
    d_both: sp.csr_matrix      # nodal -> (d/dtheta, d/dzeta) at the points, stacked
    indptr: np.ndarray         # the matrix pattern (all dofs)
    indices: np.ndarray
    positions: np.ndarray      # (nb * nb * elements,) place of each local entry
    free_rows: np.ndarray      # (nnz,) 1.0 on entries of free rows, 0.0 on held rows
    held: np.ndarray
    N: int
    band: int                  # half-bandwidth of the pattern in the band order
    band_rank: np.ndarray      # (N,) each dof's place in the band order
    band_index: np.ndarray     # (nnz,) each pattern entry's place in the band storage
    affine_p1: bool            # linear triangles: gradients constant on each element

    def band_solve(self, data: np.ndarray, rhs: np.ndarray) -> np.ndarray:
        """Solve M x = rhs, M the pattern's matrix of ``data`` with its held rows zero and
        ones on their diagonal; ``rhs`` (N,) or (N, k). Why a band: the dofs ordered
        along theta, then zeta, give a half-bandwidth of about n_z, and a banded LU
        (LAPACK) costs a fifth of a general sparse one here."""
        n, w = self.N, self.band
        ab = np.bincount(self.band_index, data * self.free_rows,
                         minlength=(2 * w + 1) * n).reshape(2 * w + 1, n)
        ab[w, self.band_rank[self.held]] = 1.0
        x = solve_banded((w, w), ab, np.asarray(rhs)[self.band_order], overwrite_ab=True,
                         check_finite=False)
        return x[self.band_rank]

    def band_factor(self, data: np.ndarray):
        """The LU factors of the matrix :meth:`band_solve` solves with (LAPACK's banded
        LU, kept): a function rhs (N,) or (N, k) -> x, for solves that come one at a
        time (the conducting bush's iteration)."""
        n, w = self.N, self.band
        ab = np.zeros((3 * w + 1, n), order="F")     # LAPACK's order: no copy on the way in
        ab[w:] = np.bincount(self.band_index, data * self.free_rows,
                             minlength=(2 * w + 1) * n).reshape(2 * w + 1, n)
        ab[2 * w, self.band_rank[self.held]] = 1.0
        lu, piv, info = dgbtrf(ab, w, w)
        if info != 0:
            raise ValueError("the energy equation's matrix is singular (a film without "
                             "flow through it?)")
        order, rank = self.band_order, self.band_rank

        def solve(rhs):
            x, info = dgbtrs(lu, w, w, np.asarray(rhs, float)[order], piv)
            return x[rank]
        return solve

    @property
    def band_order(self) -> np.ndarray:
        return np.argsort(self.band_rank)

    def at_points(self, T: np.ndarray) -> np.ndarray:
        """Values at the points (elements, points) of nodal ``T`` (N,), or (k, elements,
        points) of k nodal fields (N, k) in one product."""
        v = self.value @ T
        return v.reshape(self.dx.shape) if v.ndim == 1 else \
            np.moveaxis(v, 1, 0).reshape((v.shape[1], *self.dx.shape))

    def gradient(self, P: np.ndarray) -> np.ndarray:
        """(2, elements, points) d/dtheta, d/dzeta of nodal ``P`` (one product)."""
        return (self.d_both @ P).reshape((2, *self.dx.shape))

    def flow(self, bearing, state, P, fraction, viscosity, lubricant) -> EnergyFlow:
        """:func:`film_flow` on the arcs, by the operator's maps (the mesh fixed in the
        bearing: the film angle is the mesh's angle less gamma)."""
        return _flow(bearing, state, self.theta - state.gamma, self.gradient(P),
                     self.at_points(fraction),
                     np.asarray(viscosity), lubricant,
                     _gap(self, bearing.clearance, state.eps, state.gamma))

    def matrix(self, local: np.ndarray) -> sp.csr_matrix:
        """The (N, N) matrix of element matrices ``local`` (nb, nb, elements)."""
        n = len(self.indices)
        data = np.bincount(self.positions, local.ravel(), minlength=n)
        return sp.csr_matrix((data, self.indices, self.indptr), shape=(self.N, self.N))

    def vector(self, local: np.ndarray) -> np.ndarray:
        """The (N,) vector of element vectors ``local`` (nb, elements)."""
        dofs = self.basis.element_dofs
        return np.bincount(dofs.ravel(), local.ravel(), minlength=self.N)


def energy_operator(mesh, reverse: bool = False, degree: int | None = None) -> EnergyOperator:
    """The :class:`EnergyOperator` of a film mesh (cached per mesh), for a journal turning
    towards increasing angle (omega > 0) or, ``reverse``, the other way: the held inlet
    rows sit on the other edges (:func:`film_edges`). ``degree``: its quadrature's
    (default :func:`arc_degree`; ``arc_degree(mesh, bush=True)`` with a conducting bush)."""
    return _energy_operator(mesh, film_edges(mesh, bool(reverse)),
                            arc_degree(mesh) if degree is None else int(degree))


@cached(maxsize=16)
def _energy_operator(mesh, edges: FilmEdges, degree: int) -> EnergyOperator:
    basis = arc_basis(mesh, edges, degree)
    nb, N = basis.Nbfun, basis.N
    dofs = basis.element_dofs                                 # (nb, elements)
    phi = np.array([np.asarray(basis.basis[i][0]) for i in range(nb)])
    grad = np.array([np.asarray(basis.basis[i][0].grad) for i in range(nb)])
    E, Q = basis.dx.shape
    rows = np.repeat(np.arange(E * Q), nb)
    cols = np.repeat(dofs.T, Q, axis=0).ravel()

    def interp(values):                                      # (nb, E, Q) -> (E*Q, N)
        return sp.csr_matrix((np.moveaxis(values, 0, -1).ravel(), (rows, cols)),
                             shape=(E * Q, N))
    m = basis.mesh
    x = m.p[:, m.t[:, basis.tind]]                            # (2, 3, elements)
    cell = (x.max(axis=1) - x.min(axis=1))[:, :, None]
    r = np.broadcast_to(dofs[:, None, :], (nb, nb, E)).ravel()
    c = np.broadcast_to(dofs[None, :, :], (nb, nb, E)).ravel()
    pattern = sp.csr_matrix((np.ones(len(r)), (r, c)), shape=(N, N))
    pattern.sum_duplicates()
    pattern.sort_indices()
    keys = np.repeat(np.arange(N, dtype=np.int64), np.diff(pattern.indptr)) * N \
        + pattern.indices
    positions = np.searchsorted(keys, r.astype(np.int64) * N + c)
    held = edges.held
    free_rows = np.ones(pattern.nnz)
    is_held = np.zeros(N, bool)
    is_held[held] = True
    free_rows[np.repeat(is_held, np.diff(pattern.indptr))] = 0.0
    # the band order: along theta, then zeta (or the other way, whichever band is narrower)
    rows_all = np.repeat(np.arange(N), np.diff(pattern.indptr))
    best = None
    for major, minor in ((mesh.theta, mesh.zeta), (mesh.zeta, mesh.theta)):
        order = np.lexsort((np.round(minor, 12), np.round(major, 12)))
        rank = np.empty(N, int)
        rank[order] = np.arange(N)
        w = int(np.max(np.abs(rank[rows_all] - rank[pattern.indices])))
        if best is None or w < best[0]:
            best = (w, rank)
    band, rank = best
    band_index = (band + rank[rows_all] - rank[pattern.indices]) * N + rank[pattern.indices]
    return EnergyOperator(
        basis=basis, edges=edges, theta=np.asarray(basis.global_coordinates()[0]),
        dx=np.asarray(basis.dx), phi=phi, grad=grad, cell=cell, value=interp(phi),
        d_theta=interp(grad[:, 0]), d_zeta=interp(grad[:, 1]),
        d_both=sp.vstack([interp(grad[:, 0]), interp(grad[:, 1])], format="csr"),
        indptr=pattern.indptr,
        indices=pattern.indices, positions=positions, free_rows=free_rows, held=held, N=N,
        band=band, band_rank=rank, band_index=band_index,
        affine_p1=bool(nb == 3 and np.allclose(grad, grad[..., :1], rtol=1e-12, atol=0.0)))


def _supg_tau(op: EnergyOperator, flow: EnergyFlow, R: float) -> np.ndarray:
    """SUPG's tau [m^2 K / W] at the quadrature points: h_e / (2 |beta|) xi(Pe),
    xi = coth(Pe) - 1/Pe (its series Pe/3 below Pe = 1e-3, no cancellation; 1 - 1/Pe
    above Pe = 20, where tanh(Pe) is 1 in double precision: the same values, and the film's
    Pe of 1e3 .. 1e5 needs no tanh)."""
    bt, bz = flow.beta_theta, flow.beta_zeta
    speed = np.hypot(bt, bz)
    moving = speed > 0.0
    inverse = 1.0 / np.where(moving, speed, 1.0)
    he = R * (np.abs(bt) * op.cell[0] + np.abs(bz) * op.cell[1]) * inverse   # along the flow [m]
    pe = 0.5 * speed * he / flow.diffusivity
    xi = 1.0 - 1.0 / np.maximum(pe, 1e-3)
    low = pe < 20.0
    if np.any(low):
        p = pe[low]
        xi[low] = np.where(p > 1e-3, 1.0 / np.tanh(np.maximum(p, 1e-3))
                           - 1.0 / np.maximum(p, 1e-3), p / 3.0)
    return np.where(moving, 0.5 * he * xi * inverse, 0.0)


def energy_system(op: EnergyOperator, flow: EnergyFlow, s, f, R: float):
    """(A, b, test) of the Galerkin/SUPG energy equation with reaction ``s`` [W/(m^2 K)]
    and source ``f`` [W/m^2] at the quadrature points, per d(theta) d(zeta):

        a(T, v) = int (R v + tau beta.grad v) (beta.grad T + R s T) + k h grad T.grad v
        l(v) = int (R v + tau beta.grad v) R f

    (gradients in theta, zeta), ``test`` the weighted test functions (R v + tau beta.grad
    v) dx (nb, elements, points) for further loads."""
    tau = _supg_tau(op, flow, R)
    bt, bz = flow.beta_theta, flow.beta_zeta
    g = op.grad
    bu = bt * g[:, 0] + bz * g[:, 1]                          # (nb, E, Q) beta.grad phi
    test = (R * op.phi + tau * bu) * op.dx
    Ddx = flow.diffusivity * op.dx
    local = np.einsum("ieq,jeq->ije", test, bu + R * s * op.phi)
    if op.affine_p1:
        # gradients constant on each element: the diffusion's points summed first
        g1, D = g[:, :, :, 0], np.sum(Ddx, axis=1)
        local += np.einsum("ie,je->ije", g1[:, 0] * D, g1[:, 0])
        local += np.einsum("ie,je->ije", g1[:, 1] * D, g1[:, 1])
    else:
        local += np.einsum("ieq,jeq->ije", g[:, 0] * Ddx, g[:, 0])
        local += np.einsum("ieq,jeq->ije", g[:, 1] * Ddx, g[:, 1])
    return op.matrix(local), op.vector(np.einsum("ieq,eq->ie", test, R * f)), test


