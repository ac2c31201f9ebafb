"""Elastohydrodynamic (EHD) journal films: a pressure-dependent lubricant and an elastic
bush in the finite-element film, solved by Newton with load continuation."""
from .coupling import EHDFilm, ehd_film
from .newton import ConvergenceError, EHDResult, solve_ehd

__all__ = ["EHDFilm", "ehd_film", "EHDResult", "solve_ehd", "ConvergenceError"]
