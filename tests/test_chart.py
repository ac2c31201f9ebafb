"""design_chart (bearingfem.design.chart): a Sommerfeld walk of equilibria and coefficients,
warm-started point to point, against Lund & Thomsen (1978), Petroff's law and the
designer functions it chains."""
import math

import numpy as np
import pytest

from bearingfem import Bearing
from bearingfem.design import coefficients, design_chart, equilibrium, load_from_sommerfeld
from studies.lund_thomsen import GROOVES, TABLE, bearing, largest_entry_error

#: P2 meshes that hold the table's tolerances of tests/test_lund_thomsen.py (measured over
#: the five rows: L/D 0.5 on 72x6 eps 0.0004, attitude 0.09 deg, K 1.1 %, B 1.3 %; L/D 1
#: on 48x8 eps 0.0008, 0.12 deg, K 1.0 %, B 1.1 %; on 48x4 at L/D 0.5 B is 2.8 % off)
MESH = {0.5: dict(n_theta=72, n_z=6), 1.0: dict(n_theta=48, n_z=8)}


def _chart(ld, S, **mesh):
    opts = dict(MESH[ld], **mesh)
    return design_chart(bearing(ld), 100.0, S, "fem", grooves=GROOVES, element="P2",
                        cavitation="reynolds", **opts)


@pytest.mark.parametrize("ld", [0.5, 1.0])
def test_the_chart_walks_lund_and_thomsens_table(ld):
    """All five rows of each L/D in one walk (each point started from the previous one),
    held to test_lund_thomsen's tolerances: eps 0.002, attitude 0.2 deg, K and B 2 % of
    the largest entry. Fails (run) with the chart's K in the turning-grooves form, or
    with the coefficients taken in the inertial frame."""
    rows = TABLE[ld]
    chart = _chart(ld, [r[0] for r in rows])
    for p, (S, eps, phi, *table) in zip(chart.points, rows):
        assert p.sommerfeld == S
        assert p.eps == pytest.approx(eps, abs=0.002)
        assert math.degrees(p.attitude) == pytest.approx(phi, abs=0.2)
        assert largest_entry_error(p.K.ravel(), table[:4]) < 0.02
        assert largest_entry_error(p.B.ravel()[[0, 1, 3]], table[4:]) < 0.02


def test_each_point_is_the_equilibrium_and_its_coefficients():
    """The walk against equilibrium() and coefficients() called cold at each Sommerfeld
    number (closed-form start, default xtol): eps, attitude and the dimensionless K, B
    and the friction variable agree to 1e-7 (Newton's stop at xtol 1e-10). Fails with the
    previous point's state kept instead of the new equilibrium, B scaled by omega twice
    or the friction's Poiseuille part read from F_r."""
    S = (2.0, 0.5, 0.1)
    chart = _chart(1.0, S, n_theta=24, n_z=4)
    b = bearing(1.0)
    opts = dict(grooves=GROOVES, element="P2", cavitation="reynolds", n_theta=24, n_z=4)
    for p, s in zip(chart.points, S):
        eq = equilibrium(b, load_from_sommerfeld(b, s, 100.0), 100.0, "fem",
                         direction=-0.5 * math.pi, **opts)
        K, B = coefficients(b, eq.state, "fem", frame="load", **opts).dimensionless()
        assert p.eps == pytest.approx(eq.eps, rel=1e-7)
        assert p.attitude == pytest.approx(eq.attitude, abs=1e-7)
        assert p.friction_variable == pytest.approx(
            b.radius / b.clearance * eq.friction_coefficient, rel=1e-7)
        np.testing.assert_allclose(p.K, K, rtol=0, atol=1e-7 * np.abs(K).max())
        np.testing.assert_allclose(p.B, B, rtol=0, atol=1e-7 * np.abs(B).max())


def test_a_light_load_has_petroffs_friction_and_any_bearing_the_same_chart():
    """At S = 10 (eps 0.015) the friction variable is Petroff's 2 pi^2 S (measured
    1.6e-4 above it: the 1/sqrt(1 - eps^2) of the Couette shear); and a bearing twice the
    size, three times the viscosity at another speed walks the same dimensionless chart
    (S is the only group: agreement 1e-8). Fails with the friction read from F_r, or K
    made dimensionless with the wrong load."""
    S = (10.0, 0.3)
    chart = _chart(1.0, S, n_theta=24, n_z=4)
    assert chart.points[0].friction_variable == pytest.approx(2 * math.pi ** 2 * 10.0,
                                                              rel=1e-3)
    big = Bearing(radius=0.1, length=0.2, clearance=2e-4, viscosity=0.03)
    other = design_chart(big, 40.0, S, "fem", grooves=GROOVES, element="P2",
                         cavitation="reynolds", n_theta=24, n_z=4)
    for name in ("eps", "attitude", "friction_variable", "K", "B"):
        np.testing.assert_allclose(other.column(name), chart.column(name), rtol=1e-8,
                                   atol=1e-10, err_msg=name)


