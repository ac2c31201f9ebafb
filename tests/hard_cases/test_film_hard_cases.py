"""Hard film states are ordinary inputs: every model returns finite forces, continuous
across the special points, and the numerical solvers converge there."""
import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from bearingfem import (Bearing, JournalState, fvm_reynolds, long_bearing_exact_force,
                        long_bearing_force, short_bearing_exact_force, short_bearing_force,
                        solve_reynolds)

B = Bearing(radius=0.01, length=0.01, clearance=20e-6, viscosity=0.0117)
CLOSED = [short_bearing_force, long_bearing_force, short_bearing_exact_force,
          long_bearing_exact_force]
NUMERIC = {
    "fem-P1-reynolds": lambda s: solve_reynolds(B, s, 60, 10, "P1", "reynolds"),
    "fem-P2-gumbel": lambda s: solve_reynolds(B, s, 60, 10, "P2", "gumbel"),
    "fvm-reynolds": lambda s: fvm_reynolds(B, s, 60, 10, "reynolds"),
}
HARD = {
    "eps=0": JournalState(0.0, 0.0, 0.0, 0.0, 250.0),
    "eps=1e-12": JournalState(1e-12, 0.0, 0.0, 0.0, 250.0),
    "eps=0.99": JournalState(0.99, 0.0, 0.0, 0.0, 250.0),
    "eps=0.999": JournalState(0.999, 0.0, 0.0, 0.0, 250.0),
    "pure squeeze omega=0": JournalState(0.5, 20.0, 0.0, 0.0, 0.0),
    "squeeze at eps=0": JournalState(0.0, 20.0, 0.0, 0.0, 0.0),
    "zero wedge gamma_dot=omega/2": JournalState(0.6, 5.0, 0.0, 125.0, 250.0),
    "negative omega": JournalState(0.6, 0.0, 0.0, 0.0, -250.0),
    "huge eps_dot": JournalState(0.6, 1e6, 0.0, 0.0, 250.0),
    "huge negative eps_dot": JournalState(0.6, -1e6, 0.0, 0.0, 250.0),
}


@pytest.mark.parametrize("name", HARD)
@pytest.mark.parametrize("model", CLOSED, ids=lambda f: f.__name__)
def test_closed_forms_finite(model, name):
    assert np.all(np.isfinite(model(B, HARD[name])))


@pytest.mark.parametrize("name", HARD)
@pytest.mark.parametrize("model", NUMERIC)
def test_numerical_solvers_finite_and_converged(model, name):
    sol = NUMERIC[model](HARD[name])
    assert np.all(np.isfinite(sol.force_local)) and np.all(np.isfinite(sol.pressure))
    assert sol.converged and sol.residual < 1e-8
    assert np.isfinite(sol.friction_force) and np.isfinite(sol.side_leakage)
    if sol.cavitation != "none":
        assert sol.pressure.min() >= 0.0


SMOOTH_SHORT = lambda b, s: short_bearing_force(b, s, switch_speed=1.0)  # noqa: E731


@pytest.mark.parametrize("model", [SMOOTH_SHORT] + CLOSED[1:]
                         + [lambda b, s: NUMERIC["fem-P1-reynolds"](s).force_local],
                         ids=["short(switch 1 rad/s)", "long", "short-exact", "long-exact", "fem"])
@pytest.mark.parametrize("base,field", [
    (JournalState(0.6, 0.0, 0.0, 0.0, 250.0), "eps_dot"),      # E = 0 in seed Eq. 13
    (JournalState(0.6, 5.0, 0.0, 125.0, 250.0), "gamma_dot"),  # wedge changes sign
    (JournalState(1e-9, 0.0, 0.0, 0.0, 250.0), "eps"),          # eps -> 0
])
def test_continuous_across_special_points(model, base, field):
    h = 1e-7
    at = np.array(model(B, base))
    scale = max(np.abs(at).max(), np.abs(model(B, JournalState(0.6, 0, 0, 0, 250.0))).max())
    for d in (h, -h):
        v = getattr(base, field) + d
        if field == "eps" and v < 0:
            continue
        s = JournalState(**{**base.__dict__, field: v})
        assert np.abs(np.array(model(B, s)) - at).max() < 1e-4 * scale


def test_sharp_half_film_switch_jumps_by_the_squeeze_term():
    """Eq. 9 with its half film turned toward the wedge: F_t jumps by 8 k eps eps_dot where
    omega - 2 gamma_dot changes sign (k = mu L^3 R / (2 c^2 (1 - eps^2)^2))."""
    base = dict(eps=0.6, eps_dot=5.0, gamma=0.0, omega=250.0)
    up = short_bearing_force(B, JournalState(gamma_dot=125.0 - 1e-9, **base))
    down = short_bearing_force(B, JournalState(gamma_dot=125.0 + 1e-9, **base))
    k = B.viscosity * B.length ** 3 * B.radius / (2 * B.clearance ** 2 * (1 - 0.36) ** 2)
    assert up[1] - down[1] == pytest.approx(8 * k * 0.6 * 5.0, rel=1e-6)
    assert up[0] == pytest.approx(down[0], rel=1e-6)


states = st.builds(JournalState, eps=st.floats(0.0, 0.98), eps_dot=st.floats(-500, 500),
                   gamma=st.floats(-4, 4), gamma_dot=st.floats(-300, 300),
                   omega=st.floats(-500, 500))


@settings(max_examples=60, deadline=None, derandomize=True)
@given(states, st.floats(0.1, 10.0))
def test_properties_closed_forms(s, k):
    for f in CLOSED:
        a = np.array(f(B, s))
        assert np.all(np.isfinite(a))
        # positively homogeneous of degree 1 in the velocities
        sk = JournalState(s.eps, k * s.eps_dot, s.gamma, k * s.gamma_dot, k * s.omega)
        assert np.allclose(f(B, sk), k * a, rtol=1e-8, atol=1e-9 * (1 + np.abs(a).max()))


@settings(max_examples=15, deadline=None, derandomize=True)
@given(states)
def test_properties_fem(s):
    sol = solve_reynolds(B, s, 32, 6, "P1", "reynolds")
    assert np.all(np.isfinite(sol.force_local)) and sol.pressure.min() >= 0.0
    # mirror: omega, gamma_dot -> -omega, -gamma_dot keeps F_r and flips F_t. On one mesh
    # that holds to discretisation error, estimated by one mesh doubling.
    m = solve_reynolds(B, JournalState(s.eps, s.eps_dot, s.gamma, -s.gamma_dot, -s.omega),
                       32, 6, "P1", "reynolds")
    fine = solve_reynolds(B, s, 64, 12, "P1", "reynolds")
    est = np.abs(np.subtract(sol.force_local, fine.force_local)).max()
    tol = 2.0 * est + 1e-9 * (np.abs(sol.force_local).max() + 1e-12)
    assert abs(m.force_local[0] - sol.force_local[0]) < tol
    assert abs(m.force_local[1] + sol.force_local[1]) < tol


def test_load_grows_with_eccentricity():
    loads = [np.hypot(*solve_reynolds(B, JournalState(e, omega=250.0), 60, 10, "P1",
                                      "reynolds").force_local)
             for e in (0.1, 0.3, 0.5, 0.7, 0.9, 0.95)]
    assert np.all(np.diff(loads) > 0)
