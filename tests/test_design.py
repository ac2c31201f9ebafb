"""Designer's numbers: equilibrium, dynamic coefficients, stability (bearingfem.design)."""
import math
from dataclasses import replace

import numpy as np
import pytest

from bearingfem import Bearing, Groove, JournalState, Lubricant, solve_reynolds
from bearingfem.design import (coefficients, equilibrium, journal_orbit, lund_stability,
                               sommerfeld_number, threshold_speed)
from bearingfem.differentiate import central_differences
from bearingfem.film import local_to_inertial
from bearingfem.closed.long_bearing import long_bearing_derivatives, long_bearing_force
from bearingfem.models import FILM_MODELS, film_model
from bearingfem.routes import fe_force
from bearingfem.fe.sensitivity import fe_force_derivatives
from bearingfem.closed.short_bearing import short_bearing_derivatives, short_bearing_force

# Friswell, Penny, Garvey & Lees, Dynamics of Rotating Machines (2010), Example 5.5.1:
# short bearing D 0.1 m, c 0.1 mm, L 0.03 m, mu 0.1 Pa s, 1500 rpm (157.1 rad/s), 525 N.
# Their x is horizontal, y vertical up, the load the journal's weight (0, -525) N and the
# shaft turning counter-clockwise: the contract's inertial frame.
FRISWELL = Bearing(radius=0.05, length=0.03, clearance=0.1e-3, viscosity=0.1)
FRISWELL_EPS = 0.2663
FRISWELL_K = np.array([[12.81, 16.39], [-25.06, 8.815]]) * 1e6     # N/m
FRISWELL_C = np.array([[232.9, -81.92], [-81.92, 294.9]]) * 1e3    # N s/m


def test_friswell_example_5_5_1():
    eq = equilibrium(FRISWELL, (0.0, -525.0), 157.1, "short")
    assert eq.eps == pytest.approx(FRISWELL_EPS, rel=1e-3)
    kc = coefficients(FRISWELL, eq.state, "short", frame="inertial")
    # the book prints four digits: 0.1 % holds every entry
    np.testing.assert_allclose(kc.K, FRISWELL_K, rtol=1e-3)
    np.testing.assert_allclose(kc.C, FRISWELL_C, rtol=1e-3)
    assert kc.method == "analytic"


def test_equilibrium_balances_the_load_and_reports_the_film():
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    opts = dict(n_theta=48, n_z=8, element="P2", cavitation="reynolds")
    eq = equilibrium(b, 300.0, 250.0, "fem", direction=-0.5 * math.pi, **opts)
    np.testing.assert_allclose(np.add(eq.film_force, eq.load), 0.0, atol=1e-9 * 300.0)
    assert 0.0 < eq.eps < 1.0 and 0.0 < eq.attitude < 0.5 * math.pi
    assert eq.sommerfeld == pytest.approx(sommerfeld_number(b, 300.0, 250.0))
    sol = eq.solution
    np.testing.assert_allclose(sol.force, eq.film_force, rtol=1e-9)
    # the friction identity (Couette + c eps F_t / 2R) against the FE shear integral
    assert eq.friction_force == pytest.approx(sol.friction_force, rel=1e-4)
    assert eq.power_loss == pytest.approx(eq.friction_force * b.radius * 250.0)
    assert eq.film_min == pytest.approx(b.clearance * (1 - eq.eps))
    # Reynolds' condition makes up its own oil in the cavity: no feed of its own (the side
    # leakage was copied into flow_in before, so the command line printed it twice)
    assert eq.side_leakage > 0.0 and eq.flow_in is None
    # plain floats, so that the record prints as numbers (np.float64(...) before)
    assert {type(v) for v in (*eq.film_force, eq.friction_force, eq.friction_coefficient,
                              eq.power_loss)} == {float}
    assert "np.float64" not in repr(eq)


