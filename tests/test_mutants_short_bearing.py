"""Short bearing (bearingfem.closed.short_bearing) against independent references where
mutants survived the closed-form tests (docs/mutation.md): the axial pressure profile, the
partial derivatives, slow and switched wedge speeds, the exact Gumbel region."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from bearingfem import JournalState, short_bearing_exact_force, short_bearing_force
from bearingfem.bearing import seed_bearing
from bearingfem.closed.short_bearing import short_bearing_derivatives, short_bearing_pressure
from bearingfem.film import film_thickness, reynolds_source


def test_pressure_solves_the_axial_equation_and_vanishes_at_the_ends():
    """P = p / (mu (R/c)^2) solves -H^3 d2P/dzeta2 = f(theta) (zeta = z/R; central
    differences, exact for a parabola up to rounding) and is 0 at z = +-L/2. Fails with
    zeta = z R, or lam^2 + zeta^2, or the zeta^2 term dropped (short_bearing.py:31-32)."""
    b, s = seed_bearing(0.5), JournalState(0.6, 30.0, 0.0, 0.0, 250.0)
    th = np.linspace(0.1, 6.2, 13)
    R, L = b.radius, b.length
    assert short_bearing_pressure(b, s, th, L / 2) == pytest.approx(0.0, abs=1e-9)
    assert short_bearing_pressure(b, s, th, -L / 2) == pytest.approx(0.0, abs=1e-9)
    z, dz = 0.3 * L / 2, 1e-4 * L
    P = lambda zz: short_bearing_pressure(b, s, th, zz) / b.pressure_scale     # noqa: E731
    d2P = (P(z + dz) - 2 * P(z) + P(z - dz)) / (dz / R) ** 2
    f = reynolds_source(th, s.eps, s.eps_dot, s.wedge_speed)
    assert -film_thickness(th, s.eps) ** 3 * d2P == pytest.approx(f, rel=1e-5, abs=1e-6)


@pytest.mark.parametrize("state", [JournalState(0.6, 20.0, 0.0, 0.0, 250.0),
                                   JournalState(0.4, -3.0, 0.0, 0.0, 0.5)])
def test_derivatives_against_central_differences(state):
    """The complex-step partials against central differences of short_bearing_force in
    eps, eps_dot and w (relative steps 1e-6: error ~1e-9 relative). The slow state
    (w = 0.5 rad/s) fails if the default switch speed were 1 rad/s, the other if the
    partials' sign flipped (short_bearing.py:58, 63)."""
    b = seed_bearing(0.5)
    d = short_bearing_derivatives(b, state)

    def force(eps, eps_dot, omega):
        return np.array(short_bearing_force(b, JournalState(eps, eps_dot, 0.0, 0.0, omega)))

    e, ed, w = state.eps, state.eps_dot, state.omega
    he, hd, hw = 1e-6, 1e-6 * max(abs(ed), 1.0), 1e-6 * abs(w)
    ref = [(force(e + he, ed, w) - force(e - he, ed, w)) / (2 * he),
           (force(e, ed + hd, w) - force(e, ed - hd, w)) / (2 * hd),
           (force(e, ed, w + hw) - force(e, ed, w - hw)) / (2 * hw)]
    scale = [np.abs(r).max() for r in ref]
    for got, want, sc in zip((d.d_eps, d.d_eps_dot, d.d_wedge), ref, scale):
        assert np.array(got) == pytest.approx(want, rel=1e-6, abs=1e-7 * sc)


def _short_gumbel_by_quad(b, s):
    """(F_r, F_t) integrating max(p, 0) of the short-bearing pressure over theta (adaptive
    quad, the positive region found by quad itself) and z (2 L / 3 from the parabola)."""
    def comp(trig, epsabs=0.0):
        g = lambda th: max(short_bearing_pressure(b, s, th, 0.0), 0.0) * trig(th)   # noqa
        v, _ = quad(g, 0.0, 2 * math.pi, limit=500, epsabs=epsabs, epsrel=1e-11)
        return v

    scale = comp(lambda th: 1.0)      # the load's magnitude: a component may be 0
    k = b.radius * (2.0 / 3.0) * b.length
    return k * comp(math.cos, 1e-12 * scale), k * comp(math.sin, 1e-12 * scale)


