"""Mechanism parameters (seed Table 1 defaults) as a frozen dataclass."""
from __future__ import annotations

import math
from dataclasses import dataclass

from bearingfem.bearing import check_finite, check_positive

__all__ = ["Mechanism", "GRAVITY", "PIN_SPEED_MAX", "check_crank_speed"]

GRAVITY = 9.81  # [m/s^2]
#: The fastest crank pin of any slider-crank [m/s]: a racing engine at 18000 rpm with a
#: 40 mm stroke moves its crank pin at 38 m/s (mean piston speed 24 m/s). Above it a speed
#: in rpm typed as rad/s is far likelier than such a machine.
PIN_SPEED_MAX = 60.0


@dataclass(frozen=True)
class Mechanism:
    """Slider-crank geometry and inertia (seed Section 2.1, Table 1; seed-corrections §6).

    Frame: X along the slider axis pointing up (gravity along -X), Y across it; crank
    angle q counter-clockwise from X; rod angle A clockwise, so the pin sits at
    (R cos q + L cos A, R sin q - L sin A).

    Parameters
    ----------
    crank_length R [m], rod_length L [m]
    crank_inertia I_MO about the crank pivot [kg m^2]
    rod_inertia I_B about the rod's centre of mass [kg m^2]
    crank_mass M_M, rod_mass M_B, slider_mass M_PT [kg]
    crank_cm (U_PM, V_PM): crank centre of mass in the crank frame [m]
    rod_cm (U_PB, V_PB): rod centre of mass from the crank pin, along / across the rod [m]
    """

    crank_length: float = 0.0508
    rod_length: float = 0.2032
    crank_inertia: float = 0.006
    rod_inertia: float = 0.010
    crank_mass: float = 0.80
    rod_mass: float = 1.36
    slider_mass: float = 0.91
    crank_cm: tuple = (0.0, 0.0)
    rod_cm: tuple = (0.0508, 0.0)

    def __post_init__(self):
        for name in ("crank_length", "rod_length", "crank_inertia", "rod_inertia",
                     "crank_mass", "rod_mass", "slider_mass"):
            object.__setattr__(self, name, check_positive(name, getattr(self, name)))
        for name in ("crank_cm", "rod_cm"):
            v = getattr(self, name)
            if len(v) != 2:
                raise ValueError(f"{name} must be a pair (U, V) [m], got {v!r}")
            object.__setattr__(self, name, tuple(check_finite(f"{name}[{i}]", x)
                                                 for i, x in enumerate(v)))
        if self.crank_length >= self.rod_length:
            raise ValueError(f"crank_length must be smaller than rod_length, got "
                             f"{self.crank_length} >= {self.rod_length}")


def check_crank_speed(mechanism: Mechanism, crank_speed: float, name: str = "crank_speed",
                      rpm: bool = False) -> float:
    """``crank_speed`` [rad/s] as float, or ValueError naming ``name``: not finite and
    positive, or driving the crank pin (at ``crank_length``) faster than
    :data:`PIN_SPEED_MAX`, the likely mistake being a speed in rpm given as rad/s.
    ``rpm``: the caller's value was given in 1/min (the message then speaks of it so)."""
    w = check_positive(name, crank_speed)
    r = mechanism.crank_length
    w_max = PIN_SPEED_MAX / r
    if w * r <= PIN_SPEED_MAX:
        return w
    if rpm:
        raise ValueError(
            f"{name} {w * 30 / math.pi:g} 1/min ({w:.4g} rad/s) drives the crank pin at "
            f"{w * r:.4g} m/s (crank_length {r:g} m), faster than any slider-crank's "
            f"(<= {PIN_SPEED_MAX:g} m/s): {name} must lie in (0, {w_max * 30 / math.pi:.5g}] "
            f"1/min for this crank")
    raise ValueError(
        f"{name} {w:g} rad/s drives the crank pin at {w * r:.4g} m/s (crank_length {r:g} m), "
        f"faster than any slider-crank's (<= {PIN_SPEED_MAX:g} m/s): {name} must lie in "
        f"(0, {w_max:.4g}] rad/s for this crank; a speed in rpm given as rad/s? "
        f"({w:g} rpm = {w * math.pi / 30:.4g} rad/s: give rpm = {w:g} instead)")
