"""The bush's compliance on the film's dofs: the deflection w = C p of a nodal pressure.

The full compliance of an axisymmetric bush is circulant in theta: per theta harmonic one
(n_z + 1) x (n_z + 1) block, diagonal for the ring and one number per node for the liner.
:class:`CirculantCompliance` applies it by FFT without the dense matrix, and
:class:`BushJacobian` the film Jacobian's bush part T_H C with it (cost N log N, memory
linear); a reduced (modal) compliance is :class:`DofCompliance`, its factors read at the
dofs. :func:`dof_compliance` gives the one a bush takes on a film mesh
(:mod:`bearingfem.ehd.coupling` couples it to the film).
"""
from __future__ import annotations

import logging
import time
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp
from scipy.fft import irfft, rfft

from ..caches import cached
from ..elastic import BushCompliance, ElasticBush, ReducedCompliance, bush_compliance
from ..elastic.harmonic import HarmonicBlocks

#: the bush's compliance build, told at INFO (the command line shows it): a 3-D solid's
#: takes tens of seconds, which passed in silence before the first Newton step's line
LOG = logging.getLogger(__name__)

__all__ = ["dof_compliance", "DofCompliance", "CirculantCompliance", "BushJacobian"]


@dataclass(frozen=True, eq=False)
class DofCompliance:
    """The compliance on the film's dofs, C = left diag(s) right^T [m/Pa] (dense: left is
    the full matrix, right None)."""

    left: np.ndarray
    singular: np.ndarray | None = None
    right: np.ndarray | None = None

    def apply(self, p: np.ndarray) -> np.ndarray:
        if self.right is None:
            return self.left @ p
        return self.left @ (self.singular * (self.right.T @ p))


@dataclass(frozen=True, eq=False)
class CirculantCompliance:
    """The full compliance on the film's dofs, applied per theta harmonic by FFT: the
    pressure is read on the (n_theta, n_z + 1) bush grid (one dof per grid node,
    ``source``), each harmonic m multiplied by its real block ((n_z + 1)^2,
    :class:`~bearingfem.elastic.harmonic.HarmonicBlocks`, banded in z where the bush's
    kernel is local; or its diagonal (n_z + 1) where the slices do not couple: the ring; a
    local compliance, the liner's, is one factor per axial node, applied without FFT), and
    the deflection read back at every dof (``node``: its grid node). Cost per product
    n_theta log n_theta (n_z + 1) plus the blocks' numbers (at most n_theta (n_z + 1)^2 / 2;
    n_theta (n_z + 1) diagonal); no dense matrix unless :attr:`left` is asked for."""

    spectrum: HarmonicBlocks | np.ndarray  # blocks; (M, nz) diagonal or (nz,) local
    shape: tuple              # (n_theta, nz)
    node: np.ndarray          # grid node of each dof (C order of the grid)
    source: np.ndarray        # the dof whose pressure each grid node takes
    singular = None
    right = None

    def apply(self, p: np.ndarray) -> np.ndarray:
        """Nodal deflection [m] under nodal pressure ``p`` [Pa] (dofs; or (dofs, k))."""
        return self.on_grid(np.asarray(p, float)[self.source])[self.node]

    def on_grid(self, p: np.ndarray) -> np.ndarray:
        """The deflection at the grid nodes [m] under the grid nodes' pressure [Pa]
        (C order of the grid; or (grid nodes, k))."""
        extra = p.shape[1:]
        grid = p.reshape(self.shape + extra)
        if isinstance(self.spectrum, HarmonicBlocks):
            harmonics = self.spectrum.apply(rfft(grid, axis=0))
        elif self.spectrum.ndim == 1:        # local: each node's own compliance
            return (self.spectrum.reshape((-1,) + (1,) * len(extra)) * grid).reshape(p.shape)
        else:
            harmonics = self.spectrum.reshape(self.spectrum.shape + (1,) * len(extra)) \
                * rfft(grid, axis=0)
        return irfft(harmonics, n=self.shape[0], axis=0).reshape((-1,) + extra)

    @cached_property
    def left(self) -> np.ndarray:
        """The dense (dofs, dofs) matrix [m/Pa] (the routes that still take the dense
        compliance: the summits' contact, :mod:`.asperity`); built once, on demand."""
        n = self.node.size
        C = np.zeros((n, n))
        C[:, self.source] = self.on_grid(np.eye(self.source.size))[self.node]
        return C


