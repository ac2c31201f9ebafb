"""Mixed lubrication: the Greenwood-Tripp asperity contact inside the film solve, the "fem"
model and the designer's equilibrium (bearingfem.fe.mixed), against independent
references: an adaptive quadrature of the asperity pressure over the rigid gap
(F_5/2 by QUADPACK, not bearingfem.contact), the smooth-surface film, the dry limit solved
by brentq by hand, and central differences."""
import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from bearingfem import JournalState, Roughness, solve_reynolds
from bearingfem.bearing import seed_bearing
from bearingfem.design.coefficients import coefficients
from bearingfem.design.equilibrium import equilibrium
from bearingfem.fe.assembly import fe_operator
from bearingfem.fe.mixed import contact_partial_eps, film_contact
from bearingfem.models import film_model

ROUGH = Roughness(sigma=0.31e-6, contact_modulus=53.3e9, elastic_factor=1e-3, friction=0.02)
#: sigma 1 nm: h/sigma >= 2000 on the seed bearing (c = 20 um) at eps <= 0.9, F_5/2 = 0
SMOOTH = Roughness(sigma=1e-9, contact_modulus=53.3e9, elastic_factor=1e-3, friction=0.02)
SOLVES = [dict(cavitation="none"), dict(cavitation="gumbel"), dict(cavitation="reynolds"),
          dict(cavitation="jfo", ambient_pressure=1e5)]


def f52(l):
    """F_5/2(l) by QUADPACK with the t^(5/2) endpoint weight, independent of
    bearingfem.contact.gaussian."""
    v, _ = quad(lambda t: math.exp(-0.5 * (t + l) ** 2), 0.0, 12.0 + max(-l, 0.0),
                weight="alg", wvar=(2.5, 0.0), epsabs=0.0, epsrel=1e-13, limit=200)
    return v / math.sqrt(2.0 * math.pi)


def reference_contact(b, eps, rough, parts=("cos", "sin", "load")):
    """(F_r, F_t, load) [N] of the rigid gap c (1 + eps cos theta): the GT pressure
    K E* F_5/2(h / sigma) integrated over the journal surface by adaptive quadrature in
    theta (split at the thinnest film, theta = pi) times R L (the rigid gap is uniform in
    z, so the z-integral is exact; epsabs 1e-6 Pa m is 1e-12 of the cos part here)."""
    R, L, c = b.radius, b.length, b.clearance

    def p(th):
        return rough.factor * rough.contact_modulus * f52(c * (1 + eps * math.cos(th))
                                                          / rough.sigma)
    g = dict(cos=math.cos, sin=math.sin, load=lambda th: 1.0)
    return [R * L * quad(lambda th: p(th) * g[k](th), 0.0, 2 * math.pi, points=[math.pi],
                         epsabs=1e-6, epsrel=1e-11, limit=200)[0] for k in parts]


@pytest.mark.parametrize("opts", SOLVES, ids=lambda o: o["cavitation"])
def test_large_gap_no_contact_and_film_unchanged(opts):
    """h/sigma >= 2000: the asperity force and torque are exactly 0 and the film (force,
    pressure, friction) is today's smooth film to the last bit, for every cavitation model.
    Fails when the roughness reroutes the film solve (the whole length meshed instead of
    the half) or the contact replaces the film's ``force``."""
    b = seed_bearing()
    s = JournalState(0.9, omega=100.0, gamma=0.4)
    rough = solve_reynolds(b, s, 48, 8, roughness=SMOOTH, **opts)
    smooth = solve_reynolds(b, s, 48, 8, **opts)
    assert rough.asperity_force == (0.0, 0.0) and rough.asperity_friction_torque == 0.0
    assert rough.force == smooth.force and rough.total_force == pytest.approx(smooth.force)
    assert np.array_equal(rough.pressure, smooth.pressure)
    assert rough.friction_torque == smooth.friction_torque


@pytest.mark.parametrize("element, cavitation", [("P1", "reynolds"), ("P2", "gumbel"),
                                                 ("P1", "jfo")])
