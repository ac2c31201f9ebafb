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

__all__ = ["FilmGrid", "BushSystem", "bush_system", "unit_pressure_response", "elasticity"]


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

    def interpolate(self, pressure, x) -> np.ndarray:
        """The nodal film pressure (n_theta, n_z) [Pa] at Cartesian points ``x`` (3-D):
        linear in theta (periodic) and in z between nodes, i.e. Sum of nodal values times
        the :meth:`hat` functions."""
        t = np.mod(np.arctan2(x[1], x[0]), 2.0 * np.pi) * self.n_theta / (2.0 * np.pi)
        j = np.floor(t).astype(int)
        s = (x[2] + 0.5 * self.length) * (self.n_z - 1) / self.length
        k = np.clip(np.floor(s).astype(int), 0, self.n_z - 2)
        t, s = t - j, s - k
        j0, j1 = j % self.n_theta, (j + 1) % self.n_theta
        return ((1 - t) * ((1 - s) * pressure[j0, k] + s * pressure[j0, k + 1])
                + t * ((1 - s) * pressure[j1, k] + s * pressure[j1, k + 1]))


@dataclass(frozen=True, eq=False)
class BushSystem:
    """A bush mesh with its condensed stiffness factorised once (sparse LU).

    Attributes
    ----------
    bush_mesh : :class:`~.mesh.BushMesh`
    basis : vector scikit-fem basis on the bush; surface : its ``FacetBasis`` on the
        inner surface (the film side)
    free : dofs not held; lu : ``splu`` of the stiffness on them
    """

    bush_mesh: object
    basis: object
    surface: object
    free: np.ndarray
    lu: object

    def solve(self, pressures) -> np.ndarray:
        """Displacement dofs [m] (N, len(pressures)) under each film pressure, given as a
        function of the Cartesian points x returning the pressure [Pa] there."""
        def load(pressure):
            # the film pushes the bush outward: traction -p n, n the bush's outward normal
            @LinearForm
            def traction(v, w):
                return -pressure(w.x) * dot(w.n, v)
            return asm(traction, self.surface)

        rhs = np.column_stack([load(p) for p in pressures])
        solution = np.zeros_like(rhs)
        solution[self.free] = self.lu.solve(np.ascontiguousarray(rhs[self.free]))
        return solution

    def radial(self, solution, nodes, theta) -> np.ndarray:
        """u . e_r [m] at ``nodes`` (at angles ``theta``), one column per solution."""
        ux = solution[self.basis.nodal_dofs[0][nodes]]
        uy = solution[self.basis.nodal_dofs[1][nodes]]
        return ux * np.cos(theta)[..., None] + uy * np.sin(theta)[..., None]


def bush_system(bush_mesh, element, lame, held) -> BushSystem:
    """Assemble and factorise the bush's stiffness; ``held`` lists (node mask, components)
    pairs of displacement components held at zero."""
    mesh = bush_mesh.mesh
    # 2 x 2 (x 2) Gauss points: the full integration of bilinear (trilinear) cells; the
    # default rule of scikit-fem (4 x 4 x 4 in 3-D) costs 8 times more for no gain in order
    basis = Basis(mesh, ElementVector(element), intorder=2)
    stiffness = asm(elasticity(*lame), basis)
    surface = FacetBasis(mesh, ElementVector(element), facets=bush_mesh.inner_facets,
                         intorder=4)
    held_dofs = np.unique(np.concatenate(
        [basis.nodal_dofs[list(comps)][:, mask].ravel() for mask, comps in held]))
    # held dofs are zero, so a condensed right-hand side is rhs[free]; the minimum degree
    # ordering of K + K^T fills 4x less than scipy's default COLAMD (3-D, measured)
    reduced, _, _, free = condense(stiffness, np.zeros(basis.N), D=held_dofs)
    return BushSystem(bush_mesh, basis, surface, free,
                      splu(reduced.tocsc(), permc_spec="MMD_AT_PLUS_A"))


def unit_pressure_response(system: BushSystem, film: FilmGrid, axial_loads,
                           refine_theta: int, refine_z: int) -> np.ndarray:
    """Radial displacement [m/Pa] at every film node under a unit nodal film pressure at
    (theta = 0, z_k) for each k in ``axial_loads`` (None: the z-independent 2-D load).
    Returns (n_theta, n_z_read, len(loads))."""
    solution = system.solve([lambda x, k=k: film.hat(x, k) for k in axial_loads])
    j = np.arange(film.n_theta) * refine_theta
    n_read = film.n_z if axial_loads[0] is not None else 1
    nodes = system.bush_mesh.node(0, j[:, None], np.arange(n_read)[None, :] * refine_z)
    return system.radial(solution, nodes, film.angles[:, None])
