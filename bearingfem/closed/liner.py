"""Independent references for a film on a thin compliant liner (Winkler, w = k p, k = t/M,
:mod:`bearingfem.elastic.liner`), supply line at the largest rigid gap, no finite
elements: the infinitely long bearing by shooting on the Reynolds ODE, and the infinitely
short one (full film) by the method of lines (:func:`liner_short_bearing`).

Dimensionless, phi = theta - gamma from the largest gap, P = p c^2 / (mu omega R^2):

    H = 1 + eps cos(phi) + K P,   K = k mu omega R^2 / c^3   (the liner's deformation
    parameter), and the long-bearing Reynolds equation integrates once to

    H^3 dP/dphi = 6 (H - H*),     P(0) = 0 (the supply line),

an explicit ODE in P for each flux constant H* (the gap where dP/dphi = 0). The second
condition fixes H*: "none" (full film) P(2 pi) = 0; "reynolds" (Swift-Stieber) the film
ends at phi_c where P = dP/dphi = 0, i.e. P(phi_c) = 0 with 1 + eps cos(phi_c) = H*.
K = 0 is Sommerfeld's long bearing (tests check it).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from ..errors import ConvergenceError
from ..validation import check_finite, check_int

__all__ = ["LinerLongBearing", "liner_long_bearing", "LinerShortBearing", "liner_short_bearing"]

_TOL = dict(method="DOP853", rtol=1e-12, atol=1e-14)


@dataclass(frozen=True)
class LinerLongBearing:
    """The long bearing on a Winkler liner.

    Attributes
    ----------
    eps, compliance : the state's eccentricity ratio and K (see the module docstring)
    cavitation : "none" or "reynolds"
    flux_gap : H*, the dimensionless gap where dP/dphi = 0 (2 H* is the flow)
    film_end : phi_c [rad], where the film cavitates (2 pi for "none")
    """

    eps: float
    compliance: float
    cavitation: str
    flux_gap: float
    film_end: float

    def rate(self, phi, P):
        H = 1.0 + self.eps * np.cos(phi) + self.compliance * P
        return 6.0 * (H - self.flux_gap) / H**3

    def pressure(self, phi) -> np.ndarray:
        """Dimensionless pressure P at angles phi from the largest gap (any real angles:
        taken mod 2 pi; zero on the cavitated arc)."""
        phi = np.mod(np.asarray(phi, float), 2.0 * np.pi)
        angles, where = np.unique(phi, return_inverse=True)
        inside = angles <= self.film_end
        values = np.zeros(angles.size)
        if inside.any():
            sol = solve_ivp(self.rate, (0.0, self.film_end), [0.0], t_eval=angles[inside],
                            **_TOL)
            values[inside] = sol.y[0]
        return values[where].reshape(phi.shape)


def _shoot_to(eps, K, flux_gap, phi_end):
    """The ODE from the supply line to ``phi_end`` (stopped where the liner's gap closes
    under suction)."""
    def gap_closes(phi, P):            # a full film's suction closing the liner's gap
        return 1.0 + eps * np.cos(phi) + K * P[0] - 0.25 * (1.0 - eps)
    gap_closes.terminal = True
    rate = LinerLongBearing(eps, K, "", flux_gap, 0.0).rate
    sol = solve_ivp(rate, (0.0, phi_end), [0.0], events=[gap_closes], **_TOL)
    if sol.status == -1:
        raise ConvergenceError("long liner film ODE", sol.nfev, where=sol.message)
    return sol


def liner_long_bearing(eps: float, compliance: float, cavitation: str = "reynolds"
                       ) -> LinerLongBearing:
    """Solve the long bearing on a Winkler liner (module docstring) to 1e-12 relative.

    eps in [0, 1); compliance K >= 0; cavitation "none" or "reynolds"."""
    eps = check_finite("eps", eps)
    if not 0.0 <= eps < 1.0:
        raise ValueError(f"eps must lie in [0, 1), got {eps!r}")
    K = check_finite("compliance", compliance)
    if K < 0.0:
        raise ValueError(f"compliance must be >= 0, got {compliance!r}")
    if cavitation not in ("none", "reynolds"):
        raise ValueError(f"cavitation must be 'none' or 'reynolds', got {cavitation!r}")
    if cavitation == "none":
        def miss(flux_gap):
            sol = _shoot_to(eps, K, flux_gap, 2.0 * np.pi)
            # the gap closing under suction: H* too large, P(2 pi) -> -infinity
            return sol.y[0, -1] if sol.status == 0 else -1.0 / K
        # H* lies between the rigid gap's extremes
        flux_gap = brentq(miss, 1.0 - eps, 1.0 + eps, xtol=1e-14, rtol=1e-14)
        return LinerLongBearing(eps, K, cavitation, flux_gap, 2.0 * np.pi)

    # Reynolds' condition P = dP/dphi = 0 at the film's end phi_c: there H = 1 + eps
    # cos(phi_c) (P = 0), and dP/dphi = 0 makes that the flux gap H*. So phi_c is the root
    # of the pressure shot from the supply line to phi_c with H* = 1 + eps cos(phi_c): a
    # smooth function of phi_c (shooting in H* for the touch of P = 0 is ill-conditioned:
    # a shallow dip below zero goes unseen and the film ends early).
    def end_pressure(phi_c):
        sol = _shoot_to(eps, K, 1.0 + eps * np.cos(phi_c), phi_c)
        # the suction closing the liner's gap: H* too large, P at the end far below 0
        return sol.y[0, -1] if sol.status == 0 else -1.0 / max(K, 1e-300)
    last = 2.0 * np.pi - 0.2       # a film ending 0.2 rad before the supply line
    if end_pressure(last) >= 0.0:
        raise ValueError(f"the Reynolds film reaches the supply line at eps={eps!r}, "
                         f"compliance={K!r}: take a smaller compliance")
    end = brentq(end_pressure, np.pi, last, xtol=1e-15, rtol=1e-15)
    flux_gap = 1.0 + eps * np.cos(end)
    return LinerLongBearing(eps, K, cavitation, flux_gap, float(end))


@dataclass(frozen=True)
class LinerShortBearing:
    """The infinitely short bearing on a Winkler liner, full film, supply line at the
    largest gap (see :func:`liner_short_bearing`).

    Attributes
    ----------
    theta : (n,) film angles from the largest gap [rad]
    Z : (N + 1,) Chebyshev points 2 z / L in [-1, 1] (Z[N // 2] = 0, the mid-plane)
    pressure : (n, N + 1) Pi = p c^2 / (6 mu omega (L/2)^2)
    """

    eps: float
    compliance: float
    theta: np.ndarray
    Z: np.ndarray
    pressure: np.ndarray

    @property
    def mid_plane(self) -> np.ndarray:
        return self.pressure[:, self.Z.size // 2]


def _chebyshev(n: int):
    """Chebyshev points cos(pi j / n) and their differentiation matrix (Trefethen,
    Spectral Methods in MATLAB, SIAM 2000, cheb.m)."""
    x = np.cos(np.pi * np.arange(n + 1) / n)
    w = np.r_[2.0, np.ones(n - 1), 2.0] * (-1.0) ** np.arange(n + 1)
    dx = x[:, None] - x[None, :]
    D = np.outer(w, 1.0 / w) / (dx + np.eye(n + 1))
    return D - np.diag(D.sum(axis=1)), x


def liner_short_bearing(eps: float, compliance: float, theta, n_points: int = 24
                        ) -> LinerShortBearing:
    """The short-bearing limit (L/D -> 0) of the film on a liner, full film ("none"),
    pressure zero at a supply line at the largest gap (theta = 0), to ~1e-10.

    With Z = 2 z / L, Pi = p c^2 / (6 mu omega (L/2)^2), H = H0 + kappa Pi,
    H0 = 1 + eps cos(theta) and ``compliance`` kappa = 6 k mu omega (L/2)^2 / c^3, the
    Reynolds equation without its circumferential flow is

        kappa dPi/dtheta = d/dZ(H^3 dPi/dZ) - dH0/dtheta,   Pi(theta, +-1) = 0, Pi(0, Z) = 0:

    the liner makes dH/dtheta carry the pressure's own theta derivative, so the limit is a
    parabolic problem with theta as time (not an ODE in z per angle). Solved by the method
    of lines: Chebyshev collocation in Z (``n_points`` + 1 points, spectral), Radau in theta
    (rtol 1e-11). kappa -> 0 is Ocvirk's Pi = -H0' (1 - Z^2) / (2 H0^3). The FE film's
    mid-plane is compared on theta < 3 pi / 2: upstream of the supply line the finite
    bearing has a layer of width ~L that the limit does not have.

    theta : increasing angles in [0, 2 pi) [rad]; eps in [0, 1); compliance > 0."""
    eps = check_finite("eps", eps)
    if not 0.0 <= eps < 1.0:
        raise ValueError(f"eps must lie in [0, 1), got {eps!r}")
    kappa = check_finite("compliance", compliance)
    if kappa <= 0.0:
        raise ValueError(f"compliance must be > 0 (kappa = 0 is Ocvirk's closed form), "
                         f"got {compliance!r}")
    theta = np.asarray(theta, float)
    if theta.ndim != 1 or np.any(np.diff(theta) <= 0) or theta[0] < 0 or theta[-1] >= 2 * np.pi:
        raise ValueError("theta must be increasing angles in [0, 2 pi)")
    D, Z = _chebyshev(check_int("n_points", n_points, 4))

    def rate(angle, interior):
        Pi = np.r_[0.0, interior, 0.0]
        H = 1.0 + eps * np.cos(angle) + kappa * Pi
        return ((D @ (H**3 * (D @ Pi)))[1:-1] + eps * np.sin(angle)) / kappa

    def jacobian(angle, interior):    # d/dPi of D (H^3 D Pi), H = H0 + kappa Pi
        Pi = np.r_[0.0, interior, 0.0]
        H = 1.0 + eps * np.cos(angle) + kappa * Pi
        J = D @ (H[:, None] ** 3 * D + np.diag(3.0 * kappa * H**2 * (D @ Pi)))
        return J[1:-1, 1:-1] / kappa
    sol = solve_ivp(rate, (0.0, max(theta[-1], 1e-12)), np.zeros(Z.size - 2),
                    method="Radau", t_eval=theta, rtol=1e-11, atol=1e-13, jac=jacobian)
    if sol.status != 0:
        raise ConvergenceError("short liner film (method of lines)", sol.nfev,
                               where=sol.message)
    pressure = np.zeros((theta.size, Z.size))
    pressure[:, 1:-1] = sol.y.T
    return LinerShortBearing(eps, kappa, theta, Z, pressure)
