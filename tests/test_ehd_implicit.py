"""The EHD film with the bush's whole deflection advanced by the film's own backward-Euler
step (coupling "implicit", bearingfem.ehd.implicit.ImplicitStepEHD): at dt = 0 it is the
states film (FullStateEHD) at q = w_n; its force is continuous across a commit; its
Newton matrix against differences; a still journal relaxes to the steady EHD film with
the full compliance; as tau -> 0 the deflection is the quasi-static bush's; a short run
of the seed pin against the states film."""
from dataclasses import replace

import numpy as np
import pytest
import scipy.linalg as la

from bearingfem import ElasticJournalState, JournalState, solve_reynolds
from bearingfem.contact import FlowFactors
from bearingfem.ehd.coupling import jacobian_tables
from bearingfem.ehd.implicit import ImplicitStepEHD
from bearingfem.ehd.newton import _newton
from bearingfem.ehd.states import FullStateEHD
from bearingfem.ehd.transient import ehd_compliance
from bearingfem.models.ehd import ehd_run_film

from test_ehd_states import B, NT, NZ, SOLID, STALLED_Q, stalled_film


def _heavy(tau=1e-5, barus=None):
    """The implicit film and the states film at :data:`STALLED_Q`'s state (past the
    circle, summits carrying, cavitated, whirling, Dowson-Higginson oil, 48 x 4), and that
    state's deflection on the bush grid, committed as w_n at t = 0 (``barus`` [1/Pa]: the
    oil's Barus pressure-viscosity coefficient)."""
    part, state = stalled_film()
    w = part.left @ np.asarray(STALLED_Q)
    oil = replace(part.lubricant, barus=barus)
    full = FullStateEHD(B, oil, SOLID, 48, 4, tau, part.roughness)
    film = ImplicitStepEHD(B, oil, SOLID, 48, 4, tau, part.roughness)
    film.start(state, 0.0)
    film._w = w.copy()
    return film, full, state, w


def test_at_no_step_the_film_is_the_states_film():
    """At dt = 0 the step leaves w = w_n and (tau) v = C (p + p_a) - w_n: the states film
    at q = w_n. Force and dw/dt to 1e-8 (measured 1e-15 and 1.2e-15; both films converged
    to the Newton test of 1e-10). Fails with the bush's rate taken at (tau + 2 dt) or the
    summits left out of the bush's load."""
    film, full, state, w = _heavy()
    F_full, rate = full.rates(state, w)
    F = film.force(state, 0.0)
    w_step, v = film.deflection_rate(state, 0.0)
    assert np.allclose(F, F_full, rtol=1e-8, atol=1e-8 * np.hypot(*F_full))
    assert np.array_equal(w_step, w)
    assert np.max(np.abs(v - rate)) < 1e-8 * np.max(np.abs(rate))


def test_the_force_is_continuous_across_a_commit():
    """A commit at t = 1e-7 s moves w_n to the step's w; the film at the same state and
    time (now dt = 0) has the same pressure, force and bush rate: (tau + dt) v = C p - w_n
    gives tau v = C p - (w_n + dt v). Force to 1e-7, rate to 1e-6 of their largest (each
    film converged to 1e-10; measured 0 and 8e-15). Fails when the commit keeps w_n."""
    film, _, state, _ = _heavy()
    t = 1e-7
    before = film.force(state, t)
    _, v_before = film.deflection_rate(state, t)
    step = film.commit(state, t)
    assert step is not None and film.steps == 1 and film.t == t
    after = film.force(state, t)
    _, v_after = film.deflection_rate(state, t)
    assert np.allclose(after, before, rtol=0, atol=1e-7 * np.hypot(*before))
    assert np.max(np.abs(v_after - v_before)) < 1e-6 * np.max(np.abs(v_before))
    assert np.allclose(step.force_local, before, rtol=0, atol=1e-7 * np.hypot(*before))
    # a snapshot restores the kept film: the same force after a further commit undone
    snap = film.snapshot()
    film.commit(state, 2 * t)
    film.restore(snap)
    assert np.allclose(film.force(state, t), after, rtol=0, atol=1e-9 * np.hypot(*after))


