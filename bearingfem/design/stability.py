"""Stability of a rigid rotor on its film: Lund's threshold from K and C, and a check by
time integration of the nonlinear film.

A rigid journal of mass m on the linearised film, m x'' + C x' + K x = 0, loses stability
when a pair of eigenvalues crosses the imaginary axis at s = i nu. Separating real and
imaginary parts of det(K - m nu^2 I + i nu C) = 0 gives (Lund 1966; Childs 1993, Ch. 3)

    K_eq  = (K_xx C_yy + K_yy C_xx - K_xy C_yx - K_yx C_xy) / (C_xx + C_yy)
    nu^2  = ((K_xx - K_eq)(K_yy - K_eq) - K_xy K_yx) / (C_xx C_yy - C_xy C_yx)
    m_crit = K_eq / nu^2,

frame-independent. The eigenvalues move with m only through that one crossing (or at
s = 0, det K = 0, for every m alike), so the stability is the same for all masses on either
side of m_crit; the verdict checks one mass on each side. With nu^2 <= 0 or K_eq <= 0 there
is no crossing at a positive mass and one mass decides for all: stable for any mass or
unstable for any mass - never a critical mass of "inf" from dividing by K_eq <= 0.

Near the centre (eps -> 0) every film here has K = [[0, k], [-k, 0]] + O(eps): the full film
(Sommerfeld) has K_eq = 0 at every eps, so m_crit = 0 - unstable for any mass, whirling at
nu / omega -> 1/2 (k / C = omega / 2 because the film force depends on omega - 2 gamma_dot).
Gumbel's and Reynolds' films give K_eq ~ eps, so m_crit ~ eps -> 0 and nu / omega -> 1/2:
for the long Gumbel film m_crit omega / S -> (24 + 9 pi) eps, S = mu R^3 L / c^3; the FE
film at L/D 1 gives m_crit omega / (S eps) -> 14.5 (Gumbel) and 15.5 (Reynolds' condition,
whose cavity moves with the squeeze: C_rr = C_tt only in the mesh limit, nu / omega =
0.4966, 0.4993, 0.49992 at 60 x 10, 120 x 20, 240 x 40). Tests: tests/test_stability.py.
"""
from __future__ import annotations

import enum
import math
from dataclasses import dataclass, replace
from typing import Optional

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from ..accuracy import refuse_estimate, refuse_rtol
from ..bearing import (PLAUSIBLE, Bearing, JournalState, check_finite, check_positive,
                       check_surface_speed)
from ..film import local_to_inertial
from ..models import film_model
from .coefficients import DynamicCoefficients, coefficients
from .equilibrium import Equilibrium, equilibrium

__all__ = ["Stability", "Verdict", "lund_stability", "ThresholdSpeed", "threshold_speed",
           "Orbit", "journal_orbit"]


class Verdict(enum.Enum):
    """What a rigid journal of any mass does on a linearised film."""

    STABLE_FOR_ANY_MASS = "stable for any mass"
    UNSTABLE_FOR_ANY_MASS = "unstable for any mass"
    CRITICAL_MASS = "stable below the critical mass"
    #: the crossing the other way round (unstable light journals); not met in plain films
    STABLE_ABOVE_CRITICAL_MASS = "stable above the critical mass"


