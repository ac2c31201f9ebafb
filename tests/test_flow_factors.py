"""The flow of a rough gap (Patir & Cheng's average flow model, bearingfem.contact.
flow_factors) and the film that takes it, against independent references: the fits' own
consistency and a second public statement of the isotropic fit, the Gaussian mean gap by
quadrature, the smooth film in the limit h/sigma -> infinity, exact similarity solutions
of the film's operator, and a flow simulation of rough cells of its own (studies/
flow_factors.py: scikit-fem, not the toolkit's film assembly), itself checked against the
exact flow across and along ridges.

Each test names the planted defect it was run against and failed on."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from bearingfem import (Bearing, ElasticBush, ElasticJournalState, FlowFactors,
                        JournalState, Roughness, solve_reynolds)
from bearingfem.bearing import seed_bearing
from bearingfem.contact.flow_factors import (PATTERNS, PRESSURE_FIT, SHEAR_FIT, FlowFields,
                                             flow_fields, mean_gap, pressure_flow_factor,
                                             pressure_flow_slope, shear_flow_factor,
                                             shear_flow_slope)
from bearingfem.fe.assembly import fe_operator
from bearingfem.fe.general import general_film
from bearingfem.fe.kernel import solve_film
from bearingfem.fields import FilmFields
from bearingfem.routes import film_problem, route_for
from bearingfem.ehd.states import ModalStateEHD
from bearingfem.lubricant import Lubricant
from tests.test_ehd_states import differenced_jacobian
from studies.flow_factors import (cell_factors, cell_flow_factor,
                                  longitudinal_exact, measured_factors,
                                  transverse_exact, transverse_shear_exact)

B = seed_bearing()                                   # c = 20 um
PIN = Bearing(radius=0.01, length=0.004, clearance=20e-6, viscosity=0.0117)
SOLID = ElasticBush(outer_radius=0.016, modulus=110e9, poisson=0.34, model="solid")


def rough(sigma, **flow):
    return Roughness(sigma=sigma, contact_modulus=53.3e9, elastic_factor=1e-3,
                     flow=FlowFactors(**flow))


# -- the fits -----------------------------------------------------------------------------
def test_isotropic_fit_is_the_published_one():
    """gamma = 1: phi_x = phi_y = 1 - 0.90 exp(-0.56 H) (Patir & Cheng 1978, Table 1, as
    also typed in public implementations) at H = 0.5 ... 6, held below H = 0.5; Phi_s at
    H = 1, 3 and 6 from its two forms typed out here. Fails with r = 0.65 for 0.56."""
    H = np.array([0.5, 1.0, 2.0, 3.0, 6.0])
    f = FlowFactors(pattern=1.0, journal_share=1.0)
    phi_x, phi_y, phi_s = f.factors(H)
    np.testing.assert_allclose(phi_x, 1.0 - 0.9 * np.exp(-0.56 * H), rtol=1e-15)
    np.testing.assert_array_equal(phi_x, phi_y)
    assert pressure_flow_factor(0.2, 1.0) == pressure_flow_factor(0.5, 1.0)
    np.testing.assert_allclose(shear_flow_factor([1.0, 3.0, 6.0], 1.0),
                               [1.899 * math.exp(-0.92 + 0.05),
                                1.899 * 3 ** 0.98 * math.exp(-2.76 + 0.45),
                                1.126 * math.exp(-1.5)], rtol=1e-14)
    np.testing.assert_allclose(phi_s, shear_flow_factor(H, 1.0), rtol=1e-15)


@pytest.mark.parametrize("gamma", PATTERNS)
def test_shear_fit_forms_meet_at_five(gamma):
    """The two forms of Phi_s, fitted separately by Patir & Cheng (1979, Table 2), meet
    at H = 5 to their 3-4 printed digits for every gamma: a check of the typed table
    (measured: 3e-5 to 8e-4 relative). Fails with A2 of gamma = 1 typed 1.26."""
    A1, a1, a2, a3, A2 = SHEAR_FIT[gamma]
    low = A1 * 5 ** a1 * math.exp(-5 * a2 + 25 * a3)
    assert low == pytest.approx(A2 * math.exp(-1.25), rel=1e-3)


@pytest.mark.parametrize("gamma", PATTERNS)
def test_pressure_fits_and_their_limits(gamma):
    """phi_y(H, gamma) = phi_x(H, 1/gamma); phi_x < 1 for gamma < 1 and > 1 for gamma > 1,
    tending to 1 (exponentially for gamma <= 1: round-off at H = 100; as C H^-1.5 for
    gamma > 1); phi_x stays positive down to each fit's least H (0.03 for gamma = 1/9 at
    H = 1) and is held there below it. Fails with the branches of gamma swapped."""
    C, r, least = PRESSURE_FIT[gamma]
    H = np.array([least, 1.0, 2.0, 4.0, 8.0])
    f = FlowFactors(pattern=gamma)
    np.testing.assert_array_equal(f.factors(H)[1], pressure_flow_factor(H, 1.0 / gamma))
    phi = pressure_flow_factor(H, gamma)
    assert np.all(phi > 0.0)
    if gamma < 1:
        assert np.all(phi < 1) and pressure_flow_factor(100.0, gamma) == 1.0
    elif gamma > 1:
        assert np.all(phi > 1)
        np.testing.assert_allclose(pressure_flow_factor(1e3, gamma) - 1.0, C * 1e3 ** -1.5,
                                   rtol=1e-9)
    assert pressure_flow_factor(0.5 * least, gamma) == pressure_flow_factor(least, gamma)


@pytest.mark.parametrize("gamma", PATTERNS)
def test_slopes_against_differences(gamma):
    """d phi_x/dH, d Phi_s/dH and the flow fields' slopes in the nominal gap against
    central differences (1e-7), across the fits' limits and the switch at H = 5 (0 below
    a limit, where a factor is held). Fails with the shear slope's -0.25 beyond H = 5
    typed -0.5."""
    H = np.array([0.3, 0.7, 1.2, 2.0, 4.0, 4.9, 5.1, 8.0])
    d = 1e-6
    for f, slope in ((pressure_flow_factor, pressure_flow_slope),
                     (shear_flow_factor, shear_flow_slope)):
        fd = (f(H + d, gamma) - f(H - d, gamma)) / (2 * d)
        np.testing.assert_allclose(slope(H, gamma), fd, rtol=1e-7, atol=1e-9)
    flow = FlowFactors(pattern=gamma, journal_share=0.9)
    Hc, sig = np.array([0.001, 0.02, 0.06, 0.1, 0.3]), 0.05      # h/c, sigma/c
    ff = flow_fields(flow, Hc, sig, 10.0)
    up, dn = flow_fields(flow, Hc + d * sig, sig, 10.0), flow_fields(flow, Hc - d * sig, sig,
                                                                       10.0)
    for a in range(2):
        np.testing.assert_allclose(ff.conductance_slope[a],
                                   (up.conductance[a] - dn.conductance[a]) / (2 * d * sig),
                                   rtol=1e-6, atol=1e-12)
    for name, deriv in (("mean_gap", "gap_slope"), ("gap_slope", "gap_curvature"),
                        ("shear", "shear_slope")):
        np.testing.assert_allclose(getattr(ff, deriv),
                                   (getattr(up, name) - getattr(dn, name)) / (2 * d * sig),
                                   rtol=1e-6, atol=1e-9)


def test_mean_gap_against_quadrature():
    """E(h_T)/sigma = E[max(H + X, 0)], X standard normal, by adaptive quadrature, and its
    slope dE/dh = P(X > -H) against central differences, for H in [-3, 6]. Fails with the
    density term's 1/sqrt(2 pi) dropped."""
    for H in (-3.0, -1.0, 0.0, 0.5, 1.0, 2.0, 3.0, 6.0):
        ref, _ = quad(lambda x: (H + x) * math.exp(-0.5 * x * x) / math.sqrt(2 * math.pi),
                      -H, np.inf, epsabs=1e-14, epsrel=1e-13)
        E, slope = mean_gap(H)
        assert float(E) == pytest.approx(ref, rel=1e-12, abs=1e-15)
        d = 1e-5
        fd = (mean_gap(H + d)[0] - mean_gap(H - d)[0]) / (2 * d)
        assert float(slope) == pytest.approx(float(fd), rel=1e-8)
    assert mean_gap(40.0)[0] == 40.0                # the smooth gap to round-off