@pytest.mark.parametrize("rough", [False, True, "flow"])
def test_the_newton_matrix_is_the_residuals_derivative(rough):
    """dR/dP = J (gap and rate held) + (dR/dv) (dv/dP), the bush's part matrix-free (its
    rate through the compliance by FFT; with summits, S^-1 by Woodbury on their nodes), at dt = 1e-6 s and
    s = 1 and 0.5, along a random direction, against central differences of the residual
    (step 1e-6 max |P|): to 1e-8 of the largest entry (measured 1e-13 smooth and 1e-12
    rough; the held-gap J alone is 7e-4 off). Fails with the gap's step dt dropped from
    the coupling, or the summits' stiffness dropped from S; with Patir & Cheng's flow
    factors ("flow", measured 2e-11 at s = 1, 5e-10 at 0.5), fails with their gap slope
    dE(h_T)/dh dropped from the bush rate's squeeze load (planted: 1.5e-5)."""
    film, _, state, w = _heavy()
    if rough is not True:
        roughness = replace(film.roughness, flow=FlowFactors()) if rough else None
        film = ImplicitStepEHD(B, film.lubricant, SOLID, 48, 4, 1e-5, roughness)
        film.start(state, 0.0)
        film._w = w
    film.force(state, 1e-7)
    P = film._P.copy()
    step = film.step_film(state, 1e-6)
    free = step.op.mesh.free
    d = np.random.default_rng(0).uniform(-1.0, 1.0, P.size) * np.max(np.abs(P))
    h = 1e-6
    for s in (1.0, 0.5):
        J, U, _ = step.jacobian(P, s, step.evaluate(P, s))
        fd = (step.evaluate(P + h * d, s).residual - step.evaluate(P - h * d, s).residual) / (2 * h)
        an = J @ d + U.apply(d)
        assert np.max(np.abs(an - fd)[free]) < 1e-8 * np.max(np.abs(fd[free]))


def _dense_rate_matrix(step, stiffness, s=1.0):
    """S = (tau + dt) I + s dt C T^T K T, dense (C from the compliance's columns)."""
    n = step.run.size
    C = step.run.compliance.on_grid(np.eye(n))
    T = step.frame.left.toarray()
    return step.tau * np.eye(n) + s * step.dt * C @ T.T @ (stiffness[:, None] * T)


@pytest.mark.parametrize("dt", [1e-6, 1e-4])
def test_the_rate_inverse_is_the_dense_solve(dt, monkeypatch):
    """S^-1 of the Newton matrix's products (Woodbury on the nodes whose summits'
    stiffness counts) against a dense solve of S, at the heavy state where the summits
    carry (dt |C| k / (tau + dt) up to 0.41 at dt 1e-6 s, 4.3 at 1e-4 s: S far from
    (tau + dt) I): the residual |S y - b| within the asked 1e-6 |b| (measured 1e-12 to
    4e-12 with 25 of the 65 nodes that have a stiffness), and with all 65 in the set
    (rtol 1e-300) the dense solve to 1e-12 (measured 6e-16). Past the cap (5 nodes) the
    solve is GMRES on S, and a set of the 5 stiffest fails the left-out nodes' bound and
    falls back to GMRES from its solve: both meet 1e-6.
    Fails with the Woodbury's small matrix missing its tau I, or the left-out nodes' bound
    not checked (the capped set returned as it is)."""
    from bearingfem.ehd import bush_rate, implicit
    film, _, state, _ = _heavy()
    film.force(state, 1e-7)
    step = film.step_film(state, dt)
    k = step.at(film._P).stiffness
    S = _dense_rate_matrix(step, k, 0.5)
    b = np.random.default_rng(1).uniform(-1.0, 1.0, (film.size, 2)) * 1e-9
    gain = np.max(k) * dt * film.compliance_norm / step.tau
    assert gain > 0.05
    for rtol in (1e-6, 1e-300):
        inverse = implicit._RateInverse(step, k, rtol, 0.5)
        y = inverse.solve(b)
        assert inverse.active.size > 0 and film.rate_fallbacks == 0
        r = np.linalg.norm(S @ y - b, axis=0) / np.linalg.norm(b, axis=0)
        assert np.all(r <= max(rtol, 1e-12)), r
    assert np.allclose(y, np.linalg.solve(S, b), rtol=0, atol=1e-12 * np.max(np.abs(y)))
    monkeypatch.setattr(bush_rate, "WOODBURY_NODES", 5)
    inverse = implicit._RateInverse(step, k, 1e-6, 0.5)
    y = inverse.solve(b)
    assert inverse.capped and inverse.lu is None
    r = np.linalg.norm(S @ y - b, axis=0) / np.linalg.norm(b, axis=0)
    assert np.all(r <= 1e-6), r
    # the left-out nodes' bound: a set of the stiffest 5 (planted by hand) fails it and
    # falls back to GMRES from its solve
    monkeypatch.setattr(bush_rate, "WOODBURY_NODES", 128)
    inverse = implicit._RateInverse(step, k, 1e-6, 0.5)
    keep = np.argsort(k)[-5:]
    inverse.active = keep
    inverse.left_out = np.max(np.delete(k, keep)) * 0.5 * dt * film.compliance_norm / step.tau
    inverse.dk = 0.5 * dt * k[keep]
    unit = np.zeros((k.size, 5))
    unit[keep, np.arange(5)] = 1.0
    U = film.compliance.on_grid(step.shift.to_grid(unit)) * inverse.dk
    inverse.lu = la.lu_factor(step.tau * np.eye(5) + step.shift.to_nodes(U)[keep])
    y = inverse.solve(b)
    assert film.rate_fallbacks == 2
    r = np.linalg.norm(S @ y - b, axis=0) / np.linalg.norm(b, axis=0)
    assert np.all(r <= 1e-6), r