def test_asperity_force_matches_quadrature(element, cavitation):
    """Asperity force, inertial force and Coulomb friction torque of the film solve against
    adaptive quadrature of the GT pressure over the rigid gap, eps = 0.99 (h_min = 0.65 sigma).
    Convergence study (measured, P1/P2): relative error 5e-3/2e-4 at n_theta = 24,
    2e-5/6e-7 at 48, 6e-10/2e-11 at 96 (spectral: a smooth periodic integrand), so 1e-8 at
    96. Fails with the half-mesh doubling dropped (factor 2), cos/sin swapped in the
    force, the clearance left out of the gap, or the friction's radius dropped."""
    b = seed_bearing()
    eps, gamma = 0.99, 0.3
    s = JournalState(eps, omega=100.0, gamma=gamma)
    extra = dict(ambient_pressure=1e5) if cavitation == "jfo" else {}
    sol = solve_reynolds(b, s, 96, 8, element, cavitation, roughness=ROUGH, **extra)
    f_r, f_t, load = reference_contact(b, eps, ROUGH)
    assert f_r < 0.0     # the summits push the journal back toward the centre
    assert sol.asperity_force_local[0] == pytest.approx(f_r, rel=1e-8)
    assert abs(sol.asperity_force_local[1]) < 1e-10 * abs(f_r)    # symmetric about theta = pi
    fx = f_r * math.cos(gamma) - f_t * math.sin(gamma)
    fy = f_r * math.sin(gamma) + f_t * math.cos(gamma)
    assert sol.asperity_force == pytest.approx((fx, fy), rel=1e-8, abs=1e-10 * abs(f_r))
    assert sol.asperity_friction_torque == pytest.approx(0.02 * load * b.radius, rel=1e-8)
    assert sol.total_force == pytest.approx(
        tuple(np.add(sol.force, sol.asperity_force)), rel=1e-14)


def test_equilibrium_film_and_asperities_carry_the_load():
    """At omega = 100 rad/s the film plus asperity force balances the load to 1e-9 W
    (measured 2e-11: brentq at rtol 1e-13 on eps), the share lies in (0, 1) at the heavy
    8 kN load and rises with the load (measured 1e-8, 0.019, 0.064 at 1, 4, 8 kN).
    Fails when the contact is left out of the model's force, added into the solution's
    film ``force`` (counted twice), or the share is taken from the film's force."""
    b = seed_bearing()
    shares = []
    for W in (1e3, 4e3, 8e3):
        eq = equilibrium(b, load=(0.0, -W), omega=100.0, model="fem", roughness=ROUGH,
                         eps_max=0.9999)
        total = eq.solution.total_force
        assert math.hypot(total[0], total[1] - W) < 1e-9 * W
        assert math.hypot(eq.film_force[0], eq.film_force[1] - W) < 1e-9 * W
        shares.append(eq.asperity_load_share)
    assert 0.0 < shares[-1] < 1.0
    assert shares[0] < shares[1] < shares[2]
    smooth = equilibrium(b, load=(0.0, -4e3), omega=100.0, model="fem")
    assert smooth.asperity_load_share == 0.0


def test_dry_limit_at_zero_speed():
    """omega = 0: no film, the asperities carry everything (share 1) and eps is the root of
    |F_a(eps)| = W found here by brentq on the quadrature force (independent of the mesh and
    of bearingfem.contact). eps to 1e-9 relative: the n_theta = 96 quadrature is within
    1e-9 of quadrature in force (test above) and dF/deps ~ 3e4 N per unit eps here. Fails with
    the radial force's sign flipped (no root), or the share computed against the film."""
    b = seed_bearing()
    W = 200.0
    eq = equilibrium(b, load=(W, 0.0), omega=0.0, model="fem", roughness=ROUGH,
                     n_theta=96, eps_max=0.9999)
    eps = brentq(lambda e: -reference_contact(b, e, ROUGH, ('cos',))[0] - W, 0.95, 0.9999,
                 xtol=1e-14, rtol=1e-13)
    assert eq.eps == pytest.approx(eps, rel=1e-9)
    assert eq.asperity_load_share == pytest.approx(1.0, rel=1e-12)
    assert math.cos(eq.state.gamma) == pytest.approx(1.0)   # pressed along the load
    assert abs(eq.friction_force) < 1e-12                    # no sliding, no Coulomb


