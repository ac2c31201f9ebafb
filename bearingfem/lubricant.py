"""Lubricant: how the oil's viscosity and density follow the film pressure and temperature.

Pressures are gauge pressures [Pa] (zero at ambient), as in the films; temperatures are
in kelvin. Viscosity against pressure (one of, or neither for a constant-viscosity oil):

* Barus (1893): mu = mu_T exp(alpha p), ``barus=alpha`` [1/Pa].
* Roelands (1966), in the form of Houpert (1985):
  mu = mu_T exp((ln mu_T + 9.67) (-1 + (1 + 5.1e-9 p)^Z)), ``roelands=Z``, mu_T in Pa s.
  Its slope at ambient is the equivalent Barus alpha* = 5.1e-9 Z (ln mu_T + 9.67).

mu_T is the viscosity at ambient pressure and the temperature T: ``viscosity`` (mu0) at
the reference temperature ``temperature`` (T0), and against temperature (one of, or
neither for an oil at one temperature):

* Walther's equation as ASTM D341 writes it: log10 log10(nu + 0.7) = A - B log10 T, nu the
  kinematic viscosity mu/rho in mm^2/s, T in K, ``walther=(A, B)``. D341 holds it for
  nu >= 2 mm^2/s (below, its correction terms add less than 1e-3 mm^2/s at 2 mm^2/s and
  are left out). The straight line of the D341 chart through two measured viscosities.
* The exponential law mu_T = mu0 exp(-beta (T - T0)), ``temperature_exponent=beta``
  [1/K]: the law of ROSS's fluid-film bearings and of many THD codes.

Both laws keep the density ``mass_density`` [kg/m^3] at every temperature (a liquid's
thermal expansion, ~7e-4 1/K, moves a film far less than its viscosity does, and an
incompressible film keeps its mass balance); ``specific_heat`` cp [J/(kg K)] and
``conductivity`` k [W/(m K)] complete the oil for the energy equation
(:mod:`bearingfem.thermal`).

Presets: :meth:`Lubricant.two_point` (two measured viscosities) and
:meth:`Lubricant.iso_vg` (an ISO 3448 grade: its 40 C kinematic viscosity midpoint and the
100 C viscosity that gives viscosity index 100, ASTM D2270).

Density against pressure (one of, or neither for an incompressible oil):

* ``density="dowson-higginson"`` (Dowson & Higginson 1966):
  rho/rho0 = 1 + 0.6e-9 p / (1 + 1.7e-9 p), tending to 1 + 0.6/1.7 = 1.353 as p -> inf.
* ``bulk_modulus=B`` [Pa]: a constant bulk modulus B = rho dp/drho, so
  rho/rho0 = exp(p/B), the law of Elrod's (1981) compressible cavitation algorithm.

References: C. Barus, Am. J. Sci. 45 (1893) 87-96. C.J.A. Roelands, Correlational
aspects of the viscosity-temperature-pressure relationship of lubricating oils, PhD
thesis, TU Delft (1966). L. Houpert, J. Tribol. 107 (1985) 241-248. D. Dowson and
G.R. Higginson, Elasto-hydrodynamic lubrication, Pergamon (1966). H.G. Elrod, J. Lubr.
Technol. 103 (1981) 350-354. C. Walther, Erdoel und Teer 7 (1931) 382-384. ASTM D341-20,
Standard practice for viscosity-temperature equations and charts for liquid petroleum
or hydrocarbon products. ASTM D2270-10, Standard practice for calculating viscosity index
from kinematic viscosity at 40 and 100 C (Table 1). ISO 3448:1992, Industrial liquid
lubricants - ISO viscosity classification. M.M. Khonsari and E.R. Booser, Applied
Tribology, 3rd ed., Wiley (2017), ch. 2 (mineral oil density, specific heat and
conductivity).
"""
from __future__ import annotations

import math
import re
import warnings
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from .errors import OilRangeWarning, TemperatureRangeError
from .oil_range import (CELSIUS, OIL_TEMPERATURE_RANGE, check_oil_temperature,
                        temperature_range_note)