def test_bad_input_is_refused():
    """A gamma off Patir & Cheng's table, a variance share outside [0, 1] and a flow that
    is not a FlowFactors raise ValueError naming the parameter."""
    with pytest.raises(ValueError, match="pattern"):
        FlowFactors(pattern=2.0)
    with pytest.raises(ValueError, match="journal_share"):
        FlowFactors(journal_share=1.5)
    with pytest.raises(ValueError, match="flow"):
        Roughness(sigma=1e-6, contact_modulus=1e11, elastic_factor=1e-3, flow="patir-cheng")
    assert FlowFactors(pattern=1 / 3 + 1e-12).pattern == 1 / 3


# -- the film ---------------------------------------------------------------------------
@pytest.mark.parametrize("cavitation", ["none", "reynolds"])
def test_smooth_limit_is_todays_film(cavitation):
    """h/sigma -> infinity: sigma = 1e-12 m (H >= 2e6) gives today's film on the same mesh
    (the general film without roughness) to round-off for gamma = 1 (pressure 1e-13, the
    factors' exponential tail is below it); for gamma = 9 the fits' algebraic tail
    C H^-1.5 remains, and falls as sigma^1.5 (x 31.6 for sigma / 10). Fails with the
    squeeze's factor dE(h_T)/dh taken as 0 (eps_dot != 0 here)."""
    s = JournalState(0.8, omega=300.0, eps_dot=2.0)
    ref = solve_reynolds(B, s, 48, 8, cavitation=cavitation, fields=FilmFields())
    iso = solve_reynolds(B, s, 48, 8, cavitation=cavitation, roughness=rough(1e-12))
    scale = np.max(np.abs(ref.pressure))
    assert np.max(np.abs(iso.pressure - ref.pressure)) <= 1e-12 * scale
    np.testing.assert_allclose(iso.force_local, ref.force_local, rtol=0,
                               atol=1e-12 * np.hypot(*ref.force_local))
    diffs = [np.max(np.abs(solve_reynolds(B, s, 48, 8, cavitation=cavitation,
                                          roughness=rough(sig, pattern=9.0)).pressure
                           - ref.pressure)) / scale for sig in (1e-9, 1e-10)]
    assert 1e-8 < diffs[0] < 1e-5
    assert diffs[0] / diffs[1] == pytest.approx(10 ** 1.5, rel=0.02)


