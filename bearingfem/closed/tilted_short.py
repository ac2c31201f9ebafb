"""The short bearing with a tilted journal: the exact film of the axial Reynolds equation.

Dropping the circumferential flow (the short-bearing limit L/D -> 0, Ocvirk), the film of a
journal tilted by (tilt_x, tilt_y) (:func:`bearingfem.fields.tilted_gap`) is

    -d/dzeta (H^3 dP/dzeta) = f0(theta) + f1(theta) zeta,    P(-lam) = P(lam) = 0,

with H = a(theta) + b(theta) zeta linear in zeta = z/R (a = 1 + eps cos theta, b the
tilt's gap per unit zeta), lam = L/D, and the source -6 w dH/dtheta - 12 dH/dt also
linear in zeta. One integration gives H^3 P' = C1 - f0 zeta - f1 zeta^2 / 2, a second

    P(zeta) = C1 J0(zeta) - f0 J1(zeta) - f1 J2(zeta) / 2,
    J_m(zeta) = int_{-lam}^{zeta} s^m / (a + b s)^3 ds,   C1 from P(lam) = 0.

The J_m are elementary (J0 and J1 rational, J2 with a logarithm), but J1 and J2 divide by
b^2 and b^3, which vanishes at two film angles: evaluated in closed form they lose every
digit there. They are taken instead by Gauss-Legendre quadrature of their integrands,
analytic on [-lam, zeta] with the pole s = -a/b outside the film: 40 nodes reach round-off
while the least gap stays above 1 % of c (the pole's Bernstein ellipse). The aligned
journal (b = 0) gives back Ocvirk's P = f0 (lam^2 - zeta^2) / (2 a^3).

Forces and moments are the film's generalised forces Q_j = c int p dH/dq_j dA (as
:func:`bearingfem.fe.sensitivity.generalised_forces`), over the whole film ("none", full
Sommerfeld) or its positive part ("gumbel", half Sommerfeld: p < 0 set to ambient). For
each film angle the pressure changes sign at most once inside the length (H^3 P' is a
quadratic in zeta, P vanishes at both ends), so the positive part is integrated exactly
piecewise in zeta (the sign change found by bisection); around the circumference the
trapezoidal rule on ``n_theta`` angles is spectrally accurate for the full film and
second order across the kinks of Gumbel's.

Reference: Ocvirk, F. W. (1952), Short-bearing approximation for full journal bearings,
NACA TN 2808 (the aligned film this one extends).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..bearing import Bearing, JournalState
from ..fields import check_tilt, tilted_gap
from ..validation import check_choice, check_inputs

__all__ = ["TiltedShortFilm", "tilted_short_bearing", "tilted_short_pressure"]

#: Gauss-Legendre nodes of the J_m quadratures (module docstring).
J_NODES = 40
_GL_X, _GL_W = np.polynomial.legendre.leggauss(J_NODES)


@dataclass(frozen=True)
class TiltedShortFilm:
    """Force and moment of the tilted short-bearing film.

    force : (F_x, F_y) [N], inertial; moment : (M_x, M_y) [N m] about the bearing centre
    (mid-plane), inertial, as ``FilmSolution.moment``; force_local : (F_r, F_t) [N]
    """

    force: tuple
    moment: tuple
    force_local: tuple


def _gap_terms(bearing, state, theta, tilt, tilt_rate):
    """a, b of H = a + b zeta and the source's f0, f1 at the film angles ``theta``."""
    a = 1.0 + state.eps * np.cos(theta)
    b, b_rate = tilted_gap(bearing, state, theta, 1.0, tilt, tilt_rate)
    al = theta + state.gamma     # b = (R/c)(tilt_y cos(al) - tilt_x sin(al)): its d/dtheta
    db = -bearing.radius / bearing.clearance * (tilt[1] * np.sin(al) + tilt[0] * np.cos(al))
    w = state.wedge_speed
    f0 = 6.0 * w * state.eps * np.sin(theta) - 12.0 * state.eps_dot * np.cos(theta)
    f1 = -6.0 * w * db - 12.0 * b_rate
    return a, b, f0, f1


def _J(a, b, lo, hi):
    """(J0, J1, J2) = int_lo^hi s^m / (a + b s)^3 ds, arrays broadcast over a, b, hi."""
    half = 0.5 * (hi - lo)
    s = (lo + half)[..., None] + half[..., None] * _GL_X
    u = (a[..., None] + b[..., None] * s) ** -3
    wts = half[..., None] * _GL_W
    return tuple(np.sum(wts * s ** m * u, axis=-1) for m in range(3))


def _pressure(a, b, f0, f1, lam, zeta):
    """Dimensionless P at zeta (broadcast against the film-angle arrays)."""
    zeta = np.broadcast_to(zeta, np.broadcast_shapes(np.shape(zeta), a.shape)).astype(float)
    A, B_, F0, F1 = (np.broadcast_to(v, zeta.shape) for v in (a, b, f0, f1))
    lo = np.full(zeta.shape, -lam)
    J0L, J1L, J2L = _J(A, B_, lo, np.full(zeta.shape, lam))
    C1 = (F0 * J1L + 0.5 * F1 * J2L) / J0L
    J0, J1, J2 = _J(A, B_, lo, zeta)
    return C1 * J0 - F0 * J1 - 0.5 * F1 * J2


