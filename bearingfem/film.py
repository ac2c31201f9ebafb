"""Film physics shared by every model, in the line-of-centres frame.

theta is measured from the maximum film, in the sense of positive omega; z along the axis.
The journal centre sits at e (cos gamma, sin gamma), so theta = alpha - gamma - pi for an
inertial position angle alpha.

Reynolds equation (seed Eq. 6) in dimensionless form, with H = h/c, zeta = z/R and the
dimensional pressure p = mu (R/c)^2 P:

    -div(H^3 grad P) = f,   f = 6 (omega - 2 gamma_dot) eps sin(theta) - 12 eps_dot cos(theta)

P carries units of 1/s and is linear in (omega - 2 gamma_dot, eps_dot).
"""
from __future__ import annotations

import numpy as np

__all__ = ["film_thickness", "film_thickness_at", "film_thickness_integral",
           "cubed_thickness_coefficients", "reynolds_source",
           "source_coefficients", "reynolds_source_integral", "theta_from_inertial",
           "inertial_from_theta", "local_to_inertial"]


def film_thickness(theta, eps, clearance=1.0):
    """h = c (1 + eps cos theta) [m] (seed Eq. 7); dimensionless H when clearance=1."""
    return film_thickness_at(np.cos(theta), eps, clearance)


def film_thickness_at(cos_theta, eps, clearance=1.0):
    """:func:`film_thickness` from cos(theta) given: a fixed mesh's points keep their
    cosine, which costs more than the gap itself at every film evaluation."""
    return clearance * (1.0 + eps * cos_theta)


def film_thickness_integral(theta_lo, theta_hi, eps):
    """Exact integral of H = 1 + eps cos(theta) over [theta_lo, theta_hi] [rad]: the film
    content of a control volume per unit width (JFO films)."""
    return (theta_hi - theta_lo) + eps * (np.sin(theta_hi) - np.sin(theta_lo))


def cubed_thickness_coefficients(eps, derivative: bool = False):
    """(a_0..a_3) with H^3 = sum_k a_k cos^k(theta): (1, 3 eps, 3 eps^2, eps^3); with
    ``derivative`` their d/d(eps), (0, 3, 6 eps, 3 eps^2). Discretisations assemble one
    matrix per cos^k and combine them with these."""
    e = float(eps)
    if derivative:
        return (0.0, 3.0, 6.0 * e, 3.0 * e * e)
    return (1.0, 3.0 * e, 3.0 * e * e, e ** 3)


def source_coefficients(eps, eps_dot, wedge_speed):
    """(a_sin, a_cos) [1/s] with f = a_sin sin(theta) + a_cos cos(theta):
    the wedge 6 w eps and the squeeze -12 eps_dot. f is linear in each of them."""
    return 6.0 * wedge_speed * eps, -12.0 * eps_dot


def reynolds_source(theta, eps, eps_dot, wedge_speed):
    """Right-hand side f of -div(H^3 grad P) = f [1/s]."""
    a_sin, a_cos = source_coefficients(eps, eps_dot, wedge_speed)
    return a_sin * np.sin(theta) + a_cos * np.cos(theta)


def reynolds_source_integral(theta_lo, theta_hi, eps, eps_dot, wedge_speed):
    """Exact integral of f over theta in [theta_lo, theta_hi] [rad/s] (finite volumes)."""
    a_sin, a_cos = source_coefficients(eps, eps_dot, wedge_speed)
    return (a_sin * (np.cos(theta_lo) - np.cos(theta_hi))
            + a_cos * (np.sin(theta_hi) - np.sin(theta_lo)))


def theta_from_inertial(alpha, gamma):
    """Film angle theta in [0, 2 pi) of the inertial position angle alpha."""
    return np.mod(alpha - gamma - np.pi, 2.0 * np.pi)


def inertial_from_theta(theta, gamma):
    """Inertial position angle alpha [rad] of the film angle theta (not wrapped)."""
    return theta + gamma + np.pi


def local_to_inertial(f_r, f_t, gamma):
    """F = F_r r_hat + F_t t_hat with r_hat = (cos g, sin g), t_hat = (-sin g, cos g)."""
    c, s = np.cos(gamma), np.sin(gamma)
    return f_r * c - f_t * s, f_r * s + f_t * c