def test_without_flow_the_film_is_todays():
    """A roughness without flow factors keeps the film's route (the rigid film, its
    pressure bit for bit); with them the film is the general film. Fails when the flow
    is taken as given whatever the roughness."""
    s = JournalState(0.8, omega=300.0)
    plain = Roughness(sigma=0.3e-6, contact_modulus=53.3e9, elastic_factor=1e-3)
    p = film_problem(B, s, 48, 8, "reynolds", roughness=plain)
    assert route_for(p).name == "rigid"
    assert route_for(film_problem(B, s, 48, 8, "reynolds",
                                  roughness=rough(0.3e-6))).name == "general"
    a = solve_reynolds(B, s, 48, 8, roughness=plain)
    b = solve_reynolds(B, s, 48, 8)
    np.testing.assert_array_equal(a.pressure, b.pressure)


def _solve_with(state, conductance, mean=None, shear=0.0, length=None, nz=8):
    bearing = B if length is None else B.__class__(
        radius=B.radius, length=length, clearance=B.clearance, viscosity=B.viscosity)
    op = fe_operator(bearing, state, 48, nz, "P1", None, False)
    film, gap = general_film(bearing, state, op)
    H = film.gap
    flow = FlowFields(conductance=tuple(c * H ** 3 for c in conductance),
                      mean_gap=H if mean is None else mean(H, op),
                      gap_slope=np.ones_like(H), shear=shear if np.ndim(shear) else
                      np.full_like(H, shear), shear_speed=state.omega)
    return solve_film(bearing, state, op, "P1", "none", film=film, gap=gap, flow=flow)


