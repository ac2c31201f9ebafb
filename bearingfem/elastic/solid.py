"""The solid bush: a hollow cylinder of trilinear hexahedra, outer surface held (all three
displacement components: a press fit does not slide), end faces free or held axially."""
from __future__ import annotations

import numpy as np
from skfem import ElementHex1

from .mesh import cylinder_mesh
from .surface import BushSystem, FilmGrid, bush_system, unit_pressure_response

__all__ = ["solid_system", "solid_columns"]


def solid_system(bush, radius: float, film: FilmGrid, refine_theta: int, refine_z: int,
                 n_radial: int, grading: float) -> BushSystem:
    """The solid's mesh (film nodes on its inner surface) and factorised stiffness."""
    solid = cylinder_mesh(radius, bush.outer_radius, film.length,
                          film.n_theta * refine_theta, n_radial, (film.n_z - 1) * refine_z,
                          grading)
    held = [(solid.radial == solid.radii.size - 1, (0, 1, 2))]
    if bush.ends == "plane-strain":
        ends = (solid.axial == 0) | (solid.axial == solid.heights.size - 1)
        held.append((ends, (2,)))
    return bush_system(solid, ElementHex1(), bush.lame, held)


def solid_columns(system: BushSystem, film: FilmGrid, refine_theta: int,
                  refine_z: int) -> np.ndarray:
    """Compliance columns (n_theta, n_z, n_z) [m/Pa]: radial deflection at film node
    (j, l) under a unit pressure at film node (0, k)."""
    return unit_pressure_response(system, film, list(range(film.n_z)), refine_theta,
                                  refine_z)