def test_the_node_compliance_gathered_is_the_products():
    """(T C T^T)[A, A], gathered from the compliance's n_z + 1 grid columns (circulant in
    theta, T a blend of two shifts), against the film nodes' deflection under unit
    pressures by compliance products, T C T^T e_i, at every node of a 48 x 4 film at the
    heavy state at a journal angle a fraction 0.31 of a cell on the grid's and at half a
    cell: to 1e-12 of the largest entry (measured 4e-16). Fails with the blend's a (1 - a)
    (c(d - 1) + c(d + 1)) dropped (planted, run once; with it the dense solve of S
    fails too)."""
    film, _, state, _ = _heavy()
    for a in (0.31, 0.5):
        step = film.step_film(replace(state, gamma=2 * np.pi / 48 * (7 + a) - np.pi), 1e-6)
        assert np.isclose(step.shift.frac, a, atol=1e-9)
        nodes = np.arange(film.size)
        products = step.shift.to_nodes(step.comply(np.eye(film.size)))
        gathered = step.node_compliance(nodes)
        assert np.max(np.abs(gathered - products)) < 1e-12 * np.max(np.abs(products))
    some = np.random.default_rng(2).choice(film.size, 40, replace=False)
    assert np.array_equal(step.node_compliance(some), gathered[np.ix_(some, some)])



@pytest.mark.parametrize("model", ["ring", "liner", "solid-3d"])
def test_the_node_compliance_gathered_is_the_products_for_every_bush(model):
    """The gather of (T C T^T)[A, A] holds for every bush model the film takes: each
    compliance is applied per theta harmonic (circulant by construction: the bush is
    axisymmetric), the ring's diagonal in z, the liner's local. Every node of a 24 x 4
    film at journal angles a fraction 0.31 and 0.5 of a cell on the grid, against
    T C T^T e_i by products: to 1e-12 of the largest entry (measured 4e-16 to 6e-16).
    Fails with the blend's cross term dropped (planted, run once)."""
    film = ImplicitStepEHD(B, None, replace(SOLID, model=model), 24, 4, 1e-5, None)
    state = JournalState(0.6, 0.0, 0.4, 0.0, 100.0)
    film.start(state, 0.0)
    for a in (0.31, 0.5):
        step = film.step_film(replace(state, gamma=2 * np.pi / 24 * (5 + a) - np.pi), 1e-6)
        products = step.shift.to_nodes(step.comply(np.eye(film.size)))
        gathered = step.node_compliance(np.arange(film.size))
        assert np.max(np.abs(gathered - products)) < 1e-12 * np.max(np.abs(products))

