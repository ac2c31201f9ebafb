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
temperature (an extra unknown with int H_j (T - T_j) dA = 0). With a conducting bush
(``solve_energy(..., bush=)``) the bush's term is H (T - T_w) instead, T_w the bush's
inner temperature from its own heat equation, solved with the film
(:mod:`bearingfem.thermal.bush`).

Discretised by Galerkin with streamline-upwind Petrov-Galerkin stabilisation on element
tables built once per mesh (:mod:`bearingfem.thermal.operator`), solved by a banded LU,
each groove's carried-over oil (a rank-one coupling of its held rows to the upstream
exit) by Woodbury's identity and a zero-flux journal by eliminating its one unknown. A
time step (``storage``) adds rho cp h (T - T_old)/dt, backward Euler.

The equation lives on the film's arcs only: the elements inside a groove are left out (a
groove is a well-mixed volume at its inlet temperature T_in), so the groove's leading
edge is an outflow boundary (natural condition) and its trailing edge the next arc's inflow
(T = T_in). A supply line is a groove of zero width (inflow at the mesh's first line,
outflow at its last). A journal turning the other way (omega < 0) carries the oil towards
decreasing angle: the edges swap (``energy_operator(mesh, reverse=True)``), the film's
mirror image. The axial ends are natural: a Reynolds-condition film's end flux points out
(p >= 0 inside, 0 at the ends).

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

from dataclasses import dataclass, field
from functools import cached_property
from typing import NamedTuple

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import LinearOperator, gmres

from ..errors import ConvergenceError
# the discretisation's names, kept importable from here where the equation is solved
from .operator import (EnergyFlow, EnergyOperator, FilmEdges, arc_basis,  # noqa: F401
                       energy_operator, energy_system, film_edges, film_flow)

__all__ = ["EnergyFlow", "EnergySolution", "EnergyParts", "BushCoupling", "EnergyBalance",
           "solve_energy", "film_flow",
           "EnergyOperator", "energy_operator", "energy_system",
           "film_edges", "FilmEdges", "Mixing"]


@dataclass(frozen=True)
class EnergyBalance:
    """Where the film's heat goes [W] (whole bearing): ``dissipation`` = ``convected``
    (int rho cp q . grad T, the oil's temperature rise along its paths) + ``bush`` +
    ``journal`` (conducted; ``bush`` the conducting bush's heat in, when it has one) +
    ``grooves`` (minus the held nodes' reactions: what holding
    the inlet temperatures takes away) + ``stored`` (a time step's int rho cp h dT/dt, 0 in
    a steady film); ``residual`` = dissipation - (convected + bush + journal + grooves +
    stored)."""

    dissipation: float
    convected: float
    bush: float
    journal: float
    grooves: float
    residual: float
    stored: float = 0.0


class BushCoupling(NamedTuple):
    """A conducting bush as solved with the film: what its temperatures and heat come
    from."""

    wall: object               # the bush's wall (:func:`bearingfem.thermal.bush.bush_wall`)
    coefficient: np.ndarray    # film -> bush coefficient H at the quadrature points [W/(m^2 K)]
    temperature: np.ndarray    # the bush's inner temperature T_w at the quadrature points [K]
    rise: np.ndarray           # its inner nodal temperatures above the ambient [K]
    loads: object              # the heat the film gives the bush (the wall's loads)
    ambient: float             # T_a [K]


class EnergyParts(NamedTuple):
    """What an energy solution's balance is made of, kept to compute it when asked."""

    radius: float              # journal radius R [m]
    operator: EnergyOperator   # the mesh's element tables
    flow: EnergyFlow           # the film's flux, diffusivity, dissipation
    dissipation: np.ndarray    # Phi at the quadrature points [W/m^2] (linearised if asked)
    walls: tuple               # (H_b [W/(m^2 K)], T_a [K], H_j [W/(m^2 K)], T_j [K] or None)
    matrix: object             # the assembled system's matrix A
    rhs: np.ndarray            # its right-hand side b (the bush's wall load included)
    journal_column: np.ndarray  # the journal temperature's column (zero without H_j)
    half: bool                 # the mesh is the half z >= 0: the balance is doubled
    storage: tuple | None      # a time step's (rho cp h / dt [W/(m^2 K)], T_old [K]) or None
    bush: BushCoupling | None  # the conducting bush, or None


