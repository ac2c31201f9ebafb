"""The thin compliant liner (Winkler foundation): a layer of thickness t << R bonded to a
rigid housing compresses locally, each point as a column in uniaxial strain (radial strain
only: the layer is held tangentially and axially by its bond and by its neighbours), so

    w = t p / M,   M = E (1 - nu) / ((1 + nu) (1 - 2 nu))   (the constrained modulus).

This is the liner model of the compliant journal-bearing literature (Higginson 1965; the
factor (1+nu)(1-2nu)/(1-nu) of the deformation coefficient of Jain, Malik & Sinhasan,
Periodica Polytechnica Mech. Eng. (1988); Lahmar, Ellagoune & Bou-Said, Tribol. Trans. 53
(2010) 349-368, deformation proportional to the local pressure). It is the thin-wall limit of the plane-strain ring and of the solid bush at a wavelength of the
pressure long against t (tests/test_ehd_reference.py shows the rate).
"""
from __future__ import annotations

import numpy as np

from .surface import FilmGrid

__all__ = ["liner_stiffness", "liner_columns"]


def liner_stiffness(modulus: float, poisson: float) -> float:
    """The constrained (oedometric) modulus M = E (1 - nu) / ((1 + nu) (1 - 2 nu)) [Pa]."""
    return modulus * (1.0 - poisson) / ((1.0 + poisson) * (1.0 - 2.0 * poisson))


def liner_columns(bush, radius: float, film: FilmGrid) -> np.ndarray:
    """The compliance columns' diagonals (n_theta, n_z) [m/Pa] of the liner of thickness
    outer_radius - radius: t / M at the loaded node itself (j = 0), zero elsewhere
    (local: the columns are zero off their diagonals, and are not stored)."""
    diagonals = np.zeros((film.n_theta, film.n_z))
    diagonals[0] = (bush.outer_radius - radius) / liner_stiffness(bush.modulus, bush.poisson)
    return diagonals
