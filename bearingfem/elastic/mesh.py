"""Structured meshes of the bush: an annulus of quadrilaterals (the plane-strain ring) and
a hollow cylinder of hexahedra (the solid), both built by scikit-fem's ``init_tensor`` in
cylindrical coordinates (r, theta, z), mapped to Cartesian and closed at the theta seam.

Every mesh is invariant under a turn by one cell in theta: the discrete bush is exactly
axisymmetric, which makes its surface compliance circulant (see :mod:`.compliance`).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from skfem import MeshHex1, MeshQuad1

__all__ = ["BushMesh", "annulus_mesh", "cylinder_mesh", "radial_lines"]


def radial_lines(inner: float, outer: float, n_radial: int, grading: float) -> np.ndarray:
    """Radii [m] of the cell layers: r(s) = inner + (outer - inner)(e^(g s) - 1)/(e^g - 1)
    at s = 0, 1/n, ..., 1 with g = ln(grading), so cells grow smoothly outward to
    ``grading`` times the inner one (the load is on the inner surface; a smooth map keeps
    the elements' order under uniform refinement)."""
    s = np.linspace(0.0, 1.0, n_radial + 1)
    g = np.log(grading)
    return inner + (outer - inner) * (s if g == 0.0 else np.expm1(g * s) / np.expm1(g))


@dataclass(frozen=True, eq=False)
class BushMesh:
    """A bush mesh with its nodes' grid indices.

    Attributes
    ----------
    mesh : scikit-fem ``MeshQuad1`` (ring) or ``MeshHex1`` (solid), Cartesian [m]
    radial, angular, axial : per node, its index along r (0 on the inner surface), theta
        (0..n_theta - 1) and z (0 in 2-D)
    radii, angles, heights : the grid lines [m], [rad], [m] (``heights`` empty in 2-D)
    """

    mesh: object
    radial: np.ndarray
    angular: np.ndarray
    axial: np.ndarray
    radii: np.ndarray
    angles: np.ndarray
    heights: np.ndarray

    @property
    def inner_facets(self) -> np.ndarray:
        """Boundary facets whose nodes all lie on the inner surface r = radii[0]."""
        facets = self.mesh.boundary_facets()
        on_inner = np.all(self.radial[self.mesh.facets[:, facets]] == 0, axis=0)
        return facets[on_inner]

    def node(self, radial: int, angular, axial) -> np.ndarray:
        """Node numbers at grid indices (broadcast)."""
        n_theta = self.angles.size
        n_z = max(self.heights.size, 1)
        return (np.asarray(radial) * n_theta * n_z + np.asarray(angular) % n_theta * n_z
                + np.asarray(axial))


def _closed(points_param, cells, axes, mesh_type, mapping):
    """Map the (r, theta[, z]) box mesh to Cartesian, merging the theta = 2 pi nodes onto
    theta = 0, and renumber nodes as radial-major, then angular, then axial."""
    idx = [np.searchsorted(ax, x) for ax, x in zip(axes, points_param)]
    n_theta = axes[1].size - 1
    idx[1] = idx[1] % n_theta                       # the seam: 2 pi is 0
    n_z = axes[2].size if len(axes) == 3 else 1
    iz = idx[2] if len(axes) == 3 else np.zeros_like(idx[0])
    number = idx[0] * n_theta * n_z + idx[1] * n_z + iz
    n_nodes = axes[0].size * n_theta * n_z
    r, th, z = np.meshgrid(axes[0], axes[1][:-1], axes[2] if n_z > 1 else [0.0],
                           indexing="ij")
    coords = mapping(r.ravel(), th.ravel(), z.ravel())
    grid = np.meshgrid(np.arange(axes[0].size), np.arange(n_theta), np.arange(n_z),
                       indexing="ij")
    mesh = mesh_type(coords, number[cells])
    assert mesh.p.shape[1] == n_nodes
    return mesh, [g.ravel() for g in grid]


def annulus_mesh(inner: float, outer: float, n_theta: int, n_radial: int,
                 grading: float = 1.0) -> BushMesh:
    """Quadrilaterals on inner <= r <= outer [m], n_theta cells around, n_radial across."""
    radii = radial_lines(inner, outer, n_radial, grading)
    angles = np.linspace(0.0, 2.0 * np.pi, n_theta + 1)
    box = MeshQuad1.init_tensor(radii, angles)
    mesh, (ir, it, iz) = _closed(box.p, box.t, (radii, angles), MeshQuad1,
                                 lambda r, t, z: np.array([r * np.cos(t), r * np.sin(t)]))
    return BushMesh(mesh, ir, it, iz, radii, angles[:-1], np.array([]))


def cylinder_mesh(inner: float, outer: float, length: float, n_theta: int, n_radial: int,
                  n_axial: int, grading: float = 1.0) -> BushMesh:
    """Hexahedra on inner <= r <= outer, -length/2 <= z <= length/2 [m]."""
    radii = radial_lines(inner, outer, n_radial, grading)
    angles = np.linspace(0.0, 2.0 * np.pi, n_theta + 1)
    heights = np.linspace(-0.5 * length, 0.5 * length, n_axial + 1)
    box = MeshHex1.init_tensor(radii, angles, heights)
    mesh, (ir, it, iz) = _closed(
        box.p, box.t, (radii, angles, heights), MeshHex1,
        lambda r, t, z: np.array([r * np.cos(t), r * np.sin(t), z]))
    return BushMesh(mesh, ir, it, iz, radii, angles[:-1], heights)
