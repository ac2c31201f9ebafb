"""Inputs of a film solve: the bearing geometry and the journal's kinematic state.

Both are small frozen dataclasses validated on construction, so that bad input fails
before any work starts with a message naming the parameter and its allowed range.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from .film import theta_from_inertial

__all__ = ["Bearing", "JournalState", "Groove", "seed_bearing", "SEED_TABLE1",
           "check_positive", "check_finite", "plausibility_errors", "PLAUSIBLE",
           "check_surface_speed", "check_squeeze_speed"]


def check_finite(name: str, value) -> float:
    """Return ``value`` as float or raise ``ValueError`` naming ``name``."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number, got {value!r}") from None
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return v


def check_turn_angle(name: str, value) -> float:
    """``value`` [rad] finite and within a turn either way, [-2 pi, 2 pi]; ValueError
    naming ``name`` otherwise, with degrees typed for radians as the likely slip (90 was
    an angle of 90 rad, unseen: every angle of the API is in radians)."""
    a = check_finite(name, value)
    if abs(a) > 2.0 * math.pi:
        raise ValueError(f"{name} {a:g} rad is more than a turn: typed in degrees? "
                         f"({a:g} deg = {math.radians(a):.4g} rad); it lies in "
                         "[-2 pi, 2 pi] rad (a computed one: wrap it, angle % (2 pi))")
    return a


def check_positive(name: str, value) -> float:
    """Return ``value`` as float if finite and > 0, else raise ``ValueError``."""
    v = check_finite(name, value)
    if v <= 0.0:
        raise ValueError(f"{name} must be positive (> 0), got {value!r}")
    return v


#: The range every hydrodynamic journal bearing lies in (from hard-disk spindles to
#: turbine bearings): outside it a number was almost surely typed in the wrong unit.
#: diameter [m], clearance ratio c/R, L/D, viscosity [Pa s] (gases to cold heavy oil),
#: surface speed omega R [m/s], squeeze speed c |eps_dot| [m/s] (the journal centre's
#: speed along the line of centres: the seed's short-bearing runs reach |eps_dot| ~2e3 1/s
#: at c = 20 um and 250 rad/s, c |eps_dot| ~0.05 m/s (the centre's whole speed, with the
#: attitude's rate, 0.2 m/s); 10 m/s is 50 times the whole speed).
PLAUSIBLE = dict(diameter=(0.5e-3, 5.0), clearance_ratio=(1e-5, 0.05),
                 length_ratio=(0.01, 10.0), viscosity=(1e-6, 10.0), surface_speed=300.0,
                 squeeze_speed=10.0)


def plausibility_errors(diameter, length_ratio, clearance, viscosity,
                        names=("diameter", "L/D", "clearance", "viscosity")) -> list:
    """Messages for the inputs outside :data:`PLAUSIBLE`, each naming the likely unit
    mistake (``names``: how the caller spells the four inputs)."""
    n_d, n_ld, n_c, n_mu = names
    lo, hi = PLAUSIBLE["diameter"]
    out = []
    if diameter > hi:
        out.append(f"{n_d} {diameter:g} m is larger than any journal bearing's (<= {hi:g} m): "
                   f"typed in mm? ({diameter:g} mm = {diameter / 1e3:g} m)")
    elif diameter < lo:
        out.append(f"{n_d} {diameter:g} m is smaller than any journal bearing's "
                   f"(>= {lo * 1e3:g} mm): give it in m")
    ratio = clearance / (diameter / 2)
    lo, hi = PLAUSIBLE["clearance_ratio"]
    if not out and ratio > hi:
        # the unit that brings it into the range: um for a number like 50, mm for 0.05
        unit, scale = ("um", 1e-6) if lo <= ratio * 1e-6 <= hi else ("mm", 1e-3)
        out.append(f"{n_c} {clearance:g} m is {ratio:.3g} of the radius (a journal bearing's "
                   f"radial clearance is {lo:g} to {hi:g} of it): typed in {unit}? "
                   f"({clearance:g} {unit} = {clearance * scale:g} m)")
    elif not out and ratio < lo:
        out.append(f"{n_c} {clearance:g} m is {ratio:.3g} of the radius (a journal bearing's "
                   f"radial clearance is {lo:g} to {hi:g} of it): {n_d} typed in mm, or the "
                   f"clearance in um? (the clearance is radial, in m: 20 um = 20e-6)")
    lo, hi = PLAUSIBLE["length_ratio"]
    if not lo <= length_ratio <= hi:
        out.append(f"{n_ld} {length_ratio:g} is outside any journal bearing's ({lo:g} to "
                   f"{hi:g}): the length over the diameter, in the same unit")
    lo, hi = PLAUSIBLE["viscosity"]
    if viscosity > hi:
        out.append(f"{n_mu} {viscosity:g} Pa s is more than any lubricant's (<= {hi:g} Pa s): "
                   f"typed in cSt (mm^2/s) or mPa s? ({viscosity:g} mPa s = "
                   f"{viscosity / 1e3:g} Pa s; {viscosity:g} cSt of oil ~ "
                   f"{viscosity * 0.87e-3:.3g} Pa s)")
    elif viscosity < lo:
        out.append(f"{n_mu} {viscosity:g} Pa s is less than any fluid's (>= {lo:g} Pa s): "
                   f"give the dynamic viscosity in Pa s")
    return out