@pytest.mark.parametrize("barus", [None, 2e-8])
def test_the_pressure_slopes_are_taken_when_a_newton_matrix_asks(barus, monkeypatch):
    """The lubricant's pressure slopes (Dowson-Higginson density; with Barus's
    pressure-viscosity or without) are not taken at a film evaluation, only when unpacked
    (a Newton matrix); then they are the lubricant's at the evaluation's pressure, bit for
    bit, taken once. Fails with them taken at every evaluation (the count), their order
    swapped, the viscosity's slope not a ratio to mu0, or taken at the pressure without
    the continuation's factor s (the values, Barus's oil)."""
    film, _, state, _ = _heavy(barus=barus)
    film.force(state, 1e-7)
    step = film.step_film(state, 1e-6)
    lub = film.lubricant
    calls = []
    density_derivative = type(lub).density_derivative
    monkeypatch.setattr(type(lub), "density_derivative",
                        lambda self, p: calls.append(1) or density_derivative(self, p))
    P, s = film._P * 1.01, 0.7
    ev = step.evaluate(P, s)
    assert calls == []
    drho, dmu = ev.slopes
    p = s * step.scale * step.op.at_quadrature(P)
    assert np.array_equal(drho, density_derivative(lub, p))
    assert np.array_equal(dmu, lub.viscosity_derivative(p) / B.viscosity)
    assert (np.max(np.abs(dmu)) > 0.0) == (barus is not None)
    drho_again, _ = ev.slopes
    assert drho_again is drho and len(calls) == 1


@pytest.mark.parametrize("dt", [0.0, 1e-4])
def test_the_bush_rate_solves_its_equation_from_the_held_summits_start(dt, monkeypatch):
    """The bush rate with the summits (_StepFilm.rate) starts from the summits' pressure
    held at the last evaluation's and returns that start, without a compliance product,
    where the bound |C| |p_a(w) - p_held| passes its test. At the heavy state (summits
    carrying) the returned v solves (tau + dt) v + w_n = C (p + p_a(w_n + dt v)) to the
    rate's test RATE_TOL, from a fresh film (held at w_n) and from a memo at another
    pressure; at dt = 0 (w = w_n: the summits cannot move) one compliance product each,
    at dt = 1e-4 s (dt |C| k / (tau + dt) up to 4.3) the Newton after the start.
    Fails with the start returned unchecked (the bound's test dropped: the film's solve
    at the heavy state no longer converges, ConvergenceError; planted, run once)."""
    from bearingfem.ehd import implicit
    film, _, state, _ = _heavy()
    film.force(state, 1e-7)
    P0 = film._P
    step = film.step_film(state, dt)
    calls = []
    comply = step.comply
    monkeypatch.setattr(step, "comply", lambda p: calls.append(1) or comply(p))
    for P in (P0, 1.01 * P0):
        calls.clear()
        v, w, pa, h = step.rate(P)
        products = len(calls)
        step._last = implicit._Memo(P.copy(), 1.0, step._build(P, 1.0))
        assert np.array_equal(pa, film.roughness.pressure(h))
        assert np.array_equal(h, film.bearing.clearance * step._nodal_gap(w))
        load = comply(step.scale * P + pa)
        r = step.tau * v + step.w_n - load
        size = np.max(np.abs(step.tau * v) + np.abs(step.w_n) + np.abs(load))
        assert np.max(np.abs(r)) <= implicit.RATE_TOL * size, np.max(np.abs(r)) / size
        assert (products == 1) if step.dt == 0.0 else (products > 1)


def _moving(s0, t):
    """The state ``s0`` carried on its own rates to time ``t`` [s]."""
    return ElasticJournalState(eps=s0.eps + s0.eps_dot * t, eps_dot=s0.eps_dot,
                               gamma=s0.gamma + s0.gamma_dot * t, gamma_dot=s0.gamma_dot,
                               omega=s0.omega)


def _predicted_and_cold(t):
    """The heavy film committed at 1e-5 and 2e-5 s (its state moving on its rates), the
    two commits' pressures, and the film's solve at the trial time ``t`` [s] from the
    start extrapolated from those commits and from the last commit's pressure alone (the
    start before)."""
    film, _, s0, _ = _heavy()
    pressures = []
    for t_k in (1e-5, 2e-5):
        film.commit(_moving(s0, t_k), t_k)
        pressures.append(film._P.copy())
    start = film.start_pressure(t, pressures[0].size)
    assert film.start_pressure(2e-5, start.size) is film._P   # the corrector at one time
    snap = film.snapshot()
    _, predicted = film.solve(_moving(s0, t), t)
    film.restore(replace(snap, committed=snap.committed[-1:]))
    _, cold = film.solve(_moving(s0, t), t)
    return pressures, start, predicted, cold


