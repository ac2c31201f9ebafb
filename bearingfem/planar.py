"""Inputs of a planar film: a rectangular gap between a fixed and a sliding surface.

x runs along the sliding direction from the inlet (x = 0) to the outlet (x = length), y
across it. The gap h(x, y, t) comes from a callable, so sliders, parallel plates that
squeeze and textured pads are the same object. Validated on construction, like
:class:`bearingfem.Bearing`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from .bearing import check_finite, check_positive

__all__ = ["PlanarFilm", "SIDES"]

SIDES = ("closed", "periodic")


@dataclass(frozen=True)
class PlanarFilm:
    """A rectangular planar film.

    Parameters
    ----------
    length : extent along the sliding direction x [m]
    width : extent across it, y [m]
    viscosity : mu [Pa s]
    gap : callable (x, y, t) -> h [m], > 0, vectorised over numpy arrays of x and y
    speed : sliding speed U of the moving surface along +x [m/s] (the other is at rest;
        the film content moves at U/2)
    inlet_pressure, outlet_pressure : pressure held at x = 0 and x = length, above the
        cavitation pressure [Pa] (>= 0)
    inlet_fraction : film fraction supplied at x = 0, in [0, 1] (1: flooded inlet)
    sides : "closed" (no flow through y = 0 and y = width) or "periodic"
    """

    length: float
    width: float
    viscosity: float
    gap: Callable
    speed: float = 0.0
    inlet_pressure: float = 0.0
    outlet_pressure: float = 0.0
    inlet_fraction: float = 1.0
    sides: str = "closed"

    def __post_init__(self):
        for name in ("length", "width", "viscosity"):
            object.__setattr__(self, name, check_positive(name, getattr(self, name)))
        if not callable(self.gap):
            raise ValueError(f"gap must be a callable (x, y, t) -> h [m], got {self.gap!r}")
        object.__setattr__(self, "speed", check_finite("speed", self.speed))
        for name in ("inlet_pressure", "outlet_pressure"):
            v = check_finite(name, getattr(self, name))
            if v < 0.0:
                raise ValueError(f"{name} must be >= 0 [Pa] (above the cavitation pressure), "
                                 f"got {getattr(self, name)!r}")
            object.__setattr__(self, name, v)
        f = check_finite("inlet_fraction", self.inlet_fraction)
        if not 0.0 <= f <= 1.0:
            raise ValueError(f"inlet_fraction must lie in [0, 1], got {self.inlet_fraction!r}")
        object.__setattr__(self, "inlet_fraction", f)
        if self.sides not in SIDES:
            raise ValueError(f"sides must be one of {', '.join(map(repr, SIDES))}, "
                             f"got {self.sides!r}")

    def film(self, x, y, t: float) -> np.ndarray:
        """The gap [m] at (x, y) and time t, checked positive and finite."""
        x = np.asarray(x, float)
        h = np.broadcast_to(np.asarray(self.gap(x, np.asarray(y, float), float(t)), float),
                            x.shape)
        if not np.all(np.isfinite(h)) or np.any(h <= 0.0):
            bad = float(np.min(h)) if np.all(np.isfinite(h)) else math.nan
            raise ValueError(f"gap must be positive and finite at t = {t!r} (min {bad!r})")
        return h
