"""The film surface on the bush: the film grid's nodal pressure becomes a traction on the
inner surface, and the bush's radial displacement is read back at the film nodes.

The film grid has ``n_theta`` nodes around (theta_j = 2 pi j / n_theta, periodic) and
``n_z`` nodes along (z_k from -L/2 to L/2, both ends included). A nodal pressure is
interpolated piecewise linearly in theta and in z (tensor-product P1, the film grid's own
interpolation), so the same film field loads every bush mesh that refines the film grid by
an integer factor: refining the bush converges to one answer.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.sparse.linalg import splu
from skfem import Basis, ElementVector, FacetBasis, LinearForm, asm, condense
from skfem import BilinearForm
from skfem.helpers import ddot, div, dot, sym_grad

__all__ = ["FilmGrid", "unit_pressure_response", "elasticity"]


def elasticity(lam: float, mu: float):
    """The isotropic elastic form lambda div u div v + 2 mu eps(u) : eps(v): the one of
    ``skfem.models.elasticity.linear_elasticity`` (same matrix, tested), written without
    its identity tensor, which made the 3-D assembly 1.6 times slower here."""
    @BilinearForm
    def form(u, v, w):
        return lam * div(u) * div(v) + 2.0 * mu * ddot(sym_grad(u), sym_grad(v))
    return form


@dataclass(frozen=True)
class FilmGrid:
    """Film nodes on the bush surface: ``n_theta`` around, ``n_z`` along ``length`` [m]."""

    n_theta: int
    n_z: int
    length: float

    @property
    def angles(self) -> np.ndarray:
        return 2.0 * np.pi * np.arange(self.n_theta) / self.n_theta

    @property
    def heights(self) -> np.ndarray:
        return np.linspace(-0.5 * self.length, 0.5 * self.length, self.n_z)

    def hat(self, x, axial: int | None):
        """The film's nodal shape function of node (theta = 0, z_axial) at points ``x``
        (Cartesian, first axes the coordinates); ``axial=None``: z-independent (2-D)."""
        theta = np.arctan2(x[1], x[0])               # in (-pi, pi]: node 0 sits at 0
        shape = np.maximum(0.0, 1.0 - np.abs(theta) * self.n_theta / (2.0 * np.pi))
        if axial is not None:
            dz = self.length / (self.n_z - 1)
            shape = shape * np.maximum(0.0, 1.0 - np.abs(x[2] - self.heights[axial]) / dz)
        return shape


def unit_pressure_response(bush_mesh, element, lame, film: FilmGrid, axial_loads, held,
                           refine_theta: int, refine_z: int) -> np.ndarray:
    """Radial displacement [m/Pa] at every film node under a unit nodal film pressure at
    (theta = 0, z_k) for each k in ``axial_loads`` (None: the z-independent 2-D load).

    ``held`` maps a node mask to the displacement components held there; one sparse LU of
    the condensed stiffness serves every load. Returns (n_theta, n_z_read, len(loads)).
    """
    mesh = bush_mesh.mesh
    # 2 x 2 (x 2) Gauss points: the full integration of bilinear (trilinear) cells; the
    # default rule of scikit-fem (4 x 4 x 4 in 3-D) costs 8 times more for no gain in order
    basis = Basis(mesh, ElementVector(element), intorder=2)
    stiffness = asm(elasticity(*lame), basis)
    surface = FacetBasis(mesh, ElementVector(element), facets=bush_mesh.inner_facets,
                         intorder=4)

    def load(k):
        # the film pushes the bush outward: traction -p n with n the bush's outward normal
        @LinearForm
        def traction(v, w):
            return -film.hat(w.x, k) * dot(w.n, v)
        return asm(traction, surface)

    rhs = np.column_stack([load(k) for k in axial_loads])
    held_dofs = np.unique(np.concatenate(
        [basis.nodal_dofs[list(comps)][:, mask].ravel() for mask, comps in held]))
    # held dofs are zero, so the condensed right-hand sides are rhs[free]; the minimum
    # degree ordering of K + K^T fills 4x less than scipy's default COLAMD (3-D, measured)
    reduced, _, _, free = condense(stiffness, np.zeros(basis.N), D=held_dofs)
    solution = np.zeros_like(rhs)
    lu = splu(reduced.tocsc(), permc_spec="MMD_AT_PLUS_A")
    solution[free] = lu.solve(np.ascontiguousarray(rhs[free]))
    j = np.arange(film.n_theta) * refine_theta
    n_read = film.n_z if axial_loads[0] is not None else 1
    nodes = bush_mesh.node(0, j[:, None], np.arange(n_read)[None, :] * refine_z)
    theta = film.angles[:, None]
    ux = solution[basis.nodal_dofs[0][nodes]]
    uy = solution[basis.nodal_dofs[1][nodes]]
    return ux * np.cos(theta)[..., None] + uy * np.sin(theta)[..., None]
