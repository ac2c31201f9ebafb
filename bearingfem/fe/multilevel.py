"""Nested iteration for the cavitated film: a good first active set from a coarser mesh.

From a cold start, the active-set method moves the cavitation front by about one node
layer per iteration, so its iteration count grows with the mesh. Solving first on a mesh
half as fine in each direction (recursively, down to a few dozen dofs) and interpolating
that pressure to the fine dofs puts the front within a layer of its place: the fine solve
then takes two or three iterations whatever the mesh, the later ones bordered solves on
the first factors (see :mod:`bearingfem.blocksolve`).

The coarse pressures only place the next level's first set, so each coarse level does one
solve (``COARSE_SOLVES``), started from the level below it; only the coarsest, a dense
system, iterates to convergence.
"""
from __future__ import annotations


import numpy as np
import scipy.sparse as sp

from ..caches import cached
from ..solvers.cavitation import active_set, active_set_iterations
from .assembly import FilmOperator, film_operator
from .mesh import MIN_N_THETA, MIN_N_Z

__all__ = ["prolongation", "free_interpolation", "coarse_shape", "coarse_level", "coarse_guess",
           "descend", "COARSEST_FREE_DOFS", "COARSE_SOLVES"]

#: Below this many free dofs a cold start is cheaper than another level.
COARSEST_FREE_DOFS = 40

#: Solves per coarse level: enough to place the next level's first cavitated set.
COARSE_SOLVES = 1


def _grid(mesh):
    """The (theta, zeta) tensor grid of a P1 mesh and the dof at each grid node."""
    theta, zeta = mesh.theta, mesh.zeta
    if mesh.periodic:
        # the seam's dofs may sit at theta = 2 pi: wrap them to 0
        tkey = np.mod(theta, 2 * np.pi)
        tkey[np.isclose(tkey, 2 * np.pi)] = 0.0
    else:
        tkey = theta
    th_u = np.unique(np.round(tkey, 12))
    ze_u = np.unique(np.round(zeta, 12))
    i = np.searchsorted(th_u, np.round(tkey, 12))
    j = np.searchsorted(ze_u, np.round(zeta, 12))
    dof_at = np.full((len(th_u), len(ze_u)), -1)
    dof_at[i, j] = np.arange(len(theta))
    if (dof_at < 0).any():
        raise ValueError("prolongation needs the vertex dofs of a tensor-product P1 mesh")
    if mesh.periodic:   # close the loop for interpolation across the seam
        th_u = np.append(th_u, th_u[0] + 2 * np.pi)
        dof_at = np.vstack([dof_at, dof_at[:1]])
    return th_u, ze_u, dof_at


def _cell(nodes, x):
    """Index of the grid interval holding x and the local coordinate in it (clipped)."""
    k = np.clip(np.searchsorted(nodes, x, side="right") - 1, 0, len(nodes) - 2)
    s = np.clip((x - nodes[k]) / (nodes[k + 1] - nodes[k]), 0.0, 1.0)
    return k, s


def prolongation(mesh, theta: np.ndarray, zeta: np.ndarray) -> sp.csr_matrix:
    """Sparse bilinear interpolation from the dofs of a P1 ``mesh`` to points (theta, zeta)."""
    th_u, ze_u, dof_at = _grid(mesh)
    t = np.asarray(theta, float)
    if mesh.periodic:
        t = np.mod(t - th_u[0], 2 * np.pi) + th_u[0]
    i, s = _cell(th_u, t)
    j, u = _cell(ze_u, np.asarray(zeta, float))
    rows = np.repeat(np.arange(len(t)), 4)
    cols = np.column_stack([dof_at[i, j], dof_at[i + 1, j], dof_at[i, j + 1],
                            dof_at[i + 1, j + 1]]).ravel()
    vals = np.column_stack([(1 - s) * (1 - u), s * (1 - u), (1 - s) * u, s * u]).ravel()
    return sp.csr_matrix((vals, (rows, cols)), shape=(len(t), len(mesh.theta)))