def check_surface_speed(radius: float, omega: float, name: str = "omega",
                        rpm: bool = False) -> None:
    """ValueError when the journal's surface speed |omega| R passes any journal bearing's
    (:data:`PLAUSIBLE`): a speed in rpm given as rad/s times a diameter in mm, say.
    ``rpm``: the caller's value was given in 1/min (``omega`` [rad/s] is its conversion);
    the message then names it and its limit so."""
    v, vmax = abs(omega) * radius, PLAUSIBLE["surface_speed"]
    if v > vmax and rpm:
        raise ValueError(
            f"{name} {omega * 30 / math.pi:g} 1/min gives a surface speed of {v:.4g} m/s at "
            f"radius {radius:g} m, above any journal bearing's ({vmax:g} m/s): |{name}| must "
            f"be at most {vmax / radius * 30 / math.pi:.5g} 1/min for this diameter, or is "
            f"the diameter in mm?")
    if v > vmax:
        raise ValueError(f"{name} {omega:g} rad/s gives a surface speed of {v:.4g} m/s at "
                         f"radius {radius:g} m, above any journal bearing's ({vmax:g} m/s): "
                         f"a speed in rpm given as rad/s ({omega:g} rpm = "
                         f"{omega * 3.141592653589793 / 30:.4g} rad/s), or the diameter in mm?")


def check_squeeze_speed(clearance: float, eps_dot: float, name: str = "eps_dot") -> None:
    """ValueError when the journal centre's speed along the line of centres, c |eps_dot|,
    passes any journal's in its bearing (:data:`PLAUSIBLE`): a rate typed with a wrong
    exponent, or the eccentricity's rate de/dt given in place of the ratio's."""
    v, vmax = abs(eps_dot) * clearance, PLAUSIBLE["squeeze_speed"]
    if v > vmax:
        raise ValueError(f"{name} {eps_dot:g} 1/s moves the journal centre at c |{name}| = "
                         f"{v:.4g} m/s (clearance {clearance:g} m), faster than any journal "
                         f"in its bearing ({vmax:g} m/s): {name} must lie in "
                         f"[{-vmax / clearance:.4g}, {vmax / clearance:.4g}] 1/s for this "
                         f"clearance (the rate of the ratio e/c, not of e)")


