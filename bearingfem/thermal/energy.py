"""The film-averaged energy equation on the film's finite-element mesh.

Steady, with T(theta, z) the temperature averaged across the film (a thin film whose
velocity profile is Couette + Poiseuille, viscosity uniform across it):

    rho cp q . grad T - div(k h grad T) + H_b (T - T_a) + H_j (T - T_j) = Phi,

q = (U F h/2 - h^3/(12 mu) dp/dx, -h^3/(12 mu) dp/dz) the volume flux per width
(x = R theta, U = omega R the journal's speed; F the film fraction: 1 in a full film and in
the cavity of a Reynolds-condition film, whose oil carries no pressure but fills the gap,
as its friction takes it; the JFO fraction in a JFO cavity, where only the oil present
carries heat), Phi = F mu U^2/h + h^3/(12 mu) |grad p|^2 the viscous dissipation per area
(Couette shear and the pressure gradient's flow; their cross term vanishes across the
film), H_b the film -> ambient coefficient through the bush and H_j the film -> journal
coefficient (zero in the adiabatic film), T_j given or the journal's zero-net-flux
temperature (an extra unknown with int H_j (T - T_j) dA = 0).

Discretised by Galerkin with streamline-upwind Petrov-Galerkin stabilisation (Brooks &
Hughes 1982): the test function v gains tau beta . grad v, beta = rho cp q, with
tau = h_e / (2 |beta|) (coth Pe - 1/Pe), Pe = |beta| h_e / (2 k h), h_e the element's
length along the flow. The film is convection-dominated (Pe ~ 1e3 .. 1e5), so the
scheme is close to a pure upwind transport; its order on smooth fields is shown by a
manufactured solution (tests/test_thermal.py).

The equation lives on the film's arcs only: the elements inside a groove are left out (a
groove is a well-mixed volume at its inlet temperature T_in), so the groove's leading
edge is an outflow boundary (natural condition) and its trailing edge the next arc's inflow
(T = T_in). A supply line is a groove of zero width (inflow at the mesh's first line,
outflow at its last). The axial ends are natural: a Reynolds-condition film's end flux
points out (p >= 0 inside, 0 at the ends).

Energy balance: the rows of the assembled system sum, for the test function 1 (whose
gradient and hence SUPG term vanish), to

    int Phi = int rho cp q . grad T + int H_b (T - T_a) + int H_j (T - T_j) - sum(reactions),

the reactions being the residuals at the held (inflow and groove) nodes: the heat their
rows leave over, which the held temperature takes away (``grooves``). :class:`EnergyBalance` reports each part; the free rows
are solved to round-off, so the balance closes to round-off by construction, and
``dissipation`` is independently the film's power loss (torque times speed plus the
grooves' pumping work, tested).

Reference: A.N. Brooks and T.J.R. Hughes, Comput. Methods Appl. Mech. Eng. 32 (1982)
199-259.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu
from skfem import Basis, BilinearForm, LinearForm

from ..caches import cached
from ..film import film_thickness

__all__ = ["EnergyFlow", "EnergySolution", "EnergyBalance", "solve_energy", "film_flow",
           "film_edges", "FilmEdges", "Mixing"]


@dataclass(frozen=True, eq=False)
class EnergyFlow:
    """The film's flow at the quadrature points of the arcs' elements (elements x points),
    dimensional: beta = rho cp q [W/(m K)] in (theta, zeta) components, diffusivity k h
    [W/K], dissipation Phi [W/m^2]."""

    beta_theta: np.ndarray
    beta_zeta: np.ndarray
    diffusivity: np.ndarray
    dissipation: np.ndarray


@dataclass(frozen=True)
class EnergyBalance:
    """Where the film's heat goes [W] (whole bearing): ``dissipation`` = ``convected``
    (int rho cp q . grad T, the oil's temperature rise along its paths) + ``bush`` +
    ``journal`` (conducted) + ``grooves`` (minus the held nodes' reactions: what holding
    the inlet temperatures takes away); ``residual`` = dissipation - (convected + bush +
    journal + grooves)."""

    dissipation: float
    convected: float
    bush: float
    journal: float
    grooves: float
    residual: float


@dataclass(frozen=True, eq=False)
class EnergySolution:
    """Nodal temperature [K] (held nodes included), the journal's temperature [K] and the
    balance."""

    temperature: np.ndarray
    journal_temperature: float
    balance: EnergyBalance


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
def film_edges(mesh) -> FilmEdges:
    """The :class:`FilmEdges` of a film mesh with grooves or a supply line (not periodic:
    a thermal film needs fresh oil); cached per mesh (the meshes are cached)."""
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
            inflow.append(np.flatnonzero(on_arc & _same_angle(th, hi)))
            outflow.append(np.flatnonzero(on_arc & _same_angle(th, lo)))
            interior.append(np.setdiff1d(mesh.grooves[k], np.flatnonzero(on_arc)))
        else:          # the supply line: the mesh's first and last lines
            inflow.append(np.flatnonzero(np.isclose(th, t_lo, rtol=0.0, atol=1e-9)))
            outflow.append(np.flatnonzero(np.isclose(th, t_hi, rtol=0.0, atol=1e-9)))
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
    rel_lo = np.array([np.mod(lo - t_lo, turn) for lo, _ in arcs])
    rel_lo = np.where(rel_lo < 1e-9, t_hi - t_lo, rel_lo)
    order = np.argsort(rel_lo)
    pos = np.searchsorted(rel_lo[order], rel_col - 1e-9)
    column_groove = order[np.minimum(pos, len(order) - 1)]
    return FilmEdges(elements=elements, inflow=tuple(inflow), outflow=tuple(outflow),
                     interior=tuple(interior), column_theta=column_theta,
                     column_groove=column_groove, column_dofs=dofs, column_index=col,
                     column_weight=weight)


def film_flow(bearing, state, basis, P, fraction, viscosity, lubricant) -> EnergyFlow:
    """:class:`EnergyFlow` at ``basis``'s quadrature points from the nodal dimensionless
    pressure ``P`` (p = mu0 (R/c)^2 P), nodal film ``fraction`` (1 outside a JFO cavity)
    and the viscosity ``viscosity`` [Pa s] at the quadrature points (elements x points)."""
    R, c = bearing.radius, bearing.clearance
    U = state.omega * R
    theta = basis.global_coordinates()[0]
    h = c * film_thickness(np.asarray(theta), state.eps)
    f = basis.interpolate(P)
    scale = bearing.pressure_scale / R                 # dp/dx = scale dP/dtheta
    dpx, dpz = scale * np.asarray(f.grad[0]), scale * np.asarray(f.grad[1])
    F = np.asarray(basis.interpolate(fraction))
    mu = np.asarray(viscosity)
    k3 = h ** 3 / (12.0 * mu)
    rho_cp = lubricant.mass_density * lubricant.specific_heat
    return EnergyFlow(beta_theta=rho_cp * (0.5 * U * F * h - k3 * dpx),
                      beta_zeta=-rho_cp * k3 * dpz,
                      diffusivity=lubricant.conductivity * h,
                      dissipation=F * mu * U ** 2 / h + k3 * (dpx ** 2 + dpz ** 2))


def _supg_tau(basis, flow: EnergyFlow, R: float) -> np.ndarray:
    """SUPG's tau [m^2 K / W] at the quadrature points: h_e / (2 |beta|) xi(Pe)."""
    m = basis.mesh
    idx = basis.tind if basis.tind is not None else np.arange(m.t.shape[1])
    x = m.p[:, m.t[:, idx]]                               # (2, 3, elements)
    dth = (x[0].max(axis=0) - x[0].min(axis=0))[:, None]
    dze = (x[1].max(axis=0) - x[1].min(axis=0))[:, None]
    bt, bz = flow.beta_theta, flow.beta_zeta
    speed = np.hypot(bt, bz)
    safe = np.where(speed > 0.0, speed, 1.0)
    he = R * (np.abs(bt) * dth + np.abs(bz) * dze) / safe     # length along the flow [m]
    pe = speed * he / (2.0 * flow.diffusivity)
    # coth(Pe) - 1/Pe, its series Pe/3 below 1e-3 (no cancellation)
    xi = np.where(pe > 1e-3, 1.0 / np.tanh(np.maximum(pe, 1e-3)) - 1.0 / np.maximum(pe, 1e-3),
                  pe / 3.0)
    return np.where(speed > 0.0, he * xi / (2.0 * safe), 0.0)


@BilinearForm
def _energy_form(u, v, w):
    # per d(theta) d(zeta): R beta.grad T v + k h grad T.grad v + R^2 s T v
    #   + tau (beta.grad v)(beta.grad T + R s T); gradients in (theta, zeta)
    bu = w["bt"] * u.grad[0] + w["bz"] * u.grad[1]
    bv = w["bt"] * v.grad[0] + w["bz"] * v.grad[1]
    return (w["R"] * bu * v + w["D"] * (u.grad[0] * v.grad[0] + u.grad[1] * v.grad[1])
            + w["R"] ** 2 * w["s"] * u * v + w["tau"] * bv * (bu + w["R"] * w["s"] * u))


@LinearForm
def _energy_load(v, w):
    # R^2 f v + tau (beta.grad v) R f: the source f and its SUPG share
    bv = w["bt"] * v.grad[0] + w["bz"] * v.grad[1]
    return w["R"] ** 2 * w["f"] * v + w["tau"] * bv * w["R"] * w["f"]


@LinearForm
def _value_load(v, w):
    return w["R"] ** 2 * w["f"] * v


@cached(maxsize=16)
def arc_basis(mesh, edges: FilmEdges):
    """The film's basis restricted to the arcs' elements, with the film's dof numbering
    (cached per mesh)."""
    b = mesh.basis
    return Basis(b.mesh, b.elem, intorder=4 if mesh.basis.Nbfun == 3 else 6,
                 elements=edges.elements, dofs=b.dofs)


@dataclass(frozen=True, eq=False)
class Mixing:
    """Each groove's inlet temperature as a linear function of the film's: per groove,
    T_in = fresh + sum(weights * T[dofs]) [K], the dofs on the upstream arc's exit
    (:func:`bearingfem.routes.thd.groove_mixing`); solved with the energy equation in
    one linear system, so the mixing needs no iteration of its own."""

    fresh: tuple
    dofs: tuple
    weights: tuple

    @classmethod
    def held(cls, temperatures) -> "Mixing":
        """Inlet temperatures given [K] (no carry-over)."""
        return cls(fresh=tuple(float(t) for t in temperatures),
                   dofs=tuple(np.zeros(0, int) for _ in temperatures),
                   weights=tuple(np.zeros(0) for _ in temperatures))


def solve_energy(bearing, basis, edges: FilmEdges, flow: EnergyFlow, mixing: Mixing,
                 walls, half: bool = False) -> EnergySolution:
    """Solve the energy equation (module docstring) on the arcs' ``basis``.

    mixing : :class:`Mixing`: each groove's (or the supply line's) inlet temperature, held
        at its inflow edge and interior
    walls : (H_b [W/(m^2 K)], T_a [K], H_j [W/(m^2 K)], T_j [K] or None: zero net flux)
    half : the mesh is the half z >= 0 (the balance is doubled to the whole bearing)
    """
    R = bearing.radius
    hb, ta, hj, tj = walls
    tau = _supg_tau(basis, flow, R)
    common = dict(bt=flow.beta_theta, bz=flow.beta_zeta, tau=tau, R=R)
    A = _energy_form.assemble(basis, D=flow.diffusivity, s=hb + hj, **common).tocsr()
    b = _energy_load.assemble(basis, f=flow.dissipation + hb * ta, **common)
    N = basis.N
    held = edges.held
    free = np.setdiff1d(np.arange(N), held)
    # held rows: T_i - sum(w T_out) = fresh, one per held dof of each groove
    rows, cols, vals, rhs_held = [], [], [], np.zeros(N)
    for k, (d_in, d_int) in enumerate(zip(edges.inflow, edges.interior)):
        d = np.concatenate([d_in, d_int]).astype(int)
        src = np.asarray(mixing.dofs[k], int)
        rows.append(np.repeat(d, 1 + len(src)))
        cols.append(np.column_stack([d, np.broadcast_to(src, (len(d), len(src)))]).ravel())
        vals.append(np.tile(np.concatenate([[1.0], -np.asarray(mixing.weights[k])]), len(d)))
        rhs_held[d] = mixing.fresh[k]
    rows, cols, vals = (np.concatenate(x) for x in (rows, cols, vals))
    H = sp.csr_matrix((vals, (rows, cols)), shape=(N, N))[held]
    zero_flux = hj > 0.0 and tj is None
    t_journal = ta if tj is None else float(tj)
    cj = -_energy_load.assemble(basis, f=np.full_like(tau, hj), **common) if hj > 0.0 \
        else np.zeros(N)
    if zero_flux:
        # the journal temperature as one more unknown: column cj, constraint row mj
        mj = _value_load.assemble(basis, f=np.full_like(tau, hj), R=R)
        K = sp.bmat([[A[free], sp.csr_matrix(cj[free][:, None])],
                     [H, None],
                     [sp.csr_matrix(mj[None, :]), sp.csr_matrix([[-float(mj.sum())]])]],
                    format="csc")
        x = splu(K).solve(np.concatenate([b[free], rhs_held[held], [0.0]]))
        T, t_journal = x[:-1], float(x[-1])
    else:
        K = sp.vstack([A[free], H], format="csc")
        T = splu(K).solve(np.concatenate([b[free] - cj[free] * t_journal, rhs_held[held]]))
    bj = cj * t_journal
    if not np.all(np.isfinite(T)):
        raise ValueError("the energy equation gave a non-finite temperature (a film "
                         "without flow through it?)")
    # the balance: rows summed with v = 1 (module docstring)
    reactions = A @ T + bj - b
    factor = 2.0 if half else 1.0
    Tq = basis.interpolate(T)
    dA = R ** 2 * np.asarray(basis.dx)
    Tv, gT = np.asarray(Tq), np.asarray(Tq.grad)
    convected = float(np.sum(R * (flow.beta_theta * gT[0] + flow.beta_zeta * gT[1])
                             * np.asarray(basis.dx)))
    dissipation = float(np.sum(flow.dissipation * dA))
    bush = float(np.sum(hb * (Tv - ta) * dA))
    journal = float(np.sum(hj * (Tv - t_journal) * dA))
    grooves = -float(np.sum(reactions[held]))
    residual = dissipation - (convected + bush + journal + grooves)
    balance = EnergyBalance(*(factor * v for v in (dissipation, convected, bush, journal,
                                                    grooves, residual)))
    return EnergySolution(temperature=T, journal_temperature=t_journal, balance=balance)