# the oil temperature range's names (oil_range's) stay importable from here
__all__ = ["Lubricant", "ISO_VG", "iso_vg_grade", "OIL_TEMPERATURE_RANGE", "check_oil_temperature",
           "temperature_range_note"]

ROELANDS_P0 = 1.0 / 5.1e-9        # [Pa] Roelands' reference pressure, 196 MPa
ROELANDS_LN_MU_INF = -9.67         # ln(mu_inf / (1 Pa s)), mu_inf = 6.31e-5 Pa s
DH_A, DH_B = 0.6e-9, 1.7e-9        # [1/Pa] Dowson-Higginson constants
DENSITY_MODELS = (None, "dowson-higginson")
WALTHER_SHIFT = 0.7                # [mm^2/s] ASTM D341's Z = nu + 0.7
LN10 = math.log(10.0)
WALTHER_LEAST = 2.0                # [mm^2/s] D341's simple form holds from here up
TEMPERATURE_LAWS = ("walther", "exponential")
LN_MAX = math.log(np.finfo(float).max)     # ln of the largest float, 709.78
LN_TINY = math.log(np.finfo(float).tiny)   # ln of the least normal float, -708.40

# ISO 3448 grades: the 40 C kinematic viscosity midpoint [mm^2/s] (the grade's number, but
# for VG 7) and the 100 C viscosity [mm^2/s] of an oil of viscosity index 100 with that
# midpoint: the Y at which ASTM D2270's Table 1 H (the 40 C viscosity of the VI 100
# reference oil) equals the midpoint, by the table's linear interpolation (every grade's
# Y is below the table's end, 70 mm^2/s). VG 2, 3 and 5 have no VI 100 oil (Y < 2 mm^2/s,
# where D2270 defines no index).
ISO_VG = {
    7: (6.8, 2.0812), 10: (10.0, 2.6585), 15: (15.0, 3.4096), 22: (22.0, 4.2940),
    32: (32.0, 5.3619), 46: (46.0, 6.7604), 68: (68.0, 8.7313), 100: (100.0, 11.3837),
    150: (150.0, 15.0200), 220: (220.0, 19.4353), 320: (320.0, 24.9538),
    460: (460.0, 31.7752), 680: (680.0, 41.1360), 1000: (1000.0, 52.7651),
    1500: (1500.0, 68.3333),
}
# Mineral oil at bearing temperatures (Khonsari & Booser, ch. 2): density 0.87 g/cm^3,
# specific heat 1.95 kJ/(kg K), conductivity 0.13 W/(m K), taken the same for every grade.
ISO_VG_DENSITY, ISO_VG_SPECIFIC_HEAT, ISO_VG_CONDUCTIVITY = 870.0, 1950.0, 0.13