def test_the_predicted_start_lands_on_the_cold_starts_step():
    """Commits at 1e-5 and 2e-5 s, a trial at 3e-5 s: the start is the two commits'
    pressures extrapolated, max(P_2 + (P_2 - P_1), 0), to round-off (the times' ratio), and from it the solve
    lands on the same pressure as from the last pressure alone, to 1e-8 of its largest
    (both converged to the Newton test of 1e-10: measured 1.1e-10). Fails with the
    extrapolation's sign flipped (planted)."""
    (P1, P2), start, predicted, cold = _predicted_and_cold(3e-5)
    assert np.allclose(start, np.maximum(P2 + (P2 - P1), 0.0), rtol=0, atol=1e-12 * P2.max())
    assert np.max(np.abs(predicted.pressure - cold.pressure)) < 1e-8 * np.max(cold.pressure)


def test_a_new_time_takes_one_fresh_newton_matrix(monkeypatch):
    """Commits at 1e-5 and 2e-5 s, then trials at 3e-5 s (the journal's eps moved by 0,
    1e-6, 2e-6: the predictor and corrector) and at 4e-5 s: the first solve at each new
    time factorises the Newton matrix once, at its start, and the solves at that time
    take their chord steps on it (no matrix built): 4 chord steps at 3e-5 s and 2 for the
    corrector's (measured; the matrix kept from the commits' time took 6 and 3), each
    pressure the cold solve's to 1e-8. Fails when the matrix is kept across times
    (planted: no factorisation at 3e-5 s, 6 and 3 chord steps)."""
    from bearingfem.ehd import newton
    built = []
    at = newton._Factor.at.__func__
    monkeypatch.setattr(newton._Factor, "at",
                        classmethod(lambda cls, *a: built.append(1) or at(cls, *a)))
    film, _, s0, _ = _heavy()
    for t in (1e-5, 2e-5):
        film.commit(_moving(s0, t), t)
    snap = film.snapshot()
    other, _, _, _ = _heavy()              # the cold solves: from the last commit's P
    for t, d, most in ((3e-5, 0.0, 4), (3e-5, 1e-6, 2), (3e-5, 2e-6, 2)):
        state = replace(_moving(s0, t), eps=_moving(s0, t).eps + d)
        before = len(built)
        _, res = film.solve(state, t)
        assert len(built) - before == (1 if d == 0.0 else 0)
        assert res.iterations <= most and film._factor_t == t
        other.restore(replace(snap, committed=snap.committed[-1:]))
        _, cold = other.solve(state, t)
        assert np.max(np.abs(res.pressure - cold.pressure)) < 1e-8 * np.max(cold.pressure)
    before = len(built)
    film.solve(_moving(s0, 4e-5), 4e-5)
    assert len(built) > before and film._factor_t == 4e-5


def test_where_the_step_doubles_newton_converges_from_the_last_pressure():
    """Commits at 1e-5 and 2e-5 s, then the trial at 4e-5 s (the step doubled, as the
    integrator does) from the last commit's pressure: the semismooth Newton at s = 1
    converges in at most 10 steps (measured 5), and its pressure solves the complementarity
    problem with the film's own diagonal as the weight, min(d P, R) = 0, not only the
    floored one: to the Newton test of 1e-10 of the residual's scale (measured 4.1e-11;
    d spans 1.9e-7 of its largest there). Fails with no floor (NCP_FLOOR = 0 in
    bearingfem.ehd.newton, planted: Newton stalls after 30 steps, and the continuation in
    s took 407 before the floor)."""
    film, _, s0, _ = _heavy()
    for t in (1e-5, 2e-5):
        film.commit(_moving(s0, t), t)
    step = film.step_film(_moving(s0, 4e-5), 4e-5)
    free = step.op.mesh.free
    out, its = _newton(step, film._P.copy(), 1.0, free, "reynolds", 1e-10)
    assert out is not None and its <= 10
    ev = step.evaluate(out[0])
    d = ev.values[jacobian_tables(step.op).stiffness_diagonal][free]
    phi = np.minimum(d * out[0][free], ev.residual[free])
    assert np.max(np.abs(phi)) <= 1e-10 * np.max(ev.size[free])


