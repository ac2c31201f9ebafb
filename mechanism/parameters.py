"""Mechanism parameters (seed Table 1 defaults) as a frozen dataclass."""
from __future__ import annotations

from dataclasses import dataclass

from bearingfem.bearing import check_finite, check_positive

__all__ = ["Mechanism", "GRAVITY"]

GRAVITY = 9.81  # [m/s^2]


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