def test_anisotropic_conductance_is_a_stretched_film():
    """A conductance (a H^3, b H^3) on a bearing of length L is the isotropic film
    (H^3, H^3) on the length L sqrt(a/b), its pressure divided by a, node for node
    (the axial coordinate stretched by sqrt(a/b)): exact for the discrete film. And
    (1, 1) is today's general film to round-off. Fails with the two axes' metrics
    swapped."""
    s = JournalState(0.6, omega=200.0, eps_dot=0.5)
    a, b = 0.7, 1.6
    aniso = _solve_with(s, (a, b))
    iso = _solve_with(s, (1.0, 1.0), length=B.length * math.sqrt(a / b))
    np.testing.assert_allclose(aniso.pressure, iso.pressure / a, rtol=0,
                               atol=1e-11 * np.max(np.abs(aniso.pressure)))
    one = _solve_with(s, (1.0, 1.0))
    ref = solve_reynolds(B, s, 48, 8, cavitation="none", fields=FilmFields())
    np.testing.assert_allclose(one.pressure, ref.pressure, rtol=0,
                               atol=1e-12 * np.max(np.abs(ref.pressure)))


def test_shear_flow_is_a_mean_gap_at_the_sliding_speed():
    """The shear flow's content sigma phi_s / c is driven by omega (the surfaces' relative
    speed) where the mean gap is driven by the wedge speed w = omega - 2 gamma_dot: a
    shear content S gives the film of the mean gap H + (omega / w) S, to round-off, on a
    whirling journal. Fails with the shear driven by w."""
    s = JournalState(0.6, omega=200.0, gamma_dot=30.0)
    w = s.wedge_speed

    def S(H, op):
        return 0.02 * np.sin(op.qp_theta) ** 2 * H

    def shear_field():
        op = fe_operator(B, s, 48, 8, "P1", None, False)
        film, _ = general_film(B, s, op)
        return S(film.gap, op)
    sheared = _solve_with(s, (1.0, 1.0), shear=shear_field())
    shifted = _solve_with(s, (1.0, 1.0), mean=lambda H, op: H + (s.omega / w) * S(H, op))
    np.testing.assert_allclose(sheared.pressure, shifted.pressure, rtol=0,
                               atol=1e-12 * np.max(np.abs(shifted.pressure)))


def test_rough_flow_changes_the_thin_film_as_the_factors_say():
    """At h_min / sigma = 2 (eps 0.8, sigma 2 um) the factors take flow out of the
    Poiseuille terms: the load rises (measured +11.3 % isotropic), most for ridges across
    the sliding (gamma = 1/9: +13.8 %), least for ridges along it (gamma = 9: +3.6 %; the
    axial factor is then phi_x(H, 1/9) < 1, less side leakage), Patir & Cheng's (1979)
    order. The general film's total force is film + summits; the flow fields on the
    film's gap are the module's factors. Fails with the conductance's factors dropped
    (all three then equal)."""
    s = JournalState(0.8, omega=300.0)
    ref = np.hypot(*solve_reynolds(B, s, 48, 8, fields=FilmFields()).force_local)
    sols = {g: solve_reynolds(B, s, 48, 8, roughness=rough(2e-6, pattern=g))
            for g in (1 / 9, 1.0, 9.0)}
    change = {g: np.hypot(*sol.force_local) / ref - 1.0 for g, sol in sols.items()}
    assert change[1 / 9] > change[1.0] + 0.01 > change[9.0] + 0.02 > 0.02
    assert 0.05 < change[1.0] < 0.2
    sol = sols[1.0]
    p = film_problem(B, s, 48, 8, "reynolds", roughness=rough(2e-6))
    total, _ = route_for(p).total_force(p)
    np.testing.assert_allclose(total, np.add(sol.force_local, sol.asperity_force_local),
                               rtol=1e-12)
    H = np.array([0.05, 0.1, 0.2])           # h / c
    ff = flow_fields(FlowFactors(), H, 0.1, 300.0)
    np.testing.assert_allclose(ff.conductance[0], pressure_flow_factor(H / 0.1) * H ** 3)