@dataclass(frozen=True, eq=False)
class BushJacobian:
    """The bush's part of dR/dP, T_H C, applied matrix-free: ``coupling`` (sparse, dofs x
    dofs) the residual's derivative in the nodal deflection [1/m scaled], C the circulant
    compliance."""

    coupling: sp.spmatrix
    compliance: CirculantCompliance
    #: (U_k, V_k) (dofs, k): a low-rank part U_k V_k^T of T_H C that the Newton step's
    #: preconditioner adds to the sparse part by Woodbury (None: the sparse part alone)
    low_rank: tuple | None = None
    #: GMRES's relative residual for the Newton step (None: the newton module's
    #: KRYLOV_TOL, the direct solve's step to round-off); a looser one makes an inexact
    #: Newton (Dembo, Eisenstat & Steihaug, SIAM J. Numer. Anal. 19 (1982) 400-408),
    #: converged by the same residual test
    tolerance: float | None = None

    def apply(self, x: np.ndarray) -> np.ndarray:
        """T_H C x (x on the dofs, or (dofs, k))."""
        return self.coupling @ self.compliance.apply(x)

    __matmul__ = apply

    def toarray(self) -> np.ndarray:
        """The dense matrix (checks on small meshes; never in a solve)."""
        return np.asarray(self.coupling @ self.compliance.left)

    def __array__(self, dtype=None, copy=None):
        return self.toarray() if dtype is None else self.toarray().astype(dtype)

    def local(self) -> np.ndarray | None:
        """Each dof's own compliance [m/Pa] where C is local and takes every dof's own
        pressure (the liner without a supply line's seam): T_H C is then the sparse T_H
        with its columns scaled by it. None otherwise."""
        c = self.compliance
        spectrum = getattr(c, "spectrum", None)       # a grid's compliance has none
        if not (isinstance(spectrum, np.ndarray) and spectrum.ndim == 1):
            return None
        if not np.array_equal(c.source[c.node], np.arange(c.node.size)):
            return None
        return c.spectrum[c.node % c.shape[1]]

    def plus(self, coupling) -> "BushJacobian":
        """T_H C + coupling C (another sparse derivative in the deflection)."""
        return BushJacobian(self.coupling + coupling, self.compliance, self.low_rank,
                            self.tolerance)


@cached(maxsize=8)
def _cached_compliance(bush: ElasticBush, radius: float, length: float, n_theta: int,
                       n_z: int) -> BushCompliance:
    LOG.info("bush %s: building its compliance on %d x %d film nodes", bush.model, n_theta,
             n_z)
    t0 = time.perf_counter()
    compliance = bush_compliance(bush, radius, length, n_theta, n_z)
    LOG.info("bush %s: compliance built in %.1f s", bush.model, time.perf_counter() - t0)
    return compliance


def dof_compliance(bush, bearing, op) -> CirculantCompliance | DofCompliance:
    """The bush's compliance between the film mesh's P1 dofs (grid node (j, k) of the
    compliance at theta = theta_start + 2 pi j / n_theta, z = -L/2 + k L / n_z).

    ``bush`` is an :class:`ElasticBush` (its full compliance is built, cached) or a
    prebuilt :class:`BushCompliance` / :class:`ReducedCompliance` on the (n_theta,
    n_z + 1) grid. The compliance is circulant in theta, so a grid starting at any film
    angle (the journal's attitude) uses the same columns. Where a supply line closes the
    film, its two seam dofs are one grid node: the deflection is read at both, the pressure
    taken from one.
    """
    mesh = op.mesh
    shape = (mesh.n_theta, mesh.n_z + 1)
    if isinstance(bush, ElasticBush):
        bush = _cached_compliance(bush, bearing.radius, bearing.length, *shape)
    elif not isinstance(bush, (BushCompliance, ReducedCompliance)):
        raise ValueError(f"bush must be an ElasticBush, BushCompliance or ReducedCompliance, "
                         f"got {type(bush).__name__}")
    if tuple(bush.shape) != shape:
        raise ValueError(f"bush compliance must be on the film grid {shape} (n_theta, n_z + 1)"
                         f", got {tuple(bush.shape)}")
    if isinstance(bush, BushCompliance) and not (
            np.isclose(bush.radius, bearing.radius) and np.isclose(bush.length, bearing.length)):
        raise ValueError(f"bush compliance built for R={bush.radius}, L={bush.length} [m], "
                         f"the bearing has R={bearing.radius}, L={bearing.length}")
    start = 0.0 if mesh.theta0 is None else mesh.theta0
    h = 2.0 * np.pi / mesh.n_theta
    j = np.rint((mesh.theta - start) / h).astype(int) % mesh.n_theta
    k = np.rint((mesh.zeta + mesh.length_ratio) / (2 * mesh.length_ratio) * mesh.n_z)
    node = j * shape[1] + k.astype(int)
    grid_nodes, rep = np.unique(node, return_index=True)
    if grid_nodes.size != shape[0] * shape[1]:
        raise ValueError("the bush needs the whole-length P1 film mesh")
    if isinstance(bush, BushCompliance):
        # slices uncoupled (the columns' diagonals alone stored), and nothing at j > 0
        # either: local. No complex spectrum of the whole (n_theta, nz, nz) is made for a
        # ring or a liner
        if bush.uncoupled:
            diagonal = bush.stored
            if not np.any(diagonal[1:]):
                return CirculantCompliance(diagonal[0].copy(), shape, node, rep)  # liner
            return CirculantCompliance(np.fft.rfft(diagonal, axis=0), shape, node,
                                       rep)                                        # ring
        return CirculantCompliance(bush.blocks, shape, node, rep)
    right = np.zeros((mesh.ndofs, bush.n_vectors))
    right[rep] = bush.right[grid_nodes]
    return DofCompliance(bush.left[node], bush.singular, right)
