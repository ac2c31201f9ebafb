"""The plane-strain ring: each axial slice of the bush as an annulus of bilinear
quadrilaterals, outer surface held, slices independent (no axial coupling)."""
from __future__ import annotations

import numpy as np
from skfem import ElementQuad1

from .mesh import annulus_mesh
from .surface import FilmGrid, bush_system, unit_pressure_response

__all__ = ["ring_columns"]


def ring_columns(bush, radius: float, film: FilmGrid, refine_theta: int,
                 n_radial: int, grading: float) -> np.ndarray:
    """The compliance columns' diagonals (n_theta, n_z) [m/Pa]: radial deflection at film
    node (j, l) under a unit pressure at film node (0, l) (the slices do not couple: the
    columns are zero off l == k, and are not stored)."""
    ring = annulus_mesh(radius, bush.outer_radius, film.n_theta * refine_theta, n_radial,
                        grading)
    outer = ring.radial == ring.radii.size - 1
    system = bush_system(ring, ElementQuad1(), bush.lame, [(outer, (0, 1))])
    response = unit_pressure_response(system, film, [None], refine_theta, 1)[:, 0, 0]
    return response[:, None] * np.ones(film.n_z)
