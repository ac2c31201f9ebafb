"""Quadrature over a film-angle interval, refined toward the minimum film (theta = pi).

The analytic pressures carry 1/H^2 or 1/H^3 with H = 1 + eps cos(theta), sharply peaked
at theta = pi as eps -> 1. Subintervals graded geometrically toward pi keep a fixed-size
Gauss-Legendre rule accurate to ~1e-10 up to eps = 0.999 (tests/test_closed_form.py).
"""
from __future__ import annotations

import numpy as np

from ..caches import cached

__all__ = ["theta_nodes"]

_GL_X, _GL_W = np.polynomial.legendre.leggauss(24)


@cached(maxsize=256)
def _graded_breaks(eps_key: float) -> np.ndarray:
    """Breakpoints on [0, 2 pi] graded toward pi on the scale sqrt(1 - eps)."""
    width = max(np.sqrt(max(1.0 - eps_key, 1e-16)), 1e-8)
    steps = width * 2.0 ** np.arange(0, 12)
    steps = steps[steps < np.pi]
    left = np.pi - steps[::-1]
    right = np.pi + steps
    return np.unique(np.concatenate(([0.0], left, [np.pi], right, [2 * np.pi])))


def theta_nodes(a: float, b: float, eps: float):
    """Nodes and weights for integrals over [a, b] (0 <= a < b <= 2 pi... any order)."""
    if b <= a:
        return np.empty(0), np.empty(0)
    br = _graded_breaks(round(float(eps), 6))
    br = np.concatenate(([a], br[(br > a) & (br < b)], [b]))
    lo, hi = br[:-1, None], br[1:, None]
    x = 0.5 * (hi - lo) * _GL_X[None, :] + 0.5 * (hi + lo)
    w = 0.5 * (hi - lo) * _GL_W[None, :]
    return x.ravel(), w.ravel()
