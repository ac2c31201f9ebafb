"""The JFO balance on the finite-element film mesh: control volumes, content, transport,
held boundary values and one solve of the balance (steady or one backward-Euler step),
for :mod:`bearingfem.fe.jfo`.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..bearing import Bearing, JournalState
from ..caches import cached
from ..errors import ConvergenceError
from ..film import film_thickness, film_thickness_integral
from ..scales import flow_factor
from ..solvers.cavitation import active_set
from ..solvers.jfo import FirstSet, JFOResult, solve_balance
from ..solvers.linsolve import principal_block
from .assembly import FilmOperator
from .mesh import FilmMesh
from .multilevel import coarse_level, free_interpolation, prolongation
from .volumes import ControlVolumes, control_volumes, transport_matrix

__all__ = ["film_volumes", "JFOFlows", "BalanceSolve", "FilmAdvance", "kept_set_pressure",
           "JFO_AMBIENT"]

#: Oil around the film at atmospheric pressure [Pa], the cavity near zero absolute: the
#: default supply of the JFO models (they need one; grooves add to it).
JFO_AMBIENT = 1e5


@cached(maxsize=32)
def film_volumes(mesh: FilmMesh) -> ControlVolumes:
    """Control volumes of the nodes of a P1 film mesh (theta is the sliding direction)."""
    th, ze = mesh.axes
    return control_volumes(mesh.theta, mesh.zeta, th, ze, mesh.periodic)


def full_content(cv: ControlVolumes, eps: float) -> np.ndarray:
    """Exact integral of H over each volume (its content when full)."""
    return cv.width * film_thickness_integral(cv.x_lo, cv.x_hi, eps)


def cos_integral(cv: ControlVolumes) -> np.ndarray:
    """Integral of cos(theta) = dH/d(eps) over each volume: a squeeze's storage rate."""
    return cv.width * film_thickness_integral(cv.x_lo, cv.x_hi, 1.0) - cv.area


def transport(cv: ControlVolumes, eps: float, speed: float) -> sp.csr_matrix:
    """Upwind transport of 6 x speed x phi H across the volumes' theta faces."""
    return transport_matrix(cv, 6.0 * speed * film_thickness(cv.face, eps) * cv.width)


@dataclass(frozen=True)
class JFOFlows:
    """Volume flows of one solve [m^3/s]: fed by grooves / supply line, out of the axial
    ends (net; and ``side_outflow``, what leaves alone), and the rate of change of the film
    content; balance = feed - leakage - storage (zero to round-off)."""

    flow_in: float
    side_leakage: float
    storage: float
    #: out of the ends where the film leaves them, not less what enters elsewhere (a film
    #: fed at its ends draws oil in where it is cavitated and loses it where it is not)
    side_outflow: float | None = None

    @property
    def balance(self) -> float:
        return self.flow_in - self.side_leakage - self.storage

    @classmethod
    def from_inflow(cls, bearing: Bearing, mesh, inflow: np.ndarray,
                    content_rate: np.ndarray) -> "JFOFlows":
        """The flows of a balance solve from its dimensionless nodal ``inflow`` (what each
        held node takes in): the feed through the held nodes other than the ends (supply
        line, grooves), the leakage out of the ends, and the film's rate of change summed
        over ``content_rate`` (per free node, dimensionless)."""
        feed = np.setdiff1d(mesh.fixed, mesh.end)
        k = flow_factor(bearing, mesh.half)
        return cls(flow_in=-k * float(np.sum(inflow[feed])),
                   side_leakage=k * float(np.sum(inflow[mesh.end])),
                   storage=k * float(np.sum(content_rate)),
                   side_outflow=k * float(np.sum(np.maximum(inflow[mesh.end], 0.0))))


@dataclass(frozen=True)
class BalanceSolve:
    """One solve of the balance: pressure P and film fraction phi on all nodes, the
    solver's record and the flows."""

    P: np.ndarray
    phi: np.ndarray
    result: JFOResult
    flows: JFOFlows


@dataclass(frozen=True)
class FilmAdvance:
    """One backward-Euler step of the content: the mesh operator at the new state, the
    balance solved there and the new content (dimensionless, per volume)."""

    op: FilmOperator
    solve: BalanceSolve
    content: np.ndarray


def boundary_values(bearing: Bearing, mesh: FilmMesh, grooves, ambient: float):
    """Pressure and film fraction held on the fixed nodes: the ends and a supply line at
    ``ambient`` (flooded), each groove at its pressure and fraction."""
    P = np.zeros(mesh.ndofs)
    phi = np.ones(mesh.ndofs)
    P[mesh.fixed] = ambient / bearing.pressure_scale
    for g, dofs in zip(grooves, mesh.grooves):
        P[dofs] = g.pressure / bearing.pressure_scale
        phi[dofs] = g.fraction
    P[mesh.end] = ambient / bearing.pressure_scale
    phi[mesh.end] = 1.0
    return P, phi