def test_exact_partial_matches_central_differences():
    """d(F_r, F_t)/d eps of the asperity force (and the "fem" model's total) against
    central differences, eps = 0.985, step 1e-6: truncation ~ h^2 F'''/6, measured
    agreement 3e-9 relative for the contact. Fails with the F_3/2 derivative's 5/2 or the
    clearance factor dropped, or the contact's partial left out of the model's."""
    b = seed_bearing()
    s = JournalState(0.985, omega=100.0, gamma=0.2)
    op = fe_operator(b, s, 96, 8, "P1")
    exact = contact_partial_eps(b, s, op, ROUGH)
    h = 1e-6

    def contact(e):
        return np.array(film_contact(b, JournalState(e, omega=100.0, gamma=0.2), op,
                                     ROUGH).force_local)
    fd = (contact(s.eps + h) - contact(s.eps - h)) / (2 * h)
    assert exact[0] == pytest.approx(fd[0], rel=1e-7)
    assert abs(exact[1]) < 1e-10 * abs(exact[0])

    m = film_model("fem")
    opts = dict(n_theta=96, n_z=8, cavitation="reynolds")
    d = m.force_derivatives(b, s, roughness=ROUGH, **opts)
    smooth = m.force_derivatives(b, s, **opts)
    assert np.subtract(d.d_eps, smooth.d_eps) == pytest.approx(exact, rel=1e-12, abs=1e-9)
    assert np.subtract(d.force, smooth.force) == pytest.approx(
        film_contact(b, s, op, ROUGH).force_local, rel=1e-12, abs=1e-9)


def test_coefficients_add_the_asperity_stiffness():
    """The local stiffness with roughness is the smooth film's plus the contact's:
    -(dF_a/deps, J F_a / eps)/c (J the quarter turn), the damping unchanged. Fails when the
    model's partials leave out the contact's eps partial (5 % of K_rr here, measured) or
    its force."""
    b = seed_bearing()
    s = JournalState(0.985, omega=100.0, gamma=0.2)
    opts = dict(model="fem", n_theta=96, n_z=8, cavitation="reynolds", frame="local")
    rough = coefficients(b, s, roughness=ROUGH, **opts)
    smooth = coefficients(b, s, **opts)
    op = fe_operator(b, s, 96, 8, "P1")
    a_r, a_t = contact_partial_eps(b, s, op, ROUGH)
    f_r, f_t = film_contact(b, s, op, ROUGH).force_local
    c = b.clearance
    dK = -np.array([[a_r, -f_t / s.eps], [a_t, f_r / s.eps]]) / c
    assert rough.K - smooth.K == pytest.approx(dK, rel=1e-9, abs=1e-9 * np.abs(dK).max())
    assert rough.C == pytest.approx(smooth.C, rel=1e-12)


def test_bad_roughness_is_refused():
    """A roughness that is not a Roughness is refused by the solve and the model options,
    naming the parameter; zero speed without roughness still is; so is roughness with a
    tilt (that path solves the film alone)."""
    b = seed_bearing()
    s = JournalState(0.5, omega=100.0)
    with pytest.raises(ValueError, match="roughness"):
        solve_reynolds(b, s, 24, 4, roughness=0.3e-6)
    with pytest.raises(ValueError, match="roughness"):
        equilibrium(b, load=(0.0, -1e3), omega=100.0, roughness="rough")
    with pytest.raises(ValueError, match="omega"):
        equilibrium(b, load=(0.0, -1e3), omega=0.0)
    with pytest.raises(ValueError, match="roughness"):     # not silently dropped
        equilibrium(b, load=(0.0, -1e3), omega=100.0, roughness=ROUGH, tilt=(1e-4, 0.0))
    with pytest.raises(ValueError, match="roughness"):
        coefficients(b, s, model="fem", roughness=ROUGH, tilt=(1e-4, 0.0))