def test_equilibrium_flow_in_is_the_grooves_feed():
    """A full film fed by a groove: flow_in is the feed at the groove's dofs, the side
    leakage the flux at the ends - two different sums that mass conservation makes equal
    at equilibrium (1e-9; measured 1e-13). Before, flow_in was the side leakage itself."""
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    eq = equilibrium(b, 300.0, 250.0, "fem", direction=-0.5 * math.pi, n_theta=48, n_z=8,
                     cavitation="none", grooves=[Groove(0.0, 0.3, 1e5)])
    assert eq.flow_in == eq.solution.flow_in
    assert eq.flow_in == pytest.approx(eq.side_leakage, rel=1e-9) and eq.flow_in > 0.0


@pytest.mark.parametrize("load", [1e-3, 1.0, 100.0, 2000.0, 8000.0])
def test_equilibrium_from_light_to_heavy_load(load):
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    for model in ("short", "long", "fem"):
        eq = equilibrium(b, (load, 0.0), 250.0, model)
        f = math.hypot(*eq.film_force)
        assert f == pytest.approx(load, rel=1e-8)
        assert np.all(np.isfinite([eq.eps, eq.attitude, eq.friction_force]))


def test_equilibrium_refuses_what_it_cannot_do():
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    with pytest.raises(ValueError, match="load .* exceeds what the film carries"):
        equilibrium(b, (0.0, -1e7), 250.0, "short")
    with pytest.raises(ValueError, match="omega must be non-zero"):
        equilibrium(b, (0.0, -10.0), 0.0, "short")
    with pytest.raises(ValueError, match="load must be non-zero"):
        equilibrium(b, (0.0, 0.0), 250.0, "short")
    with pytest.raises(ValueError, match="model must be one of"):
        equilibrium(b, (0.0, -10.0), 250.0, "fe")
    with pytest.raises(ValueError, match="n_thta is not an option of film model 'fem'"):
        equilibrium(b, (0.0, -10.0), 250.0, "fem", n_thta=10)


@pytest.mark.parametrize("model,options,mesh", [
    ("short", {}, None),                                                   # Newton, no mesh
    ("fem", dict(n_theta=8, n_z=2), dict(n_theta=8, n_z=2, element="P1")),   # Newton
    ("fvm", dict(n_theta=16, n_z=4), dict(n_theta=16, n_z=4)),              # Brent
])
def test_a_load_beyond_the_capacity_is_a_typed_refusal(model, options, mesh):
    """The capacity refusal is a LoadCapacityError (a ValueError) that carries the load,
    the film's force at eps_max and the mesh it was solved on: the command line reads the
    mesh from it to say a coarse mesh's capacity is the mesh's (it matched the message's
    words before), on both routes to the equilibrium; it survives pickling (dask)."""
    import pickle

    from bearingfem import LoadCapacityError
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    with pytest.raises(LoadCapacityError) as info:
        equilibrium(b, (0.0, -1e7), 250.0, model, eps_max=0.95, **options)
    err = info.value
    assert isinstance(err, ValueError)
    assert (err.load, err.eps_max, err.model, err.mesh) == (1e7, 0.95, model, mesh)
    film = film_model(model).options(options)
    carried = math.hypot(*film_model(model).film_force(b, JournalState(0.95, omega=250.0),
                                                       **film))
    assert err.capacity == pytest.approx(carried, rel=1e-12) and carried < 1e7
    assert str(err) == (f"load 1e+07 N exceeds what the film carries before contact: "
                        f"{carried:.6g} N at eps_max = 0.95 ({model} model)")
    again = pickle.loads(pickle.dumps(err))
    assert (str(again), again.mesh, again.capacity) == (str(err), err.mesh, err.capacity)


STATES = [JournalState(0.6, 0.0, 0.3, 0.0, 250.0), JournalState(0.8, 20.0, -1.0, 5.0, 250.0),
          JournalState(0.3, -15.0, 2.0, 40.0, -120.0), JournalState(0.95, 0.0, 0.0, 0.0, 250.0)]