def test_routes_that_cannot_take_the_flow_refuse_it_by_name():
    """The JFO films (rigid and with a bush) and the transient EHD film (a kept film
    between steps) refuse roughness.flow with a ValueError naming it, before any work."""
    from bearingfem.ehd.transient import TransientEHD
    s = JournalState(0.6, omega=100.0)
    r = rough(0.3e-6)
    bush = SOLID
    with pytest.raises(ValueError, match="roughness.flow"):
        route_for(film_problem(B, s, 48, 8, "jfo", ambient_pressure=1e5, roughness=r))
    with pytest.raises(ValueError, match="roughness.flow"):
        route_for(film_problem(B, s, 48, 8, "jfo", ambient_pressure=1e5, bush=bush,
                               roughness=r))
    with pytest.raises(ValueError, match="roughness.flow"):
        TransientEHD(B, None, bush, roughness=r)


# -- the steady EHD film -----------------------------------------------------------------
def test_steady_ehd_film_smooth_limit():
    """The steady EHD film (bush, Barus oil) with flow factors at sigma = 1e-12 m is the
    film without roughness to Newton's tolerance (pressure 1e-10 of its peak). Fails with
    the EHD film's sigma taken in micrometres."""
    oil = Lubricant(viscosity=0.0117, barus=2e-8)
    s = JournalState(eps=0.9, omega=62.5)
    a = solve_reynolds(PIN, s, 24, 4, lubricant=oil, bush=SOLID)
    b = solve_reynolds(PIN, s, 24, 4, lubricant=oil, bush=SOLID, roughness=rough(1e-12))
    np.testing.assert_allclose(b.pressure, a.pressure, rtol=0,
                               atol=1e-10 * np.max(a.pressure))
    np.testing.assert_allclose(b.force_local, a.force_local, rtol=1e-9)


@pytest.mark.parametrize("with_bush", [False, True], ids=["oil", "oil+bush"])
def test_steady_ehd_jacobian_with_flow_factors(with_bush):
    """The steady EHD film's Newton Jacobian (sparse + the bush's U V^T, the summits'
    stiffness in it) with a rough gap's flow (sigma 1 um: H from 0.4 to 5 on the film),
    against central differences of its residual, to 1e-6 of the largest entry. Fails with
    the conductance's H-slope left out (the bush's term) or its viscosity slope taken
    on H^3 (the oil's)."""
    from bearingfem.ehd.coupling import ehd_film
    from bearingfem.ehd.film_compliance import dof_compliance  # noqa: F401 (the bush's)
    oil = Lubricant(viscosity=0.0117, barus=2e-8)
    s = JournalState(eps=0.95, eps_dot=5.0, omega=625.0)      # peak 15 MPa: alpha p 0.3
    op = fe_operator(PIN, s, 16, 2, "P1", None, False)
    base, gap = general_film(PIN, s, op)
    r = Roughness(sigma=1e-6, contact_modulus=80.8e9, elastic_factor=1e-3,
                  flow=FlowFactors(pattern=1 / 3, journal_share=0.8))
    film = ehd_film(PIN, s, op, base, gap, oil, SOLID if with_bush else None, r)
    P = np.maximum(np.asarray(solve_reynolds(PIN, s, 16, 2, half=False).pressure)
                   / PIN.pressure_scale, 0.0)
    J, U, V = film.jacobian(P)
    full = J.toarray() if U is None else (
        J.toarray() + (U if V is None else U @ V.T))
    fd = differenced_jacobian(lambda x: film.evaluate(x).residual, P)
    assert np.max(np.abs(full - fd)) < 1e-6 * np.max(np.abs(fd))


# -- the modal-state EHD film (where the 0.05 sigma floor was) ---------------------------
def test_modal_state_film_smooth_limit():
    """The modal-state EHD film with flow factors at sigma = 1e-12 m is the film without
    roughness: force and dq/dt to round-off (1e-16 measured; gamma = 1, whose factors
    reach 1 exponentially). Fails with the rough film's squeeze weight dE/dh doubled in
    the bush's rate load."""
    s = JournalState(eps=0.9, eps_dot=5.0, gamma=1.0, gamma_dot=1.0, omega=62.5)
    q = 1e-7 * np.linspace(1.0, -0.5, 8)
    F0, r0 = ModalStateEHD(PIN, None, SOLID, 24, 4, 8, relaxation=1e-5).rates(s, q)
    F1, r1 = ModalStateEHD(PIN, None, SOLID, 24, 4, 8, relaxation=1e-5,
                           roughness=rough(1e-12)).rates(s, q)
    np.testing.assert_allclose(F1, F0, rtol=1e-12)
    np.testing.assert_allclose(r1, r0, rtol=0, atol=1e-12 * np.max(np.abs(r0)))