@dataclass(frozen=True)
class Stability:
    """Lund's stability of a rigid journal on the film of ``coefficients``.

    verdict : :class:`Verdict`
    critical_mass [kg]: the mass where the stability changes (CRITICAL_MASS and
        STABLE_ABOVE_CRITICAL_MASS); None when one verdict holds for every mass
    whirl_frequency nu [rad/s], whirl_ratio nu / |omega|: the frequency of the whirl at the
        critical mass, or of the unstable whirl of a light journal (UNSTABLE_FOR_ANY_MASS);
        None when stable for any mass
    stiffness_eq K_eq [N/m]
    critical_mass_range, whirl_ratio_range : (low, high) over K and C within their
        estimated errors (coefficients with ``K_error``, ``C_error``: every corner of the
        box K +- K_error, C +- C_error); None without error estimates or where the
        verdict has no critical mass there
    ill_conditioned : the verdict is not decided by K and C to within their error: the
        critical mass spans more than a decade (:data:`ILL_CONDITIONED_SPAN`) or the
        verdict itself changes inside the box (then ``verdicts`` lists those met)
    """

    verdict: Verdict
    critical_mass: Optional[float]
    whirl_frequency: Optional[float]
    whirl_ratio: Optional[float]
    stiffness_eq: float
    coefficients: DynamicCoefficients
    critical_mass_range: Optional[tuple] = None
    whirl_ratio_range: Optional[tuple] = None
    ill_conditioned: bool = False
    verdicts: tuple = ()

    def stable(self, mass: float) -> bool:
        """Whether a journal of ``mass`` [kg] is stable on this film (linear theory)."""
        mass = check_positive("mass", mass)
        v = self.verdict
        if v is Verdict.CRITICAL_MASS:
            return mass < self.critical_mass
        if v is Verdict.STABLE_ABOVE_CRITICAL_MASS:
            return mass > self.critical_mass
        return v is Verdict.STABLE_FOR_ANY_MASS

    def describe(self) -> str:
        """One line: the verdict, with the critical mass where there is one, and its range
        over K and C's error; an ill-conditioned verdict says so instead of digits."""
        r = self.critical_mass_range
        if self.ill_conditioned:
            where = "" if r is None else f"; critical mass {r[0]:.2g} .. {r[1]:.2g} kg"
            met = ", ".join(v.value for v in self.verdicts)
            return (f"ill-conditioned: K and C within their estimated error give "
                    f"{met or self.verdict.value}{where} (refine the film: smaller rtol)")
        if self.critical_mass is None:
            return self.verdict.value
        if r is None:
            return f"{self.verdict.value} {self.critical_mass:.6g} kg"
        return (f"{self.verdict.value} {self.critical_mass:.4g} kg "
                f"(range {r[0]:.3g} .. {r[1]:.3g} kg over K, C's error)")

    def __str__(self) -> str:
        """A sentence: the verdict with its critical mass and whirl, and the state (no
        digits of whirl for an ill-conditioned verdict: :meth:`describe` says why)."""
        s = self.coefficients.state
        text = (f"Lund stability of a rigid journal at eps {s.eps:.4g}, {s.omega:g} rad/s: "
                f"{self.describe()}")
        if self.ill_conditioned:
            return text + "."
        if self.whirl_frequency is not None:
            text += f", whirling at {self.whirl_frequency:.4g} rad/s"
            if self.whirl_ratio is not None:
                text += f" ({self.whirl_ratio:.3g} of the running speed)"
        return text + f"; K_eq {self.stiffness_eq:.4g} N/m."


#: A critical mass whose range over K and C's error spans more than this ratio is
#: reported as ill-conditioned.
ILL_CONDITIONED_SPAN = 10.0


def _threshold(K, C):
    """(K_eq, nu^2) of Lund's crossing for stacks of K and C (..., 2, 2)."""
    tr = C[..., 0, 0] + C[..., 1, 1]
    det = C[..., 0, 0] * C[..., 1, 1] - C[..., 0, 1] * C[..., 1, 0]
    k_eq = (K[..., 0, 0] * C[..., 1, 1] + K[..., 1, 1] * C[..., 0, 0]
            - K[..., 0, 1] * C[..., 1, 0] - K[..., 1, 0] * C[..., 0, 1]) / tr
    nu2 = ((K[..., 0, 0] - k_eq) * (K[..., 1, 1] - k_eq) - K[..., 0, 1] * K[..., 1, 0]) / det
    return k_eq, nu2


