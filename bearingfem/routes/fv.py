"""The finite-volume film (the reference discretisation, :mod:`bearingfem.fv`)."""
from __future__ import annotations

from ..fv.fvm import solve_fv
from .base import Route
from .problem import FilmProblem

__all__ = ["FiniteVolumeFilm"]


class FiniteVolumeFilm(Route):
    name = "fv"
    summary = "finite volumes on a structured grid, every cavitation model, whole length"
    uses = frozenset({"method", "supply_angle", "tol", "grooves", "ambient_pressure", "tilt",
                      "tilt_rate", "profile"})

    def solve(self, p: FilmProblem):
        return solve_fv(p.bearing, p.state, p.n_theta, p.n_z, p.cavitation, p.method,
                        p.supply_angle, p.tol, p.grooves, p.ambient_pressure, p.tilt,
                        p.tilt_rate, p.profile)