def _rel_gap(a, b):
    gaps = [np.max(np.abs(np.subtract(getattr(a, k), getattr(b, k))))
            / max(np.max(np.abs(getattr(b, k))), 1e-300)
            for k in ("force", "d_eps", "d_eps_dot", "d_wedge")]
    return max(gaps)


@pytest.mark.parametrize("state", STATES)
def test_closed_form_partials_against_central_differences(state):
    """Complex-step partials against central differences (steps 1e-6 relative). At
    eps_dot = 0 the long bearing's two branches of Eq. 13 meet with a jump in the second
    derivative, so differences there are first order (measured 2.3e-6 and 2.9e-6):
    those states get 1e-5, the others 1e-7."""
    b = Bearing(radius=0.01, length=0.004, clearance=20e-6, viscosity=0.0117)
    for exact, force, tol in (
            (short_bearing_derivatives, short_bearing_force, 1e-7),
            (long_bearing_derivatives, long_bearing_force, 1e-5 if state.eps_dot == 0 else 1e-7)):
        cd = central_differences(lambda s: force(b, s), state)
        assert _rel_gap(exact(b, state), cd) < tol


@pytest.mark.parametrize("cavitation", ["none", "gumbel", "reynolds"])
@pytest.mark.parametrize("element", ["P1", "P2"])
@pytest.mark.parametrize("state", STATES[:3])
def test_fe_exact_sensitivity_against_central_differences(state, element, cavitation):
    """Exact sensitivity with the cavitated set fixed equals the derivative of the discrete
    film; central differences with relative steps 1e-6 come within 1e-6 of it (at 1e-4
    steps a set change inside the step leaves them up to 5e-4 off)."""
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    exact = fe_force_derivatives(b, state, 40, 8, element, cavitation)
    cd = central_differences(lambda s: fe_force(b, s, 40, 8, element, cavitation)[0], state)
    assert exact.method == "exact-sensitivity"
    assert _rel_gap(exact, cd) < 1e-6


def test_differenced_coefficients_see_grooves_fixed_in_space():
    """A film whose partials are central differences (a piezoviscous oil, Barus 2e-8 1/Pa,
    with a supply groove fixed in the inertial frame): K from coefficients against K
    differenced directly in the inertial x and y of the journal centre (steps 1e-6 c; a
    second route: no local frame, no d/dgamma). Measured 1.1e-9 of the largest entry,
    bound 1e-6. Fails with the film's d/dgamma (the groove turning against the line of
    centres) taken at half its size (1e-2 off)."""
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    oil = Lubricant(viscosity=b.viscosity, barus=2e-8)
    film = dict(grooves=[Groove(angle=math.pi / 2, width=0.3, pressure=5e4)], lubricant=oil,
                cavitation="reynolds")
    s = JournalState(0.6, omega=250.0, gamma=-1.2)
    K = coefficients(b, s, "fem", n_theta=48, n_z=8, **film).K
    c, h = b.clearance, 1e-6 * b.clearance
    e = c * s.eps * np.array([math.cos(s.gamma), math.sin(s.gamma)])

    def force(dx, dy):
        ex, ey = e[0] + dx, e[1] + dy
        at = JournalState(math.hypot(ex, ey) / c, omega=250.0, gamma=math.atan2(ey, ex))
        return np.array(solve_reynolds(b, at, 48, 8, **film).force)

    direct = -np.column_stack([(force(h, 0) - force(-h, 0)) / (2 * h),
                               (force(0, h) - force(0, -h)) / (2 * h)])
    assert np.abs(K - direct).max() < 1e-6 * np.abs(direct).max()


