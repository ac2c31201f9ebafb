"""Mixed EHD (bearingfem.ehd.asperity): the elastic bush carries the film's and the
summits' pressure, w = C (p + p_a(h)). Verified by the exact Jacobian (central
differences), the infinitely stiff bush (today's rigid mixed film), the smooth limit
(today's EHD film), the dry elastic rough contact at zero speed against an independent
Fourier solve with Michell's exact ring, and near-contact films h/sigma < 1."""
import numpy as np
import pytest

from bearingfem import JournalState, Roughness, solve_reynolds
from bearingfem.bearing import seed_bearing
from bearingfem.ehd.coupling import ehd_film
from bearingfem.elastic import ElasticBush, bush_compliance
from bearingfem.fe.reynolds import fe_operator, general_film
from bearingfem.fields import FilmFields

SEED = seed_bearing(0.2)                 # R 10 mm, L 4 mm, c 20 um, mu 0.0117 Pa s
RING = ElasticBush(outer_radius=0.016, modulus=110e9, poisson=0.34, model="ring")
#: steel on bronze (E* 80.8 GPa), K 1e-3 (docs/mixed-lubrication.md's typical values)
ROUGH = Roughness(sigma=0.4e-6, contact_modulus=80.8e9, elastic_factor=1e-3, friction=0.1)
HEAVY = JournalState(eps=0.995, gamma=0.2, omega=250.0)     # rigid minimum film 0.1 um
N = (48, 4)


def rough(sigma):
    return Roughness(sigma=sigma, contact_modulus=80.8e9, elastic_factor=1e-3, friction=0.1)


def grid(sol, n_theta, n_z, field):
    """A whole-length P1 solution's nodal ``field`` on the compliance's (n_theta, n_z + 1)
    grid (theta from the film's start, z from -L/2)."""
    j = np.rint(np.mod(sol.theta, 2 * np.pi) / (2 * np.pi / n_theta)).astype(int) % n_theta
    k = np.rint((sol.z / SEED.length + 0.5) * n_z).astype(int)
    out = np.zeros((n_theta, n_z + 1))
    out[j, k] = field
    return out, j, k


@pytest.mark.parametrize("reduced", [False, True])
def test_mixed_jacobian_is_the_residuals_derivative(reduced):
    """J v + U V^T v against the central difference of the residual, the deflection
    solved with the summits' pressure at each evaluation (rigid minimum film 0.1 um,
    sigma 0.4 um: p_a up to ~10 MPa), full and reduced compliance: 1e-8 relative (3e-11
    measured). Fails with the summits' stiffness dp_a/dh left out of dw/dp (both) or the
    sign of its Woodbury update flipped (full)."""
    op = fe_operator(SEED, HEAVY, 24, 4, "P1", None, False)
    base, gap = general_film(SEED, HEAVY, op)
    comp = bush_compliance(RING, SEED.radius, SEED.length, 24, 5)
    film = ehd_film(SEED, HEAVY, op, base, gap, None, comp.reduced(40) if reduced else comp,
                    ROUGH)
    P = 2e7 / SEED.pressure_scale * np.maximum(np.sin(op.mesh.theta), 0.0) * (
        1 - (op.mesh.zeta / op.mesh.length_ratio) ** 2)
    assert np.max(film.contact(P).asperity_pressure) > 1e6
    J, U, V = film.jacobian(P)
    v = np.random.default_rng(2).standard_normal(P.size) * np.max(P)
    Jv = J @ v + (U @ v if V is None else U @ (V.T @ v))
    h = 1e-6
    diff = (film.residual(P + h * v)[0] - film.residual(P - h * v)[0]) / (2 * h)
    assert np.max(np.abs(Jv - diff)) <= 1e-8 * np.max(np.abs(diff))


