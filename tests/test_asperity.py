"""Greenwood-Tripp asperity contact (bearingfem.contact) against independent references:
scipy.integrate.quad and mpmath for F_5/2, its asymptotic tail, an adaptive quadrature of
the asperity force of a rigid journal, and the film's own force integral for the sign."""
import math

import mpmath
import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import gamma as gamma_fn

from bearingfem import JournalState, Roughness, solve_reynolds
from bearingfem.bearing import seed_bearing
from bearingfem.contact import asperity_contact, tail_moment, tail_moment_derivative
from bearingfem.contact.asperity import surface_force_local
from bearingfem.fe.assembly import fe_operator

ROUGH = Roughness(sigma=0.31e-6, contact_modulus=53.3e9, elastic_factor=1e-3, friction=0.02)


def f_quad(order, l):
    """F_n(l) = (2 pi)^-1/2 int_0^T t^n exp(-(t + l)^2 / 2) dt, with the t^n endpoint
    singularity integrated exactly by QUADPACK's algebraic weight; the cut T leaves out less
    than exp(-72) of the integrand's scale."""
    T = 12.0 + max(-l, 0.0)
    v, _ = quad(lambda t: math.exp(-0.5 * (t + l) ** 2), 0.0, T, weight="alg",
                wvar=(order, 0.0), epsabs=0.0, epsrel=1e-13, limit=200)
    return v / math.sqrt(2.0 * math.pi)


@pytest.mark.parametrize("order", [2.5, 1.5])
def test_tail_moment_matches_quad(order):
    """F_5/2 and F_3/2 to 1e-10 relative over l in [-3, 8] (measured: worst 2.3e-13, at the
    switch l = 2). Fails with the Kummer branch's second term sign flipped, or with 20
    instead of 60 Laguerre points (6e-9 at l = 2)."""
    ls = np.concatenate([np.linspace(-3.0, 8.0, 45), [1.999, 2.0, 2.001]])
    ref = np.array([f_quad(order, l) for l in ls])
    assert tail_moment(ls, order) == pytest.approx(ref, rel=1e-10, abs=0)


@pytest.mark.parametrize("order", [2.5, 1.5])
def test_tail_moment_matches_mpmath_far_out(order):
    """Far in both tails (pressed through by 1e4 sigma, apart by 37 sigma) against the
    parabolic-cylinder closed form F_n = Gamma(n+1) (2 pi)^-1/2 exp(-l^2/4) D_(-n-1)(l) at
    30 digits. Fails with a wrong moment in the l < -10 expansion ((2k)!! for (2k-1)!!)."""
    mpmath.mp.dps = 30
    ls = np.array([-1e4, -300.0, -40.0, -10.5, -10.0, -9.5, 9.0, 15.0, 25.0, 37.0])
    ref = [float(mpmath.gamma(order + 1) / mpmath.sqrt(2 * mpmath.pi)
                 * mpmath.exp(-mpmath.mpf(l) ** 2 / 4) * mpmath.pcfd(-order - 1, l))
           for l in ls]
    assert tail_moment(ls, order) == pytest.approx(ref, rel=1e-12, abs=0)


def test_derivative_is_minus_five_halves_f32():
    """dF_5/2/dl = -(5/2) F_3/2 against central differences across all three branches, and
    the pressure's derivative in h. Step 1e-5: truncation ~ d^2 l^2 / 6 relative, 1e-9 at
    l = 8 (step 1e-4 gave 1.1e-7 there); rounding ~ 1e-16 F / (d F') < 1e-10.
    Fails with the factor 5/2 dropped or F_1/2 taken for F_3/2."""
    ls = np.array([-30.0, -10.2, -3.0, -0.7, 0.0, 0.9, 1.95, 2.05, 4.0, 8.0])
    d = 1e-5
    fd = (tail_moment(ls + d) - tail_moment(ls - d)) / (2 * d)
    assert tail_moment_derivative(ls) == pytest.approx(fd, rel=1e-7)
    h = ROUGH.sigma * ls[2:]
    dh = ROUGH.sigma * d
    fd_p = (ROUGH.pressure(h + dh) - ROUGH.pressure(h - dh)) / (2 * dh)
    assert ROUGH.pressure_derivative(h) == pytest.approx(fd_p, rel=1e-7)


