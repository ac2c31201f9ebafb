"""Mixed EHD (bearingfem.ehd.asperity): the elastic bush carries the film's and the
summits' pressure, w = C (p + p_a(h)). Verified by the exact Jacobian (central
differences), the infinitely stiff bush (today's rigid mixed film), the smooth limit
(today's EHD film), the dry elastic rough contact at zero speed against an independent
Fourier solve with Michell's exact ring, and near-contact films h/sigma < 1."""
import numpy as np
import pytest
import scipy.linalg as la

from bearingfem import JournalState, Roughness, solve_reynolds
from bearingfem.bearing import seed_bearing
from bearingfem.ehd.coupling import ehd_film
from bearingfem.elastic import ElasticBush, bush_compliance
from bearingfem.fe.kernel import fe_operator, general_film
from bearingfem.fields import FilmFields

from test_elastic_bush import lame_exact, ring_exact

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
    assert_deformation_carries_the_summits(
        solve_reynolds(SEED, HEAVY, *N, bush=RING, roughness=ROUGH))


def assert_deformation_carries_the_summits(sol):
    """``sol.deformation`` (ring bush RING, roughness ROUGH, mesh N) is the compliance built
    apart on the grid applied to the film's plus the summits' nodal pressure, to 1e-10,
    and differs from the film's pressure alone by more than 1e-8 m."""
    comp = bush_compliance(RING, SEED.radius, SEED.length, N[0], N[1] + 1)
    pa = ROUGH.pressure(sol.film_thickness)
    total, j, k = grid(sol, *N, sol.pressure + pa)
    film_only, _, _ = grid(sol, *N, sol.pressure)
    w = comp.deflection(total)[j, k]
    assert np.max(np.abs(sol.deformation - w)) <= 1e-10 * np.max(np.abs(w))
    assert np.max(np.abs(comp.deflection(film_only)[j, k] - w)) > 1e-8


def michell(n, a, b, lam, mu):
    """Inner-surface radial displacement amplitude [m/Pa] of a plane-strain ring (radii a,
    b, outer surface held) under the inner pressure cos(n theta), n >= 2, in floating
    point: U = sum c_k A_k r^k, V = sum c_k B_k r^k with Navier's four exponents
    k = n + 1, 1 - n (div u and rot u from sigma's harmonic pair: beta = +-(lam + 2 mu)/mu
    alpha) and n - 1, -1 - n (div u = rot u = 0: B = -(k + 1) A / n), each power scaled
    at the radius where it is largest so that n = 500 stays well conditioned. Equal to
    test_elastic_bush.ring_exact (sympy) to 1e-14 for n = 2, 3, 5."""
    cols = []
    for k, r0 in ((n + 1, b), (n - 1, b), (1 - n, a), (-1 - n, a)):
        if k in (n - 1, -1 - n):
            A, B = 1.0, -(k + 1) / n
        else:
            beta = (1.0 if k - 1 == n else -1.0) * (lam + 2 * mu) / mu
            A, B = np.linalg.solve([[k + 1, n], [n, k + 1]], [1.0, beta])
        cols.append((k, r0, A, B))

    def at(r):
        power = np.array([(r / r0) ** k for k, r0, _, _ in cols])
        A, B = np.array([c[2] for c in cols]), np.array([c[3] for c in cols])
        k = np.array([c[0] for c in cols])
        return A * power, B * power, A * k / r * power, B * k / r * power
    Ub, Vb, _, _ = at(b)
    Ua, Va, dUa, dVa = at(a)
    srr = (lam + 2 * mu) * dUa + lam * (Ua + n * Va) / a
    srt = mu * (-n * Ua / a + dVa - Va / a)
    coeff = np.linalg.solve(np.array([Ub, Vb, srr, srt]), [0.0, 0.0, -1.0, 0.0])
    return float(Ua @ coeff)