def _inertial_force(model, b, omega, **opts):
    """F(x, y, vx, vy) in the inertial frame through the mechanism's own state map."""
    m = FILM_MODELS[model]

    def force(q):
        s = JournalState.from_eccentricity(*q, b.clearance, omega)
        f_r, f_t = m.film_force(b, s, **opts)
        return np.array([f_r * math.cos(s.gamma) - f_t * math.sin(s.gamma),
                         f_r * math.sin(s.gamma) + f_t * math.cos(s.gamma)])
    return force


def _inertial_jacobian(model, b, state, **opts):
    """d(F_x, F_y)/d(x, y, vx, vy) at ``state`` by central differences (steps 1e-6 c and
    1e-6 c |omega|) of the inertial force."""
    c, g = b.clearance, state.gamma
    e, ed, gd = state.eps * c, state.eps_dot * c, state.gamma_dot
    q0 = np.array([e * math.cos(g), e * math.sin(g),
                   ed * math.cos(g) - e * gd * math.sin(g),
                   ed * math.sin(g) + e * gd * math.cos(g)])
    force = _inertial_force(model, b, state.omega, **opts)
    h = np.array([1e-6 * c, 1e-6 * c, 1e-6 * c * abs(state.omega), 1e-6 * c * abs(state.omega)])
    return np.column_stack([(force(q0 + h[j] * np.eye(4)[j]) - force(q0 - h[j] * np.eye(4)[j]))
                            / (2 * h[j]) for j in range(4)])


@pytest.mark.parametrize("model,opts", [("short", {}), ("long", {}),
                                        ("fem", dict(n_theta=40, n_z=8, cavitation="reynolds"))])
@pytest.mark.parametrize("state", STATES[:3])
def test_coefficients_are_the_inertial_jacobian(model, opts, state):
    """K and C from the local partials against central differences of the inertial force
    in (x, y, vx, vy): checks the frame algebra, moving base states included."""
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    kc = coefficients(b, state, model, frame="inertial", **opts)
    J = _inertial_jacobian(model, b, state, **opts)
    np.testing.assert_allclose(kc.K, -J[:, :2], rtol=1e-5, atol=1e-6 * np.abs(kc.K).max())
    np.testing.assert_allclose(kc.C, -J[:, 2:], rtol=1e-5, atol=1e-6 * np.abs(kc.C).max())


def test_frames_are_rotations_of_one_another():
    b = FRISWELL
    s = JournalState(0.5, omega=157.1, gamma=0.7)
    kc = coefficients(b, s, "short", frame="local")
    for frame in ("inertial", "load"):
        other = kc.in_frame(frame)
        back = other.in_frame("local")
        np.testing.assert_allclose(back.K, kc.K, rtol=1e-12, atol=1e-6)
        # invariants of a rotation: trace and determinant
        assert np.trace(other.K) == pytest.approx(np.trace(kc.K))
        assert np.linalg.det(other.C) == pytest.approx(np.linalg.det(kc.C))
    load = kc.in_frame("load")
    np.testing.assert_allclose(load.axes[0], -np.array(kc.force) / kc.load)


def test_centred_journal_has_finite_coefficients():
    """eps = 0 is a normal input: linearised at EPS_FLOOR, it matches a nearly centred one."""
    b = FRISWELL
    for model in ("short", "long", "fem"):
        k0 = coefficients(b, JournalState(0.0, omega=157.1), model, frame="local")
        k1 = coefficients(b, JournalState(1e-4, omega=157.1), model, frame="local")
        assert np.all(np.isfinite(k0.K)) and np.all(np.isfinite(k0.C))
        np.testing.assert_allclose(k0.K, k1.K, rtol=1e-3, atol=1e-3 * np.abs(k1.K).max())
        np.testing.assert_allclose(k0.C, k1.C, rtol=1e-3, atol=1e-3 * np.abs(k1.C).max())


def _coef_vector(kc, drop=()):
    k, c = kc.dimensionless()
    v = np.concatenate([k.ravel(), c.ravel()])
    return np.delete(v, list(drop))