@dataclass(frozen=True)
class Bearing:
    """A plain cylindrical journal bearing.

    Parameters
    ----------
    radius : journal radius R [m]
    length : axial length L [m]
    clearance : radial clearance c [m]
    viscosity : dynamic viscosity mu [Pa s]

    Values outside the range of any journal bearing (:data:`PLAUSIBLE`: a diameter of
    0.5 mm to 5 m, c/R 1e-5 to 0.05, L/D 0.01 to 10, mu 1e-6 to 10 Pa s) are refused with
    a ValueError naming the likely unit mistake.
    """

    radius: float
    length: float
    clearance: float
    viscosity: float

    def __post_init__(self):
        for name in ("radius", "length", "clearance", "viscosity"):
            object.__setattr__(self, name, check_positive(name, getattr(self, name)))
        bad = plausibility_errors(self.diameter, self.length_ratio, self.clearance,
                                  self.viscosity, ("diameter (2 radius)", "L/D (length / "
                                                   "diameter)", "clearance", "viscosity"))
        if bad:
            raise ValueError("; ".join(bad))

    @property
    def diameter(self) -> float:
        return 2.0 * self.radius

    @property
    def length_ratio(self) -> float:
        """L/D, which is also the half length measured in journal radii (z/R)."""
        return self.length / (2.0 * self.radius)

    @property
    def pressure_scale(self) -> float:
        """mu (R/c)^2 [Pa s]: dimensional pressure = pressure_scale * P, P in 1/s."""
        return self.viscosity * (self.radius / self.clearance) ** 2

    @property
    def force_scale(self) -> float:
        """mu R^4 / c^2 [N s]: force = force_scale * (integral of P over (theta, z/R))."""
        return self.viscosity * self.radius ** 4 / self.clearance ** 2


#: The seed paper's Table 1 piston-pin bearing: diameter [m], radial clearance [m],
#: viscosity [Pa s]. Its length is set through L/D.
SEED_TABLE1 = dict(diameter=0.020, clearance=20e-6, viscosity=0.0117)


def seed_bearing(length_ratio: float = 1.0) -> Bearing:
    """The seed paper's Table-1 bearing (D = 20 mm, c = 20 um, mu = 0.0117 Pa s) at L/D
    ``length_ratio``: the default bearing of the command line, sweeps and studies."""
    D = SEED_TABLE1["diameter"]
    return Bearing(radius=D / 2, length=check_positive("length_ratio", length_ratio) * D,
                   clearance=SEED_TABLE1["clearance"], viscosity=SEED_TABLE1["viscosity"])


@dataclass(frozen=True)
class JournalState:
    """Kinematic state of the journal centre relative to the bearing.

    Parameters
    ----------
    eps : eccentricity ratio e/c, in [0, 1)
    eps_dot : d(eps)/dt [1/s]
    gamma : attitude angle of the eccentricity vector, inertial frame,
        counter-clockwise [rad]
    gamma_dot : d(gamma)/dt [rad/s]
    omega : angular speed of the journal relative to the bearing [rad/s]
    """

    eps: float
    eps_dot: float = 0.0
    gamma: float = 0.0
    gamma_dot: float = 0.0
    omega: float = 0.0

    def __post_init__(self):
        eps = check_finite("eps", self.eps)
        if not 0.0 <= eps < 1.0:
            raise ValueError(f"eps must lie in [0, 1), got {self.eps!r}")
        object.__setattr__(self, "eps", eps)
        for name in ("eps_dot", "gamma", "gamma_dot", "omega"):
            object.__setattr__(self, name, check_finite(name, getattr(self, name)))

    @property
    def wedge_speed(self) -> float:
        """omega - 2 gamma_dot [rad/s]: the speed that drives the wedge term."""
        return self.omega - 2.0 * self.gamma_dot

    @classmethod
    def from_eccentricity(cls, e_x, e_y, de_x, de_y, clearance, omega, eps_max=None):
        """State from the eccentricity vector (seed Eq. 2-5) and its rate [m, m/s].

        ``eps_max`` caps eps (same direction and rates), for callers that must evaluate a
        film at or beyond the wall.

        At e = 0 the attitude angle is undefined: gamma is then taken along the
        velocity (or 0) and gamma_dot = 0, which gives the correct forces because
        every model's force vanishes with eps and its squeeze part acts along r-hat.
        """
        e = math.hypot(e_x, e_y)
        if e > 0.0:
            gamma = math.atan2(e_y, e_x)
            e_dot = (e_x * de_x + e_y * de_y) / e
            gamma_dot = (e_x * de_y - e_y * de_x) / (e * e)
        else:
            gamma = math.atan2(de_y, de_x) if (de_x or de_y) else 0.0
            e_dot = math.hypot(de_x, de_y)
            gamma_dot = 0.0
        eps = e / clearance if eps_max is None else min(e / clearance, eps_max)
        return cls(eps=eps, eps_dot=e_dot / clearance, gamma=gamma, gamma_dot=gamma_dot,
                   omega=omega)