@pytest.mark.parametrize("kwargs, message", [
    (dict(sommerfeld=[0.1, -1.0]), "sommerfeld must be"),
    (dict(sommerfeld=[]), "sommerfeld must be"),
    (dict(omega=0.0), "omega must be non-zero"),
    (dict(model="fem-table"), "exact partials"),
    (dict(eps_max=1.0), "eps_max must lie in"),
    (dict(xtol=0.1), "xtol must lie in"),
])
def test_the_chart_refuses_bad_input(kwargs, message):
    args = dict(sommerfeld=[0.5], omega=100.0, model="short")
    args.update(kwargs)
    with pytest.raises(ValueError, match=message):
        design_chart(bearing(1.0), args.pop("omega"), **args)


def test_angles_in_degrees_and_a_strength_off_the_grading_are_refused_by_name():
    """direction=-90 (degrees meant) walked a chart loaded toward -90 rad, the misalignment
    angle 45 was taken as 45 rad, and a strength of 1.5 left chart_grading to fail later in
    the mesh; design_chart's rtol (a film accuracy elsewhere) is refused naming xtol."""
    from bearingfem import JournalState
    from bearingfem.design import chart_grading, design_chart
    from bearingfem.design.misalignment import misalignment_tilt
    b = Bearing(radius=0.05, length=0.1, clearance=100e-6, viscosity=0.02)
    with pytest.raises(ValueError, match="direction -90 rad is more than a turn: typed in "
                                         "degrees"):
        design_chart(b, 314.16, [0.5], "short", direction=-90.0)
    with pytest.raises(ValueError, match="direction -90 rad is more than a turn"):
        chart_grading(b, 314.16, [0.1], direction=-90.0)
    with pytest.raises(ValueError, match=r"strength must lie in \[0, 0.99\]"):
        chart_grading(b, 314.16, [0.1], strength=1.5)
    with pytest.raises(ValueError, match="angle 45 rad is more than a turn"):
        misalignment_tilt(b, JournalState(eps=0.6, omega=250.0), degree=0.5, angle=45.0)
    with pytest.raises(ValueError, match="rtol is a film-accuracy request.*Newton's "
                                         "tolerance is xtol"):
        design_chart(b, 314.16, [0.5], "short", rtol=1e-2)


def test_newtons_tolerance_is_xtol_and_rtol_is_refused_before_any_film():
    """``rtol`` is the toolkit's film accuracy; the chart's Newton tolerance was called
    rtol too, so rtol=1e-2 (1 % film accuracy asked) was read as Newton's. Now it is
    ``xtol``: a loose xtol moves the answers off the default's by what it allows (the
    short film is closed form: no discretisation to hide it) - wired to nothing, or the
    default, this fails."""
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    with pytest.raises(ValueError, match=r"rtol is a film-accuracy request, got "
                                         r"rtol=1e-06; Newton's tolerance is xtol"):
        design_chart(b, 250.0, [float("nan")], "short", rtol=1e-6)   # refused before S
    loose = design_chart(b, 250.0, [0.5, 0.1], "short", xtol=1e-4)
    tight = design_chart(b, 250.0, [0.5, 0.1], "short")
    # measured: the loose chart's eps 1.5e-9 and 3.9e-7 off the default's (within
    # Newton's xtol 1e-4 of the step, far above the default's 1e-10 round-off)
    for lo, ti in zip(loose.points, tight.points):
        assert 1e-10 < abs(lo.eps - ti.eps) / ti.eps < 1e-5


def _position(point):
    return point.eps * np.array([math.cos(point.state.gamma), math.sin(point.state.gamma)])


def test_a_charts_estimate_errs_high():
    """design_chart(..., estimate=True): each point's eps_error (the position's, h/2h
    with the chart on the half mesh) and the largest entries of K_error and B_error at
    least the true errors against the chart on P2 96 x 32 (within ~1e-4 of P2 192 x 64),
    eps_error at most 3x (P1 48 x 16, L/D 1, Reynolds' condition; measured effectivity
    1.5-1.8 for eps, 4.4-9.5 for K, 3.5-35 for B, against P2 192 x 64; P1 96 x 32 alike,
    1.5-1.6 for eps). The chart's record is the pair's; the points on the mesh given
    are the plain chart's. Fails with the half walk on the mesh given (estimates 0;
    planted)."""
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    S = [1.0, 0.1, 0.03]
    opts = dict(element="P1", cavitation="reynolds")
    ref = design_chart(b, 250.0, S, "fem", n_theta=96, n_z=32, element="P2",
                       cavitation="reynolds")
    chart = design_chart(b, 250.0, S, "fem", n_theta=48, n_z=16, estimate=True, **opts)
    plain = design_chart(b, 250.0, S, "fem", n_theta=48, n_z=16, **opts)
    assert chart.accuracy.mesh == (48, 16) and chart.accuracy.partner == (24, 8)
    for p, q, r in zip(chart.points, plain.points, ref.points):
        assert p.eps == q.eps and np.array_equal(p.K, q.K) and q.eps_error is None
        true = float(np.linalg.norm(_position(p) - _position(r)))
        assert 1.0 <= p.eps_error / true <= 3.0, (p.sommerfeld, p.eps_error, true)
        assert np.max(p.K_error) >= np.max(np.abs(p.K - r.K))
        assert np.max(p.B_error) >= np.max(np.abs(p.B - r.B))
    with pytest.raises(ValueError, match="estimate=True is for film models on a mesh"):
        design_chart(b, 250.0, S, "short", estimate=True)