def test_fe_coefficients_tend_to_the_short_bearing():
    """L/D -> 0: the FE (Gumbel) coefficients approach the short bearing's at rate 2, as
    the forces do. Measured at eps 0.6 (240x16 P2): 5.96 %, 1.81 %, 0.48 %."""
    errors = []
    for ld in (1 / 4, 1 / 8, 1 / 16):
        b = Bearing(radius=0.01, length=0.02 * ld, clearance=20e-6, viscosity=0.0117)
        s = JournalState(0.6, omega=250.0)
        fe = _coef_vector(coefficients(b, s, "fem", frame="local", n_theta=240, n_z=16,
                                       element="P2", cavitation="gumbel"))
        sh = _coef_vector(coefficients(b, s, "short", frame="local"))
        errors.append(np.max(np.abs(fe - sh)) / np.max(np.abs(sh)))
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert errors[-1] < 0.006
    assert np.all(rates > 1.7)


def test_fe_coefficients_tend_to_the_long_bearing():
    """L/D -> infinity: K and C_rr, C_rt, C_tt approach the long bearing's at rate 1, as
    the forces do (measured 29.9, 15.2, 7.6 % for K at L/D 2, 4, 8). C_tr = -dF_t/dv_r
    has no such limit: Eq. 10 fixes the squeeze pressure's level at the maximum film,
    a film with ambient ends fixes it through the ends, and the level times the clipped
    half film's integral of sin(theta) enters F_t (C_tr stays 22 % off at L/D = 16)."""
    errors = []
    for ld in (2, 4, 8):
        b = Bearing(radius=0.01, length=0.02 * ld, clearance=20e-6, viscosity=0.0117)
        s = JournalState(0.6, omega=250.0)
        fe = coefficients(b, s, "fem", frame="local", n_theta=120, n_z=32, element="P2",
                          cavitation="gumbel")
        lo = coefficients(b, s, "long", frame="local")
        errors.append(np.concatenate([np.abs(fe.K - lo.K).ravel() / np.abs(lo.K).max(),
                                      np.abs(fe.C - lo.C).ravel() / np.abs(lo.C).max()]))
    rates = np.log2(errors[0] / errors[1]), np.log2(errors[1] / errors[2])
    converging = np.delete(np.arange(8), 6)          # every entry but C_tr
    # measured 0.97-1.02 for each entry, both halvings
    assert np.all(np.abs(np.array(rates)[:, converging] - 1.0) < 0.05)
    assert np.all(np.array(rates)[:, 6] < 0.6)       # C_tr: no long-bearing limit


def test_fe_and_fv_coefficients_converge_together():
    """FE (P2, exact sensitivity) and FV (central differences), Reynolds condition, L/D 1,
    eps 0.6: their dimensionless coefficients close in on each other with the mesh
    (measured 1.4 %, 0.66 %, 0.21 % at 60x12, 120x24, 240x48)."""
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    s = JournalState(0.6, omega=250.0)
    gaps = []
    for n_theta, n_z in ((60, 12), (120, 24)):
        fe = coefficients(b, s, "fem", frame="local", n_theta=n_theta, n_z=n_z,
                          element="P2", cavitation="reynolds")
        fv = coefficients(b, s, "fvm", frame="local", n_theta=n_theta, n_z=n_z,
                          cavitation="reynolds")
        a, c = _coef_vector(fe), _coef_vector(fv)
        gaps.append(np.max(np.abs(a - c)) / np.max(np.abs(a)))
    assert gaps[1] < 0.6 * gaps[0] and gaps[1] < 0.01


