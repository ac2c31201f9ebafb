"""The EHD film with the bush's modal deflection integrated as states
(bearingfem.ehd.states): its limits, its exact Jacobian, and the mechanism carrying the
states (contract rule 16)."""
import dataclasses

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from bearingfem import Bearing, ElasticBush, JournalState, solve_reynolds
from bearingfem.contact import Roughness
from bearingfem.ehd.states import ModalStateEHD
from bearingfem.film import local_to_inertial
from bearingfem.ehd.transient import ehd_compliance
from bearingfem.lubricant import Lubricant

B = Bearing(radius=0.01, length=0.004, clearance=20e-6, viscosity=0.0117)
SOLID = ElasticBush(outer_radius=0.016, modulus=110e9, poisson=0.34, model="solid")
NT, NZ, M = 24, 4, 8


def differenced_jacobian(residual, P, step=1e-6):
    """dR/dP by central differences, column by column, at steps of ``step`` max|P|."""
    h = step * np.max(np.abs(P))
    fd = np.empty((np.size(residual(P)), P.size))
    for j in range(P.size):
        d = np.zeros_like(P)
        d[j] = h
        fd[:, j] = (residual(P + d) - residual(P - d)) / (2 * h)
    return fd


def test_a_journal_held_still_relaxes_to_the_steady_ehd_film():
    """A still journal (eps 0.9) from an undeflected bush: the modal states relax (dq/dt
    -> 0) to the steady EHD solve with the same reduced compliance, force to 1e-8
    (3e-12 measured; the grid is aligned with the film's nodes at gamma = pi). At q = 0
    the bush's own squeeze first sucks the film down to 3 % of the rigid force. Fails
    with the bush's squeeze term's sign flipped, or the modal load S R^T dropped."""
    s = JournalState(eps=0.9, gamma=np.pi, omega=62.5)
    film = ModalStateEHD(B, None, SOLID, NT, NZ, M, relaxation=1e-6)
    F0, _ = film.rates(s, np.zeros(M))
    rigid = solve_reynolds(B, s, NT, NZ, "P1", "reynolds", half=False).force_local
    assert np.hypot(*F0) < 0.05 * np.hypot(*rigid)
    sol = solve_ivp(lambda t, q: film.rates(s, q)[1], (0.0, 2e-2), np.zeros(M),
                    method="BDF", rtol=1e-8, atol=1e-14)
    F, qdot = film.rates(s, sol.y[:, -1])
    steady = solve_reynolds(B, s, NT, NZ, "P1", "reynolds",
                            bush=ehd_compliance(SOLID, B.radius, B.length, NT, NZ, M))
    assert np.allclose(F, steady.force_local, rtol=1e-8, atol=0)
    assert np.max(np.abs(qdot)) < 1e-10
    # the relaxed modes' deflection is the steady film's C p (same nodes: gamma = pi)
    w = film.solution(s, sol.y[:, -1]).deformation
    assert np.allclose(w, steady.deformation, rtol=0,
                       atol=1e-7 * np.max(np.abs(steady.deformation)))


def test_a_stiff_bush_is_the_rigid_transient_film():
    """A bush 1e10 times stiffer barely deflects: the force at q = 0 of a moving journal
    (eps_dot, gamma_dot) is the rigid Reynolds-condition film's to 1e-8 (the bush's
    squeeze at its relaxation rate is what is left: 1.7e-5 at 1e6 times stiffer, so
    ~1e-9 here). Fails with the journal's own squeeze dropped from the gap rate."""
    stiff = dataclasses.replace(SOLID, modulus=110e19)
    s = JournalState(eps=0.7, eps_dot=30.0, gamma=0.4, gamma_dot=-5.0, omega=62.5)
    film = ModalStateEHD(B, None, stiff, NT, NZ, M, relaxation=1e-6)
    F, _ = film.rates(s, np.zeros(M))
    rigid = solve_reynolds(B, s, NT, NZ, "P1", "reynolds", half=False).force_local
    assert np.allclose(F, rigid, rtol=1e-8, atol=0)


