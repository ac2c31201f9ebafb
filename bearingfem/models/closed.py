"""The closed-form films: Frene's short bearing (seed Eq. 9), the Pinkus-Sternlicht long
bearing (seed Eq. 10-13, corrected) and the exact quadratures of their pressures."""
from __future__ import annotations

from ..closed.long_bearing import (long_bearing_derivatives, long_bearing_exact_force,
                                   long_bearing_force)
from ..closed.short_bearing import (short_bearing_derivatives, short_bearing_exact_force,
                                    short_bearing_force)
from .registry import FilmModel, register

__all__ = []

# switch 1 rad/s: the literal sharp switch of Eq. 9's half film makes integrators chatter
# (a steady film, w >> 1 rad/s, is the same to round-off)
register(FilmModel("short", short_bearing_force, dict(half_film="wedge", switch_speed=1.0),
                   force_derivatives=short_bearing_derivatives))
register(FilmModel("long", long_bearing_force, force_derivatives=long_bearing_derivatives))
register(FilmModel("short-exact", short_bearing_exact_force))
register(FilmModel("long-exact", long_bearing_exact_force))