def test_lund_threshold_puts_eigenvalues_on_the_imaginary_axis():
    eq = equilibrium(FRISWELL, (0.0, -525.0), 157.1, "short")
    st = lund_stability(coefficients(FRISWELL, eq.state, "short"))
    K, C, M = st.coefficients.K, st.coefficients.C, st.critical_mass
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-K / M, -C / M]])
    lam = np.linalg.eigvals(A)
    crossing = lam[np.argmax(lam.real)]
    assert abs(crossing.real) < 1e-9 * abs(crossing.imag)
    assert abs(crossing.imag) == pytest.approx(st.whirl_frequency, rel=1e-9)
    # a plain bearing at light load whirls at about half speed
    assert 0.4 < st.whirl_ratio < 0.55
    for f, stable in ((0.99, True), (1.01, False)):
        lam = np.linalg.eigvals(np.block([[np.zeros((2, 2)), np.eye(2)],
                                          [-K / (f * M), -C / (f * M)]]))
        assert (lam.real.max() < 0) == stable == st.stable(f * M)


def test_linear_threshold_agrees_with_the_nonlinear_orbit():
    """Below the critical mass a kicked journal returns, above it the orbit grows (short
    bearing; its half-film switch smoothed over 1 rad/s, identical at equilibrium)."""
    eq = equilibrium(FRISWELL, (0.0, -525.0), 157.1, "short")
    st = lund_stability(coefficients(FRISWELL, eq.state, "short"))
    below = journal_orbit(FRISWELL, eq, 0.9 * st.critical_mass, "short", turns=40,
                          kick=0.01, switch_speed=1.0)
    above = journal_orbit(FRISWELL, eq, 1.1 * st.critical_mass, "short", turns=40,
                          kick=0.01, switch_speed=1.0)
    assert below.growth() < 0.2
    assert above.growth() > 3.0


def test_threshold_speed_is_where_the_critical_mass_is_the_journal_mass():
    mass = 50.0
    th = threshold_speed(FRISWELL, (0.0, -525.0), mass, "short", omega_range=(10.0, 5e3))
    assert th.stability.critical_mass == pytest.approx(mass, rel=1e-6)
    # the default range ends at a journal bearing's highest surface speed, 300 m/s
    assert threshold_speed(FRISWELL, (0.0, -525.0), mass, "short").omega == pytest.approx(
        th.omega, rel=1e-6)
    with pytest.raises(ValueError, match="omega_range's high end 10000 rad/s .* 500 m/s"):
        threshold_speed(FRISWELL, (0.0, -525.0), mass, "short", omega_range=(10.0, 1e4))
    slower = equilibrium(FRISWELL, (0.0, -525.0), 0.9 * th.omega, "short")
    assert lund_stability(coefficients(FRISWELL, slower.state, "short")).stable(mass)


def test_equilibrium_with_fe_reproduces_raimondi_boyd_sommerfeld():
    """Periodic FE film, Reynolds condition: the Sommerfeld number at eps 0.6, L/D 1 within
    2 % of Raimondi & Boyd's 0.121 (their film starts at the maximum film; at eps 0.6 the
    two agree to 0.5 %, see tests/test_raimondi_boyd.py)."""
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    s = JournalState(0.6, omega=250.0)
    sol = solve_reynolds(b, s, 60, 12, "P2", "reynolds")
    W = math.hypot(*sol.force_local)
    eq = equilibrium(b, (0.0, -W), 250.0, "fem", n_theta=60, n_z=12, element="P2",
                     cavitation="reynolds")
    assert eq.eps == pytest.approx(0.6, abs=1e-9)
    assert eq.sommerfeld == pytest.approx(0.121, rel=0.02)
    state_again = replace(eq.state, gamma=0.0)
    assert state_again.eps == pytest.approx(0.6)


GROOVED = dict(n_theta=40, n_z=8, element="P2", cavitation="reynolds",
               grooves=(Groove(angle=0.0, width=0.35, pressure=1e5),
                        Groove(angle=np.pi, width=0.35, pressure=1e5)))


