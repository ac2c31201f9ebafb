"""Argument checks shared by the solvers: fail before any work, naming the parameter."""
from __future__ import annotations

from .bearing import Bearing, JournalState, check_finite

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
    """None (fully periodic film) or a finite angle [rad]."""
    return None if value is None else check_finite("supply_angle", value)
