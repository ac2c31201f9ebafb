"""The film's dimensional scales and the shear integral, written once for every solver.

Dimensionless film: p = mu (R/c)^2 P, zeta = z/R, H = h/c. An integral over (theta, zeta)
of a meshed half film (z >= 0, the symmetry of an aligned journal) is doubled to cover the
whole bearing: :func:`half_film_factor`.
"""
from __future__ import annotations

import numpy as np

__all__ = ["half_film_factor", "force_factor", "moment_factor", "flow_factor",
           "shear_friction"]


def half_film_factor(half: bool) -> float:
    """2 for a half film (z >= 0 meshed, mirrored), 1 for the whole length."""
    return 2.0 if half else 1.0


def force_factor(bearing, half: bool = False) -> float:
    """mu R^4 / c^2 [N s] (times 2 for a half film): force = this * integral of P over
    (theta, zeta)."""
    return bearing.force_scale * half_film_factor(half)


def moment_factor(bearing, half: bool = False) -> float:
    """mu R^5 / c^2 [N m s]: moment = this * integral of zeta P over (theta, zeta)
    (the lever arm z = R zeta)."""
    return bearing.force_scale * bearing.radius * half_film_factor(half)


def flow_factor(bearing, half: bool = False) -> float:
    """c R^2 / 12 [m^3] (times 2 for a half film): volume flow = this * the dimensionless
    Reynolds flux (H^3 grad P - 6 w H ... in the film's units, 1/s)."""
    return bearing.clearance * bearing.radius ** 2 / 12.0 * half_film_factor(half)


def shear_friction(bearing, omega: float, weight, H, dP_dtheta, *, couette_share=1.0,
                   poiseuille_share=1.0, viscosity=1.0, half: bool = False) -> float:
    """Shear force on the journal surface opposing positive omega [N].

    Wall shear tau = mu omega R / h + (h / 2R) dp/dtheta; dimensionless, tau R / (mu0 R^2/c)
    integrates (mu/mu0) omega / H + H dP/dtheta / 2 over (theta, zeta) with ``weight`` (the
    quadrature or cell weights). ``couette_share`` and ``poiseuille_share`` (arrays or
    numbers in [0, 1]) say where each part acts (cavitated zones, JFO film fraction);
    ``viscosity`` is mu/mu0 (a field or 1).
    """
    mu, R, c = bearing.viscosity, bearing.radius, bearing.clearance
    tau = (np.asarray(viscosity) * omega / H * couette_share
           + 0.5 * H * dP_dtheta * poiseuille_share)
    return mu * R ** 3 / c * half_film_factor(half) * float(np.sum(weight * tau))