def test_a_journal_held_still_relaxes_to_the_steady_full_ehd_film():
    """A still journal (eps 0.9, 24 x 4, no summits) from an undeflected bush, committed
    every 1e-3 s (a hundred relaxation times: the step is nearly the quasi-static bush; the
    squeeze of the bush's motion slows the relaxation: at 1e-4 s steps the force is 9e-8
    off after 30): w relaxes to the steady EHD solve with the full compliance, force to
    1e-8 and deflection to 1e-7 of its largest, the bush's rate to 1e-9 m/s (measured after
    15 steps: 7e-10, 8e-10, 0). Fails with the squeeze's sign flipped or w_n left out of the
    rate."""
    s = JournalState(eps=0.9, gamma=np.pi, omega=62.5)
    film = ehd_run_film(B, bush=SOLID, n_theta=NT, n_z=NZ, modes=0, coupling="implicit",
                        relaxation=1e-5)
    assert isinstance(film, ImplicitStepEHD) and film.state_size == 0 and film.memory
    film.start(s, 0.0)
    for k in range(1, 16):
        film.commit(s, 1e-3 * k)
    F = film.force(s, film.t)
    _, v = film.deflection_rate(s, film.t)
    steady = solve_reynolds(B, s, NT, NZ, "P1", "reynolds",
                            bush=ehd_compliance(SOLID, B.radius, B.length, NT, NZ, 0))
    assert np.allclose(F, steady.force_local, rtol=1e-8, atol=0)
    assert np.max(np.abs(v)) < 1e-9
    sol, _ = film.solution(s, film.t)
    assert np.allclose(sol.deformation, steady.deformation, rtol=0,
                       atol=1e-7 * np.max(np.abs(steady.deformation)))


def test_with_no_relaxation_time_left_the_bush_is_quasi_static():
    """tau 1e-12 s against steps of 1e-5 s (a still journal, eps 0.9, 24 x 4, from an
    undeflected bush): each step's deflection is C p of its own pressure (the
    quasi-static bush) to 1e-6 of its largest (the equation leaves tau v = 1e-7 of it:
    measured 1.0e-7 and 4.5e-8), and its rate is the backward difference (w - w_n) / dt. Fails with
    the rate taken at tau alone (no dt)."""
    s = JournalState(eps=0.9, gamma=np.pi, omega=62.5)
    film = ImplicitStepEHD(B, None, SOLID, NT, NZ, 1e-12)
    film.start(s, 0.0)
    dt = 1e-5
    for k in (1, 2):
        w_n = film._w.copy()
        film.force(s, k * dt)
        step = film.step_film(s, k * dt)
        out = step.at(film._P)
        quasi = step.comply(step.scale * film._P)
        assert np.max(np.abs(out.w - quasi)) < 1e-6 * np.max(np.abs(quasi))
        assert np.allclose(out.v, (out.w - w_n) / dt, rtol=1e-9, atol=0)
        film.commit(s, k * dt)


def test_bad_input_is_refused_by_name():
    with pytest.raises(ValueError, match="relaxation"):
        ImplicitStepEHD(B, None, SOLID, NT, NZ, 0.0)
    with pytest.raises(ValueError, match="bush"):
        ImplicitStepEHD(B, None, None, NT, NZ)
    with pytest.raises(ValueError, match="modes"):
        ehd_run_film(B, bush=SOLID, n_theta=NT, n_z=NZ, modes=8, coupling="implicit")
    film = ImplicitStepEHD(B, None, SOLID, NT, NZ)
    s = JournalState(eps=0.5, omega=62.5)
    film.start(s, 1.0)
    with pytest.raises(ValueError, match="t must be"):
        film.force(s, 0.5)
    with pytest.raises(ValueError, match="state_size 0"):
        film.rates(s, np.zeros(1), 1.0)


