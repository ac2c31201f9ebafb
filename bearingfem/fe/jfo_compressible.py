"""The compressible (Elrod-type) mass-conserving film on the finite-element film mesh,
steady and transient.

Elrod (1981) lets the oil's density rise with pressure in the full film through a bulk
modulus B [Pa] and keeps the density ratio r = rho/rho0 as the one unknown everywhere:

    p = B ln(r)    where r >= 1 (full film; the law rho/rho0 = exp(p/B) of
                   :class:`~bearingfem.lubricant.Lubricant` with ``bulk_modulus=B``)
    p = 0          where r < 1 (cavity; r is then the film fraction, oil as streamers)

with the mass balance of the content r H (dimensionless, as in :mod:`bearingfem.fe.jfo`)

    div(r H^3 grad P) = 6 w d(r H)/d theta + 12 d(r H)/dt.

With the logarithmic law the Poiseuille mass flux is linear in r: r grad P = beta grad r,
beta = B / (mu (R/c)^2) [1/s]. So with Q = beta (r - 1) in the full film (Q = 0 in the
cavity, where r = phi) the balance on the nodes' control volumes is

    K Q + A r = b,   r = phi + Q / beta,   Q >= 0, phi <= 1, Q (1 - phi) = 0,

K the P1 Poiseuille operator, A the upwind transport and storage of the content
(:mod:`bearingfem.fe.jfo_balance`). That is the incompressible JFO balance with K replaced
by K + A / beta: the same piecewise-linear complementarity in one universal variable per
volume, solved by the same semismooth Newton (active set) with its exact Jacobian
(:func:`~bearingfem.solvers.jfo.solve_balance`), which raises
:class:`~bearingfem.errors.ConvergenceError` when it does not converge. As B grows the
balance tends to the incompressible one and P = beta ln(1 + Q / beta) to Q, both at the
rate 1/B. The discrete film conserves mass exactly (every face flux leaves one volume and
enters the next); the step's flows balance to round-off.

Reference: H.G. Elrod, A cavitation algorithm, J. Lubr. Technol. 103 (1981) 350-354;
D. Vijayaraghavan and T.G. Keith, Development and evaluation of a cavitation algorithm,
Tribol. Trans. 32 (1989) 225-233.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp

from ..bearing import Bearing, JournalState, check_positive
from ..errors import ConvergenceError
from ..lubricant import Lubricant
from ..scales import force_factor
from ..solution import FilmSolution
from ..solvers.cavitation import active_set
from ..solvers.jfo import JFOResult, solve_balance
from ..solvers.linsolve import principal_block
from .assembly import FilmOperator
from .jfo import JFOFilm
from .jfo_steady import COARSEST_FREE_NODES, jfo_film_solution, coarser_mesh, prolonged_cavity
from .jfo_balance import (FilmAdvance, JFOFlows, boundary_values, full_content,
                          cos_integral, transport, film_volumes)

__all__ = ["CompressibleSolve", "CompressibleJFOFilm", "solve_compressible_jfo",
           "compressible_jfo_force", "is_elrod", "check_elrod"]


def is_elrod(lubricant) -> bool:
    """Whether ``lubricant`` asks for the compressible JFO film (it has a bulk modulus)."""
    return isinstance(lubricant, Lubricant) and lubricant.bulk_modulus is not None


def check_elrod(bearing: Bearing, lubricant: Lubricant) -> float:
    """The bulk modulus [Pa] of a lubricant the compressible JFO film takes; ValueError
    for what it does not model (a pressure-viscosity law, another viscosity than the
    bearing's), before any work."""
    if lubricant.barus or lubricant.roelands is not None:
        raise ValueError("the compressible JFO film (cavitation='jfo' with a bulk_modulus) "
                         "takes a constant viscosity: give barus=None and roelands=None")
    if not np.isclose(lubricant.viscosity, bearing.viscosity, rtol=1e-12, atol=0.0):
        raise ValueError(f"lubricant viscosity {lubricant.viscosity!r} Pa s must equal the "
                         f"bearing's {bearing.viscosity!r} Pa s for the compressible JFO film")
    return float(lubricant.bulk_modulus)


@dataclass(frozen=True)
class CompressibleSolve:
    """One solve of the compressible balance on all nodes: pressure P (dimensionless,
    p = mu (R/c)^2 P), film fraction phi in [0, 1], density ratio r = rho/rho0, the
    solver's record and the flows."""

    P: np.ndarray
    phi: np.ndarray
    density: np.ndarray
    result: JFOResult
    flows: JFOFlows


def _beta(bearing: Bearing, bulk_modulus: float) -> float:
    """Elrod's beta: the bulk modulus in the film's pressure unit [1/s]."""
    return bulk_modulus / bearing.pressure_scale


def _balance(bearing: Bearing, op: FilmOperator, eps: float, T: sp.csr_matrix,
             storage: np.ndarray, source: np.ndarray, grooves, ambient: float, beta: float,
             cavitated0=None, warm_iterations: int = 3) -> CompressibleSolve:
    """K Q + T r + storage r = source on the free volumes, r = phi + Q / beta; the fixed
    nodes hold their pressure p (Q = beta (exp(p / B) - 1)) and fraction."""
    mesh = op.mesh
    P_fix, phi_fix = boundary_values(bearing, mesh, grooves, ambient)
    Q_fix = beta * np.expm1(P_fix / beta)
    on_free = np.zeros(mesh.ndofs)
    on_free[mesh.free] = storage[mesh.free]
    # K + A / beta on the free block; its fixed columns carry T Q_fix / beta (the density
    # the held pressure adds) into the right-hand side and the fixed nodes' inflow
    K = (op.stiffness(eps) + (T + sp.diags(on_free)) / beta).tocsr()
    Q, phi, res, inflow = solve_balance(K, T, storage, source, mesh.free, Q_fix, phi_fix,
                                        cavitated0, None, warm_iterations)
    density = phi + Q / beta
    free = mesh.free
    flows = JFOFlows.from_inflow(bearing, mesh, inflow,
                                 storage[free] * density[free] - source[free])
    return CompressibleSolve(beta * np.log1p(Q / beta), phi, density, res, flows)


def _steady(bearing: Bearing, state: JournalState, operator, n_theta: int, n_z: int,
            grooves, ambient: float, beta: float, cavitated0=None):
    """Steady film (line-of-centres frame) on ``operator(n_theta, n_z)``; a cold start
    takes its first set from the same film on a mesh half as fine (recursively)."""
    op = operator(n_theta, n_z)
    cv = film_volumes(op.mesh)
    T = transport(cv, state.eps, state.wedge_speed)
    storage = 12.0 * state.eps_dot * cos_integral(cv)
    warm = 3
    if cavitated0 is None and len(op.mesh.free) > COARSEST_FREE_NODES:
        c, opc = _steady(bearing, state, operator, *coarser_mesh(n_theta, n_z), grooves,
                         ambient, beta)
        cavitated0 = prolonged_cavity(opc, op, c.P, c.phi)
        warm = 12
    try:
        s = _balance(bearing, op, state.eps, T, storage, np.zeros(op.mesh.ndofs), grooves,
                     ambient, beta, cavitated0, warm)
    except ConvergenceError as e:
        raise e.at(f"steady compressible JFO film {n_theta}x{n_z}, "
                   f"eps = {state.eps:.6g}") from None
    return s, op


def _solution(bearing, state, op, s: CompressibleSolve, method: str) -> FilmSolution:
    sol = jfo_film_solution(bearing, state, op, s.P, s.phi, s.result, s.flows, method)
    return replace(sol, density=s.density)


def solve_compressible_jfo(bearing: Bearing, state: JournalState, operator, n_theta: int,
                           n_z: int, bulk_modulus: float, grooves=(),
                           ambient_pressure: float = 0.0) -> FilmSolution:
    """Steady compressible JFO film on ``operator(n_theta, n_z)`` (arguments checked by
    ``solve_reynolds``; ``bulk_modulus`` B [Pa] > 0). ``density`` is rho/rho0 per node."""
    B = check_positive("bulk_modulus", bulk_modulus)
    s, op = _steady(bearing, state, operator, n_theta, n_z, grooves, ambient_pressure,
                    _beta(bearing, B))
    return _solution(bearing, state, op, s, "fem-P1/jfo-compressible")


def compressible_jfo_force(bearing: Bearing, state: JournalState, operator, n_theta: int,
                           n_z: int, bulk_modulus: float, grooves=(),
                           ambient_pressure: float = 0.0):
    """(F_r, F_t) [N] of the steady compressible JFO film and its solve record."""
    B = check_positive("bulk_modulus", bulk_modulus)
    s, op = _steady(bearing, state, operator, n_theta, n_z, grooves, ambient_pressure,
                    _beta(bearing, B))
    ic, is_ = op.force_integrals(s.P)
    k = force_factor(bearing, op.mesh.half)
    return (k * float(ic), k * float(is_)), s.result


class CompressibleJFOFilm(JFOFilm):
    """A transient compressible JFO film: its state is the content r H per control volume
    (r the density ratio). The mesh, its turning with the line of centres and the carry
    of the content, the steps and their cuts are those of :class:`JFOFilm`; each step
    solves the compressible balance by backward Euler on the content.

    Parameters are those of :class:`JFOFilm` and ``bulk_modulus`` B [Pa] > 0. The film
    starts at the density ratio ``fraction`` (1: full at the cavitation pressure).

    Between steps (:meth:`instant`) the kept full film carries the Reynolds film of the
    instant's motion, as in :class:`JFOFilm`, and where the gap has closed below a kept
    cavity's content m the oil is compressed: p = B ln(m / h), capped by the pressure the
    refilled film would give there, rises continuously from zero as the gap closes (no
    refill jump, hence no early film step on a refill: :meth:`refilled` is False).
    """

    def __init__(self, bearing: Bearing, state: JournalState, n_theta: int = 96,
                 n_z: int = 16, *, bulk_modulus: float, grooves=(), supply_angle=None,
                 half: bool = True, fraction=1.0, ambient_pressure: float = 0.0,
                 time: float = 0.0):
        B = check_positive("bulk_modulus", bulk_modulus)
        super().__init__(bearing, state, n_theta, n_z, grooves=grooves,
                         supply_angle=supply_angle, half=half, fraction=fraction,
                         ambient_pressure=ambient_pressure, time=time)
        self.bulk_modulus = B
        self.beta = _beta(bearing, B)
        self.density = self.fraction.copy()

    def _advance(self, state: JournalState, dt: float) -> FilmAdvance:
        op = self._operator(state)
        cv = film_volumes(op.mesh)
        old, = self._carried(cv, state, self.content)
        H = full_content(cv, state.eps)
        s = _balance(self.bearing, op, state.eps, transport(cv, state.eps, state.omega),
                     12.0 * H / dt, 12.0 * old / dt, self.grooves, self.ambient_pressure,
                     self.beta, self.cavitated)
        return FilmAdvance(op, s, s.density * H)

    def _solution(self, state: JournalState, a: FilmAdvance, dt: float) -> FilmSolution:
        return _solution(self.bearing, state, a.op, a.solve, "fem-P1/jfo-compressible")

    def _keep(self, state: JournalState, dt: float) -> FilmSolution:
        sol = super()._keep(state, dt)
        self.density = sol.density
        return sol

    def refilled(self, state: JournalState, time: float | None = None) -> bool:
        """Never: a cavity the gap closes on is compressed (:meth:`instant`), its pressure
        continuous in the state, so no early film step is needed for it."""
        return False

    def instant(self, state: JournalState, warm: np.ndarray | None = None,
                time: float | None = None):
        """The film at ``state`` with the kept film (see the class text): ((F_r, F_t) [N],
        cavitated set for ``warm`` of the next call). ``time`` is the base film's (of its
        fields), which this film does not take."""
        op = self._operator(state)
        mesh = op.mesh
        H = full_content(film_volumes(mesh), state.eps)
        P0, _ = boundary_values(self.bearing, mesh, self.grooves, self.ambient_pressure)
        closed = self.cavitated & (self.content > H)
        closed[mesh.fixed] = False
        full = ~self.cavitated
        # the kept full film with the closed cavities refilled (the incompressible film's
        # refill), then those held at the pressure of their compressed content where that
        # is lower: a refill's pressure rises from zero with the closing gap, the steeper
        # the larger B, and never above the refilled film's
        P = self._reynolds(op, state, P0, full | closed, warm)
        if np.any(closed):
            held = np.minimum(self.beta * np.log(self.content[closed] / H[closed]),
                              P[closed])
            if np.any(held < P[closed]):
                P0[closed] = np.maximum(held, 0.0)
                P = self._reynolds(op, state, P0, full, warm)
        cav = self.cavitated.copy()
        cav[mesh.fixed] = False
        cav[closed] = P[closed] <= 0.0
        keep = mesh.free[full[mesh.free]]
        cav[keep] |= P[keep] <= 0.0
        ic, is_ = op.force_integrals(P)
        k = force_factor(self.bearing, mesh.half)
        return (k * float(ic), k * float(is_)), cav

    @staticmethod
    def _reynolds(op, state, P, solved, warm):
        """Reynolds' condition film of the instant's motion on the free nodes ``solved``
        (a mask on all nodes), the others held at ``P``."""
        P = P.copy()
        K = op.stiffness(state.eps)
        load = op.load(state.eps, state.eps_dot, state.wedge_speed) - K @ P
        keep = op.mesh.free[solved[op.mesh.free]]
        if len(keep) and np.any(load[keep]):
            a0 = None if warm is None else warm[keep]
            P[keep] = active_set(principal_block(K, keep), load[keep], active0=a0).pressure
        return P