def kept_set_pressure(K: sp.csr_matrix, load: np.ndarray, P: np.ndarray, mesh: FilmMesh,
                      cavitated: np.ndarray, warm: np.ndarray | None):
    """The instant film of a kept JFO film: Reynolds' film of this instant's motion on the
    volumes full at the kept step (held values ``P`` on the fixed nodes), the others
    cavities at zero pressure. ``warm``: the last call's cavitated set. Returns (P, the
    cavitated set on all nodes); ``P`` is filled in place."""
    load = load - K @ P
    full = ~cavitated
    keep = mesh.free[full[mesh.free]]
    if len(keep) and np.any(load[keep]):
        a0 = None if warm is None else warm[keep]
        P[keep] = active_set(principal_block(K, keep), load[keep], active0=a0).pressure
    cav = ~full
    cav[mesh.fixed] = False
    cav[keep] |= P[keep] <= 0.0
    return P, cav


def solve_film_balance(bearing: Bearing, op: FilmOperator, eps: float, T: sp.csr_matrix,
           storage: np.ndarray, source: np.ndarray, grooves, ambient: float,
           cavitated0=None, warm_iterations: int = 3, start=None,
           values: np.ndarray | None = None) -> BalanceSolve:
    """The balance on the film mesh with its ends, supply line and grooves held (P and phi
    on all nodes). ``start``: see :func:`~bearingfem.solvers.jfo.jfo_solve`; ``values``:
    the Poiseuille stiffness on the operator's pattern (None: the rigid cylinder's of
    ``eps``)."""
    mesh = op.mesh
    P_fix, phi_fix = boundary_values(bearing, mesh, grooves, ambient)
    if values is None:
        values = op.values(eps)
    K = sp.csr_matrix((values, op.indices, op.indptr), shape=op.shape)
    P, phi, res, inflow = solve_balance(K, T, storage, source, mesh.free,
                                        P_fix, phi_fix, cavitated0,
                                        op.free_stiffness(eps, values), warm_iterations,
                                        start)
    free = mesh.free
    flows = JFOFlows.from_inflow(bearing, mesh, inflow,
                                 storage[free] * phi[free] - source[free])
    return BalanceSolve(P, phi, res, flows)


@cached(maxsize=32)
def mesh_prolongation(coarse: FilmMesh, fine: FilmMesh) -> sp.csr_matrix:
    return prolongation(coarse, fine.theta, fine.zeta)


def state_between(a: JournalState, b: JournalState) -> JournalState:
    """The journal state half way from ``a`` to ``b`` (linear; the attitude the short way)."""
    turn = float(np.mod(b.gamma - a.gamma + np.pi, 2.0 * np.pi) - np.pi)
    return JournalState(eps=0.5 * (a.eps + b.eps), eps_dot=0.5 * (a.eps_dot + b.eps_dot),
                        gamma=a.gamma + 0.5 * turn, gamma_dot=0.5 * (a.gamma_dot + b.gamma_dot),
                        omega=0.5 * (a.omega + b.omega))


def step_balance(bearing: Bearing, op: FilmOperator, state: JournalState, dt: float,
                  old: np.ndarray, cavitated: np.ndarray, grooves,
                  ambient: float, film=None) -> FilmAdvance:
    """One backward-Euler step of the content on ``op``'s mesh from the content ``old``
    (per volume) and the first set ``cavitated`` (both on that mesh's nodes, the set may
    be None). When that set does not settle or there is none, the first set comes from the same step on a mesh half as fine
    (recursively, :func:`~bearingfem.fe.multilevel.coarse_level`): a front that jumps many
    cells in one step is then placed within a cell or two whatever the mesh, where the
    active set alone moves it about a cell per iteration. ``film``: a function of the
    operator giving its :class:`~bearingfem.fe.jfo_fields.BalanceFilm` at ``state`` (None:
    the rigid cylinder's)."""
    cv = film_volumes(op.mesh)
    f = None if film is None else film(op)
    T = transport(cv, state.eps, state.omega) if f is None else f.transport(cv, state.omega)
    H = full_content(cv, state.eps) if f is None else f.content
    level = coarse_level(op)
    start = None
    if level is not None:
        coarse = level[0]

        def start():
            down = mesh_prolongation(op.mesh, coarse.mesh)
            up = free_interpolation(mesh_prolongation(coarse.mesh, op.mesh), coarse.mesh.free)
            Hc = (full_content(film_volumes(coarse.mesh), state.eps) if film is None
                  else film(coarse).content)
            try:
                # no first set there: the previous one already failed on this mesh
                b = step_balance(bearing, coarse, state, dt, (down @ (old / H)) * Hc,
                                  None, grooves, ambient, film).solve
            except ConvergenceError:
                return None
            return FirstSet(up @ (b.P - (1.0 - b.phi)) < 0.0, b.result.iterations,
                            b.result.factorisations)
    b = solve_film_balance(bearing, op, state.eps, T, 12.0 * H / dt, 12.0 * old / dt,
                           grooves, ambient, cavitated, start=start,
                           values=None if f is None else f.values)
    return FilmAdvance(op, b, b.phi * H)