@pytest.mark.parametrize("state", STATES[:3])
def test_grooved_coefficients_are_the_inertial_jacobian(state):
    """Grooves stay in place while the film turns with the eccentricity: the partial in
    gamma enters K[:, t]. Against central differences of the inertial force (the grooves'
    positions follow from the inertial frame there, independently)."""
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    kc = coefficients(b, state, "fem", frame="inertial", **GROOVED)
    J = _inertial_jacobian("fem", b, state, **GROOVED)
    np.testing.assert_allclose(kc.K, -J[:, :2], rtol=1e-5, atol=1e-6 * np.abs(kc.K).max())
    np.testing.assert_allclose(kc.C, -J[:, 2:], rtol=1e-5, atol=1e-6 * np.abs(kc.C).max())


def test_groove_shift_is_what_grooves_turning_with_the_journal_take_away():
    """K - K_groove_shift against central differences in (x, y) of the inertial force with
    the grooves turned with the line of centres (the convention of Someya's data book,
    studies/someya.py); zero without grooves."""
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    state = JournalState(0.5, omega=250.0, gamma=-1.0)
    kc = coefficients(b, state, "fem", frame="inertial", **GROOVED)
    assert np.abs(kc.K_groove_shift).max() > 0.05 * np.abs(kc.K).max()

    def force(x, y):
        gamma = math.atan2(y, x)
        turned = tuple(replace(g, angle=g.angle + gamma - state.gamma)
                       for g in GROOVED["grooves"])
        s = JournalState(math.hypot(x, y) / b.clearance, omega=250.0, gamma=gamma)
        f_r, f_t = fe_force(b, s, 40, 8, "P2", "reynolds", grooves=turned)[0]
        return np.array(local_to_inertial(f_r, f_t, gamma))
    x0, y0, h = 0.5 * b.clearance * math.cos(-1.0), 0.5 * b.clearance * math.sin(-1.0), 1e-9
    J = np.column_stack([(force(x0 + h, y0) - force(x0 - h, y0)) / (2 * h),
                         (force(x0, y0 + h) - force(x0, y0 - h)) / (2 * h)])
    np.testing.assert_allclose(kc.K - kc.K_groove_shift, -J, rtol=1e-5,
                               atol=1e-6 * np.abs(kc.K).max())
    plain = coefficients(b, state, "fem", n_theta=40, n_z=8, cavitation="reynolds")
    assert not np.any(plain.K_groove_shift)


def test_grooved_equilibrium_balances_and_turns_with_load_and_grooves():
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    eq = equilibrium(b, 500.0, 250.0, "fem", direction=-0.5 * math.pi, **GROOVED)
    np.testing.assert_allclose(np.add(eq.film_force, eq.load), 0.0, atol=1e-8 * 500.0)
    # turning load and grooves by the same angle turns the equilibrium, nothing else
    turn = 0.7
    turned = {**GROOVED, "grooves": tuple(Groove(angle=gr.angle + turn, width=gr.width,
                                                 pressure=gr.pressure)
                                          for gr in GROOVED["grooves"])}
    eq2 = equilibrium(b, 500.0, 250.0, "fem", direction=-0.5 * math.pi + turn, **turned)
    assert eq2.eps == pytest.approx(eq.eps, rel=1e-7)
    assert np.mod(eq2.state.gamma - eq.state.gamma - turn + np.pi, 2 * np.pi) - np.pi == \
        pytest.approx(0.0, abs=1e-7)
    # a load toward a pressurised groove is carried at another eccentricity than across them
    eq3 = equilibrium(b, 500.0, 250.0, "fem", direction=-0.25 * math.pi, **GROOVED)
    assert abs(eq3.eps - eq.eps) > 0.05
    with pytest.raises(ValueError, match="grooves is not an option of film model 'fvm'"):
        equilibrium(b, 500.0, 250.0, "fvm", grooves=GROOVED["grooves"])