def dry_ring_force(eps, roughness, points=256):
    """F_r [N] of the dry rough contact with the ring bush, solved apart from the film
    code: on ``points`` angles the deflection w = G p_a(c (1 + eps cos theta) + w), G the
    exact ring's response (Lame n = 0, Michell n >= 1) applied in Fourier space, by
    Newton's method with the dense Jacobian I - G diag(dp_a/dh); the ring's slices are
    independent, so F_r = L R int p_a cos theta dtheta. Spectrally converged: 256 and
    1024 points agree to 1e-14."""
    lam, mu = RING.lame
    a, b = SEED.radius, RING.outer_radius
    g = np.array([lame_exact(a, b, lam, mu), ring_exact(1, a, b, lam, mu)]
                 + [michell(n, a, b, lam, mu) for n in range(2, points // 2 + 1)])
    G = np.fft.irfft(g[:, None] * np.fft.rfft(np.eye(points), axis=0), n=points, axis=0)
    theta = 2 * np.pi * np.arange(points) / points
    h0 = SEED.clearance * (1 + eps * np.cos(theta))
    w = np.zeros(points)
    for _ in range(30):
        pa = roughness.pressure(h0 + w)
        r = w - G @ pa
        if np.max(np.abs(r)) <= 1e-14 * np.max(np.abs(w)):
            return SEED.length * SEED.radius * 2 * np.pi / points * np.sum(pa * np.cos(theta))
        w = w + la.solve(np.eye(points) - G * roughness.pressure_derivative(h0 + w), -r)
    raise AssertionError("the reference's Newton did not converge")


def test_zero_speed_dry_contact_against_the_exact_ring():
    """Zero speed (the hard case): no film pressure, the summits carry the whole load and
    deflect the ring bush (rigid minimum gap 0.1 um, sigma 0.4 um; deflection 0.23 um).
    The contact force converges to the independent Fourier solve with Michell's exact
    ring at the second order of the ring's finite elements (measured relative errors
    n_theta 32, 64, 128, 256: 15.4 %, 5.0 %, 1.3 %, 0.34 %; ratios 3.1, 3.8, 3.9).
    Asserted: below 2 % at 128 cells and falling > 3.5x from 64. Fails with p_a left out
    of the bush's load (the rigid contact) or subtracted from it (no solution)."""
    state = JournalState(eps=0.995, omega=0.0)
    exact = dry_ring_force(0.995, ROUGH)
    err = []
    for n_theta in (64, 128):
        sol = solve_reynolds(SEED, state, n_theta, 2, bush=RING, roughness=ROUGH)
        assert sol.pressure_max == 0.0 and np.max(sol.deformation) > 0.2e-6
        err.append(abs(sol.asperity_force_local[0] / exact - 1))
    assert err[1] < 0.02
    assert err[0] / err[1] > 3.5


def test_near_contact_films_converge_and_the_share_rises_with_sigma():
    """eps 0.999 (rigid minimum gap 0.02 um), 25 rad/s, Reynolds cavitation: for sigma
    0.1, 0.2, 0.4 um the mixed film converges with finite fields, the least gap is below
    sigma at 0.4 um (h/sigma 0.72 measured), and the asperities' share of the total force
    rises with sigma (measured 0.010, 0.072, 0.365). Fails with p_a subtracted from the
    bush's load or the film pressure's deflection sign flipped (no solution)."""
    state = JournalState(eps=0.999, gamma=0.2, omega=25.0)
    share = []
    for sigma in (0.1e-6, 0.2e-6, 0.4e-6):
        sol = solve_reynolds(SEED, state, *N, cavitation="reynolds", bush=RING,
                             roughness=rough(sigma))
        assert sol.converged and np.all(np.isfinite(sol.pressure))
        assert np.all(np.isfinite(sol.deformation))
        fa, ft = np.array(sol.asperity_force), np.array(sol.total_force)
        share.append(float(fa @ ft / (ft @ ft)))
    assert np.min(sol.film_thickness) < 0.4e-6
    assert 0.0 < share[0] < share[1] < share[2] < 1.0


def test_equilibrium_shares_the_load_with_the_summits():
    """equilibrium(model="fem-ehd", bush=, roughness=): dry (omega = 0) the summits carry
    the whole load (share 1 to 1e-9); at 25 rad/s under 200 N film and summits share it,
    and the share is the solution's asperity force against the load. Fails with the
    asperity force left out of the "fem-ehd" model's force (no dry equilibrium) or without
    the deflection solve's tolerance floor (Brent's search passes eps 0.36, summits 32 sigma
    away, deflection 1e-300 m: ConvergenceError)."""
    from bearingfem.design.equilibrium import equilibrium
    opts = dict(model="fem-ehd", bush=RING, roughness=ROUGH, n_theta=24, n_z=4, modes=16,
                eps_max=0.9999)
    dry = equilibrium(SEED, load=(0.0, -100.0), omega=0.0, **opts)
    assert abs(dry.asperity_load_share - 1.0) < 1e-9
    eq = equilibrium(SEED, load=(0.0, -200.0), omega=25.0, **opts)
    assert 0.0 < eq.asperity_load_share < 1.0
    fa = np.array(eq.solution.asperity_force)
    assert np.isclose(eq.asperity_load_share, -(fa @ [0.0, -200.0]) / 200.0 ** 2, rtol=1e-9)


def test_benchmark_smoke(capsys):
    """benchmarks/ehd_mixed.py --quick runs; every row converged with a share in (0, 1)
    that rises with sigma."""
    from benchmarks import ehd_mixed
    rows = ehd_mixed.main(["--quick"])
    assert "share" in capsys.readouterr().out
    assert all(r["residual"] <= 1e-10 for r in rows)
    shares = [r["share"] for r in rows]
    assert 0.0 < shares[0] < shares[1] < shares[2] < 1.0


def test_the_fem_model_takes_a_bush_within_the_clearance():
    """equilibrium(model="fem", bush=, roughness=) (the public contract's call): the steady EHD film
    with its summits, by the fem model. At the equilibrium it returns, an independent
    solve_reynolds of the same film and summits balances the load to 1e-9; its K by the
    model's central differences equals the test's own differences of solve_reynolds's film
    force (x, y moved by +-1e-4 c) to 1e-3 of the largest entry (the two difference steps
    differ). Old: "bush is not an option of film model 'fem'"."""
    from bearingfem import coefficients
    from bearingfem.design.equilibrium import equilibrium
    opts = dict(n_theta=24, n_z=4, cavitation="reynolds")
    eq = equilibrium(SEED, load=(0.0, -150.0), omega=100.0, model="fem", bush=RING,
                     roughness=ROUGH, **opts)
    sol = solve_reynolds(SEED, eq.state, 24, 4, cavitation="reynolds", bush=RING,
                         roughness=ROUGH)
    total = np.add(sol.force, sol.asperity_force)
    assert np.hypot(*(total + [0.0, -150.0])) / 150.0 < 1e-9
    assert 0.0 < eq.asperity_load_share < 1.0
    kc = coefficients(SEED, eq.state, "fem", bush=RING, **opts)
    c, e = SEED.clearance, eq.state.eps

    def force_at(x, y):
        s = JournalState.from_eccentricity(x, y, 0.0, 0.0, c, eq.state.omega)
        return np.array(solve_reynolds(SEED, s, 24, 4, cavitation="reynolds", bush=RING).force)
    x0, y0 = c * e * np.cos(eq.state.gamma), c * e * np.sin(eq.state.gamma)
    d = 1e-4 * c
    Kx = -(force_at(x0 + d, y0) - force_at(x0 - d, y0)) / (2 * d)
    Ky = -(force_at(x0, y0 + d) - force_at(x0, y0 - d)) / (2 * d)
    K = np.column_stack([Kx, Ky])
    assert np.allclose(kc.K, K, rtol=1e-3, atol=1e-3 * np.abs(K).max())