def _with_ranges(st: "Stability") -> "Stability":
    """``st`` with the critical mass and whirl ratio over every corner of K +- K_error,
    C +- C_error (the threshold is a smooth function of the entries: over a box as small
    as the errors its extremes are at corners)."""
    kc = st.coefficients
    if kc.K_error is None or kc.C_error is None:
        return st
    signs = np.array(np.meshgrid(*[[-1.0, 1.0]] * 8, indexing="ij")).reshape(8, -1).T
    K = kc.K + signs[:, :4].reshape(-1, 2, 2) * kc.K_error
    C = kc.C + signs[:, 4:].reshape(-1, 2, 2) * kc.C_error
    k_eq, nu2 = _threshold(K, C)
    crossing = (k_eq > 0.0) & (nu2 > 0.0)
    omega = abs(kc.state.omega)
    has = st.verdict in (Verdict.CRITICAL_MASS, Verdict.STABLE_ABOVE_CRITICAL_MASS)
    verdicts = (st.verdict,)
    m_range = w_range = None
    if crossing.any():
        m = k_eq[crossing] / nu2[crossing]
        # the threshold m = K_eq / nu^2 is continuous over the box: where some corners
        # have no crossing it runs to infinity (nu^2 -> 0+, stable for any mass) or to
        # zero (K_eq -> 0+, unstable for any mass) inside it, not to a corner's value
        m_range = (0.0 if np.any(k_eq <= 0.0) else float(m.min()),
                   math.inf if np.any((k_eq > 0.0) & (nu2 <= 0.0)) else float(m.max()))
        if omega:
            w = np.sqrt(nu2[crossing]) / omega
            w_range = (float(w.min()), float(w.max()))
    if has and not crossing.all():
        verdicts += (Verdict.STABLE_FOR_ANY_MASS,)    # (or unstable for any: no crossing)
    if not has and crossing.any():
        verdicts += (Verdict.CRITICAL_MASS,)
    ill = len(verdicts) > 1 or (m_range is not None and
                                m_range[1] > ILL_CONDITIONED_SPAN * m_range[0])
    return replace(st, critical_mass_range=m_range if has or ill else None,
                   whirl_ratio_range=w_range if has or ill else None, ill_conditioned=ill,
                   verdicts=verdicts if ill else ())


def _eigenvalues(K, C, mass):
    """Eigenvalues of m x'' + C x' + K x = 0."""
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-K / mass, -C / mass]])
    return np.linalg.eigvals(A)


def _unstable(K, C, mass) -> bool:
    return bool(_eigenvalues(K, C, mass).real.max() > 0.0)


def lund_stability(kc: DynamicCoefficients) -> Stability:
    """The verdict, critical mass and whirl frequency of a rigid journal from K and C; with
    coefficients that carry their error (``coefficients(..., rtol=...)``), the ranges of
    the critical mass and whirl ratio over it, and whether the verdict is ill-conditioned."""
    if not isinstance(kc, DynamicCoefficients):
        raise ValueError(f"kc must be the DynamicCoefficients of coefficients(...), got "
                         f"{type(kc).__name__}")
    return _with_ranges(_lund(kc))


def _lund(kc: DynamicCoefficients) -> Stability:
    K, C = kc.K, kc.C
    trace_c = C[0, 0] + C[1, 1]
    if not trace_c > 0.0:
        raise ValueError("the film has no positive direct damping (C_xx + C_yy <= 0): "
                         "no stability threshold")
    det_c = C[0, 0] * C[1, 1] - C[0, 1] * C[1, 0]
    if not det_c > 0.0:
        raise ValueError(f"the film's damping matrix is not positive (det C = {det_c:.6g} "
                         "N^2 s^2/m^2): no stability threshold")
    k_eq = float((K[0, 0] * C[1, 1] + K[1, 1] * C[0, 0] - K[0, 1] * C[1, 0]
                  - K[1, 0] * C[0, 1]) / trace_c)
    nu2 = float(((K[0, 0] - k_eq) * (K[1, 1] - k_eq) - K[0, 1] * K[1, 0]) / det_c)
    omega = abs(kc.state.omega)
    # K_eq within rounding of 0 is 0 (the centred film, K = [[0, k], [-k, 0]], in any frame):
    # m_crit = 0, unstable for any mass - not a crossing at 1e-20 kg
    if abs(k_eq) <= 1e-12 * np.linalg.norm(K) * np.linalg.norm(C) / trace_c:
        k_eq = 0.0

    def whirl(nu):
        return Stability(verdict, m_c, nu, None if nu is None or omega == 0.0 else nu / omega,
                         k_eq, kc)

    if nu2 > 0.0 and k_eq > 0.0:          # a crossing at a positive mass
        m_c = k_eq / nu2
        below, above = _unstable(K, C, 0.5 * m_c), _unstable(K, C, 2.0 * m_c)
        verdict = {(False, True): Verdict.CRITICAL_MASS,
                   (True, False): Verdict.STABLE_ABOVE_CRITICAL_MASS,
                   (False, False): Verdict.STABLE_FOR_ANY_MASS,
                   (True, True): Verdict.UNSTABLE_FOR_ANY_MASS}[(below, above)]
        if verdict in (Verdict.CRITICAL_MASS, Verdict.STABLE_ABOVE_CRITICAL_MASS):
            return whirl(math.sqrt(nu2))
        m_c = None
        return whirl(math.sqrt(nu2) if verdict is Verdict.UNSTABLE_FOR_ANY_MASS else None)
    # no crossing at a positive mass: one mass decides for all; (tr C)^2 / |K| is the mass
    # scale where inertia, damping and stiffness are alike
    m_c = None
    norm_k = float(np.linalg.norm(K))
    if norm_k == 0.0:
        raise ValueError("the film has no stiffness (K = 0): no stability verdict")
    if not _unstable(K, C, trace_c ** 2 / norm_k):
        verdict = Verdict.STABLE_FOR_ANY_MASS
        return whirl(None)
    verdict = Verdict.UNSTABLE_FOR_ANY_MASS
    # the whirl of a light journal: the first-order film C x' + K x = 0
    light = np.linalg.eigvals(-np.linalg.solve(C, K))
    return whirl(float(np.abs(light[np.argmax(light.real)].imag)))