def test_a_load_direction_in_degrees_is_named():
    """direction= is in radians, the command line's --direction in degrees: a direction of
    more than a turn is refused as degrees typed (direction=-90 was a load at -90 rad,
    solved without a word); a turn's radians are taken."""
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    with pytest.raises(ValueError, match=r"direction -90 rad is more than a turn: typed in "
                                         r"degrees\? \(-90 deg = -1.571 rad\)"):
        equilibrium(b, 1000.0, 250.0, "short", direction=-90.0)
    eq = equilibrium(b, 1000.0, 250.0, "short", direction=-0.5 * math.pi)
    assert eq.load == pytest.approx((0.0, -1000.0), abs=1e-9)
    # a full turn either way is a direction (the command line's --direction 360 is 2 pi)
    for turn in (math.radians(360.0), -2.0 * math.pi):
        assert equilibrium(b, 1000.0, 250.0, "short", direction=turn).load == pytest.approx(
            (1000.0, 0.0), abs=1e-9)
    with pytest.raises(ValueError, match=r"it lies in \[-2 pi, 2 pi\] rad"):
        equilibrium(b, 1000.0, 250.0, "short", direction=2.0 * math.pi + 1e-9)


@pytest.mark.parametrize("bad, match", [
    (dict(eps_error=float("nan")), "eps_error must be finite"),   # named eps before
    (dict(eps_error=-0.01), r"eps_error .* must be >= 0")])  # taken, the error moved
def test_coefficients_refuse_a_bad_eps_error_by_name(bad, match):
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    s = JournalState(eps=0.6, omega=250.0)
    with pytest.raises(ValueError, match=match):
        coefficients(b, s, "fem", n_theta=24, n_z=4, estimate=True, **bad)


def test_eps_error_without_an_estimate_is_refused_not_dropped():
    """eps_error is added to K and C's estimated error; without rtol or estimate the
    coefficients carried no error and the eps_error given vanished unseen."""
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    s = JournalState(eps=0.6, omega=250.0)
    with pytest.raises(ValueError, match="eps_error .* give rtol= or estimate=True"):
        coefficients(b, s, "fem", n_theta=24, n_z=4, eps_error=0.01)
    assert coefficients(b, s, "fem", n_theta=24, n_z=4, eps_error=None).error is None


def test_tilt_with_an_accuracy_request_is_refused_as_such():
    """equilibrium and coefficients take tilt on a mesh given; with rtol or estimate the
    refusal said "tilt is not an option of film model 'fem'", which it is."""
    b = Bearing(radius=0.01, length=0.01, clearance=20e-6, viscosity=0.0117)
    with pytest.raises(ValueError, match="tilt: not taken with rtol"):
        equilibrium(b, (0.0, -100.0), 250.0, "fem", rtol=1e-2, tilt=(0.0, 1e-3))
    with pytest.raises(ValueError, match="tilt: not taken with estimate"):
        equilibrium(b, (0.0, -100.0), 250.0, "fem", estimate=True, tilt=(0.0, 1e-3))
    s = JournalState(eps=0.6, omega=250.0)
    with pytest.raises(ValueError, match="tilt: not taken with rtol"):
        coefficients(b, s, "fem", rtol=1e-2, tilt=(0.0, 1e-3))


def test_coefficients_take_a_coarse_equilibriums_eps_error_of_one_or_more():
    """An equilibrium estimated on a coarse mesh can report eps_error >= 1 (1.04 here, at
    eps 0.82 on 10 x 2): the command line hands it to coefficients, which take it (the
    shifted state stops halfway to the wall) and report a large error, not a refusal of an
    argument the user never gave."""
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    eq = equilibrium(b, (0.0, -375.0), 250.0, "fem", n_theta=10, n_z=2, estimate=True)
    assert eq.eps_error >= 1.0
    kc = coefficients(b, eq.state, "fem", n_theta=10, n_z=2, estimate=True,
                      eps_error=eq.eps_error)
    alone = coefficients(b, eq.state, "fem", n_theta=10, n_z=2, estimate=True)
    assert np.isfinite(kc.error) and kc.error > alone.error
