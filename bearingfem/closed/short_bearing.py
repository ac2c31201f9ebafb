"""Short-bearing (Ocvirk/Frene) model: closed form (seed Eq. 9) and exact quadrature.

Dropping the circumferential flow, -d/dzeta(H^3 dP/dzeta) = f gives (seed Eq. 8)

    p = mu (R/c)^2 f(theta) (lam^2 - zeta^2) / (2 H^3),   lam = L/D,  zeta = z/R,
    f = 6 (omega - 2 gamma_dot) eps sin(theta) - 12 eps_dot cos(theta),

and the axial integral of (lam^2 - zeta^2) over the length gives L^3 / (6 R^3).
"""
from __future__ import annotations

import math

import numpy as np

from ..bearing import Bearing, JournalState
from ..differentiate import complex_step
from ..film import film_thickness, reynolds_source, source_coefficients
from ..validation import check_inputs
from .quadrature import theta_nodes

__all__ = ["short_bearing_force", "short_bearing_derivatives", "short_bearing_exact_force",
           "short_bearing_pressure"]


def short_bearing_pressure(bearing: Bearing, state: JournalState, theta, z):
    """Uncavitated short-bearing pressure [Pa] at film angle theta and axial z [m]."""
    th = np.asarray(theta, float)
    f = reynolds_source(th, state.eps, state.eps_dot, state.wedge_speed)
    H = film_thickness(th, state.eps)
    zeta = np.asarray(z, float) / bearing.radius
    return bearing.pressure_scale * f * (bearing.length_ratio ** 2 - zeta ** 2) / (2 * H ** 3)


def short_bearing_force(bearing: Bearing, state: JournalState, *, half_film: str = "wedge",
                        switch_speed: float = 0.0):
    """(F_r, F_t) [N]: Frene's short bearing with Gumbel's condition, seed Eq. 9.

    The pressure is integrated over a fixed half film. With ``half_film="wedge"`` (default)
    it is the half the wedge pressurises: 0 <= theta <= pi when omega - 2 gamma_dot >= 0,
    where this is seed Eq. 9 exactly, and its mirror image pi..2 pi otherwise (F_r kept,
    F_t reversed). ``half_film="fixed"`` applies Eq. 9 literally for every sign; for
    omega - 2 gamma_dot < 0 it then integrates the diverging half and pulls the journal
    outward (F_r > 0). Either way the result equals the Gumbel solution only when
    eps_dot = 0; see :func:`short_bearing_exact_force` for the exact positive region.

    Turning the half film makes the squeeze part of F_t, 4 k eps eps_dot, jump sign where
    omega - 2 gamma_dot changes sign. ``switch_speed`` > 0 [rad/s] smooths that switch to
    tanh((omega - 2 gamma_dot) / switch_speed), which a time integrator can follow.
    """
    check_inputs(bearing, state)
    _check_options(half_film, switch_speed)
    return tuple(float(np.real(f)) for f in _short_force(
        bearing, state.eps, state.eps_dot, state.wedge_speed, half_film, switch_speed))


def short_bearing_derivatives(bearing: Bearing, state: JournalState, *,
                              half_film: str = "wedge", switch_speed: float = 0.0):
    """:class:`~bearingfem.solution.ForceDerivatives` of :func:`short_bearing_force`,
    exact (complex step on the same closed form)."""
    check_inputs(bearing, state)
    _check_options(half_film, switch_speed)
    return complex_step(lambda e, ed, w: _short_force(bearing, e, ed, w, half_film,
                                                      switch_speed),
                        state.eps, state.eps_dot, state.wedge_speed)


def _check_options(half_film, switch_speed):
    if half_film not in ("wedge", "fixed"):
        raise ValueError(f"half_film must be 'wedge' or 'fixed', got {half_film!r}")
    if not (math.isfinite(switch_speed) and switch_speed >= 0.0):
        raise ValueError(f"switch_speed must be a finite number >= 0 [rad/s], got {switch_speed!r}")


def _short_force(bearing: Bearing, e, ed, w, half_film, switch_speed):
    """Seed Eq. 9 in complex-safe arithmetic (the sign of w is read off its real part)."""
    mu, R, L, c = bearing.viscosity, bearing.radius, bearing.length, bearing.clearance
    if half_film == "fixed":
        sign, w_abs = 1.0, w
    else:
        w_abs = -w if np.real(w) < 0.0 else w
        if switch_speed > 0.0:
            sign = np.tanh(w / switch_speed)
        else:
            sign = -1.0 if np.real(w) < 0.0 else 1.0
    s2 = 1.0 - e * e
    k = mu * L ** 3 * R / (2.0 * c * c * s2 * s2)
    f_r = -k * (math.pi * ed * (1.0 + 2.0 * e * e) / np.sqrt(s2) + 2.0 * e * e * w_abs)
    # sign(w) (4 eps_dot + pi/2 sqrt(1-eps^2) |w|): only the squeeze part switches
    f_t = k * e * (4.0 * ed * sign + 0.5 * math.pi * np.sqrt(s2) * w)
    return f_r, f_t


def short_bearing_exact_force(bearing: Bearing, state: JournalState, *, fixed_half_film=False):
    """(F_r, F_t) [N] integrating the short-bearing pressure where it is positive.

    f(theta) = A sin(theta) + B cos(theta) is positive on one interval of length pi,
    theta in (-delta, pi - delta) with delta = atan2(B, A); integrating there is the exact
    Gumbel (half-Sommerfeld) short bearing for any squeeze rate. With
    ``fixed_half_film=True`` the (signed) pressure is integrated over [0, pi] instead,
    which reproduces seed Eq. 9.
    """
    check_inputs(bearing, state)
    e = state.eps
    A, B = source_coefficients(e, state.eps_dot, state.wedge_speed)
    if A == 0.0 and B == 0.0:
        return 0.0, 0.0
    if fixed_half_film:
        parts = [(0.0, math.pi)]
    else:
        lo = (-math.atan2(B, A)) % (2 * math.pi)
        hi = lo + math.pi
        parts = [(lo, min(hi, 2 * math.pi))]
        if hi > 2 * math.pi:
            parts.append((0.0, hi - 2 * math.pi))
    th = np.concatenate([theta_nodes(a, b, e)[0] for a, b in parts])
    wq = np.concatenate([theta_nodes(a, b, e)[1] for a, b in parts])
    g = reynolds_source(th, e, state.eps_dot, state.wedge_speed) / film_thickness(th, e) ** 3
    # Axial integral: R^2 * int (lam^2 - zeta^2)/2 dzeta = L^3 / (12 R) ... times mu R^2/c^2.
    k = bearing.viscosity * bearing.length ** 3 * bearing.radius / (12.0 * bearing.clearance ** 2)
    return k * float(np.sum(wq * g * np.cos(th))), k * float(np.sum(wq * g * np.sin(th)))