@pytest.mark.slow
def test_the_seed_pin_runs_as_with_the_states_film():
    """The seed pin at 250 rad/s, 1 % of a turn from a centred start, 24 x 4, rough (sigma
    0.2 um), 2 um crown: the implicit step against the whole deflection integrated as
    states (FullStateEHD, the integrator's error control on w): peak eps to 2e-3 and least
    film to 3e-3 c, every accepted step recorded. Measured at the test's rtol 1e-6: 8.5e-4
    and 9e-5 c; the least film's bound is the backward Euler step's O(dt) error, which the
    integrator does not control and any change of the steps re-samples: 1.7e-3 c and
    2.0e-3 c from the states film at rtol 1e-7 and 1e-8 (docs/ehd-states.md, "Why 1.74x
    the steps"). Fails with the bush's rate halved in the squeeze (peak eps 1.2512 against
    1.2917, least film -0.07 um against 1.47 um); with the rate dropped the run does not
    finish in 15 min."""
    from bearingfem.contact import Roughness
    from bearingfem.fields import EdgeProfile
    from benchmarks.ehd_run import scene
    from mechanism import simulate
    rough = Roughness(sigma=0.2e-6, contact_modulus=80.8e9, elastic_factor=1e-3)
    runs = {}
    for coupling in ("states", "implicit"):
        sc = scene("paper-short-ehd-sharp", 250.0, 0.01, n_theta=NT, n_z=NZ, modes=0,
                   film_step=0.0, lubricant=None, coupling=coupling, relaxation=1e-5,
                   roughness=rough, profile=EdgeProfile("crown", 2e-6))
        runs[coupling] = simulate(sc, progress=False)
    states, implicit = runs["states"], runs["implicit"]
    assert not implicit.partial and len(implicit.film_record) == implicit.stats["steps"]
    assert abs(implicit.eps.max() - states.eps.max()) < 2e-3 * states.eps.max()
    assert abs(implicit.film_min.min() - states.film_min.min()) < 3e-3 * 20e-6


def test_a_ctrl_c_keeps_the_steps_taken(ctrl_c_at_film_force):
    """A real Ctrl-C (SIGINT to this process) at the 80th film force of the seed pin's run
    with the implicit film (24 x 4, rough, crowned; 0.2 turn asked): the run comes back
    partial, marked interrupted, with every accepted step's film record (the film's
    commits) from t = 0. Fails when the film's commit does not return its step (the
    record is then empty)."""
    from bearingfem.contact import Roughness
    from bearingfem.fields import EdgeProfile
    from benchmarks.ehd_run import scene
    from mechanism import simulate
    forces = ctrl_c_at_film_force(80)
    rough = Roughness(sigma=0.2e-6, contact_modulus=80.8e9, elastic_factor=1e-3)
    sc = scene("paper-short-ehd-sharp", 250.0, 0.2, n_theta=NT, n_z=NZ, modes=0, film_step=0.0,
               lubricant=None, coupling="implicit", relaxation=1e-5, roughness=rough,
               profile=EdgeProfile("crown", 2e-6))
    r = simulate(sc, progress=False)
    assert forces["n"] >= 80
    assert r.partial and r.message.startswith("interrupted at t = ")
    assert r.t[0] == 0.0 and np.all(np.isfinite(r.eps))
    assert len(r.film_record) == r.stats["steps"] > 10


def test_the_shipped_scene_is_the_benchmarks_pin_with_the_scenes_oil():
    """paper-short-ehd (the shipped scene, whose five turns run: 487 s wall on the 2-core
    machine, peak eps 1.22) is benchmarks/ehd_implicit.py's crowned rough pin at 48 x 4
    with the scenes' Roelands oil, and paper-short-ehd-sharp's slider-crank, bearing,
    start and run: its film options equal the benchmark's, built from
    paper-short-ehd-sharp (the sharp bore's modal film), to the last value. Fails with any
    of the scene's film tables (coupling, relaxation, profile, roughness) changed."""
    from benchmarks.common import scene
    from benchmarks.ehd_implicit import CROWN
    from benchmarks.ehd_states import ROUGH
    from mechanism import load_scene
    base = load_scene("paper-short-ehd-sharp")
    shipped = load_scene("paper-short-ehd")
    bench = scene("paper-short-ehd-sharp", 250.0, 5, n_theta=48, n_z=4, modes=0, film_step=0.0,
                  coupling="implicit", relaxation=1e-5, roughness=ROUGH, profile=CROWN)
    assert shipped.lubrication.options == bench.lubrication.options
    assert shipped.lubrication.model == base.lubrication.model == "fem-ehd"
    assert (shipped.mechanism, shipped.bearing, shipped.crank_speed, shipped.run) == \
        (base.mechanism, base.bearing, base.crank_speed, base.run)