def _positive(name: str, value, *, allowed: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
        raise ValueError(f"{name} must be a number {allowed}, got {value!r}")
    value = float(value)
    if not (math.isfinite(value) and value > 0.0):
        raise ValueError(f"{name} must be finite and {allowed}, got {value!r}")
    return value


def _finite(name: str, value) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
        raise ValueError(f"{name} must be a finite number, got {value!r}")
    if not math.isfinite(float(value)):
        raise ValueError(f"{name} must be a finite number, got {value!r}")
    return float(value)


#: a grade as the command line, scenes and sweeps take it: 'ISO VG 32', 'ISO-VG-32', 'VG32', '32'
#: (a separator only after ISO or VG: -32 and '-32' are a negative number, not ISO VG 32)
_GRADE = re.compile(r"^\s*(?:ISO[\s_-]*)?(?:VG[\s_-]*)?(\d+)\s*$", re.IGNORECASE)


def iso_vg_grade(grade, name: str = "grade") -> int:
    """An ISO VG grade (32, 'ISO VG 32', 'ISO-VG-32', 'VG32' or '32') as its number;
    ValueError naming ``name`` and the grades otherwise."""
    ok = isinstance(grade, (str, int, np.integer)) and not isinstance(grade, bool)
    m = _GRADE.match(str(grade)) if ok else None
    if not m or int(m.group(1)) not in ISO_VG:
        raise ValueError(f"{name} must be an ISO VG grade (a VI 100 mineral oil), one of "
                         f"{', '.join(f'ISO VG {g}' for g in sorted(ISO_VG))}, got {grade!r}")
    return int(m.group(1))


def walther_constants(t1: float, nu1: float, t2: float, nu2: float) -> tuple:
    """(A, B) of log10 log10(nu + 0.7) = A - B log10 T through (T1 [K], nu1 [mm^2/s]) and
    (T2, nu2): the D341 chart's straight line through two measured points."""
    y1 = math.log10(math.log10(nu1 + WALTHER_SHIFT))
    y2 = math.log10(math.log10(nu2 + WALTHER_SHIFT))
    b = (y1 - y2) / (math.log10(t2) - math.log10(t1))
    return y1 + b * math.log10(t1), b


@dataclass(frozen=True)
class Lubricant:
    """A Newtonian oil whose viscosity follows the pressure and the temperature.

    Parameters
    ----------
    viscosity : dynamic viscosity mu0 at ambient pressure and ``temperature`` [Pa s], > 0.
    barus : Barus pressure-viscosity coefficient alpha [1/Pa], >= 0 (0: constant).
    roelands : Roelands pressure-viscosity index Z [-], in (0, 2]; exclusive with barus.
    density : ``None`` (incompressible) or ``"dowson-higginson"`` (rho/rho0 against p).
    bulk_modulus : constant bulk modulus B [Pa], > 0; rho/rho0 = exp(p/B). Exclusive with
        ``density``.
    temperature : reference temperature T0 [K] of ``viscosity`` (> 0); needed by a
        temperature law.
    walther : (A, B) of ASTM D341's log10 log10(nu + 0.7) = A - B log10 T (nu in mm^2/s,
        T in K), B > 0; needs ``mass_density``. Its value at T0 sets mu0: give
        ``viscosity`` consistent with it (:meth:`two_point` does).
    temperature_exponent : beta [1/K] of mu = mu0 exp(-beta (T - T0)), >= 0; exclusive
        with ``walther``.
    mass_density : rho [kg/m^3] at ambient pressure, > 0, the same at every temperature.
    specific_heat : cp [J/(kg K)], > 0.
    conductivity : k [W/(m K)], > 0.

    An oil without a temperature law has its viscosity at every temperature.
    """

    viscosity: float
    barus: float | None = None
    roelands: float | None = None
    density: str | None = None
    bulk_modulus: float | None = None
    temperature: float | None = None
    walther: tuple | None = None
    temperature_exponent: float | None = None
    mass_density: float | None = None
    specific_heat: float | None = None
    conductivity: float | None = None

    def __post_init__(self):
        _positive("viscosity", self.viscosity, allowed="> 0 [Pa s]")
        if self.barus is not None and self.roelands is not None:
            raise ValueError("give barus or roelands, not both (one pressure-viscosity law)")
        if self.barus is not None:
            if self.barus != 0.0:
                _positive("barus", self.barus, allowed=">= 0 [1/Pa]")
        if self.roelands is not None:
            z = _positive("roelands", self.roelands, allowed="in (0, 2]")
            if z > 2.0:
                raise ValueError(f"roelands must be in (0, 2], got {z!r}")
        if self.density not in DENSITY_MODELS:
            raise ValueError(f"density must be one of {DENSITY_MODELS}, got {self.density!r}")
        if self.bulk_modulus is not None:
            _positive("bulk_modulus", self.bulk_modulus, allowed="> 0 [Pa]")
            if self.density is not None:
                raise ValueError("give density or bulk_modulus, not both (one density law)")
        for name in ("temperature", "mass_density", "specific_heat", "conductivity"):
            value = getattr(self, name)
            if value is not None:
                _positive(name, value, allowed={"temperature": "> 0 [K]",
                                                "mass_density": "> 0 [kg/m^3]",
                                                "specific_heat": "> 0 [J/(kg K)]",
                                                "conductivity": "> 0 [W/(m K)]"}[name])
        if self.walther is not None and self.temperature_exponent is not None:
            raise ValueError("give walther or temperature_exponent, not both (one "
                             "temperature-viscosity law)")
        if self.temperature_exponent is not None and self.temperature_exponent != 0.0:
            _positive("temperature_exponent", self.temperature_exponent,
                      allowed=">= 0 [1/K]")
        if self.walther is not None:
            try:
                a, b = self.walther
            except (TypeError, ValueError):
                raise ValueError(f"walther must be a pair (A, B), got {self.walther!r}") \
                    from None
            _finite("walther[0]", a)
            _positive("walther[1]", b, allowed="> 0 (viscosity falls as T rises)")
            if self.mass_density is None:
                raise ValueError("walther needs mass_density [kg/m^3] (D341 is a law of "
                                 "the kinematic viscosity)")
        if self.is_thermal and self.temperature is None:
            raise ValueError("a temperature law needs temperature, the reference "
                             "temperature T0 [K] of viscosity")
        if self.walther is not None:
            mu0 = float(self._viscosity_ambient(self.temperature)[0])
            if not math.isclose(mu0, self.viscosity, rel_tol=1e-9):
                raise ValueError(f"viscosity {self.viscosity!r} Pa s must be walther's "
                                 f"value at temperature {self.temperature!r} K, "
                                 f"{mu0!r} Pa s")

    # -- presets -------------------------------------------------------------------------
    @classmethod
    def two_point(cls, point1, point2, *, density: float, specific_heat: float,
                  conductivity: float, law: str = "walther", **pressure_laws) -> "Lubricant":
        """An oil through two measured viscosities (T1 [K], mu1 [Pa s]) and (T2, mu2).

        ``law="walther"``: ASTM D341 through the kinematic viscosities mu/density (each
        >= 2 mm^2/s, D341's range); ``"exponential"``: mu = mu1 exp(-beta (T - T1)).
        ``density`` [kg/m^3], ``specific_heat`` [J/(kg K)], ``conductivity`` [W/(m K)];
        further keywords (``barus``, ``roelands``, ``bulk_modulus``, ...) are the
        pressure laws, applied at each temperature. The reference temperature is T1.
        """
        if law not in TEMPERATURE_LAWS:
            raise ValueError(f"law must be one of {TEMPERATURE_LAWS}, got {law!r}")
        points = []
        for k, point in enumerate((point1, point2), start=1):
            try:
                t, mu = point
            except (TypeError, ValueError):
                raise ValueError(f"point{k} must be a pair (temperature [K], viscosity "
                                 f"[Pa s]), got {point!r}") from None
            # any fluid's points (a synthetic oil at 250 C, a cryogen at 80 K): > 0 K only
            points.append((_positive(f"point{k} temperature", t, allowed="> 0 [K]"),
                           _positive(f"point{k} viscosity", mu, allowed="> 0 [Pa s]")))
        (t1, mu1), (t2, mu2) = points
        rho = _positive("density", density, allowed="> 0 [kg/m^3]")
        if t1 == t2:
            raise ValueError(f"point1 and point2 need two temperatures, got {t1!r} twice")
        if (mu2 - mu1) * (t2 - t1) >= 0.0:
            raise ValueError(f"the viscosity must fall as the temperature rises, got "
                             f"{mu1!r} Pa s at {t1!r} K and {mu2!r} Pa s at {t2!r} K")
        common = dict(temperature=t1, mass_density=rho, specific_heat=specific_heat,
                      conductivity=conductivity, **pressure_laws)
        if law == "exponential":
            return cls(mu1, temperature_exponent=math.log(mu1 / mu2) / (t2 - t1), **common)
        nu1, nu2 = 1e6 * mu1 / rho, 1e6 * mu2 / rho
        if min(nu1, nu2) < WALTHER_LEAST:
            raise ValueError(f"law 'walther' (ASTM D341) holds for kinematic viscosities "
                             f">= {WALTHER_LEAST} mm^2/s, got {min(nu1, nu2):.4g} mm^2/s; "
                             f"use law='exponential'")
        return cls(mu1, walther=walther_constants(t1, nu1, t2, nu2), **common)

    @classmethod
    def iso_vg(cls, grade: int | str, *, density: float = ISO_VG_DENSITY,
               specific_heat: float = ISO_VG_SPECIFIC_HEAT,
               conductivity: float = ISO_VG_CONDUCTIVITY, **pressure_laws) -> "Lubricant":
        """An ISO 3448 grade (VG 7 .. 1500: 32, 'ISO VG 32', 'VG32', 'ISO-VG-32') as a
        mineral oil of viscosity index 100.

        Its kinematic viscosity is the grade's midpoint at 40 C and, at 100 C, the value
        that gives VI 100 by ASTM D2270 (:data:`ISO_VG`); Walther's equation (D341)
        through the two. Density 870 kg/m^3, cp 1950 J/(kg K), k 0.13 W/(m K) unless
        given (the same at every temperature). The reference temperature is 40 C.
        """
        grade = iso_vg_grade(grade)
        rho = _positive("density", density, allowed="> 0 [kg/m^3]")
        nu40, nu100 = ISO_VG[grade]
        return cls.two_point((40.0 + CELSIUS, 1e-6 * nu40 * rho),
                             (100.0 + CELSIUS, 1e-6 * nu100 * rho), density=rho,
                             specific_heat=specific_heat, conductivity=conductivity,
                             law="walther", **pressure_laws)

    @property
    def is_thermal(self) -> bool:
        """True when the viscosity follows the temperature (a temperature law is given)."""
        return self.walther is not None or self.temperature_exponent is not None

    def at_temperature(self, temperature: float) -> "Lubricant":
        """The same oil held at ``temperature`` [K]: viscosity mu(T) as its mu0, the same
        pressure laws and properties, no temperature law (what an isothermal film
        takes)."""
        if isinstance(temperature, bool) or not isinstance(
                temperature, (int, float, np.floating, np.integer)):
            raise ValueError(f"temperature must be a number > 0 [K], got {temperature!r}")
        t = float(temperature)
        mu = float(self.viscosity_at(0.0, temperature=t))    # refused outside the law's range
        if self.is_thermal:       # the law extrapolated: said, not refused (a hot transient)
            note = temperature_range_note(t, "the oil held at a temperature")
            if note is not None:
                warnings.warn(note, OilRangeWarning, stacklevel=2)
        return replace(self, viscosity=mu, temperature=t, walther=None,
                       temperature_exponent=None)

    # -- viscosity ---------------------------------------------------------------------
    @property
    def pressure_viscosity(self) -> float:
        """d ln(mu)/dp at ambient and the reference temperature [1/Pa]: alpha for Barus,
        alpha* for Roelands, 0 else."""
        if self.roelands is not None:
            return self.roelands * (math.log(self.viscosity) - ROELANDS_LN_MU_INF) / ROELANDS_P0
        return float(self.barus or 0.0)

    @cached_property          # once per oil: it bounds every call's temperatures
    def temperature_range(self) -> tuple[float, float]:
        """(T_lo, T_hi) [K]: the open range where the temperature law gives a finite
        viscosity > 0 and a finite slope d mu/dT at ambient pressure (a pressure law
        multiplies them further); (0, inf) without a law.

        Walther's nu + 0.7 = z = 10^x, x = 10^(A - B log10 T), overflows towards 0 K: T_lo
        is where its slope d nu/dT = -z ln10 x ln10 B / T, as evaluated (its partial
        products up to z ln10 x max(1, B, B/T)), reaches the largest float, a fraction of a
        kelvin above where nu itself does (x = log10 of the largest float, 308.25); it has
        no upper end (nu -> 0.3 mm^2/s). The exponential law mu0 exp(x), x = -beta (T - T0),
        overflows where exp(x), mu or beta mu reaches the largest float and vanishes where
        exp(x) or mu falls below the least normal float (T_hi). Where an ISO VG oil's law
        is its measured chart is :data:`~bearingfem.oil_range.OIL_TEMPERATURE_RANGE`; this
        is only where the law's numbers exist."""
        if self.walther is not None:
            a, b = self.walther
            # Newton on u = log10 T for ln(z ln10 x max(1, B, B/T)) = LN_MAX, x = 10^(A - B u)
            # (z = 10^x): from where z overflows (x ln10 = LN_MAX) it moves up, a few steps
            u = (a - math.log10(LN_MAX / LN10)) / b
            for _ in range(30):
                x = 10.0 ** (a - b * u)
                # the slope's largest partial product as evaluated: z ln10 x max(1, B, B/T)
                last = max(0.0, math.log(b), math.log(b) - u * LN10)
                f = x * LN10 + math.log(LN10 * x) + last - LN_MAX
                df = -b * LN10 * (x * LN10 + 1.0) - (LN10 if last > max(0.0, math.log(b))
                                                     else 0.0)
                step = f / df
                u -= step
                if abs(step) < 1e-14 * abs(u):
                    break
            # the rounding of the law's evaluation (a few ulp of its 709 in the exponent)
            return 10.0 ** u * (1.0 + 1e-12), math.inf
        beta = self.temperature_exponent
        if beta:                  # mu = mu0 exp(x), x = -beta (T - T0)
            t0, ln_mu0 = self.temperature, math.log(self.viscosity)
            # exp(x), mu and beta mu floats; exp(x) and mu at least the least normal float
            lo = t0 - (LN_MAX - max(0.0, ln_mu0, ln_mu0 + math.log(beta))) / beta
            hi = t0 + (min(0.0, ln_mu0) - LN_TINY) / beta
            return max(lo, 0.0), hi
        return 0.0, math.inf

    def _temperature(self, temperature) -> np.ndarray:
        """``temperature`` [K] as an array, refused (ValueError) where the law has no
        finite viscosity: <= 0 K, NaN, or outside :attr:`temperature_range`."""
        t = np.asarray(temperature, dtype=float)
        lo, hi = self.temperature_range
        if t.size == 0:
            return t
        # one pass over the points (a thermal film's every quadrature point); NaN fails it
        least = float(t.min()) if hi == math.inf else None
        if least is not None and least > lo:
            return t
        if least is None and float(t.min()) > lo and float(t.max()) < hi:
            return t
        bad = t[~((t > lo) & (t < hi))].flat[0]
        span = f"({lo:.6g}, {hi:.6g}) K" if hi < math.inf else f"({lo:.6g}, inf) K"
        hint = (f": temperatures are in kelvin ({bad:g} degC = {bad + CELSIUS:g} K)"
                if math.isfinite(bad) and bad <= lo else "")
        raise TemperatureRangeError(f"temperature {bad:g} K is outside {span}, where the "
                                    f"oil's viscosity law gives a finite viscosity{hint}")

    def _viscosity_ambient(self, temperature) -> tuple[np.ndarray, np.ndarray]:
        """mu_T [Pa s] at ambient pressure and d ln(mu_T)/dT [1/K] at ``temperature``
        (refused outside :attr:`temperature_range`)."""
        if temperature is None:
            return np.full((), self.viscosity), np.zeros(())
        t = self._temperature(temperature)
        if not self.is_thermal:
            return np.full(t.shape, self.viscosity), np.zeros(t.shape)
        if self.temperature_exponent is not None:
            beta = self.temperature_exponent
            return self.viscosity * np.exp(-beta * (t - self.temperature)), \
                np.full_like(t, -beta)
        a, b = self.walther
        # nu + 0.7 = 10^(10^(A - B log10 T)); mu = rho nu. The powers of ten as exp(x ln 10):
        # the same values to round-off at a fifth of np.power's cost (a thermal film
        # evaluates the law at every quadrature point of every step)
        inner = np.exp(LN10 * (a - b * np.log10(t)))
        z = np.exp(LN10 * inner)
        nu = z - WALTHER_SHIFT
        mu = 1e-6 * self.mass_density * nu
        # d nu/dT = z ln10 * inner ln10 * (-B / (T ln10))
        dnu = -z * LN10 * inner * b / t
        return mu, dnu / nu

    def _log_viscosity_ratio(self, p: np.ndarray, mu_t) -> tuple[np.ndarray, np.ndarray]:
        """ln(mu/mu_T) and its derivative d/dp at gauge pressure p, mu_T the ambient
        viscosity at the temperature."""
        if self.roelands is not None:
            z = self.roelands
            c = np.log(mu_t) - ROELANDS_LN_MU_INF
            # below -p0 the law has no meaning; clip so a Newton iterate cannot make NaN
            s = np.maximum(1.0 + p / ROELANDS_P0, 1e-12)
            return c * (s**z - 1.0), c * z * s**(z - 1.0) / ROELANDS_P0
        alpha = float(self.barus or 0.0)
        return alpha * p, np.full_like(p, alpha)

    def viscosity_at(self, p=0.0, *, temperature=None) -> np.ndarray:
        """Viscosity mu(p, T) [Pa s] at gauge pressure p [Pa] and ``temperature`` [K]
        (arrays broadcast, or scalars; None: the reference temperature)."""
        mu_t, _ = self._viscosity_ambient(temperature)
        p = np.asarray(p, dtype=float)
        p = p + np.zeros_like(mu_t)
        return mu_t * np.exp(self._log_viscosity_ratio(p, mu_t)[0])

    def viscosity_derivative(self, p=0.0, *, temperature=None) -> np.ndarray:
        """d mu / d p [Pa s / Pa] at gauge pressure p [Pa] and ``temperature`` [K]."""
        mu_t, _ = self._viscosity_ambient(temperature)
        p = np.asarray(p, dtype=float)
        p = p + np.zeros_like(mu_t)
        log_ratio, slope = self._log_viscosity_ratio(p, mu_t)
        return mu_t * np.exp(log_ratio) * slope

    def viscosity_temperature_derivative(self, temperature, p=0.0) -> np.ndarray:
        """d mu / d T [Pa s / K] at ``temperature`` [K] and gauge pressure p [Pa]
        (0 for an oil without a temperature law)."""
        mu_t, dlog = self._viscosity_ambient(np.asarray(temperature, dtype=float))
        p = np.asarray(p, dtype=float) + np.zeros_like(mu_t)
        log_ratio, _ = self._log_viscosity_ratio(p, mu_t)
        mu = mu_t * np.exp(log_ratio)
        if self.roelands is not None:     # Roelands' exponent grows with ln mu_T
            s = np.maximum(1.0 + p / ROELANDS_P0, 1e-12)
            return mu * dlog * s**self.roelands
        return mu * dlog

    def viscosity_and_slopes(self, p, temperature) -> tuple:
        """(mu [Pa s], d mu/dp [Pa s/Pa], d mu/dT [Pa s/K]) at gauge pressure p [Pa] and
        ``temperature`` [K], the temperature law evaluated once (a coupled Newton's
        Jacobian needs all three at every point); the same values as
        :meth:`viscosity_at`, :meth:`viscosity_derivative` and
        :meth:`viscosity_temperature_derivative`."""
        mu_t, dlog = self._viscosity_ambient(np.asarray(temperature, dtype=float))
        p = np.asarray(p, dtype=float) + np.zeros_like(mu_t)
        log_ratio, slope = self._log_viscosity_ratio(p, mu_t)
        mu = mu_t * np.exp(log_ratio)
        d_t = mu * dlog
        if self.roelands is not None:     # Roelands' exponent grows with ln mu_T
            d_t = d_t * np.maximum(1.0 + p / ROELANDS_P0, 1e-12) ** self.roelands
        return mu, mu * slope, d_t

    def kinematic_viscosity_at(self, temperature=None) -> np.ndarray:
        """Kinematic viscosity mu/rho [m^2/s] at ambient pressure and ``temperature`` [K];
        needs ``mass_density``."""
        if self.mass_density is None:
            raise ValueError("kinematic_viscosity_at needs the oil's mass_density [kg/m^3]")
        return self._viscosity_ambient(temperature)[0] / self.mass_density

    # -- density -----------------------------------------------------------------------
    def density_at(self, p) -> np.ndarray:
        """Density ratio rho/rho0 [-] at gauge pressure p [Pa]."""
        p = np.asarray(p, dtype=float)
        if self.density == "dowson-higginson":
            return 1.0 + DH_A * p / (1.0 + DH_B * p)
        if self.bulk_modulus is not None:
            return np.exp(p / self.bulk_modulus)
        return np.ones_like(p)

    def density_derivative(self, p) -> np.ndarray:
        """d(rho/rho0)/dp [1/Pa] at gauge pressure p [Pa]."""
        p = np.asarray(p, dtype=float)
        if self.density == "dowson-higginson":
            return DH_A / (1.0 + DH_B * p) ** 2
        if self.bulk_modulus is not None:
            return np.exp(p / self.bulk_modulus) / self.bulk_modulus
        return np.zeros_like(p)