def test_the_coupled_jacobian_is_the_residuals_derivative():
    """The film with dq/dt eliminated, R(P) = K P - load(P): its Jacobian (sparse + the
    rank-n squeeze of the bush's rate, U V^T) against central differences, with a Barus
    oil (2e-8 1/Pa) and a deflected bush, to 1e-6 of the largest entry. Fails with the
    low-rank term dropped or its 12 rho weight halved."""
    oil = Lubricant(viscosity=0.0117, barus=2e-8)
    s = JournalState(eps=0.8, eps_dot=10.0, gamma=0.3, omega=62.5)
    film = ModalStateEHD(B, oil, SOLID, 16, 2, 4, relaxation=1e-5)
    q = 1e-7 * np.linspace(1.0, -0.5, film.state_size)
    coupled = film._coupled(s, q)
    P = np.maximum(np.asarray(solve_reynolds(B, s, 16, 2, "P1", "reynolds",
                                             half=False).pressure) / B.pressure_scale, 0.0)
    ev = coupled.evaluate(P)
    J, U, V = coupled.jacobian(P, 1.0, ev)
    full = J.toarray() + U @ V.T
    fd = differenced_jacobian(lambda x: coupled.evaluate(x).residual, P)
    assert np.max(np.abs(full - fd)) < 1e-6 * np.max(np.abs(fd))


def test_chord_steps_on_the_kept_factorisation_give_the_newton_film(monkeypatch):
    """A nearby state solved by chord steps on the last solve's factorisation (as a run's
    right-hand sides are) equals a fresh film's Newton solve there: force and dq/dt to
    1e-8 (the solve's tolerance is 1e-10 of the residual's terms). The chord path must be
    the one taken. Fails with the chord's step sign flipped or its residual test loosened
    (a step short of convergence kept)."""
    import bearingfem.ehd.newton as newton     # the warm start's chord (newton.warm_solve)
    taken = []

    def chord(*args, **kw):
        out = newton_chord(*args, **kw)
        taken.append(out[0] is not None)
        return out
    newton_chord = newton._chord
    monkeypatch.setattr(newton, "_chord", chord)
    q = 1e-7 * np.linspace(1.0, -0.5, M)
    s1 = JournalState(eps=0.9, eps_dot=5.0, gamma=1.0, gamma_dot=1.0, omega=62.5)
    s2 = dataclasses.replace(s1, eps=0.9005, gamma=1.0005)
    film = ModalStateEHD(B, None, SOLID, NT, NZ, M, relaxation=1e-5)
    film.rates(s1, q)
    F, qdot = film.rates(s2, q)
    assert taken == [True]
    F0, qdot0 = ModalStateEHD(B, None, SOLID, NT, NZ, M, relaxation=1e-5).rates(s2, q)
    assert np.allclose(F, F0, rtol=1e-8, atol=0)
    assert np.allclose(qdot, qdot0, rtol=1e-8, atol=1e-8 * np.max(np.abs(qdot0)))


@pytest.mark.parametrize("rough", [False, True])
def test_the_isoviscous_film_is_affine_in_the_pressure(rough):
    """Without a lubricant the residual is built once per film as K P - load_0 + G dq/dt(P);
    against the film built whole at each P (two pressures, deflected bush, whirling
    journal, with and without the summits): residual and load to 1e-12 of their terms.
    Fails with G's sign flipped or the load at dq/dt = 0 taken at q's own rate."""
    s = JournalState(eps=0.95, eps_dot=20.0, gamma=0.7, gamma_dot=40.0, omega=62.5)
    film = ModalStateEHD(B, None, SOLID, NT, NZ, M, relaxation=1e-5,
                         roughness=Roughness(sigma=0.2e-6, contact_modulus=80.8e9,
                                             elastic_factor=1e-3) if rough else None)
    q = 2e-7 * np.linspace(1.0, -0.5, M)
    coupled = film._coupled(s, q)
    rng = np.random.default_rng(3)
    for _ in range(2):
        P = np.abs(rng.standard_normal(coupled.op.mesh.ndofs))
        P[~np.isin(np.arange(P.size), coupled.op.mesh.free)] = 0.0
        fast, whole = coupled.evaluate(P), coupled.film_state(P)
        scale = np.max(whole.size)
        assert np.max(np.abs(fast.residual - whole.residual)) < 1e-12 * scale
        assert np.max(np.abs(fast.load - whole.load)) < 1e-12 * scale
        assert np.allclose(fast.size, whole.size, rtol=1e-12, atol=0)


