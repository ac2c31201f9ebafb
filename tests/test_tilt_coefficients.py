"""4x4 stiffness and damping of a misaligned film (forces and moments against e_x, e_y,
tilt_x, tilt_y and their rates) by exact sensitivity, against central differences."""
import numpy as np
import pytest

from bearingfem import Bearing, JournalState, solve_reynolds
from bearingfem.fe.general import film_system
from bearingfem.fe.kernel import fe_operator, fe_pressure, general_film
from bearingfem.fe.sensitivity import (fe_tilt_coefficients, gap_sensitivities,
                                       generalised_forces)

B = Bearing(radius=0.01, length=0.01, clearance=20e-6, viscosity=0.0117)
S = JournalState(eps=0.6, gamma=0.3, omega=250.0)
TILT = (1.0e-3, -0.5e-3)
MESH = (48, 8, "P2")


def _fixed_mesh_forces(cavitation, dq, dq_dot):
    """Generalised forces with the gap moved by dq and its rate dq', on the state's own
    mesh (central differences see the discrete film the sensitivity differentiates). The
    load's reference cylinder follows eps = |e| / c as in ``solve_reynolds``: exact for
    the moves tested here (tilts, rates and e along the eccentricity)."""
    op = fe_operator(B, S, *MESH, None, False)
    film, _ = general_film(B, S, op, None, TILT)
    g = gap_sensitivities(B, S, op.qp_theta, op.qp_zeta)
    film = film.plus(gap=np.tensordot(dq, g, 1), gap_rate=np.tensordot(dq_dot, g, 1))
    eps = S.eps + (dq[0] * np.cos(S.gamma) + dq[1] * np.sin(S.gamma)) / B.clearance
    res = fe_pressure(op, S, cavitation, system=film_system(op, film, S.wedge_speed, eps))
    return generalised_forces(B, S, op, res.pressure, clip=cavitation == "gumbel")


@pytest.mark.parametrize("cavitation", ["none", "gumbel", "reynolds"])
def test_tilt_coefficients_match_central_differences(cavitation):
    """The entries the fixed mesh differentiates - the tilt columns of K, its column along
    the eccentricity (the mesh does not move with eps) and all of C - against central
    differences on the same mesh, steps 1e-10 m / 1e-7 rad (and rates 1e-8 m/s, 1e-6
    rad/s): agreement 1e-6 of each row's largest entry (measured <= 1e-9; Gumbel's clip
    makes its force kinked where quadrature points change sign, an error first order in
    the step: 1.6e-6 with rate steps 100 times larger).
    Fails with the dK/dq term dropped, the Couette partial's factor 6 w wrong or the
    squeeze load's sign flipped."""
    kc = fe_tilt_coefficients(B, S, TILT, *MESH, cavitation)
    h = np.array([1e-10, 1e-10, 1e-7, 1e-7])
    v = np.array([1e-8, 1e-8, 1e-6, 1e-6])
    K, C = np.zeros((4, 4)), np.zeros((4, 4))
    zero = np.zeros(4)
    for j in range(4):
        e = np.eye(4)[j]
        K[:, j] = -(_fixed_mesh_forces(cavitation, h * e, zero)
                    - _fixed_mesh_forces(cavitation, -h * e, zero)) / (2 * h[j])
        C[:, j] = -(_fixed_mesh_forces(cavitation, zero, v * e)
                    - _fixed_mesh_forces(cavitation, zero, -v * e)) / (2 * v[j])
    r_hat = np.array([np.cos(S.gamma), np.sin(S.gamma)])
    for mine, ref in ((kc.K[:, 2:], K[:, 2:]), (kc.K[:, :2] @ r_hat, K[:, :2] @ r_hat),
                      (kc.C, C)):
        scale = np.abs(ref).max(axis=-1, keepdims=True)
        assert np.all(np.abs(mine - ref) <= 1e-6 * scale), (mine - ref) / scale
    assert kc.force == pytest.approx(_fixed_mesh_forces(cavitation, zero, zero), rel=1e-12)


