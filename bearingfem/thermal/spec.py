"""How a thermal film exchanges heat: supply temperature, groove mixing, walls."""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..bearing import PLAUSIBLE
from ..elastic.bush import ElasticBush
from ..errors import OilRangeWarning
from ..oil_range import (CELSIUS, LEAST_KELVIN, OIL_TEMPERATURE_RANGE, check_kelvin,
                         temperature_range_note)

__all__ = ["Thermal", "ThermalRecord", "BushConduction", "THERMAL_MODELS", "warn_out_of_range",
           "MAX_FILM_COEFFICIENT", "DEFAULT_WALL_COEFFICIENT"]

THERMAL_MODELS = ("adiabatic", "conducting")
#: a Thermal's temperatures [K]
TEMPERATURES = ("supply_temperature", "ambient_temperature", "journal_temperature")
#: [W/(m^2 K)] film -> ambient through a steel bush and film -> journal, when the
#: "conducting" model is given no coefficient: the order of a 50 W/(m K) bush 0.15 m thick
#: in series with a 700 W/(m^2 K) outer convection (about 230 W/(m^2 K)).
DEFAULT_WALL_COEFFICIENT = 250.0
#: [W/(m^2 K)] the largest film -> bush coefficient a BushConduction takes (30x 2 k_oil/h
#: of a 100 um film of mineral oil)
MAX_FILM_COEFFICIENT = 1e5


def _number(name, value, *, lo=None, hi=None, allowed=""):
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"{name} must be a number {allowed}, got {value!r}")
    value = float(value)
    if not math.isfinite(value) or (lo is not None and value < lo) or \
            (hi is not None and value > hi):
        raise ValueError(f"{name} must be finite and {allowed}, got {value!r}")
    return value


def warn_out_of_range(temperature) -> None:
    """An :class:`~bearingfem.errors.OilRangeWarning` with the numbers when a solved film's
    nodal temperatures [K] leave the oil law's range (a film at eps 0.999 can report
    2000 C: the law extrapolated, not an oil)."""
    note = temperature_range_note(temperature)
    if note is not None:
        warnings.warn(note, OilRangeWarning, stacklevel=3)


def _count(name, value, lo):
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < lo:
        raise ValueError(f"{name} must be an integer >= {lo}, got {value!r}")
    return int(value)


@dataclass(frozen=True)
class BushConduction:
    """The bush as a conducting body: the film's heat enters its inner surface and leaves
    its outer surface by convection (:mod:`bearingfem.thermal.bush`).

    Parameters
    ----------
    bush : :class:`~bearingfem.elastic.ElasticBush`, its geometry: ``outer_radius`` [m] and
        ``model`` ("solid" or "solid-3d": the hollow cylinder of hexahedra, end faces
        insulated; "ring" or "liner": the annulus, the same at every z)
    conductivity : the bush's k [W/(m K)], > 0 (default 50: steel)
    outer_coefficient : h_o, outer surface -> ambient [W/(m^2 K)], > 0 (the ambient is
        the :class:`Thermal`'s ``ambient_temperature``)
    film_coefficient : film -> bush inner surface [W/(m^2 K)], in (0, 1e5], or None:
        2 k_oil F / h,
        conduction across half the local film (a linear profile from the film's mean
        temperature at mid-film to the wall; F the film fraction)
    n_theta, n_radial, n_axial : the bush mesh's cells around, across the wall and along
        (n_theta, n_axial None: the film's n_theta and n_z); ``grading`` the radial growth
        (:func:`~bearingfem.elastic.mesh.radial_lines`)
    """

    bush: ElasticBush
    conductivity: float = 50.0
    outer_coefficient: float = 700.0
    film_coefficient: float | None = None
    n_theta: int | None = None
    n_radial: int = 8
    n_axial: int | None = None
    grading: float = 1.0

    def __post_init__(self):
        if not isinstance(self.bush, ElasticBush):
            raise ValueError(f"bush must be an ElasticBush (its outer_radius and model), "
                             f"got {type(self.bush).__name__}")
        _number("conductivity", self.conductivity, lo=1e-300, allowed="> 0 [W/(m K)]")
        _number("outer_coefficient", self.outer_coefficient, lo=1e-300,
                allowed="> 0 [W/(m^2 K)]")
        if self.film_coefficient is not None:
            # why the cap: the film's coupling to the wall grows with it; at 1e6 the
            # film follows the wall's interpolated temperature point by point on meshes
            # that do not match, and the answer moves (docs/thd.md)
            _number("film_coefficient", self.film_coefficient, lo=1e-300,
                    hi=MAX_FILM_COEFFICIENT, allowed=f"in (0, {MAX_FILM_COEFFICIENT:g}] "
                                                     f"[W/(m^2 K)]")
        for name, lo in (("n_theta", 8), ("n_axial", 1)):
            if getattr(self, name) is not None:
                _count(name, getattr(self, name), lo)
        _count("n_radial", self.n_radial, 1)
        _number("grading", self.grading, lo=1e-300, allowed="> 0")

    @property
    def solid(self) -> bool:
        """The hollow cylinder (3-D) rather than the annulus (the same at every z)."""
        return self.bush.model in ("solid", "solid-3d")