def test_bad_input_is_named():
    """Fails with the checks dropped."""
    with pytest.raises(ValueError, match="relaxation"):
        ModalStateEHD(B, None, SOLID, NT, NZ, M, relaxation=0.0)
    with pytest.raises(ValueError, match="modes"):
        ModalStateEHD(B, None, SOLID, NT, NZ, 0)
    with pytest.raises(ValueError, match="bush"):
        ModalStateEHD(B, None, None, NT, NZ, M)
    from bearingfem.models.ehd import ehd_run_film
    with pytest.raises(ValueError, match="coupling 'states'"):
        ehd_run_film(B, bush=SOLID, modes=4, cavitation="jfo", coupling="states")


def test_the_seed_pin_runs_past_the_circle_with_its_bush_integrated():
    """Contract rule 16 in the mechanism: the seed pin at 250 rad/s, 1 % of a turn from a
    centred start, 24 x 4, 8 modes, rough surfaces (sigma 0.2 um): the run completes,
    passes eps = 1, records its film every accepted step, and its force and least film
    are finite. Fails when the mechanism does not integrate the film's states (the bush
    then never deflects and the gap closes past eps = 1)."""
    from benchmarks.ehd_run import scene
    from mechanism import simulate
    rough = Roughness(sigma=0.2e-6, contact_modulus=80.8e9, elastic_factor=1e-3)
    sc = scene("paper-short-ehd-sharp", 250.0, 0.01, n_theta=NT, n_z=NZ, modes=M, film_step=0.0,
               lubricant=None, coupling="states", relaxation=1e-5, roughness=rough)
    r = simulate(sc, progress=False)
    assert not r.partial, r.message
    assert r.eps.max() > 1.0
    assert len(r.film_record) == r.stats["steps"]
    assert np.all(np.isfinite(r.force_x)) and np.all(np.isfinite(r.film_min))


def test_the_run_keeps_the_modal_states_of_each_film_step(tmp_path):
    """The run's ``film_z`` holds the modal coordinates of each film record row: the run
    film's solution at a row's state and those coordinates gives that row's recorded force
    (to 1e-8; measured 1e-11 at the peak row) and a deflection of the bush; a saved run
    loads them back, and the film history's frames come from them, each checked against
    the record's film + summits force. Rough surfaces of sigma 1 um, so that the summits
    carry load (up to 22 N here) and the check sees them. Fails when the states kept are
    not the ones the step took (the film then solves another gap), or when the history
    checks the film's force alone against the record."""
    from benchmarks.ehd_run import scene
    from mechanism import simulate
    from mechanism.film_history import film_history
    from mechanism.result import film_column, load_result
    from studies.ehd_paper import peak_film
    rough = Roughness(sigma=1e-6, contact_modulus=80.8e9, elastic_factor=1e-3)
    sc = scene("paper-short-ehd-sharp", 250.0, 0.01, n_theta=NT, n_z=NZ, modes=M, film_step=0.0,
               lubricant=None, coupling="states", relaxation=1e-5, roughness=rough)
    r = simulate(sc, progress=False)
    rec = r.film_record
    assert r.film_z.shape == (len(rec), M)
    state, sol = peak_film(sc, r, None, 250.0)      # (a states run needs no rigid run)
    recorded = np.flatnonzero(film_column(rec, "t") >= r.t[0])
    force = np.hypot(film_column(rec, "force_x"), film_column(rec, "force_y"))
    j = int(recorded[np.argmax(force[recorded])])
    assert film_column(rec, "eps")[j] == state.eps
    F_j = [film_column(rec, "force_x")[j], film_column(rec, "force_y")[j]]
    assert np.allclose(sol.total_force, F_j, rtol=1e-8, atol=0)
    assert np.max(sol.deformation) > 1e-6            # microns: the bush opens the film
    assert np.array_equal(load_result(r.save(tmp_path)).film_z, r.film_z)
    # a frame where the summits carry most (film_history raises past 1e-9 of the peak)
    k = int(np.argmax(film_column(rec, "asperity_load")))
    assert film_column(rec, "asperity_load")[k] > 1e-4 * force.max()
    crank = np.degrees(np.interp(film_column(rec, "t")[k], r.t, r.crank_angle))
    frames = film_history(r, sc, crank_angles_deg=[0.0, crank])
    assert len(frames) == 2 and all(f.solution.deformation is not None for f in frames)
    assert max(np.hypot(*f.solution.asperity_force) for f in frames) > 1.0


