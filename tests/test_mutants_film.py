"""Film geometry helpers (bearingfem.film) against independent references: mutants of these
lines survived the closed-form and FE-vs-FV tests (docs/mutation.md)."""
import numpy as np
import pytest
from scipy.integrate import quad

from bearingfem.film import (cubed_thickness_coefficients, film_thickness,
                             film_thickness_integral, inertial_from_theta, local_to_inertial,
                             theta_from_inertial)

ANGLES = [(-2.0, 0.3), (0.1, 2.9), (1.7, 4.4), (5.0, 6.2)]


@pytest.mark.parametrize("lo, hi", ANGLES)
@pytest.mark.parametrize("eps", [0.0, 0.4, 0.93])
def test_film_thickness_integral_is_the_integral(lo, hi, eps):
    """Against adaptive quadrature of 1 + eps cos(theta). Fails with the sine difference's
    sign flipped, a term dropped or eps divided in (film.py:32)."""
    ref, _ = quad(lambda t: 1 + eps * np.cos(t), lo, hi, epsabs=0, epsrel=1e-13)
    assert film_thickness_integral(lo, hi, eps) == pytest.approx(ref, rel=1e-12, abs=1e-14)


def test_film_thickness_at_an_inertial_angle_is_the_geometric_gap():
    """The gap at inertial angle alpha, journal centre at e (cos gamma, sin gamma): to first
    order in e/R it is c - e cos(alpha - gamma) (the journal approaches the bush along
    its eccentricity). Fails with theta_from_inertial's pi or gamma sign wrong (film.py:66)."""
    rng = np.random.default_rng(7)
    alpha, gamma = rng.uniform(-7, 7, 50), rng.uniform(-7, 7, 50)
    c, eps = 20e-6, 0.6
    th = theta_from_inertial(alpha, gamma)
    assert np.all((th >= 0) & (th < 2 * np.pi))
    assert film_thickness(th, eps, c) == pytest.approx(c * (1 - eps * np.cos(alpha - gamma)),
                                                      rel=1e-12)


def test_inertial_from_theta_inverts_theta_from_inertial():
    """theta -> alpha -> theta is the identity (mod 2 pi), and theta = pi (the minimum
    film) lies at alpha = gamma. Fails with the sign of a term flipped or a term dropped
    (film.py:71)."""
    gamma = np.array([-1.0, 0.0, 0.5, 3.0])
    theta = np.array([0.2, 1.0, 3.0, 6.0])
    alpha = inertial_from_theta(theta, gamma)
    assert theta_from_inertial(alpha, gamma) == pytest.approx(theta, rel=1e-12)
    assert np.cos(inertial_from_theta(np.pi, gamma)) == pytest.approx(np.cos(gamma), abs=1e-12)
    assert np.sin(inertial_from_theta(np.pi, gamma)) == pytest.approx(np.sin(gamma), abs=1e-12)


@pytest.mark.parametrize("eps", [0.0, 0.3, 0.85])
def test_cubed_thickness_derivative_coefficients(eps):
    """d/d(eps) of the coefficients of H^3 against central differences (the coefficients
    are cubics: the central difference is off by d^2 = 1e-8 at most, step d = 1e-4).
    Fails with any derivative coefficient changed (film.py:41)."""
    d = 1e-4
    up, down = (np.array(cubed_thickness_coefficients(eps + s)) for s in (d, -d))
    assert np.array(cubed_thickness_coefficients(eps, derivative=True)) == pytest.approx(
        (up - down) / (2 * d), rel=1e-7, abs=2e-8)
    theta = np.linspace(0, 2 * np.pi, 7)     # and the coefficients are H^3's
    a = cubed_thickness_coefficients(eps)
    assert sum(a[k] * np.cos(theta) ** k for k in range(4)) == pytest.approx(
        film_thickness(theta, eps) ** 3, rel=1e-13)


def test_local_to_inertial_is_a_rotation_by_gamma():
    """F_x + i F_y = (F_r + i F_t) exp(i gamma) (the contract's r_hat, t_hat written as one
    complex rotation). Fails with either sign in the rotation flipped or a term dropped
    (film.py:77)."""
    f_r, f_t = np.array([-3.0, 2.0, 0.5]), np.array([1.5, -4.0, 2.5])
    gamma = np.array([0.4, 2.5, -1.2])
    ref = (f_r + 1j * f_t) * np.exp(1j * gamma)
    fx, fy = local_to_inertial(f_r, f_t, gamma)
    assert fx == pytest.approx(ref.real, rel=1e-13) and fy == pytest.approx(ref.imag, rel=1e-13)


@pytest.mark.parametrize("model", ["short", "long", "fem"])
def test_half_frequency_whirl_carries_no_load(model):
    """A journal whirling at half its spin (gamma_dot = omega / 2, eps_dot = 0) drags the
    oil round exactly as fast as the wedge recedes: seen from the line of centres the
    journal turns at omega - gamma_dot and the bush at -gamma_dot, and the wedge term of
    Reynolds' equation carries their sum, omega - 2 gamma_dot = 0. Every film model then
    has zero force, while the same journal without whirl carries its load. Only the
    closed forms' hand-written partials noticed omega - gamma_dot before (the wedge term's
    own tests never whirl the journal)."""
    from bearingfem import Bearing, JournalState
    from bearingfem.models import film_model
    b = Bearing(radius=0.01, length=0.01, clearance=20e-6, viscosity=0.0117)
    m = film_model(model)
    opts = dict(n_theta=48, n_z=8) if model == "fem" else {}
    still = np.hypot(*m.film_force(b, JournalState(0.6, omega=250.0), **opts))
    whirl = np.hypot(*m.film_force(b, JournalState(0.6, gamma_dot=125.0, omega=250.0),
                                   **opts))
    assert still > 10.0 and whirl <= 1e-12 * still
