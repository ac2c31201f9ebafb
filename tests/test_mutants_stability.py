"""Stability and orbits (bearingfem.design.stability) where mutants survived the design tests
(docs/mutation.md): refusals, the stable branch's record, and the orbit's start, distance
and load against the equilibrium it is kicked from."""
import math
from dataclasses import replace

import numpy as np
import pytest

from bearingfem import Bearing
from bearingfem.design import coefficients, equilibrium, journal_orbit, lund_stability
from bearingfem.design.stability import Verdict, threshold_speed

FRISWELL = Bearing(radius=0.05, length=0.03, clearance=0.1e-3, viscosity=0.1)


@pytest.fixture(scope="module")
def film():
    eq = equilibrium(FRISWELL, (0.0, -525.0), 157.1, "short")
    return eq, coefficients(FRISWELL, eq.state, "short")


def test_no_direct_damping_is_refused(film):
    """C_xx + C_yy = 0 exactly: no threshold. Fails with 'trace > 0' written '>= 0'
    (stability.py:56)."""
    kc = replace(film[1], C=np.array([[1.0, 2.0], [3.0, -1.0]]))
    with pytest.raises(ValueError, match="damping"):
        lund_stability(kc)


def test_a_film_without_cross_coupling_is_stable_for_any_mass(film):
    """K = k I, C = c I (no cross-coupling): the whirl equation has nu^2 = 0, stable for
    every mass with no whirl, so no critical mass and no whirl frequency. Fails with a
    verdict of a critical mass or a whirl frequency recorded for the stable film."""
    kc = replace(film[1], K=np.eye(2) * 1e7, C=np.eye(2) * 1e4)
    st = lund_stability(kc)
    assert st.verdict is Verdict.STABLE_FOR_ANY_MASS
    assert st.critical_mass is None and st.whirl_frequency is None
    assert st.stiffness_eq == pytest.approx(1e7, rel=1e-12)
    assert st.stable(1e6)


def test_an_empty_speed_range_is_refused():
    """omega_range (100, 100) has no width: refused as such (not by the margins at its
    ends, whose messages also name omega_range). Fails with 'lo < hi' written 'lo <= hi'
    (stability.py:91)."""
    with pytest.raises(ValueError, match="increasing"):
        threshold_speed(FRISWELL, (0.0, -525.0), 50.0, "short", omega_range=(100.0, 100.0))


def test_orbit_starts_along_the_load_and_returns_to_its_equilibrium():
    """A load with both components: the orbit starts kick * c along the load from the
    equilibrium, ``distance`` is |(x, y) - equilibrium|, and a stable journal (half the
    critical mass) settles back onto that equilibrium. Fails with the kick against the
    load, the load's x component reversed in the equation of motion, or the distance taken
    from a velocity (stability.py:145, 147, 153)."""
    load = (300.0, -450.0)
    eq = equilibrium(FRISWELL, load, 157.1, "short")
    st = lund_stability(coefficients(FRISWELL, eq.state, "short"))
    orbit = journal_orbit(FRISWELL, eq, 0.5 * st.critical_mass, "short", turns=40,
                          kick=0.01, switch_speed=1.0)
    c = FRISWELL.clearance
    x_eq = eq.eps * c * np.array([math.cos(eq.state.gamma), math.sin(eq.state.gamma)])
    along = np.array(load) / math.hypot(*load)
    assert (orbit.x[0], orbit.y[0]) == pytest.approx(tuple(x_eq + 0.01 * c * along), rel=1e-9)
    assert orbit.distance == pytest.approx(np.hypot(orbit.x - x_eq[0], orbit.y - x_eq[1]),
                                           rel=1e-12, abs=1e-15)
    assert orbit.distance[-1] < 0.05 * orbit.distance[0]


@pytest.mark.parametrize("spread", [1e-3, 3e-2])
def test_whirl_ratio_range_is_the_corners_own_whirl_ratios(film, spread):
    """The whirl ratio's range over K +- K_error, C +- C_error (vectorised over the 256
    corners in `_with_ranges`) against a second method: `lund_stability` run on each corner
    alone, with no error (its scalar path). The range must be those ratios' (min, max) and
    hold the nominal ratio. No test read `whirl_ratio_range` before: it survived the sqrt
    left out (nu^2 / omega^2 for nu / omega), and any factor."""
    kc = film[1]
    K_err, C_err = spread * np.abs(kc.K), spread * np.abs(kc.C)
    st = lund_stability(replace(kc, K_error=K_err, C_error=C_err))
    assert st.verdict is Verdict.CRITICAL_MASS and st.whirl_ratio_range is not None
    ratios = []
    for signs in np.array(np.meshgrid(*[[-1.0, 1.0]] * 8, indexing="ij")).reshape(8, -1).T:
        corner = replace(kc, K=kc.K + signs[:4].reshape(2, 2) * K_err,
                         C=kc.C + signs[4:].reshape(2, 2) * C_err)
        one = lund_stability(corner)
        assert one.verdict is Verdict.CRITICAL_MASS      # every corner has its crossing
        ratios.append(one.whirl_ratio)
    assert st.whirl_ratio_range == pytest.approx((min(ratios), max(ratios)), rel=1e-12)
    lo, hi = st.whirl_ratio_range
    assert lo < st.whirl_ratio < hi


@pytest.mark.parametrize("frame", ["local", "load"])
def test_entry_errors_turned_to_a_frame_bound_every_corner(film, frame):
    """K and C's entry errors turned to another frame against a second method: every one
    of the 16 corners of K +- K_error (and of C) turned to that frame must stay within
    the turned errors of the turned nominal entry. `in_frame` turns the errors as
    magnitudes, |T| E |T|^T; with T itself (signed), errors cancel and come out smaller
    than the corners' spread or negative, which no test noticed before."""
    kc = film[1]
    K_err, C_err = 0.05 * np.abs(kc.K), 0.05 * np.abs(kc.C)
    inertial = replace(kc, K_error=K_err, C_error=C_err)
    turned = inertial.in_frame(frame)
    T = turned.axes @ inertial.axes.T
    for M, E, M_t, E_t in ((kc.K, K_err, turned.K, turned.K_error),
                           (kc.C, C_err, turned.C, turned.C_error)):
        assert np.all(E_t >= 0.0)
        for signs in np.array(np.meshgrid(*[[-1.0, 1.0]] * 4, indexing="ij")).reshape(4, -1).T:
            corner = T @ (M + signs.reshape(2, 2) * E) @ T.T
            assert np.all(np.abs(corner - M_t) <= E_t * (1 + 1e-12) + 1e-12 * np.abs(M_t))
