"""The oil temperatures taken: the range of an ISO VG mineral oil's viscosity law, the
check that refuses a temperature outside it (an option naming an oil's temperature) and the
note that says when a solved film's temperature left it (the warning's text,
:class:`~bearingfem.errors.OilRangeWarning`).

Temperatures are in kelvin; the refusing check also takes degrees Celsius for the options
given in them. ASTM D341-20, Standard practice for viscosity-temperature equations and
charts for liquid petroleum or hydrocarbon products.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["CELSIUS", "OIL_TEMPERATURE_RANGE", "LEAST_KELVIN", "check_oil_temperature",
           "check_kelvin", "temperature_range_note"]

CELSIUS = 273.15                   # [K]
#: [K] the oil temperatures taken, -50 to 200 C: a mineral oil film's, where the D341 chart
#: and its two-point lines are drawn (Walther's law overflows towards 0 K and is an
#: extrapolation far above 200 C). It refuses the command line's --oil-temperature and a
#: scene's oil_temperature (an ISO VG oil); a solved thermal film or an oil held by
#: at_temperature outside it warns (:func:`temperature_range_note`): other fluids, hot
#: synthetic oils and cryogens, have their own laws, so a Thermal's temperatures are
#: refused against an oil only below :data:`LEAST_KELVIN` and a law's points only at or
#: below 0 K. A supply temperature is refused where the law's viscosity is none, or below
#: this range more than a Bearing takes (:meth:`bearingfem.thermal.Thermal.check_fluid`);
#: a law's numbers exist only in Lubricant.temperature_range.
OIL_TEMPERATURE_RANGE = (CELSIUS - 50.0, CELSIUS + 200.0)
#: [K] the least temperature a Thermal takes for an oil (-73.15 C): a fluid whose
#: temperature law is referenced at or above it (Lubricant.temperature, or no law). Below
#: it a number meant in kelvin was surely typed in degrees Celsius (40 for 313.15 K, the
#: likeliest slip), which the film took and warned of only once solved. An oil film colder
#: than any mineral oil's pour point (~-50 C) is none of a thermal film's, and an
#: aircraft's ambient at altitude (-56.5 C, 216.65 K) is still taken. A fluid referenced
#: below it (a cryogen's law: liquid nitrogen's at 77-90 K) takes any temperature > 0 K
#: (:meth:`bearingfem.thermal.Thermal.check_fluid`).
LEAST_KELVIN = 200.0


def _number(name: str, value, span: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
        raise ValueError(f"{name} must be a number in {span}, got {value!r}")
    return float(value)


def check_kelvin(name: str, value, why: str = "") -> float:
    """``value`` [K], finite and >= :data:`LEAST_KELVIN`; ValueError naming ``name``, the
    range (``why`` it applies, words after it) and, when the number is a temperature in
    degrees Celsius, that slip."""
    span = (f"[{LEAST_KELVIN:g}, inf) K ({LEAST_KELVIN - CELSIUS:g} C up: kelvin, not degC)"
            f"{why}")
    v = _number(name, value, span)
    if not (math.isfinite(v) and v >= LEAST_KELVIN):
        hint = (f" (typed in degC? {value!r} degC is {v + CELSIUS:g} K)"
                if math.isfinite(v) and v + CELSIUS >= LEAST_KELVIN else "")
        raise ValueError(f"{name} must lie in {span}, got {value!r}{hint}")
    return v


def check_oil_temperature(name: str, value, *, unit: str = "K") -> float:
    """``value`` [K, or degC with ``unit="degC"``] in :data:`OIL_TEMPERATURE_RANGE`;
    ValueError naming ``name`` and the range otherwise."""
    lo, hi = OIL_TEMPERATURE_RANGE
    shift = CELSIUS if unit == "degC" else 0.0
    span = (f"[{lo - shift:g}, {hi - shift:g}] degC (an oil film's)" if unit == "degC" else
            f"[{lo:g}, {hi:g}] K ({lo - CELSIUS:g} to {hi - CELSIUS:g} C, an oil film's)")
    v = _number(name, value, span)
    if not (math.isfinite(v) and lo <= v + shift <= hi):
        # the other unit's number in range is the likely slip (313 for 40 C, 40 for 313 K)
        other = v - CELSIUS if unit == "degC" else v + CELSIUS
        hint = ""
        if math.isfinite(v) and lo <= other + shift <= hi:
            typed = "K" if unit == "degC" else "degC"
            hint = f" (typed in {typed}? {value!r} {typed} is {other:g} {unit})"
        raise ValueError(f"{name} must lie in {span}, got {value!r}{hint}")
    return v


def temperature_range_note(temperature, what: str = "the film's temperature") -> str | None:
    """None when every temperature [K] lies in :data:`OIL_TEMPERATURE_RANGE`; else one
    sentence with the extreme (``what`` reaches it) and the range (the oil law is
    extrapolated there, and the numbers with it)."""
    t = np.asarray(temperature, dtype=float)
    lo, hi = OIL_TEMPERATURE_RANGE
    t_min, t_max = float(np.min(t)), float(np.max(t))
    if lo <= t_min and t_max <= hi:
        return None
    worst = t_max if t_max > hi else t_min
    return (f"{what} reaches {worst:.6g} K ({worst - CELSIUS:.4g} C), "
            f"outside the oil law's range [{lo:g}, {hi:g}] K ({lo - CELSIUS:g} to "
            f"{hi - CELSIUS:g} C, an ISO VG mineral oil's chart): the viscosity there is "
            f"the law's extrapolation, and every number taken from it")