@dataclass(frozen=True)
class Thermal:
    """The heat exchanges of a thermal film.

    Parameters
    ----------
    supply_temperature : temperature of the fresh oil fed at the grooves (or the supply
        line) [K], > 0, as ``ambient_temperature`` and ``journal_temperature``; with an
        oil (:meth:`check_fluid`, before any film is solved) >=
        :data:`~bearingfem.oil_range.LEAST_KELVIN` (200 K: a smaller number is degC typed
        for K, refused), any > 0 with a cryogen's law; a film whose temperature leaves
        :data:`~bearingfem.oil_range.OIL_TEMPERATURE_RANGE` warns once solved
        (:class:`~bearingfem.errors.OilRangeWarning`)
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
    bush : None (the bush as ``bush_coefficient``), or :class:`BushConduction`: the heat
        enters the bush's inner surface and is conducted through its finite-element mesh
        to the ambient ("conducting" only; ``bush_coefficient`` then not given)
    """

    supply_temperature: float
    model: str = "adiabatic"
    carry_over: float = 0.0
    bush_coefficient: float | None = None
    ambient_temperature: float | None = None
    journal_coefficient: float | None = None
    journal_temperature: float | None = None
    bush: BushConduction | None = None

    def __post_init__(self):
        # any fluid's, hot or cryogenic: a film that leaves the oil law's range warns once
        # solved (warn_out_of_range); check_fluid refuses degC typed for K against the oil
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
            if value is not None:     # an aircraft's ambient at altitude is -56.5 C
                _number(name, value, lo=1e-300, allowed="> 0 [K]")
        if self.bush is not None:
            if not isinstance(self.bush, BushConduction):
                raise ValueError(f"bush must be a BushConduction, got "
                                 f"{type(self.bush).__name__}")
            if self.model != "conducting":
                raise ValueError("bush is for model='conducting'; the adiabatic film "
                                 "exchanges no heat with its walls")
            if self.bush_coefficient is not None:
                raise ValueError("give bush_coefficient or bush, not both: the conducting "
                                 "bush replaces the coefficient")

    def check_fluid(self, lubricant) -> None:
        """The temperatures against the fluid they heat, before any film is solved: with a
        lubricant whose temperature law is referenced at or above
        :data:`~bearingfem.oil_range.LEAST_KELVIN` (an oil's; or one without a reference
        temperature) a temperature below it is degC typed for K (40.0 for 313.15 K) and
        refused, naming it; a law referenced below it (a cryogen's: liquid nitrogen's at
        77-90 K) takes any temperature > 0 K.

        The supply temperature is refused, naming it, where the lubricant's own law gives
        no viscosity there (outside
        :attr:`~bearingfem.lubricant.Lubricant.temperature_range`), or below the oil range
        (:data:`~bearingfem.oil_range.OIL_TEMPERATURE_RANGE`, where the law is an
        extrapolation) more than any :class:`~bearingfem.bearing.Bearing` takes
        (:data:`~bearingfem.bearing.PLAUSIBLE`, 10 Pa s). Inside the range any viscosity of
        the law is a film's: a cold start (ISO VG 32 fed at -50 C, 232 Pa s) solves, the
        film heating it; the equilibrium, whose isothermal start is a Bearing at the
        supply's viscosity, refuses more than 10 Pa s itself."""
        reference = getattr(lubricant, "temperature", None)
        if reference is None or reference >= LEAST_KELVIN:
            why = (f" with a lubricant referenced at {reference:g} K" if reference is not None
                   else " with a lubricant without a reference temperature")
            for name in TEMPERATURES:
                if getattr(self, name) is not None:
                    check_kelvin(name, getattr(self, name), why)
        t = self.supply_temperature
        try:
            mu = float(lubricant.viscosity_at(0.0, temperature=t))
        except ValueError:           # outside the law's range: no viscosity there
            mu = math.nan
        lo, hi = OIL_TEMPERATURE_RANGE
        most = PLAUSIBLE["viscosity"][1]
        if math.isfinite(mu) and not (t < lo and mu > most):
            return
        hint = (f": typed in degC? ({t:g} C = {t + CELSIUS:g} K)" if lo <= t + CELSIUS <= hi
                else "")
        # within the range any viscosity of the law is taken (a film's cold start), so the
        # message says where the limit applies
        what = (f"a viscosity of {mu:g} Pa s below the oil range's {lo:g} K, where its law "
                f"is extrapolated (at most {most:g} Pa s taken there)"
                if math.isfinite(mu) else "no finite viscosity")
        raise ValueError(f"supply_temperature {t:g} K gives the lubricant {what}{hint}; "
                         "temperatures are in K")

    @property
    def walls(self) -> tuple:
        """(bush coefficient, ambient temperature, journal coefficient, journal
        temperature or None) [W/(m^2 K), K]: zeros for the adiabatic film; the bush
        coefficient 0 when the ``bush`` conducts (its heat is the bush's own term)."""
        if self.model == "adiabatic":
            return 0.0, self.supply_temperature, 0.0, None
        hb = DEFAULT_WALL_COEFFICIENT if self.bush_coefficient is None else self.bush_coefficient
        if self.bush is not None:
            hb = 0.0
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
    whole search), the last changes (temperature [K], pressure relative to its peak: they
    may exceed the tolerances, the fixed point stopping on its error estimate,
    :func:`~bearingfem.routes.thd.solve_thd`) and, with a conducting bush, its temperature
    field (:class:`~bearingfem.thermal.bush.BushHeat`)."""

    balance: object            # the energy equation's EnergyBalance [W]
    journal_temperature: float
    inlet_temperatures: tuple
    viscosity: np.ndarray
    viscosity_quadrature: np.ndarray
    iterations: int
    temperature_change: float
    pressure_change: float
    bush: object = None        # the conducting bush's BushHeat, or None