@pytest.mark.parametrize("cavitation", ["none", "reynolds"])
def test_stiff_bush_is_todays_mixed_film(cavitation):
    """E = 1e30 Pa: the bush does not move and the mixed EHD film is today's rigid mixed
    film (bearingfem.fe.mixed): on a general gap pressure and asperity force to round-off
    (1e-12), on the rigid cylinder to the fast path's 1e-9 (its strong-form Couette term).
    Fails with the asperity contact left out of the EHD route's solution (force 0)."""
    stiff = ElasticBush(outer_radius=0.016, modulus=1e30, poisson=0.34, model="ring")
    state = JournalState(eps=0.99, gamma=0.4, omega=250.0)
    bump = FilmFields(gap=lambda t, z: 1.0 + state.eps * np.cos(t) + 0.003 * z * np.sin(t))
    today = solve_reynolds(SEED, state, *N, cavitation=cavitation, fields=bump, roughness=ROUGH)
    mixed = solve_reynolds(SEED, state, *N, cavitation=cavitation, fields=bump, bush=stiff,
                           roughness=ROUGH)
    assert np.max(np.abs(mixed.deformation)) < 1e-20
    assert np.max(np.abs(mixed.pressure - today.pressure)) <= 1e-12 * today.pressure_max
    assert np.hypot(*today.asperity_force) > 1.0
    assert np.allclose(mixed.asperity_force, today.asperity_force, rtol=1e-12, atol=0.0)
    assert np.isclose(mixed.asperity_friction_torque, today.asperity_friction_torque,
                      rtol=1e-12, atol=0.0)
    rigid = solve_reynolds(SEED, state, *N, cavitation=cavitation, roughness=ROUGH)
    mixed = solve_reynolds(SEED, state, *N, cavitation=cavitation, bush=stiff, roughness=ROUGH)
    assert np.allclose(mixed.total_force, rigid.total_force, rtol=1e-9, atol=0.0)
    assert np.allclose(mixed.asperity_force, rigid.asperity_force, rtol=1e-12, atol=0.0)


def test_smooth_surfaces_are_todays_ehd_film():
    """sigma -> 0: at sigma = 1 nm every node is > 39 sigma from the bush, p_a = 0 exactly,
    and the film is today's EHD film (pressure and deformation to the Newton tolerance
    1e-10: 2e-11 measured, the Jacobian's product taken in another order; asperity force
    0); as sigma falls 0.4 -> 0.2 -> 0.1 um the deformation's change against the
    smooth film falls (measured 2.2e-7, 1.0e-7, 3.7e-8 m). Fails with the gap passed
    to p_a in units of c (H instead of h: contact everywhere)."""
    smooth = solve_reynolds(SEED, HEAVY, *N, bush=RING)
    tiny = solve_reynolds(SEED, HEAVY, *N, bush=RING, roughness=rough(1e-9))
    assert np.max(np.abs(tiny.pressure - smooth.pressure)) <= 1e-9 * smooth.pressure_max
    assert np.max(np.abs(tiny.deformation - smooth.deformation)) <= 1e-9 * np.max(
        np.abs(smooth.deformation))
    assert tiny.asperity_force == (0.0, 0.0)
    change = [np.max(np.abs(solve_reynolds(SEED, HEAVY, *N, bush=RING, roughness=rough(s))
                            .deformation - smooth.deformation)) for s in (0.4e-6, 0.2e-6, 0.1e-6)]
    assert change[0] > change[1] > change[2] > 0.0


def test_deformation_includes_the_summits_share():
    """The returned deformation is the bush compliance (built separately on the grid)
    applied to film plus nodal asperity pressure on the returned film thickness, to the
    solver's 1e-10; and it differs from C p alone by more than 1e-8 m here. Fails with
    p_a left out of the bush's load (w = C p)."""
    sol = solve_reynolds(SEED, HEAVY, *N, bush=RING, roughness=ROUGH)
    comp = bush_compliance(RING, SEED.radius, SEED.length, N[0], N[1] + 1)
    pa = ROUGH.pressure(sol.film_thickness)
    total, j, k = grid(sol, *N, sol.pressure + pa)
    film_only, _, _ = grid(sol, *N, sol.pressure)
    w = comp.deflection(total)[j, k]
    assert np.max(np.abs(sol.deformation - w)) <= 1e-10 * np.max(np.abs(w))
    assert np.max(np.abs(comp.deflection(film_only)[j, k] - w)) > 1e-8
