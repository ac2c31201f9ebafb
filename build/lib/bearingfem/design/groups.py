"""Dimensionless groups of a journal bearing (Raimondi & Boyd 1958; Shigley's notation).

N is the journal speed in revolutions per second, P = W / (L D) the unit load.
"""
from __future__ import annotations

import math

from ..bearing import Bearing, check_finite, check_positive

__all__ = ["sommerfeld_number", "load_from_sommerfeld", "friction_variable", "flow_variable",
           "petroff_friction"]


def _speed_rev(omega) -> float:
    omega = check_finite("omega", omega)
    if omega == 0.0:
        raise ValueError("omega must be non-zero [rad/s]: a film carries no steady load "
                         "without rotation")
    return abs(omega) / (2.0 * math.pi)


def sommerfeld_number(bearing: Bearing, load, omega) -> float:
    """S = (R/c)^2 mu N / P, N = |omega| / 2 pi [rev/s], P = W / (L D) [Pa]; ``load`` is
    the load magnitude W [N]."""
    W = check_positive("load", load)
    return ((bearing.radius / bearing.clearance) ** 2 * bearing.viscosity * _speed_rev(omega)
            * bearing.length * bearing.diameter / W)


def load_from_sommerfeld(bearing: Bearing, sommerfeld, omega) -> float:
    """The load W [N] at which ``bearing`` turning at ``omega`` has Sommerfeld number S."""
    S = check_positive("sommerfeld", sommerfeld)
    return ((bearing.radius / bearing.clearance) ** 2 * bearing.viscosity * _speed_rev(omega)
            * bearing.length * bearing.diameter / S)


def friction_variable(bearing: Bearing, friction_force, load) -> float:
    """(R/c) f with f = friction force / load (Raimondi & Boyd's friction variable)."""
    return bearing.radius / bearing.clearance * friction_force / check_positive("load", load)


def flow_variable(bearing: Bearing, flow, omega) -> float:
    """Q / (R c N L): a volume flow [m^3/s] made dimensionless (Raimondi & Boyd)."""
    return flow / (bearing.radius * bearing.clearance * _speed_rev(omega) * bearing.length)


def petroff_friction(bearing: Bearing, eps, omega, f_t) -> float:
    """Friction force [N] on the journal, opposing positive omega, of any film whose
    cavitated region carries full Couette shear:

        F_f = mu omega R^2 L / c * 2 pi / sqrt(1 - eps^2)  +  c eps F_t / (2 R).

    The first term integrates mu omega R / h over the whole film, the second is the
    Poiseuille shear h/2 dp/dx integrated by parts (int h' p = -c eps int p sin theta).
    """
    mu, R, L, c = bearing.viscosity, bearing.radius, bearing.length, bearing.clearance
    couette = mu * omega * R * R * L / c * 2.0 * math.pi / math.sqrt(1.0 - eps * eps)
    return couette + c * eps * f_t / (2.0 * R)