def test_a_deflection_that_shifts_the_bush_is_a_rigid_journal_elsewhere():
    """A bush 'deflected' by w = A cos(alpha - beta) (a rigid shift of the bush, held:
    relaxation 1e3 s, no modal load) under a whirling journal (eps_dot, gamma_dot) is the
    rigid film of the journal at the shifted eccentricity vector, with its rates: the force
    agrees to the interpolation of the cosine on the grid, 2.3e-3, 5.4e-4, 1.5e-4 at 48,
    96, 192 cells around (second order; asserted 3e-3 at 48). Fails without the whirl's
    gamma_dot dw/dalpha in the film frame's squeeze (the deflection passing under the
    turning film: 68 % off)."""
    from bearingfem.film import local_to_inertial
    film = ModalStateEHD(B, None, SOLID, 48, 4, 2, relaxation=1e3)
    ga = np.repeat(2 * np.pi * np.arange(48) / 48, 5)
    film.left = np.column_stack([np.cos(ga), np.sin(ga)])
    film.modal = np.zeros((2, ga.size))
    A, beta = 4e-6, 2.0
    s = JournalState(eps=0.6, eps_dot=20.0, gamma=0.7, gamma_dot=40.0, omega=62.5)
    F, _ = film.rates(s, A * np.array([np.cos(beta), np.sin(beta)]))
    # H = 1 + v . (cos alpha, sin alpha): v = eps (-cos gamma, -sin gamma) + A/c (cos, sin) beta
    g, e, c = s.gamma, s.eps, B.clearance
    v = e * np.array([-np.cos(g), -np.sin(g)]) + A / c * np.array([np.cos(beta), np.sin(beta)])
    dv = -np.array([s.eps_dot * np.cos(g) - e * s.gamma_dot * np.sin(g),
                    s.eps_dot * np.sin(g) + e * s.gamma_dot * np.cos(g)])
    eps = np.hypot(*v)
    gamma = np.arctan2(v[1], v[0]) - np.pi
    same = JournalState(eps=eps, eps_dot=v @ dv / eps, gamma=gamma,
                        gamma_dot=(v[0] * dv[1] - v[1] * dv[0]) / eps**2, omega=62.5)
    rigid = solve_reynolds(B, same, 48, 4, "P1", "reynolds", half=False).force_local
    got = np.array(local_to_inertial(*F, s.gamma))
    want = np.array(local_to_inertial(*rigid, same.gamma))
    assert np.linalg.norm(got - want) < 3e-3 * np.linalg.norm(want)


def test_a_closed_gap_needs_the_summits():
    """Past the circle with an undeflected bush (eps 1.1, q = 0) the rigid gap is closed on
    an arc: without roughness the film raises, naming roughness; with it the summits carry
    the contact. Their force against an independent quadrature of Greenwood-Tripp's
    pressure on the rigid gap, F_r = L R int p_a(c (1 + eps cos theta)) cos theta dtheta:
    0.16 % at 24 cells (0.24 %, 0.036 % at 48, 96), asserted 0.5 %. Fails with the summits'
    pressure left out of the force or halved, its inertial share or its friction left at zero."""
    from scipy.integrate import quad
    from bearingfem import ElasticJournalState
    from bearingfem.errors import ConvergenceError
    s = ElasticJournalState(eps=1.1, omega=62.5)
    with pytest.raises(ConvergenceError, match="roughness"):
        ModalStateEHD(B, None, SOLID, NT, NZ, M).rates(s, np.zeros(M))
    rough = Roughness(sigma=0.2e-6, contact_modulus=80.8e9, elastic_factor=1e-3, friction=0.1)
    film = ModalStateEHD(B, None, SOLID, NT, NZ, M, roughness=rough)
    sol = film.solution(s, np.zeros(M))
    c = B.clearance
    exact = B.length * B.radius * quad(
        lambda t: float(rough.pressure(np.array([c * (1 + 1.1 * np.cos(t))]))[0]) * np.cos(t),
        0.0, 2 * np.pi, limit=400, points=[np.pi])[0]
    assert abs(sol.asperity_force_local[0] - exact) < 5e-3 * abs(exact)
    F, qdot = film.rates(s, np.zeros(M))
    assert np.allclose(F, np.add(sol.force_local, sol.asperity_force_local), rtol=1e-9)
    # the inertial share too (the force on the journal, film + summits, inertial); and
    # what a run's record takes: |summits' force|
    assert np.allclose(sol.total_force, local_to_inertial(*F, s.gamma), rtol=1e-9)
    assert np.isclose(sol.asperity_load, np.hypot(*np.subtract(F, sol.force_local)),
                      rtol=1e-9)
    # the summits' Coulomb friction on their load L R int p_a dtheta (quadrature as above):
    # 0.88 %, 0.10 %, 2e-4 % at 24, 48, 96 cells, asserted 1.5 %
    load = B.length * B.radius * quad(
        lambda t: float(rough.pressure(np.array([c * (1 + 1.1 * np.cos(t))]))[0]),
        0.0, 2 * np.pi, limit=400, points=[np.pi])[0]
    torque = 0.1 * load * B.radius
    assert abs(sol.asperity_friction_torque - torque) < 1.5e-2 * torque


