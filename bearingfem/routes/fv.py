"""The finite-volume film (the reference discretisation, :mod:`bearingfem.fv`)."""
from __future__ import annotations

import numpy as np

from ..fv.fvm import solve_fv
from .base import Route
from .problem import FilmProblem

__all__ = ["FiniteVolumeFilm"]


class FiniteVolumeFilm(Route):
    name = "fv"
    summary = "finite volumes on a structured grid, every cavitation model, whole length"
    uses = frozenset({"method", "supply_angle", "tol", "grooves", "ambient_pressure", "tilt",
                      "tilt_rate", "profile"})

    def check_options(self, p: FilmProblem) -> None:
        # A groove holds the cells whose centres lie in it: one narrower than a cell may
        # hold none, and the film then has no supply (a zero or diverging film, no error).
        cell = 2 * np.pi / p.n_theta
        for g in p.grooves:
            if g.width < cell:
                raise ValueError(
                    f"n_theta = {p.n_theta} gives finite-volume cells of "
                    f"{np.degrees(cell):.3g} deg, wider than the groove at "
                    f"{np.degrees(g.angle):.3g} deg ({np.degrees(g.width):.3g} deg), which "
                    f"may then hold no cell: use n_theta >= "
                    f"{int(np.ceil(2 * np.pi / g.width))}")

    def solve(self, p: FilmProblem):
        return solve_fv(p.bearing, p.state, p.n_theta, p.n_z, p.cavitation, p.method,
                        p.supply_angle, p.tol, p.grooves, p.ambient_pressure, p.tilt,
                        p.tilt_rate, p.profile)