def tilted_short_pressure(bearing: Bearing, state: JournalState, theta, z,
                          tilt=(0.0, 0.0), tilt_rate=(0.0, 0.0)):
    """Uncavitated pressure [Pa] of the tilted short bearing at film angles ``theta`` and
    axial positions ``z`` [m] (broadcast)."""
    check_inputs(bearing, state)
    tilt, tilt_rate = check_tilt("tilt", tilt), check_tilt("tilt_rate", tilt_rate)
    th, zeta = np.broadcast_arrays(np.asarray(theta, float),
                                   np.asarray(z, float) / bearing.radius)
    a, b, f0, f1 = _gap_terms(bearing, state, th, tilt, tilt_rate)
    _check_gap(a, b, bearing.length_ratio, tilt)
    return bearing.pressure_scale * _pressure(a, b, f0, f1, bearing.length_ratio, zeta)


def _check_gap(a, b, lam, tilt):
    if not np.all(a - np.abs(b) * lam > 0.01):
        raise ValueError(f"tilt {tilt} [rad] leaves less than 1 % of the clearance at the "
                         f"journal's ends (or touches): the J_m quadrature needs more")


def _positive_part(a, b, f0, f1, lam, n_zeta):
    """Gauss nodes (theta x n) and weights in zeta over where P > 0 (at most one sign change
    inside the length: module docstring); the weights vanish where P <= 0."""
    # H^3 P' at the ends: P > 0 just inside -lam iff P'(-lam) > 0, just inside lam iff P'(lam) < 0
    J0L, J1L, J2L = _J(a, b, np.full(a.shape, -lam), np.full(a.shape, lam))
    C1 = (f0 * J1L + 0.5 * f1 * J2L) / J0L
    lo_up = C1 + f0 * lam - 0.5 * f1 * lam ** 2 > 0.0
    hi_up = C1 - f0 * lam - 0.5 * f1 * lam ** 2 < 0.0
    lo, hi = np.full(a.shape, -lam), np.full(a.shape, lam)
    split = lo_up != hi_up             # one sign change inside: find it by bisection
    if np.any(split):
        left, right = lo[split].copy(), hi[split].copy()
        args = (a[split], b[split], f0[split], f1[split], lam)
        sign_left = lo_up[split]
        for _ in range(60):
            mid = 0.5 * (left + right)
            same = (_pressure(*args, mid) > 0.0) == sign_left
            left, right = np.where(same, mid, left), np.where(same, right, mid)
        root = 0.5 * (left + right)
        hi[split] = np.where(sign_left, root, lam)
        lo[split] = np.where(sign_left, -lam, root)
    x, wq = np.polynomial.legendre.leggauss(n_zeta)
    half = 0.5 * (hi - lo)
    zeta = (lo + half)[:, None] + half[:, None] * x
    weights = half[:, None] * wq * (lo_up | hi_up)[:, None]   # no positive part: no weight
    return zeta, weights


def tilted_short_bearing(bearing: Bearing, state: JournalState, tilt=(0.0, 0.0), *,
                         tilt_rate=(0.0, 0.0), cavitation: str = "gumbel",
                         n_theta: int = 4096, n_zeta: int = 24) -> TiltedShortFilm:
    """Force and moment of the tilted short bearing (module docstring) [N, N m].

    ``cavitation``: "none" (full Sommerfeld) or "gumbel" (the positive pressure);
    ``n_theta`` trapezoidal angles around the film, ``n_zeta`` Gauss nodes along each
    pressurised length (exact for the full film's polynomial-like axial profile to
    round-off at 24).
    """
    check_inputs(bearing, state)
    tilt, tilt_rate = check_tilt("tilt", tilt), check_tilt("tilt_rate", tilt_rate)
    check_choice("cavitation", cavitation, ("none", "gumbel"))
    if not (isinstance(n_theta, int) and n_theta >= 16):
        raise ValueError(f"n_theta must be an integer >= 16, got {n_theta!r}")
    if not (isinstance(n_zeta, int) and n_zeta >= 4):
        raise ValueError(f"n_zeta must be an integer >= 4, got {n_zeta!r}")
    lam = bearing.length_ratio
    theta = 2.0 * math.pi * np.arange(n_theta) / n_theta
    a, b, f0, f1 = _gap_terms(bearing, state, theta, tilt, tilt_rate)
    _check_gap(a, b, lam, tilt)
    if cavitation == "none":
        x, wq = np.polynomial.legendre.leggauss(n_zeta)
        zeta = np.broadcast_to(lam * x, (n_theta, n_zeta))
        weights = np.broadcast_to(lam * wq, (n_theta, n_zeta))
    else:
        zeta, weights = _positive_part(a, b, f0, f1, lam, n_zeta)
    P = _pressure(a[:, None], b[:, None], f0[:, None], f1[:, None], lam, zeta)
    dtheta = 2.0 * math.pi / n_theta
    al = theta[:, None] + state.gamma + 0.0 * zeta
    # p dA = mu (R/c)^2 P R^2 dtheta dzeta: force_scale = mu R^4 / c^2
    k = bearing.force_scale * dtheta
    Pw = P * weights
    fx, fy = k * np.sum(Pw * np.cos(al)), k * np.sum(Pw * np.sin(al))
    kz = k * bearing.radius
    mx, my = -kz * np.sum(Pw * zeta * np.sin(al)), kz * np.sum(Pw * zeta * np.cos(al))
    c, s = math.cos(state.gamma), math.sin(state.gamma)
    return TiltedShortFilm(force=(float(fx), float(fy)), moment=(float(mx), float(my)),
                           force_local=(float(c * fx + s * fy), float(-s * fx + c * fy)))
