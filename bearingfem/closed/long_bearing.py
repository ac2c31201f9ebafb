"""Long-bearing (Pinkus-Sternlicht) model: closed form (seed Eq. 11-13) and exact quadrature.

Dropping the axial flow, d/dtheta(H^3 dP/dtheta) = -f with P = 0 at the maximum film gives
the corrected seed Eq. 10 (seed-corrections §1: its last term is 1/(1+eps)^2):

    P = 6 w eps sin(theta) (2 + eps cos theta) / ((2 + eps^2) H^2)
        + 6 (eps_dot / eps) [1/H^2 - 1/(1 + eps)^2],      w = omega - 2 gamma_dot.
"""
from __future__ import annotations

import math

import numpy as np

from ..bearing import Bearing, JournalState
from ..differentiate import complex_step
from ..film import film_thickness
from ..validation import check_inputs
from .quadrature import theta_nodes

__all__ = ["long_bearing_force", "long_bearing_derivatives", "long_bearing_exact_force",
           "long_bearing_pressure"]


def _dimensionless_pressure(theta, eps, eps_dot, w):
    th = np.asarray(theta, float)
    H = film_thickness(th, eps)
    wedge = 6.0 * w * eps * np.sin(th) * (2.0 + eps * np.cos(th)) / ((2.0 + eps * eps) * H * H)
    # (1/H^2 - 1/(1+eps)^2)/eps without cancellation, finite as eps -> 0.
    squeeze = (6.0 * eps_dot * (1.0 - np.cos(th)) * (2.0 + eps * (1.0 + np.cos(th)))
               / (H * H * (1.0 + eps) ** 2))
    return wedge + squeeze


def long_bearing_pressure(bearing: Bearing, state: JournalState, theta):
    """Uncavitated long-bearing pressure [Pa] at film angle theta (corrected seed Eq. 10)."""
    return bearing.pressure_scale * _dimensionless_pressure(
        theta, state.eps, state.eps_dot, state.wedge_speed)


def long_bearing_force(bearing: Bearing, state: JournalState):
    """(F_r, F_t) [N]: Pinkus-Sternlicht long bearing, seed Eq. 11-13.

    Written with s = 2 eps_dot (= E omega) and w = omega - 2 gamma_dot (= (1 - G) omega) so
    that omega = 0 (pure squeeze), eps_dot = 0 (E = 0, k -> infinity) and eps = 0 are
    ordinary inputs. The prefactor is mu omega R^3 L / c^2, the dimensionally consistent
    one (seed-corrections §2), and F_t carries the contract's sign (positive for omega > 0).
    """
    check_inputs(bearing, state)
    return tuple(float(np.real(f)) for f in _long_force(
        bearing, state.eps, state.eps_dot, state.wedge_speed))


def long_bearing_derivatives(bearing: Bearing, state: JournalState):
    """:class:`~bearingfem.solution.ForceDerivatives` of :func:`long_bearing_force`,
    exact (complex step on the same closed form)."""
    check_inputs(bearing, state)
    return complex_step(lambda e, ed, w: _long_force(bearing, e, ed, w),
                        state.eps, state.eps_dot, state.wedge_speed)


def _long_force(bearing: Bearing, e, eps_dot, w):
    """Seed Eq. 11-13 (corrected) in complex-safe arithmetic: |s| and hypot are written
    out, signs read off real parts."""
    s = 2.0 * eps_dot
    root = np.sqrt(1.0 - e * e)
    v = np.sqrt((e * w) ** 2 + s * s)            # = |s| eps k / sqrt(1 - eps^2)
    s_abs = -s if np.real(s) < 0.0 else s
    inv_k = s_abs * e / (root * v) if np.real(v) > 0.0 else 0.0
    ratio = ((1.0 + 3.0 * inv_k) / (1.0 + 1.5 * inv_k) if np.real(s) >= 0.0
             else 1.0 / (1.0 + 1.5 * inv_k))
    k0 = bearing.viscosity * bearing.radius ** 3 * bearing.length / bearing.clearance ** 2
    d = 2.0 + e * e
    f_r = -3.0 * k0 / (d * root ** 3) * (4.0 * e * root * v + math.pi * s * d * ratio)
    f_t = 6.0 * math.pi * k0 * e * w * ratio / (d * root)
    return f_r, f_t


def long_bearing_exact_force(bearing: Bearing, state: JournalState, *, n_sample: int = 720):
    """(F_r, F_t) [N] integrating max(P, 0) of corrected seed Eq. 10 over the film.

    The positive region is located on a fine sample and each sign change refined by
    bisection, then integrated by graded Gauss-Legendre quadrature.
    """
    check_inputs(bearing, state)
    e, ed, w = state.eps, state.eps_dot, state.wedge_speed
    if ed == 0.0 and w == 0.0:
        return 0.0, 0.0

    def P(t):
        return _dimensionless_pressure(t, e, ed, w)

    t = np.linspace(0.0, 2 * np.pi, n_sample + 1)
    p = P(t)
    pos = p > 0.0
    roots = []
    for i in np.flatnonzero(pos[:-1] != pos[1:]):
        a, b = t[i], t[i + 1]
        pa = p[i]
        for _ in range(60):
            m = 0.5 * (a + b)
            pm = P(m)
            if (pm > 0.0) == (pa > 0.0):
                a, pa = m, pm
            else:
                b = m
        roots.append(0.5 * (a + b))
    edges = np.concatenate(([0.0], roots, [2 * np.pi]))
    fr = ft = 0.0
    for a, b in zip(edges[:-1], edges[1:]):
        if P(0.5 * (a + b)) <= 0.0:
            continue
        x, wq = theta_nodes(a, b, e)
        px = np.maximum(P(x), 0.0) * wq
        fr += float(np.sum(px * np.cos(x)))
        ft += float(np.sum(px * np.sin(x)))
    k = bearing.pressure_scale * bearing.radius * bearing.length
    return k * fr, k * ft
