"""Closed forms of the line contact: Hertz, the rigid isoviscous film, and EHL film fits.

Dimensionless groups (Hamrock's): W = w/(E' R), U = mu0 u_m/(E' R), G = alpha E', with
u_m the mean surface speed. Moes' groups, used to place a case on the regime chart,
are M = W (2U)^(-1/2) and L = G (2U)^(1/4) (Venner & Lubrecht 2000, Ch. 7).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.optimize

__all__ = ["HertzLine", "hertz_line", "moes_parameters", "pan_hamrock", "dowson_higginson",
           "rigid_isoviscous_load", "rigid_isoviscous_pressure"]

MARTIN_LOAD = 2.44748  # w h0 / (2 mu0 u_m R): rigid, isoviscous, Reynolds exit, far inlet


@dataclass(frozen=True)
class HertzLine:
    """Hertz's dry line contact: half-width b [m] and peak pressure p_h [Pa]."""

    half_width: float
    pressure: float


def hertz_line(radius: float, reduced_modulus: float, load_per_length: float) -> HertzLine:
    """b = sqrt(8 w R / (pi E')), p_h = 2 w / (pi b) (Johnson 1985, Eq. 4.45)."""
    b = math.sqrt(8.0 * load_per_length * radius / (math.pi * reduced_modulus))
    return HertzLine(b, 2.0 * load_per_length / (math.pi * b))


def moes_parameters(radius, reduced_modulus, viscosity, mean_speed, load_per_length,
                    pressure_viscosity) -> tuple[float, float]:
    """Moes' (M, L) of a line contact."""
    W = load_per_length / (reduced_modulus * radius)
    U = viscosity * mean_speed / (reduced_modulus * radius)
    return W / math.sqrt(2 * U), pressure_viscosity * reduced_modulus * (2 * U) ** 0.25


@dataclass(frozen=True)
class FilmFit:
    """Central and minimum film [m] of a fit."""

    central: float
    minimum: float


def pan_hamrock(radius, reduced_modulus, viscosity, mean_speed, load_per_length,
                pressure_viscosity) -> FilmFit:
    """Pan & Hamrock (J. Tribol. 111, 1989, 246-251), fitted to their numerical solutions:
    h_min/R = 1.714 W^-0.128 U^0.694 G^0.568, h_c/R = 2.922 W^-0.166 U^0.692 G^0.470."""
    W = load_per_length / (reduced_modulus * radius)
    U = viscosity * mean_speed / (reduced_modulus * radius)
    G = pressure_viscosity * reduced_modulus
    return FilmFit(radius * 2.922 * W**-0.166 * U**0.692 * G**0.470,
                   radius * 1.714 * W**-0.128 * U**0.694 * G**0.568)


def dowson_higginson(radius, reduced_modulus, viscosity, mean_speed, load_per_length,
                     pressure_viscosity) -> float:
    """Dowson & Higginson (1966) minimum film: h_min/R = 2.65 U^0.7 G^0.54 W^-0.13."""
    W = load_per_length / (reduced_modulus * radius)
    U = viscosity * mean_speed / (reduced_modulus * radius)
    G = pressure_viscosity * reduced_modulus
    return radius * 2.65 * U**0.7 * G**0.54 * W**-0.13


def rigid_isoviscous_pressure(xi: np.ndarray, inlet: float) -> tuple[np.ndarray, float]:
    """Pressure of the rigid isoviscous film at xi = x/sqrt(2 R h0), in units of
    12 mu0 u_m sqrt(2 R h0)/h0^2, inlet at xi = inlet < 0 with the Reynolds exit; and the
    exit xi = c. Integrated in closed form with xi = tan(gamma):
    p = int_inlet^xi (s^2 - c^2)/(1 + s^2)^3 ds, d xi/(1+xi^2)^3 = cos^4 d gamma,
    xi^2 d xi/(1+xi^2)^3 = sin^2 cos^2 d gamma, and p(c) = 0 fixes c.
    """
    def pressure(x, c):
        def antiderivative(gam):
            sin2cos2 = gam / 8 - np.sin(4 * gam) / 32
            cos4 = 3 * gam / 8 + np.sin(2 * gam) / 4 + np.sin(4 * gam) / 32
            return sin2cos2 - c**2 * cos4
        return antiderivative(np.arctan(x)) - antiderivative(np.arctan(inlet))

    c = scipy.optimize.brentq(lambda c: pressure(c, c), 1e-6, 2.0, xtol=1e-15)
    xi = np.asarray(xi, float)
    inside = (xi >= inlet) & (xi <= c)
    return np.where(inside, pressure(np.clip(xi, inlet, c), c), 0.0), c


def rigid_isoviscous_load(inlet: float) -> float:
    """w h0 / (2 mu0 u_m R) of the rigid isoviscous film with its inlet at x = inlet sqrt(2 R h0)
    (inlet < 0) and the Reynolds exit. As inlet -> -inf it tends to 3/(1 + c^2) = 2.44748
    (c = 0.475130 the exit), Martin's (1916) classical result, often quoted as 2.4493-2.4496
    from coarser evaluations of the exit.
    """
    c = rigid_isoviscous_pressure(0.0, inlet)[1]
    # int_inlet^c p dxi = -int_inlet^c s g(s) ds (by parts, p = 0 at both ends), with
    # g = (s^2 - c^2)/(1 + s^2)^3 and s g(s) ds = d/ds F(1 + s^2), F(u) = (-1/u + (1+c^2)/(2u^2))/2
    def F(u):
        return 0.5 * (-1.0 / u + (1.0 + c**2) / (2.0 * u**2))

    return -12.0 * (F(1.0 + c**2) - F(1.0 + inlet**2))
