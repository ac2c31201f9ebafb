"""Linearised film at the centred journal against its exact limit (independent of the
code's eccentricity floor).

The short (half-Sommerfeld) bearing, with k = mu L^3 R / (2 c^2), carries
F_r = -k (pi eps_dot + 2 eps^2 w) and F_t = k eps (4 eps_dot + pi/2 w) as eps -> 0
(seed Eq. 9 expanded to first order). With K = -dF/dx and C = -dF/dv in the local frame
(coefficients.py's module docstring) the limit eps -> 0 is, by hand,

    K = (k w / c) [[4 eps, pi/2], [-pi/2, 2 eps]]  ->  (k w / c) [[0, pi/2], [-pi/2, 0]]
    C = (k / c)   [[pi, -4 eps], [-4 eps, pi]]     ->  (k pi / c) I

so the diagonal of K and the off-diagonal of C at a linearisation point eps are
~2.5 eps and ~1.3 eps of the largest entry. A floor at 1e-6 leaves them at 2.5e-6; a
floor 1000x too large (1e-3) leaves them at 2.5e-3.
"""
import math

import numpy as np

from bearingfem import JournalState
from bearingfem.bearing import Bearing
from bearingfem.design.coefficients import coefficients


def test_centred_journal_coefficients_are_the_exact_limit():
    """eps = 0 gives the exact eps -> 0 limit of the short bearing to 1e-5 of the largest
    entry. Fails with EPS_FLOOR 1000x too large (1e-3: entries 2.5e-3 off; the older test,
    eps = 0 against eps = 1e-4, floors both to the same point and passes)."""
    b = Bearing(radius=0.05, length=0.03, clearance=1e-4, viscosity=0.1)
    w = 157.1
    kc = coefficients(b, JournalState(0.0, omega=w), "short", frame="local")
    k = b.viscosity * b.length ** 3 * b.radius / (2.0 * b.clearance ** 2)
    K_exact = k * w / b.clearance * np.array([[0.0, math.pi / 2], [-math.pi / 2, 0.0]])
    C_exact = k * math.pi / b.clearance * np.eye(2)
    np.testing.assert_allclose(kc.K, K_exact, rtol=0, atol=1e-5 * np.abs(K_exact).max())
    np.testing.assert_allclose(kc.C, C_exact, rtol=0, atol=1e-5 * np.abs(C_exact).max())