@pytest.mark.parametrize("state", [JournalState(0.5, 40.0, 0.0, 0.0, 250.0),
                                   JournalState(0.7, -60.0, 0.0, 0.0, 100.0),
                                   JournalState(0.3, 10.0, 0.0, 0.0, -200.0)])
def test_exact_force_is_the_positive_part_integral(state):
    """short_bearing_exact_force integrates exactly where p > 0, for squeeze rates that
    move the region off [0, pi] (it wraps past 2 pi for some): against adaptive
    quadrature of max(p, 0). Fails with the wrap test 'hi > 2 pi' written 'hi > 2 / pi'
    (short_bearing.py:114)."""
    b = seed_bearing(0.5)
    ref = _short_gumbel_by_quad(b, state)
    assert short_bearing_exact_force(b, state) == pytest.approx(
        ref, rel=1e-8, abs=1e-8 * np.abs(ref).max())


def test_slow_wedge_is_eq9():
    """For 0 < w < 1 rad/s and no squeeze, Eq. 9 on the wedge's half film is the exact
    Gumbel film. Fails if the speeds below 1 rad/s were mirrored (short_bearing.py:81)."""
    b, s = seed_bearing(0.5), JournalState(0.6, 0.0, 0.0, 0.0, 0.4)
    ref = _short_gumbel_by_quad(b, s)
    assert short_bearing_force(b, s) == pytest.approx(ref, rel=1e-8)


def test_switch_speed_scales_the_squeeze_part_by_tanh():
    """With switch_speed s the squeeze part of F_t (F_t minus its value at eps_dot = 0) is
    tanh(w / s) times the unswitched one; F_r does not change. Fails with tanh(w s), or
    with a switch speed below 1 rad/s ignored (short_bearing.py:82-83)."""
    b = seed_bearing(0.5)
    for w, sw in ((0.3, 0.5), (2.0, 4.0), (-1.0, 0.7)):
        s, s0 = JournalState(0.5, 15.0, 0.0, 0.0, w), JournalState(0.5, 0.0, 0.0, 0.0, w)
        plain = np.subtract(short_bearing_force(b, s), short_bearing_force(b, s0))
        switched = np.subtract(short_bearing_force(b, s, switch_speed=sw),
                               short_bearing_force(b, s0, switch_speed=sw))
        assert switched[1] == pytest.approx(math.tanh(abs(w) / sw) * plain[1], rel=1e-12)
        assert short_bearing_force(b, s, switch_speed=sw)[0] == pytest.approx(
            short_bearing_force(b, s)[0], rel=1e-12)


def test_exact_force_at_rest_and_on_the_sine_axis():
    """No wedge and no squeeze: no force. A pure wedge with A = 6 w eps = 1 exactly (no
    squeeze, B = 0): Eq. 9 holds; a pure squeeze with B = -12 eps_dot = 1 (A = 0): the
    positive-part quadrature. Fails with the rest state returning 1 N, or with either
    test 'A == 0', 'B == 0' written '== 1' (short_bearing.py:106-107)."""
    b = seed_bearing(0.5)
    assert short_bearing_exact_force(b, JournalState(0.4, 0.0, 0.0, 0.0, 0.0)) == (0.0, 0.0)
    s = JournalState(0.5, 0.0, 0.0, 0.0, 1.0 / 3.0)          # 6 w eps = 1
    ref = short_bearing_force(b, s)
    assert short_bearing_exact_force(b, s) == pytest.approx(ref, rel=1e-10)
    s = JournalState(0.5, -1.0 / 12.0, 0.0, 0.0, 0.0)      # -12 eps_dot = 1
    ref = _short_gumbel_by_quad(b, s)
    assert short_bearing_exact_force(b, s) == pytest.approx(ref, rel=1e-8,
                                                            abs=1e-8 * np.abs(ref).max())