def free_interpolation(P: sp.csr_matrix, free: np.ndarray) -> sp.csr_matrix:
    """The interpolation ``P`` (fine points x coarse nodes) from the coarse ``free`` nodes
    alone, each row's weights renormalised (rows with no free coarse node kept as they
    are). A field that is of another kind on the held nodes (a cavity's -(1 - phi) inside,
    the ambient pressure on the ends) then is not mixed with them: interpolated, a coarse
    cavity next to an end would lose the fine rows between (measured: a 240x2 coarse
    cavity of 65 nodes gave 129 of the 268 cavitated nodes on 480x4)."""
    keep = np.zeros(P.shape[1])
    keep[free] = 1.0
    Q = sp.csr_matrix(P @ sp.diags(keep))
    total = np.asarray(Q.sum(axis=1)).ravel()
    ok = total > 0.0
    scale = np.where(ok, 1.0 / np.where(ok, total, 1.0), 0.0)
    return sp.csr_matrix(sp.diags(scale) @ Q + sp.diags((~ok).astype(float)) @ P)


def coarse_shape(mesh) -> tuple[int, int] | None:
    """(n_theta, n_z) of the P1 mesh half as fine as ``mesh`` (a :class:`FilmMesh`), or None
    when ``mesh`` is coarse enough for a cold start.

    A direction whose cells are over twice as long as the other's is not coarsened
    (semi-coarsening): on a mesh of long thin cells the coarse film must keep what
    resolves it (3840x4 halved to 1920x2 lost the side leakage of the cavity's rows: a
    third fewer cavitated nodes, too far for the fine iterations to recover)."""
    m = mesh
    if len(m.free) <= COARSEST_FREE_DOFS:
        return None
    h_theta = 2.0 * np.pi / m.n_theta
    h_z = float(np.ptp(m.zeta)) / m.n_z
    n_theta = max(MIN_N_THETA, m.n_theta // 2 if h_theta <= 2.0 * h_z else m.n_theta)
    n_z = max(MIN_N_Z, m.n_z // 2 if h_z <= 2.0 * h_theta else m.n_z)
    return n_theta, n_z


@cached(maxsize=32)
def coarse_level(op: FilmOperator) -> tuple[FilmOperator, sp.csr_matrix] | None:
    """The P1 operator on a mesh half as fine as ``op``'s (:func:`coarse_shape`) and the
    interpolation from its dofs to ``op``'s free dofs; None when ``op`` is coarse enough
    for a cold start."""
    m = op.mesh
    shape = coarse_shape(m)
    if shape is None:
        return None
    coarse = film_operator(*shape, "P1", m.length_ratio, m.theta0, m.half, m.arcs,
                           m.grading)
    if coarse.mesh.ndofs >= m.ndofs:   # already at the coarsest mesh
        return None
    return coarse, prolongation(coarse.mesh, m.theta[m.free], m.zeta[m.free])


def descend(op: FilmOperator, film, tol: float = 1e-10,
            held: tuple = ()) -> np.ndarray | None:
    """Cavitated pressure of ``film`` on the coarser levels of ``op``, interpolated to
    ``op``'s free dofs (None when ``op`` is itself the coarsest level). ``film(level)``
    gives a level's load, its free block and a callable for its whole matrix (the
    grooves' coupling, called only with ``held``); ``held``: the dimensionless pressure of
    each groove of the mesh (held on its dofs at every level)."""
    level = coarse_level(op)
    if level is None:
        return None
    coarse, prolong = level
    free = coarse.mesh.free
    P = np.zeros(coarse.mesh.ndofs)
    for dofs, p in zip(coarse.mesh.grooves, held):
        P[dofs] = p
    b, K, whole = film(coarse)
    if held:
        b = b - whole() @ P
    P0 = descend(coarse, film, tol, held)
    # the coarsest level is solved (it raises if it cannot), the others only iterated
    res = (active_set(K, b[free], tol=tol) if P0 is None else
           active_set_iterations(K, b[free], P0=P0, tol=tol, max_iter=COARSE_SOLVES))
    P[free] = res.pressure
    return prolong @ P


def coarse_guess(op: FilmOperator, state, tol: float = 1e-10,
                 held: tuple = ()) -> np.ndarray | None:
    """:func:`descend` with the rigid film of ``state`` (a JournalState) on each level."""
    return descend(op, lambda level: (
        level.load(state.eps, state.eps_dot, state.wedge_speed),
        level.free_stiffness(state.eps), lambda: level.stiffness(state.eps)), tol, held)
