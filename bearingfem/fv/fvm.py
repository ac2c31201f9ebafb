"""Finite-volume reference solver on a structured grid (seed Eq. 14-15, derived afresh).

Cell-centred grid in (theta, zeta = z/R) over the whole length. Integrating
-div(H^3 grad P) = f over a cell and using the exact integrals of the source,

    C_P P_P = C_E P_E + C_W P_W + C_N P_N + C_S P_S + B,
    C_E = H_e^3 dzeta/dtheta,  C_N = H_n^3 dtheta/dzeta (likewise W, S),
    B   = -6 (omega - 2 gamma_dot) (H_e - H_w) dzeta - 12 eps_dot (sin th_e - sin th_w) dzeta,

which is seed Eq. 15 with mu and the wedge term's dz made consistent (seed-corrections §5). The
axial ends and a supply line hold P = 0 on the face, half a cell from the centre.
The matrix is assembled by vectorised index arithmetic; cavitation reuses
:mod:`bearingfem.cavitation` on the same complementarity problem.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..bearing import Bearing, JournalState
from ..caches import cached
from ..film import film_thickness, reynolds_source_integral, theta_from_inertial
from ..fields import tilted_gap
from ..scales import flow_factor, force_factor, moment_factor, shear_friction
from ..solution import FilmSolution, film_solution, undriven
from ..solvers.cavitation import LCPResult, active_set, psor
from ..solvers.jfo import solve_balance, upwind_transport

__all__ = ["solve_fv", "fvm_force", "FVMGrid", "fvm_grid"]


@dataclass(frozen=True, eq=False)
class FVMGrid:
    """Cell centres and faces of the unwrapped film; cell index = i_theta * n_z + j_z."""

    n_theta: int
    n_z: int
    length_ratio: float
    theta0: float | None
    theta_c: np.ndarray   # (n_theta,)
    theta_f: np.ndarray   # (n_theta + 1,) faces
    zeta_c: np.ndarray    # (n_z,)
    dtheta: float
    dzeta: float
    # Sparsity structure of the 5-point stencil, built once: COO rows/cols, and the CSR
    # layout (entry order, row pointer, column indices) the values are scattered into.
    rows: np.ndarray
    cols: np.ndarray
    order: np.ndarray = None
    indptr: np.ndarray = None
    indices: np.ndarray = None
    masks: tuple = ()          # cells with an E, W, N, S neighbour

    @property
    def n(self) -> int:
        return self.n_theta * self.n_z


@cached(maxsize=32)
def fvm_grid(n_theta: int, n_z: int, length_ratio: float, theta0: float | None) -> FVMGrid:
    lam = float(length_ratio)
    t0 = 0.0 if theta0 is None else float(theta0)
    dth = 2 * np.pi / n_theta
    dze = 2 * lam / n_z
    theta_f = t0 + dth * np.arange(n_theta + 1)
    theta_c = theta_f[:-1] + 0.5 * dth
    zeta_c = -lam + dze * (np.arange(n_z) + 0.5)
    periodic = theta0 is None
    rows, cols = _structure(n_theta, n_z, periodic)
    order = np.lexsort((cols, rows))
    indptr = np.concatenate(([0], np.cumsum(np.bincount(rows, minlength=n_theta * n_z))))
    masks = tuple(m for m, _, _ in _links(n_theta, n_z, periodic)[2])
    return FVMGrid(n_theta, n_z, lam, theta0, theta_c, theta_f, zeta_c, dth, dze,
                   rows, cols, order, indptr, cols[order], masks)


def _links(nt: int, nz: int, periodic: bool):
    """Masks of the cells that have an east/west/north/south neighbour, and the offsets."""
    I, J = np.meshgrid(np.arange(nt), np.arange(nz), indexing="ij")
    full = np.ones((nt, nz), bool)
    return I, J, [(full if periodic else I < nt - 1, 1, 0), (full if periodic else I > 0, -1, 0),
                  (J < nz - 1, 0, 1), (J > 0, 0, -1)]


def _structure(nt: int, nz: int, periodic: bool):
    """COO rows and columns of the 5-point stencil: the diagonal, then E, W, N, S links."""
    I, J, links = _links(nt, nz, periodic)
    idx = I * nz + J
    rows, cols = [idx.ravel()], [idx.ravel()]
    for mask, di, dj in links:
        rows.append(idx[mask])
        cols.append((((I + di) % nt) * nz + (J + dj))[mask])
    return np.concatenate(rows), np.concatenate(cols)


def _end_conductance(g: FVMGrid, eps: float) -> np.ndarray:
    """Conductance of each theta column's axial end faces, ambient half a cell away:
    2 H^3 dtheta / dzeta (the cell's own north/south conductance, doubled)."""
    return 2.0 * film_thickness(g.theta_c, eps) ** 3 * g.dtheta / g.dzeta


def _assemble(g: FVMGrid, eps: float, eps_dot: float, w: float):
    """Matrix (CSR, on the grid's fixed layout) and right-hand side of the balance."""
    nz = g.n_z
    He = film_thickness(g.theta_f[1:], eps)          # east face of each theta column
    Hw = film_thickness(g.theta_f[:-1], eps)
    Hc = film_thickness(g.theta_c, eps)
    ones = np.ones((1, nz))
    cE = (He ** 3 * g.dzeta / g.dtheta)[:, None] * ones
    cW = (Hw ** 3 * g.dzeta / g.dtheta)[:, None] * ones
    cN = (Hc ** 3 * g.dtheta / g.dzeta)[:, None] * ones
    A = _conductance_matrix(g, cE, cW, cN, cN)
    B = reynolds_source_integral(g.theta_f[:-1], g.theta_f[1:], eps, eps_dot, w) * g.dzeta
    rhs = np.repeat(B[:, None], nz, axis=1).ravel()
    return A, rhs


def _conductance_matrix(g: FVMGrid, cE, cW, cN, cS) -> sp.csr_matrix:
    """The balance's matrix from the cells' face conductances (n_theta x n_z arrays each)."""
    diag = cE + cW + cN + cS
    # Axial ends: ambient on the face half a cell away doubles the face conductance.
    diag[:, -1] += cN[:, -1]
    diag[:, 0] += cS[:, 0]
    if g.theta0 is not None:     # the supply line likewise
        diag[-1, :] += cE[-1, :]
        diag[0, :] += cW[0, :]
    vals = np.concatenate([diag.ravel()] + [-c[m] for c, m in zip((cE, cW, cN, cS), g.masks)])
    return sp.csr_matrix((vals[g.order], g.indices, g.indptr), shape=(g.n, g.n))


def _assemble_gap(g: FVMGrid, gap, gap_rate, w: float, eps_dot: float = 0.0):
    """Matrix and right-hand side of the balance on a gap field: ``gap(theta, zeta)`` and
    ``gap_rate(theta, zeta)`` [1/s] (functions, evaluated on the faces and centres).

    Face conductances H^3 at the faces; the Couette flux 6 w H dzeta through the theta
    faces (its difference is the cell's integral of -6 w dH/dtheta, exact in theta); the
    squeeze -12 dH/dt: the rigid cylinder's part eps_dot cos(theta) integrated exactly
    (as :func:`_assemble`), the rest at the centre times the cell area (midpoint rule),
    so the rigid gap given as a field is the rigid balance to round-off."""
    TC, ZC = np.meshgrid(g.theta_c, g.zeta_c, indexing="ij")
    half = 0.5 * g.dzeta
    He = gap(TC + 0.5 * g.dtheta, ZC)
    Hw = gap(TC - 0.5 * g.dtheta, ZC)
    cE, cW = He ** 3 * g.dzeta / g.dtheta, Hw ** 3 * g.dzeta / g.dtheta
    cN = gap(TC, ZC + half) ** 3 * g.dtheta / g.dzeta
    cS = gap(TC, ZC - half) ** 3 * g.dtheta / g.dzeta
    A = _conductance_matrix(g, cE, cW, cN, cS)
    rhs = -6.0 * w * (He - Hw) * g.dzeta + _squeeze(g, gap_rate, eps_dot)
    ends = (2.0 * cN[:, -1], 2.0 * cS[:, 0])      # the end faces' conductances
    return A, rhs.ravel(), ends


def _squeeze(g: FVMGrid, gap_rate, eps_dot: float) -> np.ndarray:
    """-12 times each cell's integral of dH/dt (n_theta x n_z): eps_dot cos(theta)
    exactly, the rest by the midpoint rule."""
    TC, ZC = np.meshgrid(g.theta_c, g.zeta_c, indexing="ij")
    rigid = eps_dot * (np.sin(g.theta_f[1:]) - np.sin(g.theta_f[:-1])) * g.dzeta
    rest = (gap_rate(TC, ZC) - eps_dot * np.cos(TC)) * g.dtheta * g.dzeta
    return -12.0 * (rigid[:, None] + rest)


def _pressure(g: FVMGrid, state: JournalState, cavitation: str, method="active-set",
              tol=1e-10, held=None, system=None) -> LCPResult:
    """Cell pressures; ``held`` = (mask, values): cells held at given pressures (grooves),
    the others solved with those values moved to the right-hand side; ``system`` = (A, rhs)
    of a gap field (None: the rigid cylinder)."""
    A, rhs = system or _assemble(g, state.eps, state.eps_dot, state.wedge_speed)
    if held is not None:
        fixed, values = held
        free = ~fixed
        Af = A[free]
        rhs = rhs[free] - Af[:, fixed] @ values[fixed]
        A = Af[:, free].tocsr()
    if not np.any(rhs):
        res = LCPResult(np.zeros(A.shape[0]), 0, 0.0, True, np.zeros(A.shape[0], bool))
    elif cavitation == "reynolds":
        res = psor(A, rhs, tol=tol) if method == "psor" else active_set(A, rhs, tol=tol)
    else:
        res = LCPResult(spla.spsolve(A.tocsc(), rhs), 1, 0.0, True, np.zeros(len(rhs), bool))
    if held is None:
        return res
    P = values.copy()
    P[free] = res.pressure
    return LCPResult(P, res.iterations, res.residual, res.converged, np.zeros(g.n, bool))


def _groove_cells(bearing, g: FVMGrid, state, grooves):
    """Cells whose centres lie in a groove: mask, held pressure, held fraction, and each
    groove's column mask."""
    fixed, values, fraction = np.zeros(g.n, bool), np.zeros(g.n), np.ones(g.n)
    columns = []
    for gr in grooves:
        lo, hi = gr.arc(state.gamma)
        col = np.mod(g.theta_c - lo, 2 * np.pi) <= hi - lo
        columns.append(col)
        cells = np.repeat(col, g.n_z)
        fixed |= cells
        values[cells] = gr.pressure / bearing.pressure_scale
        fraction[cells] = gr.fraction
    return fixed, values, fraction, columns


def _jfo(bearing, g: FVMGrid, state, grooves, ambient, gap=None, rate=None):
    """Steady JFO film on the cells: the Poiseuille balance of :func:`_assemble` with the
    content phi H carried across the theta faces from the upwind cell (6 w phi H dzeta)
    and a squeeze eps_dot changing it at eps_dot cos(theta); returns P, phi, the solve
    record and (feed, leakage, storage) in units of c R^2 / 12 [m^3/s]. On a gap field
    (``gap``, ``rate``: functions of (theta, zeta), :func:`_assemble_gap`) the faces take
    the field's H at their midpoints and the squeeze its rate at the cell centre.

    A supply line (``g.theta0``) is a row of held cells (P ambient, phi 1) appended after
    the grid and joined to its first and last columns through the supply faces, half a
    cell away (doubled conductance): what they send out is the feed, as for a groove."""
    nz, n = g.n_z, g.n
    dz = g.dzeta
    if gap is None:
        A, _ = _assemble(g, state.eps, 0.0, 0.0)
        He = np.repeat(film_thickness(g.theta_f[1:], state.eps)[:, None], nz, axis=1)
        storage = np.repeat(12.0 * state.eps_dot * (np.sin(g.theta_f[1:])
                                                    - np.sin(g.theta_f[:-1])) * dz, nz)
        ends = (_end_conductance(g, state.eps),) * 2
    else:
        A, _, ends = _assemble_gap(g, gap, rate, 0.0)
        TC, ZC = np.meshgrid(g.theta_c, g.zeta_c, indexing="ij")
        He = gap(TC + 0.5 * g.dtheta, ZC)
        storage = -_squeeze(g, rate, state.eps_dot).ravel()
    # upwind transport across each cell's east face (periodic: the last one wraps;
    # with a supply line the last column's east face and the first's west face border it)
    f = 6.0 * state.wedge_speed * He * dz
    I, J = np.meshgrid(np.arange(g.n_theta), np.arange(nz), indexing="ij")
    k = (I * nz + J).ravel()
    d = (((I + 1) % g.n_theta) * nz + J).ravel()
    flux = f.ravel()
    # the axial ends hold the ambient pressure on the face half a cell away
    cend = np.zeros((g.n_theta, nz))
    cend[:, 0] += ends[1]
    cend[:, -1] += ends[0]
    cend = cend.ravel()
    pa = ambient / bearing.pressure_scale
    fixed, values, fraction, _ = _groove_cells(bearing, g, state, grooves)
    if g.theta0 is not None:
        supply = n + np.arange(nz)
        first, last = np.arange(nz), n - nz + np.arange(nz)
        d[last] = supply
        c = 2.0 * He[-1] ** 3 * dz / g.dtheta    # both supply faces: H at theta0 + 2 pi
        links = sp.coo_matrix((np.r_[-c, -c], (np.r_[first, last],
                                                np.r_[supply, supply])), shape=(n + nz,) * 2)
        A = (sp.block_diag([A, sp.diags(2.0 * c)]) + links + links.T).tocsr()
        k, d, flux = np.r_[k, supply], np.r_[d, first], np.r_[flux, f[-1]]
        fixed, values = np.r_[fixed, np.ones(nz, bool)], np.r_[values, np.full(nz, pa)]
        fraction = np.r_[fraction, np.ones(nz)]
        storage, cend = np.r_[storage, np.zeros(nz)], np.r_[cend, np.zeros(nz)]
    T = upwind_transport(k, d, flux, len(fixed))
    free = np.flatnonzero(~fixed)
    P, phi, res, inflow = solve_balance(A, T, storage, cend * pa, free, values, fraction)
    leak = float(np.sum(cend * (P - pa)))
    # what the held cells send out, to free cells and through their own end faces
    feed = float(np.sum((-inflow - cend * pa)[fixed]))
    store = float(np.sum(storage[free] * phi[free]))
    return P[:n], phi[:n], res, (feed, leak, store)


def fvm_force(bearing: Bearing, state: JournalState, n_theta: int = 48, n_z: int = 8,
              cavitation: str = "gumbel"):
    """(F_r, F_t) [N] only: the light path used inside time integration."""
    g = fvm_grid(n_theta, n_z, bearing.length_ratio, None)
    P = _pressure(g, state, cavitation).pressure
    if cavitation != "none":
        P = np.maximum(P, 0.0)
    return _force(bearing, g, P)


def _force(bearing: Bearing, g: FVMGrid, P: np.ndarray):
    """(F_r, F_t) [N]: midpoint sums of seed Eq. 16, sum p (cos, sin)(theta) dA."""
    Pg = P.reshape(g.n_theta, g.n_z).sum(axis=1)
    k = force_factor(bearing) * g.dtheta * g.dzeta
    return k * float(Pg @ np.cos(g.theta_c)), k * float(Pg @ np.sin(g.theta_c))


def solve_fv(bearing: Bearing, state: JournalState, n_theta: int, n_z: int,
             cavitation: str, method: str = "active-set", supply_angle=None,
             tol: float = 1e-10, grooves=(), ambient_pressure: float = 0.0,
             tilt=(0.0, 0.0), tilt_rate=(0.0, 0.0), profile=None) -> FilmSolution:
    """Finite-volume Reynolds solution (arguments checked by
    :func:`bearingfem.fvm_reynolds`, whose front this is); same result type as
    ``solve_reynolds``.

    ``cavitation="jfo"`` is the mass-conserving film on the cells (upwind transport of
    the content across the theta faces), with grooves, a supply line or
    ``ambient_pressure`` > 0 as its supply.

    Forces are the midpoint sums of seed Eq. 16 (second order): F_r = sum p cos(theta) dA,
    F_t = sum p sin(theta) dA in the contract's local frame.

    ``tilt``, ``tilt_rate``: a misaligned journal (:func:`bearingfem.fields.tilted_gap`,
    every cavitation model): the balance on its gap field and ``moment`` (M_x, M_y)
    [N m], midpoint sums as the force. ``profile``: a bush edge profile
    (:class:`~bearingfem.fields.EdgeProfile`) added to the gap.
    """
    theta0 = None if supply_angle is None else float(theta_from_inertial(supply_angle,
                                                                         state.gamma))
    on_gap = any(tilt) or any(tilt_rate) or profile is not None
    g = fvm_grid(n_theta, n_z, bearing.length_ratio, theta0)
    system = gap = None
    if on_gap:       # a gap field: a tilt or an edge profile
        def gap(t, z):
            H = film_thickness(t, state.eps) + tilted_gap(bearing, state, t, z, tilt)[0]
            return H if profile is None else H + profile.film_gap(bearing, z)

        def rate(t, z):
            return (state.eps_dot * np.cos(t)
                    + tilted_gap(bearing, state, t, z, tilt, tilt_rate)[1])
        A, rhs, ends = _assemble_gap(g, gap, rate, state.wedge_speed, state.eps_dot)
        system = (A, rhs)
    held = None
    if grooves:     # cells whose centres lie in a groove hold its pressure
        fixed, values, _, columns = _groove_cells(bearing, g, state, grooves)
        held = (fixed, values)
    phi = flows = None
    if cavitation == "jfo":
        P, phi, res, flows = _jfo(bearing, g, state, grooves, ambient_pressure,
                                  gap, rate if on_gap else None)
    else:
        res = _pressure(g, state, cavitation, method, tol, held, system)
        P = res.pressure if cavitation == "none" else np.maximum(res.pressure, 0.0)

    th = np.repeat(g.theta_c, n_z)
    ze = np.tile(g.zeta_c, n_theta)
    dA = g.dtheta * g.dzeta
    f_r, f_t = _force(bearing, g, P)
    H = film_thickness(th, state.eps) if gap is None else gap(th, ze)
    # a film nothing drives is at ambient, not ruptured: all of it wet, no cavity
    wet = P > 0 if cavitation != "none" and not (
        np.all(P == 0.0) and undriven(state, gap)) else np.ones(g.n, bool)
    # JFO: Couette shear on the oil present, Poiseuille shear in the full film
    shear, full = (1.0, 1.0) if phi is None else (phi, phi >= 1.0 - 1e-12)
    # Friction: Couette everywhere (full oil in cavitated cells, no pressure) plus the
    # Poiseuille part from central differences of the pressure.
    Pg = P.reshape(n_theta, n_z)
    if g.theta0 is None:
        dP = (np.roll(Pg, -1, 0) - np.roll(Pg, 1, 0)) / (2 * g.dtheta)
    else:
        # the supply line holds its pressure on the face half a cell beyond each edge
        # column: a ghost column mirrored through that face keeps the central difference
        # second order there (a ghost of the supply's value a whole cell away is first)
        line = ambient_pressure / bearing.pressure_scale if cavitation == "jfo" else 0.0
        ghost = 2.0 * line - Pg
        dP = np.gradient(np.vstack([ghost[:1], Pg, ghost[-1:]]), g.dtheta, axis=0)[1:-1]
    friction = shear_friction(bearing, state.omega, dA, H, dP.ravel(), couette_share=shear,
                              poiseuille_share=full)
    # Side leakage through the end faces: flux H^3 (P_face=0 - P_c) / (dzeta/2) per face.
    faces = (_end_conductance(g, state.eps)[:, None] * np.column_stack([Pg[:, -1], Pg[:, 0]])
             if gap is None else np.column_stack([ends[0] * Pg[:, -1], ends[1] * Pg[:, 0]]))
    leakage = flow_factor(bearing) * float(np.sum(faces))
    # what leaves alone (the full film draws oil in at its ends where P < 0)
    outflow = flow_factor(bearing) * float(np.sum(np.maximum(faces, 0.0)))
    flow_in = mass_balance = None
    if flows is not None:
        k = flow_factor(bearing)
        flow_in, leakage = k * flows[0], k * flows[1]
        outflow = None      # the JFO balance's net end flow only
        mass_balance = k * (flows[0] - flows[1] - flows[2])
        wet = phi >= 1.0 - 1e-12
    elif held is not None and cavitation == "none":
        # what the grooves feed: their cells' net outflow, the balance's residual there
        # (the Reynolds-condition films do not conserve mass: no feed is defined for them)
        A, rhs = system or _assemble(g, state.eps, state.eps_dot, state.wedge_speed)
        r = (A @ P - rhs).reshape(n_theta, n_z)
        flow_in = flow_factor(bearing) * float(np.sum(r[np.any(np.stack(columns), axis=0)]))
    moment = (0.0, 0.0)
    if on_gap:      # M_x = -sum z dF_y, M_y = sum z dF_x, dF = p (cos, sin)(theta + gamma) dA
        a = th + state.gamma
        k = moment_factor(bearing) * dA
        Pz = P * ze
        moment = (-k * float(np.sum(Pz * np.sin(a))), k * float(np.sum(Pz * np.cos(a))))
    return film_solution(
        bearing, state, P, th, ze, (f_r, f_t), friction=friction, leakage=leakage,
        side_outflow=outflow, flow_in=flow_in, fraction=phi, mass_balance=mass_balance, moment=moment,
        gap=None if gap is None else gap(th, ze),
        cavitated_fraction=float(np.mean(~wet)), record=res,
        method="fvm" + (f"/{method}" if cavitation == "reynolds" else ""),
        cavitation=cavitation, half=False, mesh=g)