@dataclass(frozen=True)
class ThresholdSpeed:
    """The speed [rad/s] above which a journal of ``mass`` whirls, with the equilibrium
    and stability there."""

    omega: float
    mass: float
    equilibrium: Equilibrium
    stability: Stability


def threshold_speed(bearing: Bearing, load, mass: float, model: str = "fem", *,
                    omega_range=None, xtol: float = 1e-8, rtol=None, estimate=None,
                    **options) -> ThresholdSpeed:
    """The onset speed of oil whirl of a rigid journal of ``mass`` [kg] carrying ``load``
    [N] (vector, inertial), within ``omega_range`` [rad/s] (default: 1 rad/s up to the
    speed whose surface speed omega R is the highest of any journal bearing, 300 m/s).

    As the speed grows the journal rises toward the centre and its critical mass falls;
    the threshold is where the critical mass equals ``mass`` (Brent's method in ln omega,
    relative tolerance ``xtol``, formerly ``rtol``).
    ``rtol`` (a film accuracy elsewhere) is refused: a mesh chosen per speed makes the
    margin jump between meshes under Brent's steps, and the threshold would carry no error.
    ``estimate`` is refused too: the threshold carries no error estimate (estimate K and C
    at its state: ``coefficients(..., ts.equilibrium.state, estimate=True)``).
    """
    refuse_rtol(rtol, "the root search's tolerance is xtol (the films are solved on the mesh "
                "given)")
    refuse_estimate(estimate, "the threshold speed carries no error estimate (estimate K "
                    "and C at its state with coefficients(..., estimate=True))")
    xtol = check_finite("xtol", xtol)
    if not 4.0 * np.finfo(float).eps <= xtol < 1.0:     # brentq's own floor
        raise ValueError(f"xtol must lie in [{4.0 * np.finfo(float).eps:.3g}, 1), got {xtol!r}")
    mass = check_positive("mass", mass)
    if omega_range is None:
        omega_range = (1.0, PLAUSIBLE["surface_speed"] / bearing.radius)
    lo, hi = (check_positive("omega_range", w) for w in omega_range)
    if not lo < hi:
        raise ValueError(f"omega_range must be increasing (low, high) [rad/s], got {omega_range!r}")
    check_surface_speed(bearing.radius, hi, "omega_range's high end")

    def margin(log_omega):
        # exp(log(hi)) can round above hi, past the surface-speed check at the default end
        eq = equilibrium(bearing, load, min(max(math.exp(log_omega), lo), hi), model,
                         **options)
        st = lund_stability(coefficients(bearing, eq.state, model, **options))
        if st.verdict is Verdict.CRITICAL_MASS:
            return math.log(st.critical_mass / mass)
        if st.verdict is not Verdict.STABLE_ABOVE_CRITICAL_MASS:   # finite, for Brent
            return 1e3 if st.verdict is Verdict.STABLE_FOR_ANY_MASS else -1e3
        raise ValueError(f"at {math.exp(log_omega):.6g} rad/s the journal is "
                         f"{st.describe()}: no onset speed of whirl for a given mass")

    m_lo, m_hi = margin(math.log(lo)), margin(math.log(hi))
    if m_lo < 0.0:
        raise ValueError(f"the journal is already unstable at the lowest speed of "
                         f"omega_range ({lo:g} rad/s)")
    if m_hi > 0.0:
        raise ValueError(f"the journal is stable up to the highest speed of omega_range "
                         f"({hi:g} rad/s)")
    omega = min(max(math.exp(brentq(margin, math.log(lo), math.log(hi), rtol=xtol)), lo), hi)
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
                  integrator_rtol: float = 1e-9, rtol=None, estimate=None,
                  **options) -> Orbit:
    """Integrate m x'' = F_film(x, x') + load from the equilibrium ``eq`` displaced by
    ``kick`` clearances along the load (negative: against it), starting inside the
    clearance; the nonlinear check of the linear threshold. ``integrator_rtol`` (formerly
    ``rtol``): LSODA's relative tolerance (absolute: 1e-6 c).
    ``rtol`` (a film accuracy elsewhere) is refused: the orbit's films are solved on the
    mesh given (their force takes no rtol), none carries an error estimate.
    """
    refuse_rtol(rtol, "the orbit integrator's tolerance is integrator_rtol")
    refuse_estimate(estimate, "the orbit's films are solved on the mesh given and carry no "
                    "error estimate")
    integrator_rtol = check_finite("integrator_rtol", integrator_rtol)
    if not 0.0 < integrator_rtol < 1.0:
        raise ValueError(f"integrator_rtol must lie in (0, 1), got {integrator_rtol!r}")
    mass = check_positive("mass", mass)
    if not isinstance(eq, Equilibrium):
        raise ValueError(f"eq must be an Equilibrium (equilibrium(...)), got {type(eq).__name__}")
    kick = check_finite("kick", kick)
    wx, wy = eq.load
    W = math.hypot(wx, wy)
    q0 = eq.eps * np.array([math.cos(eq.state.gamma), math.sin(eq.state.gamma)])
    start = q0 + kick * np.array([wx, wy]) / W       # [clearances]
    if kick == 0.0 or not math.hypot(*start) < 1.0:     # 0: growth() a ratio of round-off
        raise ValueError(f"kick must be non-zero and keep the start inside the clearance "
                         f"(eps {math.hypot(*start):.4g} there, < 1) [clearances], got "
                         f"{kick!r}")
    turns = check_positive("turns", turns)
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) or samples < 10:
        # growth() compares the first and last fifths of the samples
        raise ValueError(f"samples must be an integer >= 10, got {samples!r}")
    m = film_model(model)
    opts = m.options(options)
    c, omega = bearing.clearance, eq.state.omega
    x0, start = q0 * c, start * c

    def rhs(t, y):
        s = JournalState.from_eccentricity(y[0], y[1], y[2], y[3], c, omega, eps_max=0.999)
        fx, fy = local_to_inertial(*m.film_force(bearing, s, **opts), s.gamma)
        return [y[2], y[3], (fx + wx) / mass, (fy + wy) / mass]

    t_end = turns * 2.0 * math.pi / abs(omega)
    sol = solve_ivp(rhs, (0.0, t_end), [start[0], start[1], 0.0, 0.0], method="LSODA",
                    rtol=integrator_rtol, atol=1e-6 * c, t_eval=np.linspace(0.0, t_end, samples))
    if not sol.success:
        raise RuntimeError(f"orbit integration stopped at t = {sol.t[-1]:.6g} s: {sol.message}")
    d = np.hypot(sol.y[0] - x0[0], sol.y[1] - x0[1])
    return Orbit(sol.t, sol.y[0], sol.y[1], d)