@pytest.mark.parametrize("oil", [False, True], ids=["isoviscous", "barus"])
@pytest.mark.parametrize("sigma", [0.5e-6, 1.5e-6])
def test_modal_state_tangent_with_flow_factors(oil, sigma):
    """The modal-state film's tangent (force and dq/dt in the modal coordinates, the
    implicit-function derivative through the rough gap's coefficients: conductance, mean
    gap and squeeze weight differentiated in H) against central differences of whole
    solves, at a least film of 2.1 and 0.69 sigma (below the fits' limits: the factors
    held), gamma = 1/3, journal_share 0.8 (shear flow), whirling journal; measured 1e-11
    and 1e-9, asserted 1e-7. Fails with the squeeze term's d(dE/dh)/dh left out, or the
    tangent taken on the affine film's rate at dq/dt = 0."""
    lub = Lubricant(viscosity=0.0117, barus=2e-8) if oil else None
    r = rough(sigma, pattern=1 / 3, journal_share=0.8)

    def film():
        return ModalStateEHD(PIN, lub, SOLID, 16, 2, 4, relaxation=1e-5, roughness=r)
    s = JournalState(eps=0.95, eps_dot=10.0, gamma=0.3, gamma_dot=20.0, omega=62.5)
    f = film()
    n = f.state_size
    q = 3e-7 * np.linspace(1.0, -0.5, n)
    f.rates(s, q)
    T = f.tangent()
    h = 1e-11
    dF, dr = np.zeros((2, n)), np.zeros((n, n))
    for j in range(n):
        d = np.zeros(n)
        d[j] = h
        (Fp, rp), (Fm, rm) = film().rates(s, q + d), film().rates(s, q - d)
        dF[:, j] = (np.array(Fp) - np.array(Fm)) / (2 * h)
        dr[:, j] = (rp - rm) / (2 * h)
    assert np.max(np.abs(T.force_local - dF)) < 1e-7 * np.max(np.abs(dF))
    assert np.max(np.abs(T.rates - dr)) < 1e-7 * np.max(np.abs(dr))


def test_modal_state_film_past_the_circle_without_a_floor():
    """Past the clearance circle (eps 1.1, q = 0) the nominal gap is negative on an arc:
    the rough film takes it (its mean gap stays > 0, no floor), the summits carry the
    contact and the film's force and friction are finite. Fails with the gap's positivity
    check kept for a rough flow (the film then does not solve)."""
    s = ElasticJournalState(eps=1.1, omega=62.5)
    film = ModalStateEHD(PIN, None, SOLID, 24, 4, 8, roughness=rough(0.5e-6))
    sol = film.solution(s, np.zeros(8))
    assert np.min(sol.film_thickness) < 0.0
    assert np.all(np.isfinite(sol.force_local)) and np.isfinite(sol.friction_torque)
    assert abs(sol.asperity_force_local[0]) > abs(sol.force_local[0])


# -- the flow simulation of rough cells ---------------------------------------------------
def test_cell_solve_is_exact_across_and_along_ridges():
    """The cell solve (periodic, unit mean gradient) against the exact flow of sinusoidal
    ridges h (1 + a cos), a = 0.5: along the flow <h_T^3>/h^3 = 1.375 to round-off; across
    it 2 (1 - a^2)^(5/2) / (2 + a^2) = 0.4330, converging at second order (errors 3.3e-2,
    7.9e-3, 2.0e-3 at 8, 16, 32 cells a ridge: ratios 4.1, 4.0). Fails with the imposed
    gradient's term left out of the flow."""
    a = 0.5
    along = cell_flow_factor(lambda x, y: 1.0 + a * np.cos(2 * np.pi * y), 1.0,
                             (1.0, 1.0), (4, 16))
    assert along == pytest.approx(longitudinal_exact(a), rel=1e-11)
    errors = [cell_flow_factor(lambda x, y: 1.0 + a * np.cos(2 * np.pi * x), 1.0,
                               (2.0, 1.0), (2 * m, 4)) - transverse_exact(a)
              for m in (8, 16, 32)]
    assert errors[2] < 2.5e-3
    assert 3.6 < errors[0] / errors[1] < 4.4 and 3.6 < errors[1] / errors[2] < 4.4