@pytest.mark.parametrize("order", [2.5, 1.5])
def test_tail_decays_faster_than_any_power(order):
    """F_n(l) -> Gamma(n+1) phi(l) l^(-n-1) (1 - (n+1)(n+2)/(2 l^2) + O(l^-4)), phi the
    normal density: a Gaussian times a power, so l^m F_n(l) -> 0 for every m. The O(l^-4)
    term is (n+1)..(n+4)/(8 l^4); the check allows twice it. Fails with l^-n for l^(-n-1)."""
    ls = np.array([10.0, 15.0, 20.0, 30.0])
    lead = gamma_fn(order + 1) * np.exp(-ls ** 2 / 2) / np.sqrt(2 * np.pi) * ls ** (-order - 1)
    ratio = tail_moment(ls, order) / lead
    second = 1 - (order + 1) * (order + 2) / (2 * ls ** 2)
    third = (order + 1) * (order + 2) * (order + 3) * (order + 4) / (8 * ls ** 4)
    assert np.all(np.abs(ratio - second) < 2 * third)
    assert np.all(np.diff(ls ** 20 * tail_moment(ls, order)) < 0)   # even l^20 F falls
    assert tail_moment(np.array([39.0, 1e6, np.inf]), order) == pytest.approx(0.0, abs=0)


def test_load_share_tends_to_film_only():
    """As the minimum film grows from 1 to 8 sigma, the asperities' share of the total load
    on a film solution at eps = 0.9 falls monotonically to nothing (< 1e-9)."""
    b, s = seed_bearing(0.5), JournalState(0.9, 0.0, 0.0, 0.0, 250.0)
    sol = solve_reynolds(b, s, 60, 8, cavitation="reynolds")
    op = fe_operator(b, s, 60, 8, "P1", None, True)
    th, area = op.qp_theta, 2 * b.radius ** 2 * op.qp_weight
    gap = b.clearance * (1 + s.eps * np.cos(th))
    film_min = b.clearance * (1 - s.eps)
    shares = []
    for ratio in (1.0, 2.0, 3.0, 4.0, 6.0, 8.0):
        rough = Roughness(sigma=film_min / ratio, contact_modulus=53.3e9, elastic_factor=1e-3)
        fa = np.array(asperity_contact(rough, gap, area, th, radius=b.radius).force_local)
        total = fa + np.array(sol.force_local)
        shares.append(np.hypot(*fa) / np.hypot(*total))
    assert np.all(np.diff(shares) < 0) and shares[0] > 0.1 and shares[-1] < 1e-9


def test_force_of_rigid_journal_matches_adaptive_quadrature():
    """Asperity force of a rigid journal at eps = 0.99, gamma = 0.7 on the FE film mesh's
    quadrature points against an adaptive quad of K E* F_5/2(h(theta)/sigma) (cos, sin)
    theta R L (h does not vary along z, so the z integral is L). Convergence with n_theta
    (P1, n_z = 10): rel. error 1.7e-6 at 60, 2.5e-13 at 120, 3e-16 at 240 (spectral, the
    integrand is smooth and periodic); hence 1e-10 at 120. Fails with cos/sin swapped or
    the force's sign flipped in surface_force_local."""
    b, s = seed_bearing(0.5), JournalState(0.99, 0.0, 0.7, 0.0, 250.0)
    R, L, c = b.radius, b.length, b.clearance
    KE = ROUGH.factor * ROUGH.contact_modulus

    def comp(trig, epsabs=0.0):
        f = lambda th: KE * f_quad(2.5, c * (1 + s.eps * math.cos(th)) / ROUGH.sigma) * trig(th)
        v, _ = quad(f, 0.0, 2 * math.pi, points=[math.pi], epsabs=epsabs, epsrel=1e-12,
                    limit=200)
        return v * R * L

    ref_r = comp(math.cos)
    ref_t = comp(math.sin, epsabs=1e-12 * abs(ref_r) / (R * L))   # it is 0: absolute
    op = fe_operator(b, s, 120, 10, "P1", None, True)
    th, area = op.qp_theta, 2 * R ** 2 * op.qp_weight
    a = asperity_contact(ROUGH, c * (1 + s.eps * np.cos(th)), area, th, radius=R,
                         gamma=s.gamma, omega=s.omega)
    assert a.force_local[0] == pytest.approx(ref_r, rel=1e-10)
    assert abs(a.force_local[1]) < 1e-10 * abs(ref_r) and abs(ref_t) < 1e-10 * abs(ref_r)
    # pushes the journal back to the centre: against r_hat = (cos gamma, sin gamma)
    assert ref_r < 0
    assert a.force == pytest.approx((ref_r * math.cos(s.gamma), ref_r * math.sin(s.gamma)),
                                    rel=1e-10)


def test_force_integral_is_the_films():
    """surface_force_local on a pressure at the quadrature points equals the FE film's own
    force integral (bearing.force_scale x force_integrals) of the same nodal field, so film
    and asperity forces add. Fails with the sign of either component flipped or cos/sin
    swapped."""
    b, s = seed_bearing(1.0), JournalState(0.8, 0.0, 0.3, 0.0, 250.0)
    op = fe_operator(b, s, 48, 8, "P1", None, True)
    rng = np.random.default_rng(3)      # any nodal field: a peak near theta = 2 plus noise
    P = 1e3 * np.exp(-(op.mesh.theta - 2.0) ** 2) + rng.normal(size=op.mesh.ndofs)
    film = b.force_scale * 2 * np.asarray(op.force_integrals(P))
    p_q = b.pressure_scale * op.at_quadrature(P)
    mine = surface_force_local(p_q, 2 * b.radius ** 2 * op.qp_weight, op.qp_theta)
    assert mine == pytest.approx(tuple(film), rel=1e-12)


