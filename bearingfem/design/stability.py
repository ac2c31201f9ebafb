"""Stability of a rigid rotor on its film: Lund's threshold from K and C, and a check by
time integration of the nonlinear film.

A rigid journal of mass m on the linearised film, m x'' + C x' + K x = 0, loses stability
when a pair of eigenvalues crosses the imaginary axis at s = i nu. Separating real and
imaginary parts of det(K - m nu^2 I + i nu C) = 0 gives (Lund 1966; Childs 1993, Ch. 3)

    K_eq  = (K_xx C_yy + K_yy C_xx - K_xy C_yx - K_yx C_xy) / (C_xx + C_yy)
    nu^2  = ((K_xx - K_eq)(K_yy - K_eq) - K_xy K_yx) / (C_xx C_yy - C_xy C_yx)
    m_crit = K_eq / nu^2,

frame-independent. Heavier journals whirl unstably at nu / omega (the whirl frequency
ratio, ~0.5 for a plain bearing at light load). nu^2 <= 0 means no mass destabilises.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from ..bearing import Bearing, JournalState, check_positive
from ..film import local_to_inertial
from ..models import film_model
from .coefficients import DynamicCoefficients, coefficients
from .equilibrium import Equilibrium, equilibrium

__all__ = ["Stability", "lund_stability", "ThresholdSpeed", "threshold_speed", "Orbit",
           "journal_orbit"]


@dataclass(frozen=True)
class Stability:
    """Lund's stability of a rigid journal on the film of ``coefficients``.

    critical_mass [kg] (inf: stable for any mass), whirl_frequency nu [rad/s],
    whirl_ratio nu / |omega|, stiffness_eq K_eq [N/m]."""

    critical_mass: float
    whirl_frequency: float
    whirl_ratio: float
    stiffness_eq: float
    coefficients: DynamicCoefficients

    def stable(self, mass: float) -> bool:
        """Whether a journal of ``mass`` [kg] is stable on this film (linear theory)."""
        return check_positive("mass", mass) < self.critical_mass


def lund_stability(kc: DynamicCoefficients) -> Stability:
    """Critical mass and whirl frequency of a rigid journal from K and C."""
    K, C = kc.K, kc.C
    trace_c = C[0, 0] + C[1, 1]
    if not trace_c > 0.0:
        raise ValueError("the film has no positive direct damping (C_xx + C_yy <= 0): "
                         "no stability threshold")
    k_eq = (K[0, 0] * C[1, 1] + K[1, 1] * C[0, 0] - K[0, 1] * C[1, 0]
            - K[1, 0] * C[0, 1]) / trace_c
    nu2 = (((K[0, 0] - k_eq) * (K[1, 1] - k_eq) - K[0, 1] * K[1, 0])
           / (C[0, 0] * C[1, 1] - C[0, 1] * C[1, 0]))
    if nu2 <= 0.0 or k_eq <= 0.0:
        return Stability(math.inf, 0.0, 0.0, float(k_eq), kc)
    nu = math.sqrt(nu2)
    return Stability(float(k_eq / nu2), nu, nu / abs(kc.state.omega), float(k_eq), kc)


@dataclass(frozen=True)
class ThresholdSpeed:
    """The speed [rad/s] above which a journal of ``mass`` whirls, with the equilibrium
    and stability there."""

    omega: float
    mass: float
    equilibrium: Equilibrium
    stability: Stability


def threshold_speed(bearing: Bearing, load, mass: float, model: str = "fem", *,
                    omega_range=(1.0, 1e5), rtol: float = 1e-8,
                    **options) -> ThresholdSpeed:
    """The onset speed of oil whirl of a rigid journal of ``mass`` [kg] carrying ``load``
    [N] (vector, inertial), within ``omega_range`` [rad/s].

    As the speed grows the journal rises toward the centre and its critical mass falls;
    the threshold is where the critical mass equals ``mass`` (Brent's method in ln omega).
    """
    mass = check_positive("mass", mass)
    lo, hi = (check_positive("omega_range", w) for w in omega_range)
    if not lo < hi:
        raise ValueError(f"omega_range must be increasing (low, high) [rad/s], got {omega_range!r}")

    def margin(log_omega):
        eq = equilibrium(bearing, load, math.exp(log_omega), model, **options)
        st = lund_stability(coefficients(bearing, eq.state, model, **options))
        return math.log(min(st.critical_mass, 1e300) / mass)

    m_lo, m_hi = margin(math.log(lo)), margin(math.log(hi))
    if m_lo < 0.0:
        raise ValueError(f"the journal is already unstable at the lowest speed of "
                         f"omega_range ({lo:g} rad/s)")
    if m_hi > 0.0:
        raise ValueError(f"the journal is stable up to the highest speed of omega_range "
                         f"({hi:g} rad/s)")
    omega = math.exp(brentq(margin, math.log(lo), math.log(hi), rtol=rtol))
    eq = equilibrium(bearing, load, omega, model, **options)
    st = lund_stability(coefficients(bearing, eq.state, model, **options))
    return ThresholdSpeed(omega, mass, eq, st)


@dataclass(frozen=True)
class Orbit:
    """A time-integrated journal orbit: t [s], x, y [m] (from the bearing centre),
    and the distance from the equilibrium [m]."""

    t: np.ndarray
    x: np.ndarray
    y: np.ndarray
    distance: np.ndarray

    def growth(self) -> float:
        """Ratio of the largest distance from equilibrium over the last fifth of the run to
        that over the first fifth: > 1 the orbit grows, < 1 it decays."""
        n = max(len(self.t) // 5, 1)
        return float(np.max(self.distance[-n:]) / np.max(self.distance[:n]))


def journal_orbit(bearing: Bearing, eq: Equilibrium, mass: float, model: str = "fem", *,
                  kick: float = 0.02, turns: float = 60.0, samples: int = 4000,
                  rtol: float = 1e-9, **options) -> Orbit:
    """Integrate m x'' = F_film(x, x') + load from the equilibrium ``eq`` displaced by
    ``kick`` clearances along the load; the nonlinear check of the linear threshold."""
    mass = check_positive("mass", mass)
    m = film_model(model)
    opts = m.options(options)
    c, omega = bearing.clearance, eq.state.omega
    wx, wy = eq.load
    x0 = np.array([eq.eps * math.cos(eq.state.gamma), eq.eps * math.sin(eq.state.gamma)]) * c
    W = math.hypot(wx, wy)

    def rhs(t, y):
        s = JournalState.from_eccentricity(y[0], y[1], y[2], y[3], c, omega, eps_max=0.999)
        fx, fy = local_to_inertial(*m.force(bearing, s, **opts), s.gamma)
        return [y[2], y[3], (fx + wx) / mass, (fy + wy) / mass]

    start = x0 + kick * c * np.array([wx, wy]) / W
    t_end = turns * 2.0 * math.pi / abs(omega)
    sol = solve_ivp(rhs, (0.0, t_end), [start[0], start[1], 0.0, 0.0], method="LSODA",
                    rtol=rtol, atol=1e-6 * c, t_eval=np.linspace(0.0, t_end, samples))
    if not sol.success:
        raise RuntimeError(f"orbit integration stopped at t = {sol.t[-1]:.6g} s: {sol.message}")
    d = np.hypot(sol.y[0] - x0[0], sol.y[1] - x0[1])
    return Orbit(sol.t, sol.y[0], sol.y[1], d)