@dataclass(frozen=True, eq=False)
class EnergySolution:
    """Nodal temperature [K] (held nodes included), the journal's temperature [K] and the
    balance (computed when asked: a thermal iteration needs only the last one's)."""

    temperature: np.ndarray
    journal_temperature: float
    parts: EnergyParts | None = field(default=None, repr=False)  # what the balance is made of

    @property
    def bush_inner(self):
        """The conducting bush's inner nodal temperatures [K] (None without one)."""
        coupled = None if self.parts is None else self.parts.bush
        return None if coupled is None else coupled.ambient + coupled.rise

    @cached_property
    def bush(self):
        """The conducting bush's temperatures (:class:`~bearingfem.thermal.bush.BushHeat`:
        nodal [K], heat in and out [W], inner mean [K]), or None."""
        coupled = None if self.parts is None else self.parts.bush
        if coupled is None:
            return None
        return coupled.wall.response.field(coupled.loads, coupled.ambient)

    @cached_property
    def balance(self) -> EnergyBalance:
        """Where the heat goes: the assembled rows summed with v = 1 (module docstring)."""
        R, op, flow, phi, walls, A, b, c_all, half, storage, wall = self.parts
        hb, ta, hj, _ = walls
        T, t_journal = self.temperature, self.journal_temperature
        reactions = A @ T + c_all * t_journal - b
        Tv, gT = op.at_points(T), op.gradient(T)
        dA = R ** 2 * op.dx
        convected = float(np.sum(R * (flow.beta_theta * gT[0] + flow.beta_zeta * gT[1])
                                 * op.dx))
        dissipation = float(np.sum(phi * dA))
        bush = float(np.sum(hb * (Tv - ta) * dA))
        if wall is not None:                    # the conducting bush: H (T - T_w)
            bush += float(np.sum(wall.coefficient * (Tv - wall.temperature) * dA))
        journal = float(np.sum(hj * (Tv - t_journal) * dA))
        grooves = -float(np.sum(reactions[op.held]))
        stored = 0.0 if storage is None else \
            float(np.sum(storage[0] * (Tv - storage[1]) * dA))
        residual = dissipation - (convected + bush + journal + grooves + stored)
        k = 2.0 if half else 1.0
        return EnergyBalance(dissipation=k * dissipation, convected=k * convected,
                             bush=k * bush, journal=k * journal, grooves=k * grooves,
                             residual=k * residual, stored=k * stored)