def _moving_journal_coefficients(cavitation, h, v):
    """K and C by central differences of ``solve_reynolds`` over the journal's inertial
    position, tilt and their rates (the mesh then turns with the attitude angle)."""
    c = B.clearance

    def Q(q, rate):
        st = JournalState.from_eccentricity(q[0], q[1], rate[0], rate[1], c, S.omega)
        r = solve_reynolds(B, st, *MESH, cavitation, tilt=tuple(q[2:]),
                           tilt_rate=tuple(rate[2:]))
        return np.r_[r.force, r.moment]

    q0 = np.array([S.eps * c * np.cos(S.gamma), S.eps * c * np.sin(S.gamma), *TILT])
    K, C = np.zeros((4, 4)), np.zeros((4, 4))
    for j in range(4):
        e = np.eye(4)[j]
        K[:, j] = -(Q(q0 + h * e, 0 * e) - Q(q0 - h * e, 0 * e)) / (2 * h[j])
        if v is not None:
            C[:, j] = -(Q(q0, v * e) - Q(q0, -v * e)) / (2 * v[j])
    return K, C


def test_tilt_coefficients_match_moving_the_journal():
    """Full film: the same K and C from central differences of ``solve_reynolds`` over
    the journal's inertial position, tilt and their rates: 1e-6 of each row (measured
    4e-8 for K, 2e-13 for C at 48x8 P2).
    Fails with the tilt rate's gamma_dot term or a generalised force's axis wrong."""
    kc = fe_tilt_coefficients(B, S, TILT, *MESH, "none")
    K, C = _moving_journal_coefficients("none", np.array([1e-9, 1e-9, 1e-6, 1e-6]),
                                        np.array([1e-4, 1e-4, 1e-2, 1e-2]))
    for mine, ref in ((kc.K, K), (kc.C, C)):
        scale = np.abs(ref).max(axis=1, keepdims=True)
        assert np.all(np.abs(mine - ref) <= 1e-6 * scale), (mine - ref) / scale


@pytest.mark.parametrize("cavitation", ["gumbel", "reynolds"])
def test_tilt_stiffness_is_the_derivative_of_the_solved_film(cavitation):
    """Cavitated films: K is the exact derivative of the force and moment that
    ``solve_reynolds`` returns as the journal moves (its mesh turning with gamma), the
    Jacobian the tilted equilibrium's Newton iteration needs. Central differences, steps
    1e-10 m / 1e-7 rad: 1e-7 of each row (measured <= 6e-10, falling as the step squared:
    6e-8 at 1e-9 m). Fails with the position columns taken on the fixed mesh (the cavity's
    front held on it: off by 2e-3 (Gumbel) and 8e-2 (Reynolds) of the row at 48x8 P2), or
    the tilt's share J tilt of the turning dropped or its sign flipped."""
    kc = fe_tilt_coefficients(B, S, TILT, *MESH, cavitation)
    K, _ = _moving_journal_coefficients(cavitation, np.array([1e-10, 1e-10, 1e-7, 1e-7]),
                                        None)
    scale = np.abs(K).max(axis=1, keepdims=True)
    assert np.all(np.abs(kc.K - K) <= 1e-7 * scale), (kc.K - K) / scale


@pytest.mark.parametrize("cavitation", ["none", "gumbel", "reynolds"])
def test_tilt_stiffness_differentiates_the_split_couette_load(cavitation):
    """The load ``solve_reynolds`` assembles holds the reference cylinder 1 + eps cos(theta)
    in strong form and only the departure in weak form; the two forms differ by the weak
    term's quadrature error (largest on coarse P1 meshes), so K's column along the
    eccentricity must carry the reference's own partial. Fourth-order central differences
    of ``solve_reynolds`` (steps 1e-9 m, 1e-6 rad; their error and round-off measured
    <= 1.7e-11 of each row over P1/P2 at 30x6 and 48x8, all three films) at P1 30x6:
    5e-11 of each row (measured <= 4e-12). Fails with the reference's partial dropped
    (the weak form differentiated as if it were the whole load): 5.8e-10 (Reynolds),
    7.6e-10 (Gumbel), 1.7e-9 (full film) of the row."""
    mesh, c = (30, 6, "P1"), B.clearance
    kc = fe_tilt_coefficients(B, S, TILT, *mesh, cavitation)

    def Q(q):
        st = JournalState.from_eccentricity(q[0], q[1], 0.0, 0.0, c, S.omega)
        r = solve_reynolds(B, st, *mesh, cavitation, tilt=tuple(q[2:]))
        return np.r_[r.force, r.moment]

    q0 = np.array([S.eps * c * np.cos(S.gamma), S.eps * c * np.sin(S.gamma), *TILT])
    h = np.array([1e-9, 1e-9, 1e-6, 1e-6])
    K = np.zeros((4, 4))
    for j in range(4):
        e = h[j] * np.eye(4)[j]
        K[:, j] = -(8.0 * (Q(q0 + e) - Q(q0 - e)) - (Q(q0 + 2 * e) - Q(q0 - 2 * e))) / (
            12.0 * h[j])
    scale = np.abs(K).max(axis=1, keepdims=True)
    assert np.all(np.abs(kc.K - K) <= 5e-11 * scale), (kc.K - K) / scale