#: A trial state of the seed pin's 24-mode run (48 x 4, tau 1e-5 s, isoviscous
#: Dowson-Higginson oil, sigma 0.2 um) 0.82 turn from top dead centre, past the clearance
#: circle: the modal coordinates q [m] and the journal's state where the film's Newton
#: with a monotone line search stalled from every start, and the integration loop cut
#: the step seven times.
STALLED_Q = [8.186035980059215e-07, -1.113441045147666e-06, -9.820708785141343e-07,
             -7.720995503263812e-07, -1.1852608088032059e-12, 1.5659628855920592e-12,
             -5.153262140793355e-07, 1.3014465220507385e-12, -2.5754977846141253e-07,
             1.0038547456786452e-12, -3.7691274556946686e-08, 7.38127815141578e-13,
             1.2548957081672396e-07, -2.821805313348825e-07, -5.393807447615801e-07,
             -7.305870279463734e-07, 2.983824997416429e-13, -8.253178549215168e-07,
             5.151290753742706e-13, -8.195747182992909e-07, 6.376756455693716e-13,
             -7.36464481365951e-07, 6.952040820693769e-13, -6.095143338808372e-07]


def stalled_film():
    """The film and journal state of :data:`STALLED_Q` (24 modes, 48 x 4, rough)."""
    from bearingfem import ElasticJournalState
    state = ElasticJournalState(eps=1.0173895031337534, eps_dot=-31.85916587452895,
                                gamma=0.2613119896931125, gamma_dot=-39.118469493646735,
                                omega=-2.256261384742247)
    oil = Lubricant(viscosity=B.viscosity, density="dowson-higginson")
    rough = Roughness(sigma=0.2e-6, contact_modulus=80.8e9, elastic_factor=1e-3)
    return ModalStateEHD(B, oil, SOLID, 48, 4, 24, 1e-5, rough), state


def test_nonmonotone_newton_solves_where_a_monotone_one_stalled():
    """At :data:`STALLED_Q` the film's cold Newton converges with the nonmonotone line
    search (the last 10 merits), and to the same film from other starts: its pressure
    perturbed by 20 % noise (five draws) gives back the force and dq/dt to 1e-9 relative
    (measured 1e-15 and 6e-14). Fails with a monotone search (MEMORY = 1 in
    bearingfem.ehd.newton): the film raises ConvergenceError there, and from most of the
    perturbed starts (the state is where the monotone search stalled in the run; whether
    it does hangs on round-off, so the test asserts the convergence, not the old stall)."""
    one, state = stalled_film()
    force, rate = one.rates(state, STALLED_Q)
    P = one._P.copy()
    for seed in range(5):
        noise = np.random.default_rng(seed).standard_normal(P.size)
        one._P, one._factor = P * (1 + 0.2 * noise), []
        again, rate_again = one.rates(state, STALLED_Q)
        assert np.max(np.abs(np.subtract(again, force))) <= 1e-9 * np.max(np.abs(force))
        assert np.max(np.abs(rate_again - rate)) <= 1e-9 * np.max(np.abs(rate))
