"""The pressure-dependent lubricant in the FE film (bearingfem.ehd): limits, the exact
reduced-pressure solution of a Barus oil, the Newton Jacobian, and bad input."""
import numpy as np
import pytest

from bearingfem import Bearing, JournalState, solve_reynolds
from bearingfem.closed.long_bearing import long_bearing_pressure
from bearingfem.ehd import ConvergenceError
from bearingfem.ehd.coupling import ehd_film
from bearingfem.fe.kernel import fe_operator, general_film
from bearingfem.fields import FilmFields
from bearingfem.lubricant import Lubricant

B = Bearing(radius=0.01, length=0.01, clearance=20e-6, viscosity=0.0117)
S = JournalState(eps=0.6, eps_dot=0.1, gamma=0.3, gamma_dot=0.0, omega=250.0)
BUMP = FilmFields(gap=lambda t, z: 1.0 + S.eps * np.cos(t) + 0.1 * z * np.sin(t))


@pytest.mark.parametrize("element", ["P1", "P2"])
@pytest.mark.parametrize("cavitation", ["none", "reynolds"])
def test_zero_alpha_is_todays_film(cavitation, element):
    """Barus alpha = 0: the Newton film takes no step and is today's film on the same fields
    to round-off (1e-13; a general gap), and the rigid fast path to 1e-9 (the fast path's
    strong-form Couette term differs by quadrature error: 5e-11 measured at 60 x 10).
    Fails when the start is not the isoviscous film (e.g. the lubricant's viscosity taken
    as a ratio to itself when the bearing's differs: viscosity 2 mu0 gives 1.0 here)."""
    oil = Lubricant(viscosity=B.viscosity, barus=0.0)
    n = (60, 10) if element == "P1" else (30, 6)
    today = solve_reynolds(B, S, *n, element, cavitation=cavitation, fields=BUMP)
    ehd = solve_reynolds(B, S, *n, element, cavitation=cavitation, fields=BUMP,
                         lubricant=oil)
    assert ehd.iterations == 0
    scale = np.max(np.abs(today.pressure))
    assert np.max(np.abs(ehd.pressure - today.pressure)) <= 1e-13 * scale
    rigid = solve_reynolds(B, S, *n, element, cavitation=cavitation)
    whole = solve_reynolds(B, S, *n, element, cavitation=cavitation, lubricant=oil)
    assert np.allclose(whole.force, rigid.force, rtol=1e-9, atol=0.0)
    thick = Lubricant(viscosity=2 * B.viscosity)
    doubled = solve_reynolds(B, S, *n, element, cavitation=cavitation, lubricant=thick)
    assert np.allclose(doubled.force, 2 * np.asarray(rigid.force), rtol=1e-9, atol=0.0)


def test_barus_light_load_is_isoviscous_to_first_order():
    """At alpha p_max = 1e-3 and 5e-4 the force moves from the isoviscous film by an amount
    proportional to alpha (ratio 2 to 1e-3: the O(alpha^2) remainder), upward (a Barus oil
    is thicker under pressure). Fails with the viscosity's pressure dependence ignored
    (ratio 0/0) or inverted (force drops)."""
    rigid = solve_reynolds(B, S, 48, 8, cavitation="reynolds")
    alpha = 1e-3 / rigid.pressure_max
    shift = []
    for a in (alpha, alpha / 2):
        sol = solve_reynolds(B, S, 48, 8, cavitation="reynolds",
                             lubricant=Lubricant(viscosity=B.viscosity, barus=a))
        shift.append(np.hypot(*sol.force) / np.hypot(*rigid.force) - 1.0)
    assert shift[0] > 0.0
    assert abs(shift[0] / shift[1] - 2.0) < 1e-3
    assert shift[0] < 2e-3          # O(alpha p_max): 1.2e-3 measured


def test_barus_long_bearing_reduced_pressure():
    """A Barus incompressible oil: q = (1 - exp(-alpha p))/alpha solves the isoviscous
    Reynolds equation, so on a long bearing's mid-plane p = -ln(1 - alpha q)/alpha with q
    the closed-form long-bearing (Sommerfeld) pressure; alpha q_max = 0.6 (p_max 1.53 q_max).
    L/D = 8, 32 axial cells, max error / p_max: 2.8e-2, 1.4e-2, 7.2e-3 at 48, 96, 192 cells
    around (the isoviscous FE film has 3.3e-2, 1.7e-2, 8.3e-3 against its own closed form:
    the same first order in the nodal maximum). Asserted: < 1e-2 at 192 and halving from
    96. Fails with the Barus law's sign flipped (error 0.5) or the viscosity read at the
    clipped pressure."""
    b = Bearing(radius=0.01, length=0.16, clearance=20e-6, viscosity=0.0117)
    s = JournalState(eps=0.6, omega=250.0)
    q_max = np.max(long_bearing_pressure(b, s, np.linspace(0, 2 * np.pi, 721)))
    alpha = 0.6 / q_max
    oil = Lubricant(viscosity=b.viscosity, barus=alpha)
    errors = []
    for n in (96, 192):
        sol = solve_reynolds(b, s, n, 32, cavitation="none", lubricant=oil)
        mid = np.abs(sol.z) < 1e-12
        q = long_bearing_pressure(b, s, sol.theta[mid])
        p = -np.log1p(-alpha * q) / alpha
        errors.append(np.max(np.abs(sol.pressure[mid] - p)) / np.max(p))
    assert errors[1] < 1e-2
    assert errors[0] / errors[1] > 1.8