def test_cell_shear_flow_is_exact_across_and_along_ridges():
    """The cell's shear flow (the rough surface sliding over a smooth one) against the
    exact flow of ridges h (1 + a cos), a = 0.5: across the flow
    sigma Phi_s = h - <h_T^-2>/<h_T^-3> = 0.9428 sigma, converging at second order
    (errors 4.3e-2, 1.0e-2, 2.5e-3 at 8, 16, 32 cells a ridge); along it 0. Fails with
    the roughness' squeeze taken with the wrong sign."""
    a = 0.5
    sigma = a / math.sqrt(2.0)
    along = cell_factors(lambda x, y: 1.0 + a * np.cos(2 * np.pi * y), 1.0, (1.0, 1.0),
                         (4, 16), sigma)[1]
    assert abs(along) < 1e-12
    errors = [transverse_shear_exact(1.0, a)
              - cell_factors(lambda x, y: 1.0 + a * np.cos(2 * np.pi * x), 1.0, (2.0, 1.0),
                             (2 * m, 4), sigma)[1] for m in (8, 16, 32)]
    assert 0.0 < errors[2] < 3e-3
    assert 3.6 < errors[0] / errors[1] < 4.4 and 3.6 < errors[1] / errors[2] < 4.4


@pytest.mark.parametrize("H, tol", [pytest.param(3.0, 0.05, marks=pytest.mark.slow),
                                    (4.0, 0.02),
                                    pytest.param(6.0, 0.02, marks=pytest.mark.slow)])
def test_isotropic_rough_cells_against_the_fit(H, tol):
    """Four isotropic Gaussian surfaces (16 x 16 correlation lengths, 8 cells each), the
    flow of the periodic cell against Patir & Cheng's isotropic fit 1 - 0.9 exp(-0.56 H)
    where the fit holds to a few %: the tolerances from the study's eight surfaces of
    32 x 32 lengths (docs/mixed-lubrication.md: fit - measured -3.1 +- 0.8 %, -0.9 +- 0.4 %,
    +1.0 +- 0.2 % at H = 3, 4, 6; here -1.8, -0.3, +1.3 %). Below H = 3 the fit falls
    below the cells (-7 % at H = 2, -20 % at H = 1): not asserted. The shear flow factor
    of the same cells: the fit 1.899 H^0.98 exp(-0.92 H + 0.05 H^2) is 8.0 %, 7.0 % above
    them at H = 3, 4 and 2.6 % below at H = 6 (the table's eight surfaces: +6.9, +7.0,
    -1.4 %), asserted within 10 %. Fails with the fit's C = 0.9 typed 1.2, or A1 typed
    2.1."""
    phi, shear = measured_factors([H], range(4), length=16.0, per_correlation=8)
    assert phi.mean() == pytest.approx(float(pressure_flow_factor(H, 1.0)), rel=tol)
    assert shear.mean() == pytest.approx(float(shear_flow_factor(H, 1.0)), rel=0.1)


@pytest.mark.slow
@pytest.mark.parametrize("gamma", [1 / 3, 3.0])
def test_anisotropic_rough_cells_against_the_fits(gamma):
    """Four Gaussian surfaces stretched along the flow by Peklenik's gamma (16 x 16
    correlation lengths across it, 8 cells each), the periodic cell's flow at H = 3
    against Patir & Cheng's phi_x(H, gamma) within 3 % (measured -0.2 % and +0.4 %) and
    Phi_s(H, gamma) within 5 % (-1.2 %, -3.0 %); the table of docs/mixed-lubrication.md
    gives the other gamma and H. Fails with the cell stretched across the flow instead
    (gamma and 1/gamma swapped)."""
    phi, shear = measured_factors([3.0], range(4), length=16.0, per_correlation=8,
                                  pattern=gamma)
    assert phi.mean() == pytest.approx(float(pressure_flow_factor(3.0, gamma)), rel=0.03)
    assert shear.mean() == pytest.approx(float(shear_flow_factor(3.0, gamma)), rel=0.05)