#: The largest eccentricity ratio an elastic film admits (:class:`ElasticJournalState`):
#: the journal centre may pass the clearance circle by at most one clearance. There the
#: rigid gap overlaps the bush by a whole clearance, so the bush's deflection exceeds the
#: clearance itself: beyond it a small-strain linear bush is no longer a fair model.
ELASTIC_EPS_CAP = 2.0


@dataclass(frozen=True)
class ElasticJournalState(JournalState):
    """A journal state an elastic film may take beyond the rigid clearance circle.

    As :class:`JournalState`, but eps lies in [0, ``ELASTIC_EPS_CAP``): at eps >= 1 the
    rigid gap c (1 + eps cos theta) is negative on an arc and only a bush's deflection w
    opens it (h = c (1 + eps cos theta) + w > 0), as in an EHL contact. Only films with a
    bush accept eps >= 1 (their model declares ``beyond_clearance``,
    :mod:`bearingfem.contract` rule 15); a rigid film refuses it with a ValueError naming
    eps. Below 1 it is the same state as a :class:`JournalState`.
    """

    def __post_init__(self):
        eps = check_finite("eps", self.eps)
        if not 0.0 <= eps < ELASTIC_EPS_CAP:
            raise ValueError(f"eps must lie in [0, {ELASTIC_EPS_CAP}) for an elastic film, "
                             f"got {self.eps!r}")
        object.__setattr__(self, "eps", eps)
        for name in ("eps_dot", "gamma", "gamma_dot", "omega"):
            object.__setattr__(self, name, check_finite(name, getattr(self, name)))


def check_inside_clearance(state: JournalState, what: str) -> None:
    """ValueError naming eps when a rigid film (``what``) is asked beyond the clearance
    circle (an :class:`ElasticJournalState` with eps >= 1): its gap would be negative."""
    if state.eps >= 1.0:
        raise ValueError(f"eps must lie in [0, 1) for {what} (a rigid film: its gap closes "
                         f"at eps = 1; only a film with a bush goes beyond), got {state.eps!r}")


@dataclass(frozen=True)
class Groove:
    """An axial supply groove over the whole length of the bearing.

    Parameters
    ----------
    angle : centre of the groove, inertial frame, counter-clockwise [rad]
    width : its angular width [rad], in (0, pi)
    pressure : supply pressure [Pa], >= 0; the film holds it over the groove (flooded)
    fraction : film fraction supplied, in [0, 1]; 1 is a flooded groove. A starved groove
        (fraction < 1) needs a mass-conserving film, which the Reynolds-condition films
        refuse.

    A pressurised groove over the full length meets the ambient ends: the pressure jumps
    there, and the flow it sends straight out of its ends grows without bound as the mesh
    is refined (a corner singularity of the model, not of the solver); forces and
    pressures converge.
    """

    angle: float
    width: float
    pressure: float = 0.0
    fraction: float = 1.0

    def __post_init__(self):
        object.__setattr__(self, "angle", check_turn_angle("groove angle", self.angle))
        w = check_finite("groove width", self.width)
        if not 0.0 < w < math.pi:
            raise ValueError(f"groove width must lie in (0, pi) [rad], got {self.width!r}")
        object.__setattr__(self, "width", w)
        p = check_finite("groove pressure", self.pressure)
        if p < 0.0:
            raise ValueError(f"groove pressure must be >= 0 [Pa], got {self.pressure!r}")
        object.__setattr__(self, "pressure", p)
        f = check_finite("groove fraction", self.fraction)
        if not 0.0 <= f <= 1.0:
            raise ValueError(f"groove fraction must lie in [0, 1], got {self.fraction!r}")
        object.__setattr__(self, "fraction", f)

    def arc(self, gamma: float):
        """(start, end) of the groove in the film angle theta of a journal at attitude
        ``gamma`` [rad], start in [0, 2 pi)."""
        lo = float(theta_from_inertial(self.angle - 0.5 * self.width, gamma))
        return lo, lo + self.width
