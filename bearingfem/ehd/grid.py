"""The bush's grid and the film's nodes (:mod:`bearingfem.ehd.states`).

The bush's modal deflection lives on a tensor grid fixed in the bush (inertial angles
2 pi j / n_theta, the film's axial nodes); the film's P1 nodes turn with the journal's
angle gamma. Both grids have one spacing, so the film's nodes sit a fraction of a cell
along the bush's: :class:`FrameShift` interpolates between them by two index gathers,
:func:`grid_interpolation` is the general bilinear map it is tested against.
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..caches import cached

__all__ = ["FrameShift", "grid_interpolation", "node_grid"]


def grid_interpolation(alpha: np.ndarray, zeta: np.ndarray, n_theta: int, n_z: int,
                       half_width: float) -> sp.csr_matrix:
    """Bilinear, periodic in alpha, interpolation from the bush's grid (n_theta x (n_z + 1)
    nodes at inertial angles 2 pi j / n_theta, zeta = -h + 2 h k / n_z, flattened in C
    order) to the points (alpha, zeta): a sparse matrix (points x grid)."""
    m = n_z + 1
    u = np.mod(alpha, 2 * np.pi) / (2 * np.pi) * n_theta
    v = np.clip((zeta + half_width) / (2 * half_width) * n_z, 0, n_z)
    j, k = np.floor(u).astype(int), np.minimum(np.floor(v).astype(int), n_z - 1)
    a, b = u - j, v - k
    j0, j1 = j % n_theta, (j + 1) % n_theta
    rows = np.repeat(np.arange(alpha.size), 4)
    cols = np.stack([j0 * m + k, j0 * m + k + 1, j1 * m + k, j1 * m + k + 1], axis=1).ravel()
    vals = np.stack([(1 - a) * (1 - b), (1 - a) * b, a * (1 - b), a * b], axis=1).ravel()
    return sp.csr_matrix((vals, (rows, cols)), shape=(alpha.size, n_theta * m))


@cached(maxsize=16)
def node_grid(mesh) -> np.ndarray:
    """(n_theta, n_z + 1): the periodic P1 film mesh's node at angle index j (theta = j h)
    and axial index k."""
    n, nz = mesh.n_theta, mesh.n_z
    h = 2 * np.pi / n
    lam = mesh.length_ratio
    j = np.rint(np.mod(mesh.theta, 2 * np.pi) / h).astype(int) % n
    k = np.rint((mesh.zeta + lam) / (2 * lam) * nz).astype(int)
    node = np.full((n, nz + 1), -1)
    node[j, k] = np.arange(mesh.theta.size)
    if np.any(node < 0) or mesh.theta.size != node.size:
        raise ValueError("the modal-state film needs a whole periodic P1 mesh")
    return node


class FrameShift:
    """Interpolation between the bush's grid and the film's nodes at journal angle gamma.

    Both are tensor grids of spacing h = 2 pi / n_theta with the same axial nodes; film
    node j sits at the inertial angle j h + gamma + pi, i.e. g = (gamma + pi) / h grid
    cells on: linear interpolation in the angle is a blend of two shifts, (1 - a) by
    floor(g) and a by floor(g) + 1 cells (a = g - floor(g)). Equal to
    :func:`grid_interpolation` at the nodes (tests/test_ehd_states.py), without a sparse
    matrix per state.
    """

    def __init__(self, node: np.ndarray, gamma: float):
        n, m = node.shape
        g = np.mod(gamma + np.pi, 2 * np.pi) / (2 * np.pi) * n
        whole = int(np.floor(g))
        self.frac = g - whole
        j, k = np.arange(n)[:, None], np.arange(m)[None, :]
        # to_nodes: film node (j, k) from grid nodes j + whole and j + whole + 1 (flat)
        self._from0 = np.empty(n * m, int)
        self._from1 = np.empty(n * m, int)
        self._from0[node.ravel()] = (((j + whole) % n) * m + k).ravel()
        self._from1[node.ravel()] = (((j + whole + 1) % n) * m + k).ravel()
        # to_grid: grid node (J, k) from film nodes J - whole and J - whole - 1
        self._to0 = node[(j - whole) % n, k].ravel()
        self._to1 = node[(j - whole - 1) % n, k].ravel()

    def to_nodes(self, G: np.ndarray) -> np.ndarray:
        """Grid values (grid, ...) (C order, angle first) -> film nodal values (nodes, ...)."""
        G = np.asarray(G)
        return (1 - self.frac) * G[self._from0] + self.frac * G[self._from1]

    def matrix(self) -> sp.csr_matrix:
        """:meth:`to_nodes` as a sparse (nodes x grid) matrix (two entries a row)."""
        n = self._from0.size
        rows = np.concatenate([np.arange(n), np.arange(n)])
        vals = np.concatenate([np.full(n, 1 - self.frac), np.full(n, self.frac)])
        return sp.csr_matrix((vals, (rows, np.concatenate([self._from0, self._from1]))),
                             shape=(n, n))

    def to_grid(self, F: np.ndarray) -> np.ndarray:
        """Film nodal values (nodes, ...) -> grid values (grid, ...): to_nodes' transpose."""
        F = np.asarray(F)
        return (1 - self.frac) * F[self._to0] + self.frac * F[self._to1]
