"""The EHD-JFO film with rough surfaces (``solve_reynolds(..., cavitation="jfo", bush=,
roughness=)``, the public contract): the bush carries the film's and the summits' pressure,
w = C (p + p_a(h)), in the mass-conserving balance. Verified as the Reynolds-condition
mixed EHD film is (tests/test_ehd_mixed.py): the balance's exact Jacobian against central
differences, the infinitely stiff bush (today's rigid mixed JFO film) and the returned
deformation against the bush's compliance built apart on the grid."""
import numpy as np

from bearingfem import ElasticBush, JournalState, solve_reynolds
from bearingfem.ehd.jfo import jfo_coupling
from bearingfem.fe.kernel import fe_operator

from test_ehd_mixed import (HEAVY, RING, ROUGH, SEED, N,
                            assert_deformation_carries_the_summits)

AMBIENT = 1e5


def test_mixed_jfo_jacobian_is_the_balances_derivative():
    """dR/dP = J + U V^T against the central difference of the balance's residual (phi
    held, the deflection solved with the summits' pressure at each evaluation; rigid
    minimum film 0.1 um, sigma 0.4 um): 1e-8 relative (1.8e-11 measured). Fails with the
    summits' stiffness left out of the Couette faces' dw/dp (C in place of
    (I - C D)^-1 C): 1.5e-6."""
    op = fe_operator(SEED, HEAVY, 24, 4, "P1", None, False)
    film = jfo_coupling(SEED, HEAVY, op, None, RING, (), AMBIENT, ROUGH)
    P = 2e7 / SEED.pressure_scale * np.maximum(np.sin(op.mesh.theta), 0.0) * (
        1 - (op.mesh.zeta / op.mesh.length_ratio) ** 2)
    phi = np.where(P > 0.0, 1.0, 0.7)
    st = film.evaluate(P, phi)
    assert np.max(st.ev.contact.asperity_pressure) > 1e6
    J, U, V, _ = film.jacobian(P, phi, 1.0, st)
    v = np.random.default_rng(3).standard_normal(P.size) * np.max(P)
    Jv = J @ v + (U @ v if V is None else U @ (V.T @ v))
    h = 1e-6
    diff = (film.evaluate(P + h * v, phi).residual
            - film.evaluate(P - h * v, phi).residual) / (2 * h)
    assert np.max(np.abs(Jv - diff)) <= 1e-8 * np.max(np.abs(diff))


def test_stiff_bush_is_todays_rigid_mixed_jfo_film():
    """E = 1e30 Pa: the bush does not move and the film is today's rigid JFO film with
    its summits (the 'jfo' route): pressure to the Newton tolerance, the summits' force
    and friction to 1e-12. Fails with the contact left out of the EHD-JFO solution."""
    stiff = ElasticBush(outer_radius=0.016, modulus=1e30, poisson=0.34, model="ring")
    state = JournalState(eps=0.99, gamma=0.4, omega=250.0)
    today = solve_reynolds(SEED, state, *N, cavitation="jfo", roughness=ROUGH,
                           ambient_pressure=AMBIENT, half=False)
    mixed = solve_reynolds(SEED, state, *N, cavitation="jfo", bush=stiff, roughness=ROUGH,
                           ambient_pressure=AMBIENT)
    assert np.max(np.abs(mixed.deformation)) < 1e-20
    assert np.hypot(*today.asperity_force) > 1.0
    assert np.max(np.abs(mixed.pressure - today.pressure)) <= 1e-9 * today.pressure_max
    assert np.allclose(mixed.asperity_force, today.asperity_force, rtol=1e-12, atol=0.0)
    assert np.isclose(mixed.asperity_friction_torque, today.asperity_friction_torque,
                      rtol=1e-12, atol=0.0)
    assert np.allclose(mixed.total_force, today.total_force, rtol=1e-9, atol=0.0)


def test_jfo_deformation_includes_the_summits_share():
    """The returned deformation is the bush's compliance (built apart on the grid) applied
    to the film's plus the summits' nodal pressure on the returned film, to the Newton
    tolerance (1e-10); it differs from C p alone by more than 1e-8 m, and the summits
    carry a share of the load. Fails with p_a left out of the bush's load (w = C p)."""
    sol = solve_reynolds(SEED, HEAVY, *N, cavitation="jfo", bush=RING, roughness=ROUGH,
                         ambient_pressure=AMBIENT)
    assert_deformation_carries_the_summits(sol)
    assert np.hypot(*sol.asperity_force) > 0.01 * np.hypot(*sol.force)
