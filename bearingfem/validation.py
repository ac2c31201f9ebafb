"""Argument checks shared by the solvers: fail before any work, naming the parameter."""
from __future__ import annotations

import math

from .bearing import Bearing, JournalState

CAVITATION = ("none", "gumbel", "reynolds")
METHODS = ("active-set", "psor")


def check_choice(name: str, value, allowed) -> str:
    if value not in allowed:
        raise ValueError(f"{name} must be one of {', '.join(map(repr, allowed))}, got {value!r}")
    return value


def check_int(name: str, value, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int,)) and not (
            isinstance(value, float) and value.is_integer()):
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    v = int(value)
    if v < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return v


def check_inputs(bearing, state):
    if not isinstance(bearing, Bearing):
        raise ValueError(f"bearing must be a bearingfem.Bearing, got {type(bearing).__name__}")
    if not isinstance(state, JournalState):
        raise ValueError(f"state must be a bearingfem.JournalState, got {type(state).__name__}")


def check_supply_angle(value):
    if value is None:
        return None
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"supply_angle must be None or a finite angle [rad], got {value!r}") from None
    if not math.isfinite(v):
        raise ValueError(f"supply_angle must be None or a finite angle [rad], got {value!r}")
    return v