def test_friction_is_coefficient_times_load_for_uniform_gap():
    """Uniform gap h0 = 1.3 sigma over the whole journal (area 2 pi R L): load =
    K E* F_5/2(1.3) 2 pi R L with F_5/2 from quad, no net force, friction = mu x load with the
    sign of omega, torque = friction R. Fails with the friction coefficient or R dropped."""
    R, L, n = 0.01, 0.01, 4000
    th = (np.arange(n) + 0.5) * 2 * np.pi / n
    area = np.full(n, 2 * np.pi * R * L / n)
    h = np.full(n, 1.3 * ROUGH.sigma)
    load = ROUGH.factor * ROUGH.contact_modulus * f_quad(2.5, 1.3) * 2 * np.pi * R * L
    for omega, sign in ((250.0, 1.0), (-40.0, -1.0), (0.0, 0.0)):
        a = asperity_contact(ROUGH, h, area, th, radius=R, omega=omega)
        assert a.load == pytest.approx(load, rel=1e-10)
        assert np.hypot(*a.force) < 1e-12 * load
        assert a.friction_force == pytest.approx(sign * 0.02 * load, rel=1e-10, abs=0)
        assert a.friction_torque == pytest.approx(sign * 0.02 * load * R, rel=1e-10, abs=0)


def test_elastic_factor_from_summits():
    """K from (eta, beta) written as (16 sqrt 2 pi / 15) sigma^5/2 eta^2 beta^3/2 (the same
    formula, regrouped) for sigma eta beta = 0.05, sigma/beta = 1e-3 (Hu et al. 1994's
    range): K = 3.7467e-4. Fails with sqrt(beta/sigma) for sqrt(sigma/beta)."""
    sigma, beta = 0.31e-6, 0.31e-3
    eta = 0.05 / (sigma * beta)
    K = 16 * math.sqrt(2) * math.pi / 15 * sigma ** 2.5 * eta ** 2 * beta ** 1.5
    assert K == pytest.approx(3.7467e-4, rel=1e-4)
    by_summits = Roughness(sigma=sigma, contact_modulus=80e9, asperity_density=eta,
                           asperity_radius=beta)
    by_factor = Roughness(sigma=sigma, contact_modulus=80e9, elastic_factor=K)
    assert by_summits.factor == pytest.approx(K, rel=1e-13)
    h = np.array([-0.5, 0.3, 2.0]) * sigma
    assert by_summits.pressure(h) == pytest.approx(by_factor.pressure(h), rel=1e-13)


@pytest.mark.parametrize("kwargs, name", [
    (dict(sigma=0.0, contact_modulus=1e9, elastic_factor=1e-3), "sigma"),
    (dict(sigma=1e-6, contact_modulus=-1.0, elastic_factor=1e-3), "contact_modulus"),
    (dict(sigma=1e-6, contact_modulus=1e9, elastic_factor=float("nan")), "elastic_factor"),
    (dict(sigma=1e-6, contact_modulus=1e9), "elastic_factor"),
    (dict(sigma=1e-6, contact_modulus=1e9, asperity_density=1e9), "asperity_radius"),
    (dict(sigma=1e-6, contact_modulus=1e9, elastic_factor=1e-3, asperity_density=1e9,
          asperity_radius=1e-4), "not both"),
    (dict(sigma=1e-6, contact_modulus=1e9, asperity_density=0.0, asperity_radius=1e-4),
     "asperity_density"),
    (dict(sigma=1e-6, contact_modulus=1e9, elastic_factor=1e-3, friction=-0.1), "friction"),
])
def test_bad_roughness_raises(kwargs, name):
    with pytest.raises(ValueError, match=name):
        Roughness(**kwargs)


def test_bad_fields_raise():
    th = np.zeros(3)
    with pytest.raises(ValueError, match="one shape"):
        asperity_contact(ROUGH, np.ones(3), np.ones(2), th, radius=0.01)
    with pytest.raises(ValueError, match="finite"):
        asperity_contact(ROUGH, np.array([1e-6, np.nan, 1e-6]), np.ones(3), th, radius=0.01)
    with pytest.raises(ValueError, match="radius"):
        asperity_contact(ROUGH, np.ones(3), np.ones(3), th, radius=0.0)
    with pytest.raises(ValueError, match="order"):
        tail_moment(1.0, order=-1.0)