def test_tilt_coefficients_need_a_steady_state():
    with pytest.raises(ValueError, match="eps_dot"):
        fe_tilt_coefficients(B, JournalState(eps=0.5, eps_dot=1.0, omega=100.0), TILT, 16, 4)


def test_coefficients_with_tilt():
    """``coefficients(..., tilt=)`` is the (x, y) block of the 4x4 in every frame, and at
    tilt (0, 0) the aligned film's 2x2 (fails if the tilt is ignored or the block taken
    from the moment rows)."""
    from bearingfem import coefficients
    opts = dict(n_theta=48, n_z=8, element="P2", cavitation="reynolds")
    kc = fe_tilt_coefficients(B, S, TILT, *MESH, "reynolds")
    tilted = coefficients(B, S, "fem", tilt=TILT, **opts)
    assert np.allclose(tilted.K, kc.K[:2, :2], rtol=1e-12, atol=0.0)
    assert np.allclose(tilted.C, kc.C[:2, :2], rtol=1e-12, atol=0.0)
    local = coefficients(B, S, "fem", frame="local", tilt=TILT, **opts)
    assert np.allclose(local.in_frame("inertial").K, tilted.K, rtol=1e-12)

@pytest.mark.parametrize("cavitation", ["none", "gumbel", "reynolds"])
@pytest.mark.parametrize("tilt", [(0.0, 0.0), (1e-12, 0.0), (0.0, -1e-12)])
def test_zero_tilt_limit_is_the_aligned_film(cavitation, tilt):
    """At zero tilt (and as the tilt goes to 0) the 4x4's (x, y) block is the aligned
    film's 2x2 (half film there, whole length here) to round-off: both turn the mesh with
    the journal. Measured <= 7e-15 at 48x8, 7e-13 at 192x32 (P2, eps 0.6). Fails with the
    position columns taken on the fixed mesh: Reynolds' film then differs by 5e-3, 8e-4
    and 1.3e-3 at 48x8, 96x16, 192x32 - not falling with the mesh."""
    from bearingfem import coefficients
    opts = dict(n_theta=48, n_z=8, element="P2", cavitation=cavitation)
    tilted = coefficients(B, S, "fem", tilt=tilt, **opts)
    block = fe_tilt_coefficients(B, S, tilt, *MESH, cavitation)
    ref = coefficients(B, S, "fem", **opts)
    for K in (tilted.K, block.K[:2, :2]):
        assert np.abs(K - ref.K).max() <= 1e-11 * np.abs(ref.K).max()
    for C in (tilted.C, block.C[:2, :2]):
        assert np.abs(C - ref.C).max() <= 1e-11 * np.abs(ref.C).max()


def test_centred_tilted_journal_has_finite_coefficients():
    """At eps = 0 the turning form divides by eps: below EPS_TURN the position columns stay
    the fixed mesh's (the centred journal has no attitude to turn) and finite. Fails if
    the turning form is used at eps = 0 (inf, NaN)."""
    centred = JournalState(eps=0.0, omega=250.0)
    kc = fe_tilt_coefficients(B, centred, TILT, 32, 8, "P1", "reynolds")
    assert np.all(np.isfinite(kc.K)) and np.all(np.isfinite(kc.C))
    assert np.abs(kc.K[:2, :2]).max() > 0.0