@dataclass(frozen=True, eq=False)
class Mixing:
    """Each groove's inlet temperature as a linear function of the film's: per groove,
    T_in = fresh + sum(weights * T[dofs]) [K], the dofs on the upstream arc's exit
    (:func:`bearingfem.thermal.mixing.groove_mixing`); solved with the energy equation in
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


def _film_coefficient(wall, flow: EnergyFlow) -> np.ndarray:
    """Film -> bush coefficient H [W/(m^2 K)] at the points: the spec's, or 2 k F / h,
    conduction across half the local film (k h is the flow's diffusivity)."""
    given = wall.spec.film_coefficient
    if given is not None:
        return np.full_like(flow.diffusivity, float(given))
    if flow.gap is None or flow.fraction is None:
        raise ValueError("a conducting bush needs the flow's gap and fraction (film_flow)")
    return 2.0 * flow.fraction * flow.diffusivity / flow.gap ** 2


class _FilmSolver:
    """The film's energy system factorised once: x(rhs) with the held rows' carried-over
    oil (rank one per groove) by Woodbury's identity and the zero-flux journal
    eliminated; linear in ``rhs`` (N,) or (N, k). Returns (T, journal temperature's
    share of rhs). ``first``: the rhs of the first solve, taken in one banded solve with
    the Woodbury and journal columns (one call to LAPACK instead of two or three); its
    answer is :meth:`first_solution`."""

    def __init__(self, op, A, U, V, cj, mj, first=None):
        self.band = op.band_factor(A.data)
        columns = [U] + ([cj[:, None]] if mj is not None else []) \
            + ([np.reshape(first, (len(first), -1))] if first is not None else [])
        X = self.band(np.hstack(columns))
        g = U.shape[1]
        self.Z, self.V = X[:, :g], V
        self.small = np.eye(g) + V.T @ self.Z
        self.mj = mj
        if mj is not None:
            self.Tc = self._woodbury(X[:, g])
            self.den = float(mj @ self.Tc + mj.sum())
            g += 1
        self._first = None if first is None else \
            (X[:, g] if np.ndim(first) == 1 else X[:, g:])

    def _woodbury(self, X):
        if not self.Z.shape[1]:
            return X
        return X - self.Z @ np.linalg.solve(self.small, self.V.T @ X)

    def __call__(self, rhs):
        return self._finish(self.band(rhs))

    def first_solution(self):
        """(T, journal share) of the ``first`` rhs given when built."""
        return self._finish(self._first)

    def _finish(self, X):
        """The band's answer X to (T, journal share): Woodbury, then the journal."""
        X = self._woodbury(X)
        if self.mj is None:
            return X, 0.0
        t = (self.mj @ X) / self.den
        return X - np.multiply.outer(self.Tc, t) if X.ndim == 2 else X - t * self.Tc, t


def solve_energy(bearing, op: EnergyOperator, flow: EnergyFlow, mixing: Mixing, walls,
                 half: bool = False, linearised=None, storage=None, bush=None,
                 bush_tol: float = 1e-12, bush_start=None) -> EnergySolution:
    """Solve the energy equation (module docstring) on the arcs of ``op``
    (:func:`energy_operator`).

    mixing : :class:`Mixing`: each groove's (or the supply line's) inlet temperature, held
        at its inflow edge and interior
    walls : (H_b [W/(m^2 K)], T_a [K], H_j [W/(m^2 K)], T_j [K] or None: zero net flux)
    half : the mesh is the half z >= 0 (the balance is doubled to the whole bearing)
    linearised : None, or (a, T0) at the quadrature points: the dissipation is taken as
        Phi + a (T - T0) (its first-order change with the temperature [W/(m^2 K)] about
        T0), the Newton step of a coupled solve; the balance's ``dissipation`` is that
        linearised one
    storage : None (steady), or (C, T_old) at the quadrature points: one backward-Euler
        step of rho cp h dT/dt, C = rho cp h / dt [W/(m^2 K)] and T_old the last step's
        temperatures [K] (the balance's ``stored``)
    bush : None, or a conducting bush (:func:`bearingfem.thermal.bush.bush_wall`, its
        ambient T_a): the film loses H (T - T_w) to the bush's inner surface, T_w the
        bush's temperature there (module docstring of :mod:`bearingfem.thermal.bush`);
        film and bush are solved together, the bush's inner temperatures by GMRES on
        their Schur complement to ``bush_tol`` (relative residual), started from
        ``bush_start`` (an earlier solution's ``bush_inner``) if given
    """
    R = bearing.radius
    hb, ta, hj, tj = walls
    s, f = hb + hj, flow.dissipation + hb * ta
    if linearised is not None:
        a, T0 = linearised
        s, f = s - a, f - a * T0
    if storage is not None:
        s, f = s + storage[0], f + storage[0] * storage[1]
    H = None
    if bush is not None:
        if half:
            raise ValueError("a conducting bush needs the whole-length film (half=False)")
        H = _film_coefficient(bush, flow)
        s, f = s + H, f + H * ta
    A, b, test = energy_system(op, flow, s, f, R)
    N, held = op.N, op.held
    rhs = b.copy()
    zero_flux = hj > 0.0 and tj is None
    t_journal = ta if tj is None else float(tj)
    # the journal's share of the wall term, -int (R v + tau beta.grad v) R H_j T_j
    c_all = -op.vector(np.sum(test, axis=2) * R * hj) if hj > 0.0 else np.zeros(N)
    cj = c_all.copy()
    cj[held] = 0.0
    if not zero_flux:
        rhs -= cj * t_journal
    # held rows: T_i - sum(w T_out) = fresh per groove; the band holds T_i, the carried
    # share is a rank-one term per groove, U_k V_k^T (U_k: the groove's held rows,
    # V_k: -w on its upstream exit), taken by Woodbury's identity
    G = len(op.edges.inflow)
    U, V = np.zeros((N, G)), np.zeros((N, G))
    for k, (d_in, d_int) in enumerate(zip(op.edges.inflow, op.edges.interior)):
        d = np.concatenate([d_in, d_int]).astype(int)
        rhs[d] = mixing.fresh[k]
        U[d, k] = 1.0
        V[np.asarray(mixing.dofs[k], int), k] = -np.asarray(mixing.weights[k])
    # the journal temperature as one more unknown: K T + cj t = rhs with the row
    # int H_j (T - t) dA = 0, eliminated: T = T0 - t T_c, t = m.T0 / (m.T_c + sum m)
    mj = op.vector(np.sum(op.phi * op.dx, axis=2) * R ** 2 * hj) if zero_flux else None
    solver = _FilmSolver(op, A, U, V, cj, mj, first=rhs)
    T, t_lin = solver.first_solution()
    if zero_flux:
        t_journal = float(t_lin)
    wall = None
    if bush is not None:
        T, t_add, wall, b = _with_bush(op, solver, bush, H, test, T, ta, R, b, bush_tol,
                                       bush_start)
        if zero_flux:
            t_journal += t_add
    if not np.all(np.isfinite(T)):
        raise ValueError("the energy equation gave a non-finite temperature (a film "
                         "without flow through it?)")
    phi = flow.dissipation if linearised is None else \
        flow.dissipation + linearised[0] * (op.at_points(T) - linearised[1])
    return EnergySolution(temperature=T, journal_temperature=t_journal,
                          parts=EnergyParts(bearing.radius, op, flow, phi, walls, A, b,
                                            c_all, half, storage, wall))


def _with_bush(op, solver, wall, H, test, T_p, ta, R, b, tol, start):
    """The film's temperatures with the conducting bush: T = T_p + L u, u the bush's inner
    nodal temperatures above the ambient and L u the film's answer to the wall load
    int (R v + tau beta.grad v) R H (I u); u = S I^T (H dA (V T - T_a - I u)) (S the
    bush's inner response, I the transfer), solved for u by GMRES on
    (1 + S I^T H dA (I - V L)) u = S I^T H dA (V T_p - T_a). Why GMRES: each product costs
    one banded solve, one FFT and three sparse products, and the operator is the identity
    plus a part bounded by H over the bush's conductance (about 17 iterations from zero
    at 2 k_oil/h); the dense complement would take a film solve per inner node."""
    I, S = wall.transfer, wall.response.inner_response
    dA = (R ** 2 * op.dx).ravel()
    HdA = np.ravel(H) * dA
    # the products GMRES repeats, as sparse matrices built once per solve: the film's
    # wall load C u (held rows zero), and the bush's loads B_f T - B_w u
    E, Q = op.dx.shape
    dofs = op.basis.element_dofs
    weighted = test * (R * H)
    P = sp.csr_matrix((weighted.ravel(), (np.repeat(dofs, Q, axis=1).ravel(),
                                          np.tile(np.arange(E * Q), dofs.shape[0]))),
                      shape=(op.N, E * Q))
    C_all = (P @ I).tocsr()
    keep = np.ones(op.N)
    keep[op.held] = 0.0
    C = sp.diags(keep) @ C_all
    IH = (I.T @ sp.diags(HdA)).tocsr()
    B_f, B_w = (IH @ op.value).tocsr(), (IH @ I).tocsr()

    def film(u):
        return solver(C @ u)

    def apply(u):
        Tu, _ = film(u)
        return u - S(B_f @ Tu - B_w @ u)

    rhs = S(B_f @ T_p - ta * np.asarray(IH.sum(axis=1)).ravel())
    n = I.shape[1]
    M = LinearOperator((n, n), matvec=apply, dtype=float)
    x0 = None if start is None or np.shape(start) != (n,) else np.asarray(start) - ta
    u, info = gmres(M, rhs, x0=x0, rtol=tol, atol=0.0, restart=min(n, 60), maxiter=20)
    res = float(np.linalg.norm(apply(u) - rhs) / max(np.linalg.norm(rhs), 1e-300))
    if info != 0 or not res <= 10.0 * tol:
        raise ConvergenceError("film and bush temperatures (GMRES)", 20 * min(n, 60), res)
    Tu, t_add = film(u)
    T = T_p + Tu
    Tw = ta + (I @ u).reshape(op.dx.shape)                 # the wall's temperature [K]
    flux_dA = HdA * ((op.value @ T) - np.ravel(Tw))
    return (T, float(t_add), BushCoupling(wall, H, Tw, u, wall.loads(flux_dA), ta),
            b + C_all @ u)