@pytest.mark.parametrize("element", ["P1", "P2"])
@pytest.mark.parametrize("state", [S, JournalState(eps=0.6, eps_dot=20.0, omega=0.0)])
@pytest.mark.parametrize("oil", [Lubricant(viscosity=0.0117, barus=2e-8,
                                           density="dowson-higginson"),
                                 Lubricant(viscosity=0.0117, roelands=0.6, bulk_modulus=2e9)])
def test_jacobian_is_the_residuals_derivative(oil, state, element):
    """J v against the central difference of the residual (step 1e-6 |P|, truncation
    ~1e-12; 3e-11 P1, 8e-11 P2 measured): agreement 1e-7 relative, on a rotating and a
    pure-squeeze film. Fails with the density slope in the Couette term, the density slope in the
    squeeze term or the viscosity slope dropped."""
    op = fe_operator(B, state, 24, 6, element, None, False)
    base, gap = general_film(B, state, op, BUMP)
    film = ehd_film(B, state, op, base, gap, oil, None)
    P = 0.5e9 / B.pressure_scale * np.maximum(np.sin(op.mesh.theta), 0.0) * (
        1 - (op.mesh.zeta / op.mesh.length_ratio) ** 2)
    J, U, V = film.jacobian(P)
    assert U is None and V is None
    v = np.random.default_rng(1).standard_normal(P.size) * np.max(P)
    h = 1e-6
    diff = (film.residual(P + h * v)[0] - film.residual(P - h * v)[0]) / (2 * h)
    assert np.max(np.abs(J @ v - diff)) <= 1e-7 * np.max(np.abs(diff))


def test_newton_converges_quadratically():
    """A Barus and Dowson-Higginson oil at eps 0.9 (alpha p_max = 0.43) converges to 1e-10
    in at most 4 Newton steps from the isoviscous film (3 measured). Fails with a Jacobian
    term dropped (the viscosity slope: the damped Newton then needs more steps)."""
    oil = Lubricant(viscosity=0.0117, barus=2e-8, density="dowson-higginson")
    sol = solve_reynolds(B, JournalState(eps=0.9, omega=250.0), 60, 10, lubricant=oil)
    assert sol.iterations <= 4 and sol.residual <= 1e-10


def test_no_solution_raises():
    """A Barus oil whose isoviscous pressure reaches alpha q >= 1 has no film (the
    reduced pressure caps q at 1/alpha): the solve raises ConvergenceError, no NaN."""
    rigid = solve_reynolds(B, S, 24, 4, cavitation="none")
    oil = Lubricant(viscosity=B.viscosity, barus=3.0 / rigid.pressure_max)
    with pytest.raises(ConvergenceError, match="EHD Newton"):
        solve_reynolds(B, JournalState(eps=0.6, omega=250.0), 24, 4, cavitation="none",
                       lubricant=oil)


@pytest.mark.parametrize("kwargs, match", [
    (dict(lubricant=0.0117), "lubricant must be"),
    (dict(lubricant=Lubricant(viscosity=0.0117, density="dowson-higginson"),
          cavitation="jfo", ambient_pressure=1e5), "density=None"),
    (dict(lubricant=Lubricant(viscosity=0.0117), fields=FilmFields(viscosity=2.0)),
     "not both"),
])
def test_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        solve_reynolds(B, S, 24, 4, **kwargs)


def test_gumbel_film_is_refused_with_a_lubricant():
    """Gumbel's film clips after the solve: its viscosity and bush load would follow the
    unclipped suction. Refused before any work (fails when 'gumbel' is let through)."""
    with pytest.raises(ValueError, match="cavitation 'none' or 'reynolds'"):
        solve_reynolds(B, S, 24, 4, cavitation="gumbel", lubricant=Lubricant(viscosity=0.01))


def test_a_singular_newton_matrix_is_a_stall_without_a_step():
    """A film whose full-compliance Jacobian J + U vanishes: the Newton solve stops at
    once as stalled (None after 0 iterations, no LAPACK warning, no inf step tried), as
    scipy's solve did before the factorised step. Fails with the singular check of the
    dense LU dropped (lu_factor only warns; the line search then meets an inf step)."""
    import warnings

    from bearingfem.ehd import newton
    from bearingfem.ehd.coupling import ehd_film
    from bearingfem.fe.assembly import fe_operator
    st = JournalState(eps=0.6, omega=250.0)
    op = fe_operator(B, st, 12, 2, "P1", None, False)
    base, gap = general_film(B, st, op, BUMP)
    film = ehd_film(B, st, op, base, gap, None, None)
    P = np.zeros(op.mesh.ndofs)
    J, _, _ = film.jacobian(P)

    class Singular:
        op = film.op

        def evaluate(self, P, s=1.0):
            return film.evaluate(P, s)

        def jacobian(self, P, s, ev):
            return J, -J.toarray(), None

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert newton._newton(Singular(), P, 1.0, op.mesh.free, "none", 1e-10) == (None, 0)
