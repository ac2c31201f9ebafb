"""The flow of a rough gap: Patir & Cheng's average flow model.

Between rough surfaces the local gap is h_T = h + delta, h the nominal gap (between the
mean planes) and delta the combined roughness, Gaussian with standard deviation sigma.
Averaged over a patch many correlation lengths wide, the flow per unit width obeys
(Patir & Cheng 1978, their Eq. 3; 1979, Eq. 2)

    q_x = -phi_x h^3/(12 mu) dp/dx + (U1 + U2)/2 E(h_T) + (U1 - U2)/2 sigma phi_s,
    q_y = -phi_y h^3/(12 mu) dp/dy,

x the sliding direction. The pressure flow factors phi_x, phi_y and the shear flow factor
phi_s depend on H = h / sigma and on Peklenik's surface pattern parameter gamma (the ratio
of the correlation lengths at half height along x and y: gamma < 1 ridges across the
flow, gamma > 1 along it, 1 isotropic). Patir & Cheng computed them by solving the
Reynolds equation on generated surfaces and fitted (1978, Table 1; 1979, Table 2):

    phi_x = 1 - C exp(-r H)       (gamma <= 1),    1 + C H^-r    (gamma > 1),
    phi_y(H, gamma) = phi_x(H, 1/gamma),
    phi_s = (V_r1 - V_r2) Phi_s(H, gamma),
    Phi_s = A1 H^a1 exp(-a2 H + a3 H^2)  (H <= 5),  A2 exp(-0.25 H)  (H > 5),

V_ri = sigma_i^2 / sigma^2 the share of surface i (1 the moving one) in the variance.
The fits hold for H above the limits of :data:`PRESSURE_FIT` (0.5 to 1) and H > 0.5 for
phi_s; below its limit a factor is held at its limit's value (the fits are not continued
into the contact range, where Patir & Cheng computed nothing).

The mean gap of a Gaussian roughness, contact closing the gap where h_T would be negative
(Patir & Cheng 1978, their Eq. 20), in closed form:

    E(h_T) = h Phi(H) + sigma phi(H),   dE(h_T)/dh = Phi(H),

Phi and phi the standard normal distribution and density. It carries the Couette and the
squeeze terms; the pressure term's h^3 is floored at :data:`FLOW_FLOOR` sigma, where the
surfaces are pressed through, so the film's operator stays positive definite.

Smooth limit (H -> infinity): E(h_T) = h to round-off beyond H ~ 9 (Gaussian tail),
phi_x -> 1 exponentially for gamma <= 1 (round-off beyond H ~ 65), but only as C H^-1.5
for gamma > 1 (4e-6 at H = 1000 for gamma = 9): the fits' algebraic tail; Phi_s -> 0 as
exp(-H/4) (round-off beyond H ~ 150).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.special import ndtr

from ..bearing import check_finite

__all__ = ["FlowFactors", "FlowFields", "PATTERNS", "PRESSURE_FIT", "SHEAR_FIT",
           "SHEAR_FIT_LIMIT", "FLOW_FLOOR", "pressure_flow_factor", "shear_flow_factor",
           "pressure_flow_slope", "shear_flow_slope", "mean_gap", "flow_fields"]

#: Peklenik's gamma values Patir & Cheng tabulate (their fits hold at these alone).
PATTERNS = (1 / 9, 1 / 6, 1 / 3, 1.0, 3.0, 6.0, 9.0)

#: phi_x fits, Patir & Cheng (1978) Table 1: gamma -> (C, r, least H of the fit).
PRESSURE_FIT = {1 / 9: (1.48, 0.42, 1.0), 1 / 6: (1.38, 0.42, 1.0),
                1 / 3: (1.18, 0.42, 0.75), 1.0: (0.90, 0.56, 0.5),
                3.0: (0.225, 1.5, 0.5), 6.0: (0.520, 1.5, 0.5), 9.0: (0.870, 1.5, 0.5)}

#: Phi_s fits, Patir & Cheng (1979) Table 2: gamma -> (A1, a1, a2, a3, A2).
SHEAR_FIT = {1 / 9: (2.046, 1.12, 0.78, 0.03, 1.856), 1 / 6: (1.962, 1.08, 0.77, 0.03, 1.754),
             1 / 3: (1.858, 1.01, 0.76, 0.03, 1.561), 1.0: (1.899, 0.98, 0.92, 0.05, 1.126),
             3.0: (1.560, 0.85, 1.13, 0.08, 0.556), 6.0: (1.290, 0.62, 1.09, 0.08, 0.388),
             9.0: (1.011, 0.54, 1.07, 0.08, 0.295)}

#: Phi_s fit's least H (Patir & Cheng 1979) and the switch between its two forms.
SHEAR_FIT_LIMIT = 0.5
SHEAR_SWITCH = 5.0

#: The pressure term's gap h^3 is floored at this many sigma (surfaces pressed through).
FLOW_FLOOR = 0.05


def _pattern(gamma) -> float:
    """The tabulated gamma equal to ``gamma`` (to 1e-9 relative), or ValueError."""
    g = check_finite("pattern", gamma)
    for p in PATTERNS:
        if abs(g - p) <= 1e-9 * p:
            return p
    raise ValueError(f"pattern (Peklenik's gamma) must be one of Patir & Cheng's tabulated "
                     f"values 1/9, 1/6, 1/3, 1, 3, 6, 9, got {gamma!r}")


def pressure_flow_factor(H, gamma: float = 1.0) -> np.ndarray:
    """phi_x(H, gamma) [-] of Patir & Cheng's fit at H = h/sigma (held at the fit's least
    H below it); phi_y(H, gamma) is ``pressure_flow_factor(H, 1/gamma)``."""
    g = _pattern(gamma)
    C, r, least = PRESSURE_FIT[g]
    H = np.maximum(np.asarray(H, dtype=float), least)
    if g <= 1.0:
        return 1.0 - C * np.exp(-r * H)
    return 1.0 + C * H ** -r


def pressure_flow_slope(H, gamma: float = 1.0) -> np.ndarray:
    """d phi_x / dH of :func:`pressure_flow_factor` (0 below the fit's least H, where the
    factor is held)."""
    g = _pattern(gamma)
    C, r, least = PRESSURE_FIT[g]
    H = np.asarray(H, dtype=float)
    Hc = np.maximum(H, least)
    slope = C * r * np.exp(-r * Hc) if g <= 1.0 else -r * C * Hc ** (-r - 1.0)
    return np.where(H > least, slope, 0.0)


def shear_flow_slope(H, gamma: float = 1.0) -> np.ndarray:
    """d Phi_s / dH of :func:`shear_flow_factor` (0 below H = 0.5, where it is held)."""
    _, a1, a2, a3, _ = SHEAR_FIT[_pattern(gamma)]
    H = np.asarray(H, dtype=float)
    Hc = np.maximum(H, SHEAR_FIT_LIMIT)
    log_slope = np.where(Hc <= SHEAR_SWITCH, a1 / Hc - a2 + 2.0 * a3 * Hc, -0.25)
    return np.where(H > SHEAR_FIT_LIMIT, shear_flow_factor(Hc, gamma) * log_slope, 0.0)


def shear_flow_factor(H, gamma: float = 1.0) -> np.ndarray:
    """Phi_s(H, gamma) [-] of Patir & Cheng's fit (phi_s = (V_r1 - V_r2) Phi_s), held at
    H = 0.5 below it."""
    A1, a1, a2, a3, A2 = SHEAR_FIT[_pattern(gamma)]
    H = np.maximum(np.asarray(H, dtype=float), SHEAR_FIT_LIMIT)
    low = np.minimum(H, SHEAR_SWITCH)      # the first form's branch, evaluated in range
    return np.where(H <= SHEAR_SWITCH, A1 * low ** a1 * np.exp(-a2 * low + a3 * low * low),
                    A2 * np.exp(-0.25 * H))


def mean_gap(H) -> tuple:
    """(E(h_T)/sigma, dE(h_T)/dh) at H = h/sigma for a Gaussian roughness, contact where
    h_T < 0: H Phi(H) + phi(H) and Phi(H) (module docstring)."""
    H = np.asarray(H, dtype=float)
    cdf = ndtr(H)
    return H * cdf + np.exp(-0.5 * H * H) / math.sqrt(2.0 * math.pi), cdf


@dataclass(frozen=True)
class FlowFactors:
    """Patir & Cheng's average flow model for a :class:`~bearingfem.contact.Roughness`
    (``Roughness(..., flow=FlowFactors(...))``).

    Parameters
    ----------
    pattern : Peklenik's gamma of the combined roughness along the sliding direction
        (circumferential) over the axial one, one of 1/9, 1/6, 1/3, 1, 3, 6, 9
        (Patir & Cheng's tables); 1 isotropic
    journal_share : V_r1 = sigma_journal^2 / sigma^2 in [0, 1], the moving surface's
        share of the variance (the bush's is 1 - V_r1): phi_s = (2 V_r1 - 1) Phi_s; the
        default 0.5 (equally rough) has no shear flow
    """

    pattern: float = 1.0
    journal_share: float = 0.5

    def __post_init__(self):
        object.__setattr__(self, "pattern", _pattern(self.pattern))
        v = check_finite("journal_share", self.journal_share)
        if not 0.0 <= v <= 1.0:
            raise ValueError(f"journal_share must lie in [0, 1], got {self.journal_share!r}")
        object.__setattr__(self, "journal_share", v)

    def factors(self, H) -> tuple:
        """(phi_x, phi_y, phi_s) at H = h/sigma (x the sliding direction)."""
        return (pressure_flow_factor(H, self.pattern),
                pressure_flow_factor(H, 1.0 / self.pattern),
                (2.0 * self.journal_share - 1.0) * shear_flow_factor(H, self.pattern))

    def slopes(self, H) -> tuple:
        """d(phi_x, phi_y, phi_s)/dH at H = h/sigma."""
        return (pressure_flow_slope(H, self.pattern),
                pressure_flow_slope(H, 1.0 / self.pattern),
                (2.0 * self.journal_share - 1.0) * shear_flow_slope(H, self.pattern))


@dataclass(frozen=True, eq=False)
class FlowFields:
    """A rough film's coefficient fields at the film's points (dimensionless, gaps in
    units of the clearance c): what the Reynolds form takes in place of the smooth gap's.

    conductance : (phi_x H^3, phi_z H^3), H^3 floored at (FLOW_FLOOR sigma/c)^3
    mean_gap : E(h_T)/c, the Couette and squeeze content
    gap_slope : dE(h_T)/dh, the squeeze's factor on dH/dt
    shear : sigma phi_s / c, the shear flow's content
    shear_speed : omega [rad/s], the surfaces' relative speed that drives it
    conductance_slope, gap_curvature, shear_slope : the derivatives of conductance,
        gap_slope and shear in the nominal gap H (for a Newton film whose gap moves)
    """

    conductance: tuple
    mean_gap: np.ndarray
    gap_slope: np.ndarray
    shear: np.ndarray
    shear_speed: float
    conductance_slope: tuple = None
    gap_curvature: np.ndarray = None
    shear_slope: np.ndarray = None


def flow_fields(flow: FlowFactors, gap: np.ndarray, roughness_ratio: float,
                omega: float) -> FlowFields:
    """The :class:`FlowFields` of ``flow`` on the nominal gap H = h/c (any array shape),
    ``roughness_ratio`` sigma/c, at the relative speed ``omega`` [rad/s]."""
    s = float(roughness_ratio)
    H = np.asarray(gap, dtype=float)
    Hs = H / s
    phi_x, phi_z, phi_s = flow.factors(Hs)
    dphi_x, dphi_z, dphi_s = flow.slopes(Hs)               # d/dHs = s d/dH
    floor = FLOW_FLOOR * s
    cube = np.maximum(H, floor) ** 3
    dcube = np.where(H > floor, 3.0 * H * H, 0.0)
    E, slope = mean_gap(Hs)
    return FlowFields(conductance=(phi_x * cube, phi_z * cube), mean_gap=s * E,
                      gap_slope=slope, shear=s * phi_s, shear_speed=float(omega),
                      conductance_slope=(dphi_x * cube / s + phi_x * dcube,
                                         dphi_z * cube / s + phi_z * dcube),
                      gap_curvature=np.exp(-0.5 * Hs * Hs) / (math.sqrt(2.0 * math.pi) * s),
                      shear_slope=dphi_s)
