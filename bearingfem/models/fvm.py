"""The finite-volume film ("fvm"): the reference discretisation."""
from __future__ import annotations

from ..fv.fvm import fvm_force
from ..reynolds import fvm_reynolds
from .registry import FilmModel, register

__all__ = ["FiniteVolumeModel"]


class FiniteVolumeModel(FilmModel):
    name = "fvm"
    defaults = dict(n_theta=48, n_z=8, cavitation="gumbel")
    numeric = True

    def _film_force(self, bearing, state, n_theta, n_z, cavitation):
        return fvm_force(bearing, state, n_theta, n_z, cavitation)

    def _film_solution(self, bearing, state, n_theta, n_z, cavitation):
        return fvm_reynolds(bearing, state, n_theta, n_z, cavitation)


register(FiniteVolumeModel())
