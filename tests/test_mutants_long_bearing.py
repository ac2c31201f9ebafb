"""Long bearing (bearingfem.closed.long_bearing) against independent references where
mutants survived the closed-form tests (docs/mutation.md): seed Eq. 11-13 in the paper's
own variables (E, G, k) for both signs of the squeeze, and the exact Gumbel force against
adaptive quadrature."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from bearingfem import JournalState, long_bearing_exact_force, long_bearing_force
from bearingfem.bearing import seed_bearing
from bearingfem.closed.long_bearing import long_bearing_pressure


def seed_eq_11_13(b, s):
    """Seed Eq. 11 (E > 0) and Eq. 12 (E < 0) as printed, in E = 2 eps_dot / omega,
    G = 2 gamma_dot / omega and Eq. 13's k, with the two corrections of seed-corrections §2:
    the prefactor mu omega R^3 L / c^2 and F_t's sign (positive for omega > 0)."""
    e, w = s.eps, s.omega
    E, G = 2 * s.eps_dot / w, 2 * s.gamma_dot / w
    k = math.sqrt(1 - e * e) * math.sqrt(((1 - G) / E) ** 2 + 1 / e ** 2)
    pre = b.viscosity * w * b.radius ** 3 * b.length / b.clearance ** 2
    d, root = 2 + e * e, math.sqrt(1 - e * e)
    if E > 0:
        f_r = -pre * 3 * E / (d * (1 - e * e) * root) * (4 * k * e * e + d * math.pi
                                                          * (k + 3) / (k + 1.5))
        f_t = pre * 6 * math.pi * e * (1 - G) / (d * root) * (k + 3) / (k + 1.5)
    else:
        f_r = pre * 3 * E / (d * (1 - e * e) * root) * (4 * k * e * e - d * math.pi
                                                         * k / (k + 1.5))
        f_t = pre * 6 * math.pi * e * (1 - G) / (d * root) * k / (k + 1.5)
    return f_r, f_t


@pytest.mark.parametrize("state", [JournalState(0.6, 40.0, 0.0, 10.0, 250.0),
                                   JournalState(0.6, -40.0, 0.0, 10.0, 250.0),
                                   JournalState(0.3, -150.0, 1.0, -30.0, 120.0),
                                   JournalState(0.85, 5.0, 0.0, 0.0, 80.0),
                                   JournalState(0.5, 0.2, 0.0, 0.0, 50.0)])
def test_closed_form_is_seed_eq_11_13(state):
    """The code's form in s = 2 eps_dot and w = omega - 2 gamma_dot equals the paper's
    (E, G, k) form for either sign of the squeeze, and for a slow one (2 eps_dot = 0.4 1/s).
    Fails with the E < 0 ratio k / (k + 3/2) written (k + 3/2) / k, a term of either ratio
    dropped, the squeeze term of F_r dropped, or the sign test of s moved from 0 to 1
    (long_bearing.py:68-74)."""
    b = seed_bearing(2.0)
    assert long_bearing_force(b, state) == pytest.approx(seed_eq_11_13(b, state), rel=1e-12)


@pytest.mark.parametrize("state", [JournalState(0.5, 60.0, 0.0, 0.0, 250.0),
                                   JournalState(0.7, -80.0, 0.0, 0.0, 100.0),
                                   JournalState(0.4, 30.0, 0.0, 0.0, 0.0),
                                   JournalState(0.5, 0.0, 0.0, 0.0, 1.0),
                                   JournalState(0.5, 1.0, 0.0, 0.0, 0.0),
                                   JournalState(0.5, 0.0, 0.0, 0.0, 0.1)])
def test_exact_force_is_the_positive_part_integral(state):
    """long_bearing_exact_force against adaptive quadrature of max(p, 0) of the corrected
    Eq. 10 times (cos, sin) theta R L. Squeeze moves the positive region away from
    theta = 0; w = 1 rad/s and eps_dot = 1 1/s alone are ordinary states; at w = 0.1 rad/s
    the dimensionless P stays below 1. Fails if the sign changes were searched on
    [0, 2/pi] only, with the rest-state test 'eps_dot == 0 and w == 0' written with 1 for
    either 0, or with regions whose mid-point P <= 1 skipped (long_bearing.py:87, 93, 111)."""
    b = seed_bearing(2.0)

    def comp(trig, epsabs=0.0):
        g = lambda th: max(float(long_bearing_pressure(b, state, th)), 0.0) * trig(th)  # noqa
        v, _ = quad(g, 0.0, 2 * math.pi, limit=500, epsabs=epsabs, epsrel=1e-11)
        return v

    scale = comp(lambda th: 1.0)
    ref = np.array([comp(math.cos, 1e-12 * scale), comp(math.sin, 1e-12 * scale)])
    ref *= b.radius * b.length
    assert long_bearing_exact_force(b, state) == pytest.approx(
        tuple(ref), rel=1e-8, abs=1e-9 * np.abs(ref).max())


def test_exact_force_at_rest_is_zero():
    """Fails with the rest state's early return giving 1 N (long_bearing.py:88)."""
    assert long_bearing_exact_force(seed_bearing(2.0),
                                    JournalState(0.5, 0.0, 0.0, 0.0, 0.0)) == (0.0, 0.0)
