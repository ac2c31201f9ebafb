"""How a thermal film exchanges heat: supply temperature, groove mixing, walls."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Thermal", "ThermalRecord", "THERMAL_MODELS", "DEFAULT_WALL_COEFFICIENT"]

THERMAL_MODELS = ("adiabatic", "conducting")
#: [W/(m^2 K)] film -> ambient through a steel bush and film -> journal, when the
#: "conducting" model is given no coefficient: the order of a 50 W/(m K) bush 0.15 m thick
#: in series with a 700 W/(m^2 K) outer convection (about 230 W/(m^2 K)).
DEFAULT_WALL_COEFFICIENT = 250.0


def _number(name, value, *, lo=None, hi=None, allowed=""):
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"{name} must be a number {allowed}, got {value!r}")
    value = float(value)
    if not math.isfinite(value) or (lo is not None and value < lo) or \
            (hi is not None and value > hi):
        raise ValueError(f"{name} must be finite and {allowed}, got {value!r}")
    return value


@dataclass(frozen=True)
class Thermal:
    """The heat exchanges of a thermal film.

    Parameters
    ----------
    supply_temperature : temperature of the fresh oil fed at the grooves (or the supply
        line) [K], > 0
    model : "adiabatic" (no heat to the walls: all the film's heat leaves with its oil) or
        "conducting" (heat to the bush and to the journal by heat-transfer coefficients)
    carry_over : share, in [0, 1], of an arc's exit flow that passes the groove into the
        next arc's inlet and mixes there with fresh oil (ROSS's ``hot_oil_lambda``): the
        inlet temperature is (lambda Q_out T_out + (Q_in - lambda Q_out) T_supply) / Q_in,
        or T_out when lambda Q_out >= Q_in
    bush_coefficient : film -> ambient heat-transfer coefficient through the bush
        [W/(m^2 K)], >= 0 ("conducting" only; default 250)
    ambient_temperature : the far side of the bush [K] (default: the supply temperature)
    journal_coefficient : film -> journal heat-transfer coefficient [W/(m^2 K)], >= 0
        ("conducting" only; default 250)
    journal_temperature : the journal's temperature [K], or None: the one temperature of
        the journal at which the film's net heat flux into it is zero
    """

    supply_temperature: float
    model: str = "adiabatic"
    carry_over: float = 0.0
    bush_coefficient: float | None = None
    ambient_temperature: float | None = None
    journal_coefficient: float | None = None
    journal_temperature: float | None = None

    def __post_init__(self):
        _number("supply_temperature", self.supply_temperature, lo=1e-300, allowed="> 0 [K]")
        if self.model not in THERMAL_MODELS:
            raise ValueError(f"model must be one of {THERMAL_MODELS}, got {self.model!r}")
        _number("carry_over", self.carry_over, lo=0.0, hi=1.0, allowed="in [0, 1]")
        for name in ("bush_coefficient", "journal_coefficient"):
            value = getattr(self, name)
            if value is not None:
                _number(name, value, lo=0.0, allowed=">= 0 [W/(m^2 K)]")
                if self.model == "adiabatic" and value != 0.0:
                    raise ValueError(f"{name} is for model='conducting'; the adiabatic "
                                     f"film exchanges no heat with its walls")
        for name in ("ambient_temperature", "journal_temperature"):
            value = getattr(self, name)
            if value is not None:
                _number(name, value, lo=1e-300, allowed="> 0 [K]")

    @property
    def walls(self) -> tuple:
        """(bush coefficient, ambient temperature, journal coefficient, journal
        temperature or None) [W/(m^2 K), K]: zeros for the adiabatic film."""
        if self.model == "adiabatic":
            return 0.0, self.supply_temperature, 0.0, None
        hb = DEFAULT_WALL_COEFFICIENT if self.bush_coefficient is None else self.bush_coefficient
        hj = DEFAULT_WALL_COEFFICIENT if self.journal_coefficient is None \
            else self.journal_coefficient
        ta = self.supply_temperature if self.ambient_temperature is None \
            else self.ambient_temperature
        return hb, ta, hj, self.journal_temperature


@dataclass(frozen=True, eq=False)
class ThermalRecord:
    """What a thermal solve found besides the film: the energy balance [W], the journal's
    temperature [K], each groove's (or the supply line's) inlet temperature [K], the
    viscosity [Pa s] at the nodes and at the film's quadrature points (the field the film
    was solved with), the film solves of the thermal iteration (an equilibrium's: over its
    whole search) and the last changes (temperature [K],
    pressure relative to its peak)."""

    balance: object            # the energy equation's EnergyBalance [W]
    journal_temperature: float
    inlet_temperatures: tuple
    viscosity: np.ndarray
    viscosity_quadrature: np.ndarray
    iterations: int
    temperature_change: float
    pressure_change: float
