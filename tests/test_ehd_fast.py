"""The EHD film with its compliance applied by FFT and the Newton step by GMRES
(bearingfem.ehd.film_compliance.CirculantCompliance, bearingfem.ehd.newton._KrylovLU) against the
dense route it replaced: the same compliance, the same Newton iterates, the same film to
round-off; an unconverged Krylov solve never returns a film."""
import numpy as np
import pytest
import scipy.linalg as la

import bearingfem.ehd.coupling as coupling
import bearingfem.ehd.film as film
import bearingfem.ehd.newton as newton
from bearingfem import ElasticBush, JournalState, solve_reynolds
from bearingfem.bearing import seed_bearing
from bearingfem.ehd.film_compliance import CirculantCompliance, DofCompliance, dof_compliance
from bearingfem.ehd.implicit import _Frame
from bearingfem.elastic import bush_compliance
from bearingfem.errors import ConvergenceError
from bearingfem.fe.kernel import fe_operator
from bearingfem.lubricant import Lubricant
from bearingfem.ehd.film_compliance import BushJacobian

SEED = seed_bearing(0.2)                 # R 10 mm, L 4 mm, c 20 um, mu 0.0117 Pa s
BRONZE = dict(outer_radius=0.016, modulus=110e9, poisson=0.34)
SOFT = dict(outer_radius=0.016, modulus=5e9, poisson=0.34)
OIL = Lubricant(viscosity=0.0117, barus=2e-8, density="dowson-higginson")
HEAVY = JournalState(eps=0.995, gamma=0.0, omega=250.0)


@pytest.fixture
def dense_route(monkeypatch):
    """Route every EHD film through the dense compliance matrix (the toolkit's route
    before the FFT): the same matrix, materialised, so Newton takes dense LU steps."""
    fast = coupling.dof_compliance

    def dense(bush, bearing, op):
        c = fast(bush, bearing, op)
        return DofCompliance(c.left) if isinstance(c, CirculantCompliance) else c
    return lambda: monkeypatch.setattr(coupling, "dof_compliance", dense)


@pytest.mark.parametrize("model", ["ring", "solid", "liner"])
def test_circulant_compliance_is_the_dense_matrix(model):
    """The FFT product equals the dense compliance matrix (BushCompliance.matrix, the
    toolkit's earlier operator) read at the dofs, to round-off (1e-13 of the largest
    deflection), and so does its materialised matrix. Fails with the spectrum's block
    transposed (solid: the z-coupling is not symmetric on the free ends' rows)."""
    n_theta, n_z = 16, 4
    op = fe_operator(SEED, HEAVY, n_theta, n_z, "P1", None, False, ())
    bush = ElasticBush(model=model, **BRONZE)
    full = bush_compliance(bush, SEED.radius, SEED.length, n_theta, n_z + 1)
    c = dof_compliance(full, SEED, op)
    assert isinstance(c, CirculantCompliance)
    p = np.random.default_rng(3).random(op.mesh.ndofs) * 1e7
    # the dense matrix on the grid: node (j, k) at j (n_z + 1) + k
    expect = (full.matrix() @ p[c.source])[c.node]
    got = c.apply(p)
    assert np.max(np.abs(got - expect)) <= 1e-13 * np.max(np.abs(expect))
    assert not np.any(np.delete(c.left, c.source, axis=1))     # one dof per grid node
    assert np.allclose(c.left @ p, expect, rtol=0, atol=1e-13 * np.max(np.abs(expect)))


@pytest.mark.parametrize("model, oil, state", [
    ("ring", None, HEAVY), ("ring", OIL, HEAVY), ("solid", OIL, HEAVY),
    ("liner", OIL, JournalState(eps=0.9, gamma=0.3, omega=250.0))])
def test_fast_solve_is_the_dense_solve(model, oil, state, dense_route):
    """The seed pin's heavy state (eps 0.995, Reynolds' condition; the bush carries the
    film: p_max falls tenfold from the rigid film's): the FFT-GMRES film takes the same
    Newton iterations as the dense LU film and gives its pressure and deflection to 1e-13
    of their maxima (GMRES stops at 1e-12 of each step's right-hand side; the films
    measured agree to 1.4e-16 .. 3.5e-16: the last Newton step's error squared).
    Fails with the bush's Jacobian left out of the Krylov product (more Newton steps) or
    the compliance's spectrum taken conjugate."""
    bush = ElasticBush(model=model, **(SOFT if model == "liner" else BRONZE))
    n = (48, 4)
    fast = solve_reynolds(SEED, state, *n, bush=bush, lubricant=oil)
    dense_route()
    dense = solve_reynolds(SEED, state, *n, bush=bush, lubricant=oil)
    assert fast.iterations == dense.iterations
    assert np.max(np.abs(fast.pressure - dense.pressure)) <= 1e-13 * dense.pressure_max
    assert np.max(np.abs(fast.deformation - dense.deformation)) <= 1e-13 * np.max(
        np.abs(dense.deformation))


@pytest.mark.parametrize("model", ["ring", "solid"])
def test_fast_jfo_solve_is_the_dense_solve(model, dense_route):
    """The EHD-JFO film (mass-conserving cavitation, soft ring/solid bush, Barus oil) by
    FFT-GMRES equals the dense route's to 1e-13 in pressure, fraction and deflection, in
    as many Newton steps (measured 3e-16 .. 6e-16). Fails with the bush's columns not masked where the Newton step
    takes dR/dphi (the JFO's complementarity columns)."""
    bush = ElasticBush(model=model, **SOFT)
    state = JournalState(eps=0.8, gamma=0.4, omega=250.0)
    kw = dict(cavitation="jfo", ambient_pressure=1e5, bush=bush,
              lubricant=Lubricant(viscosity=SEED.viscosity, barus=2e-8))
    fast = solve_reynolds(SEED, state, 32, 4, **kw)
    dense_route()
    dense = solve_reynolds(SEED, state, 32, 4, **kw)
    assert fast.iterations == dense.iterations
    assert np.max(np.abs(fast.pressure - dense.pressure)) <= 1e-13 * dense.pressure_max
    assert np.max(np.abs(fast.fraction - dense.fraction)) <= 1e-13
    assert np.max(np.abs(fast.deformation - dense.deformation)) <= 1e-13 * np.max(
        np.abs(dense.deformation))


def test_unconverged_krylov_solve_raises(monkeypatch):
    """GMRES held to one product per solve cannot reach the step: every Newton step
    stalls and the solve raises ConvergenceError (no film is returned). Fails if the
    Krylov solve's residual is not checked (a wrong step would then be taken)."""
    monkeypatch.setattr(newton, "KRYLOV_RESTART", 1)
    monkeypatch.setattr(newton, "KRYLOV_MAXITER", 1)
    with pytest.raises(ConvergenceError):
        solve_reynolds(SEED, HEAVY, 48, 4, bush=ElasticBush(model="ring", **BRONZE))


def test_a_solve_reports_its_progress(caplog):
    """The load continuation logs each step at INFO and each Newton iteration at DEBUG
    (bearingfem.ehd.newton); the last step reaches s = 1. Nothing is printed."""
    import logging
    with caplog.at_level(logging.DEBUG, logger="bearingfem.ehd"):
        sol = solve_reynolds(SEED, HEAVY, 24, 4, bush=ElasticBush(model="ring", **BRONZE))
    steps = [r.getMessage() for r in caplog.records if r.levelno == logging.INFO]
    newton_its = [r for r in caplog.records if r.levelno == logging.DEBUG]
    assert steps and steps[-1].startswith("EHD Newton (load continuation): coupling s = 1 "
                                          "converged")
    assert len(newton_its) >= sol.iterations


@pytest.mark.parametrize("model, kw", [
    ("ring", {}), ("solid", dict(lubricant=OIL)),
    ("solid", dict(cavitation="jfo", ambient_pressure=1e5,
                   lubricant=Lubricant(viscosity=SEED.viscosity, barus=2e-8)))])
def test_film_ordering_keeps_the_solve(model, kw, monkeypatch):
    """The Newton block's SuperLU ordering (newton.ORDERING, minimum degree on B^T + B)
    against SuperLU's default (COLAMD), seed pin, eps 0.995 (Reynolds) / 0.8 (JFO, soft
    bush): the same Newton steps, load to 1e-8 (measured 1e-15 .. 1e-16: the same LU up to
    round-off), and GMRES takes as many products within one per solve (the same
    preconditioner). Fails with the block factorised untransposed (a wrong
    preconditioner: GMRES still converges, in more products)."""
    counts = {}

    def counted(solve):
        def wrapper(self, rhs):
            before = self.products
            out = solve(self, rhs)
            counts.setdefault(newton.ORDERING, []).append(self.products - before)
            return out
        return wrapper
    monkeypatch.setattr(newton._KrylovLU, "solve", counted(newton._KrylovLU.solve))
    soft = model == "solid" and "cavitation" in kw
    bush = ElasticBush(model=model, **(SOFT if soft else BRONZE))
    state = JournalState(eps=0.8, gamma=0.4, omega=250.0) if soft else HEAVY
    new = solve_reynolds(SEED, state, 48, 8, bush=bush, **kw)
    monkeypatch.setattr(newton, "ORDERING", "COLAMD")
    old = solve_reynolds(SEED, state, 48, 8, bush=bush, **kw)
    assert new.iterations == old.iterations
    force_new, force_old = np.asarray(new.force), np.asarray(old.force)
    assert np.linalg.norm(force_new - force_old) <= 1e-8 * np.linalg.norm(force_old)
    a, b = np.array(counts["MMD_AT_PLUS_A"]), np.array(counts["COLAMD"])
    assert a.size == b.size and np.max(np.abs(a - b)) <= 1


@pytest.mark.parametrize("model, oil", [("ring", None), ("solid", OIL), ("liner", OIL)])
def test_nested_start_keeps_the_solve(model, oil, monkeypatch):
    """A cold solve on a mesh of more than film.NESTED_NODES nodes starts Newton from the
    film of the mesh half as fine (nested iteration). Seed pin, eps 0.995 (liner: soft,
    eps 0.9), 48 x 8 nested from 24 x 4 against the cold load continuation: the load to
    1e-8 (measured 2e-16 .. 7e-11: both converge to the solver's tolerance), in fewer
    Newton steps on the fine mesh. Fails with the coarse pressure interpolated at the
    wrong angles (a start that stalls: the cold route after MAX_NEWTON wasted steps)."""
    bush = ElasticBush(model=model, **(SOFT if model == "liner" else BRONZE))
    state = JournalState(eps=0.9, gamma=0.3, omega=250.0) if model == "liner" else HEAVY
    prebuilt = bush_compliance(bush, SEED.radius, SEED.length, 48, 9)
    monkeypatch.setattr(film, "NESTED_NODES", 200)
    nested = solve_reynolds(SEED, state, 48, 8, bush=prebuilt, lubricant=oil)
    monkeypatch.setattr(film, "NESTED_NODES", 10**9)
    cold = solve_reynolds(SEED, state, 48, 8, bush=prebuilt, lubricant=oil)
    force_nested, force_cold = np.asarray(nested.force), np.asarray(cold.force)
    assert np.linalg.norm(force_nested - force_cold) <= 1e-8 * np.linalg.norm(force_cold)
    assert nested.iterations < cold.iterations


def test_nested_solve_still_raises(monkeypatch):
    """A Krylov solve held to one product fails on every level: the nested start gives
    up and the cold route raises ConvergenceError (no film is returned)."""
    monkeypatch.setattr(film, "NESTED_NODES", 200)
    monkeypatch.setattr(newton, "KRYLOV_RESTART", 1)
    monkeypatch.setattr(newton, "KRYLOV_MAXITER", 1)
    with pytest.raises(ConvergenceError):
        solve_reynolds(SEED, HEAVY, 48, 8, bush=ElasticBush(model="ring", **BRONZE))


def test_local_compliance_is_factorised_whole(monkeypatch):
    """The liner's compliance is local, so T_H C is sparse on the film's own pattern: the
    Newton matrix is factorised whole (no GMRES: a Krylov solver built for it raises
    here) and the film is the FFT-GMRES route's (BushJacobian.local disabled), the same
    Newton iterations, pressure and deflection to 1e-13 of their maxima (measured 2e-15
    .. 6e-15 on the heavy state, 120 x 20 .. 480 x 80, where it takes half the CPU
    time). Fails with the bush's part added with its sign flipped or without the
    compliance factor (more Newton steps, or none converges)."""
    bush = ElasticBush(model="liner", **SOFT)
    state = JournalState(eps=0.9, gamma=0.3, omega=250.0)

    def refuse(*args, **kwargs):
        raise AssertionError("a GMRES solve for a local compliance")
    with monkeypatch.context() as m:
        m.setattr(newton, "_KrylovLU", refuse)
        whole = solve_reynolds(SEED, state, 96, 8, bush=bush, lubricant=OIL)
    monkeypatch.setattr(BushJacobian, "local", lambda self: None)
    krylov = solve_reynolds(SEED, state, 96, 8, bush=bush, lubricant=OIL)
    assert whole.iterations == krylov.iterations
    assert np.max(np.abs(whole.pressure - krylov.pressure)) <= 1e-13 * krylov.pressure_max
    assert np.max(np.abs(whole.deformation - krylov.deformation)) <= 1e-13 * np.max(
        np.abs(krylov.deformation))


class _LocalFilm:
    """A film of a fixed Jacobian (J, T_H C): what _Factor.at asks of a film."""

    def __init__(self, op, J, bush):
        self.op, self.J, self.bush = op, J, bush

    def jacobian(self, P, s, ev):
        return self.J, self.bush, None


@pytest.mark.parametrize("supply_angle", [None, np.pi])
def test_folded_local_compliance_is_the_dense_bush_part(supply_angle):
    """Where the bush's part T_H C is folded into the sparse Newton matrix (a local
    compliance: BushJacobian.local), the matrix factorised is J + T_H C, the dense
    product of the coupling and the compliance matrix (BushJacobian.toarray), to 1e-14
    of its largest entry: a random T_H and J on the film's pattern, a local compliance
    varying along z (a liner's own compliance times 0.5 .. 1.5 across the length; the
    uniform liner cannot tell a row scaling from a column scaling), 16 x 4, with and
    without a supply line (whose seam's second dof takes no pressure of its own: not
    folded). Fails with T_H scaled by rows instead of columns, or with the seam taken
    as local (each planted)."""
    op = fe_operator(SEED, HEAVY, 16, 4, "P1", supply_angle, False, ())
    liner = bush_compliance(ElasticBush(model="liner", **SOFT), SEED.radius, SEED.length,
                            16, 5)
    c = dof_compliance(liner, SEED, op)
    c = CirculantCompliance(c.spectrum * np.linspace(0.5, 1.5, c.shape[1]), c.shape,
                            c.node, c.source)
    tables = coupling.jacobian_tables(op)
    rng = np.random.default_rng(7)
    data = rng.uniform(-1.0, 1.0, tables.pattern.nnz)
    data[tables.diagonal] += 20.0
    J = tables.pattern.matrix(data)
    T = tables.pattern.matrix(rng.uniform(-1.0, 1.0, tables.pattern.nnz) * 1e12)
    bush = BushJacobian(T, c)
    free = op.mesh.free
    f = newton._Factor.at(_LocalFilm(op, J, bush), np.zeros(op.mesh.ndofs), 1.0, free,
                          np.zeros(free.size, bool), None)
    assert (f.U is None) == (supply_angle is None)
    got = f.J.toarray() + (0.0 if f.U is None else f.U.toarray())
    expect = J.toarray() + bush.toarray()
    assert np.max(np.abs(got - expect)) <= 1e-14 * np.max(np.abs(expect))


@pytest.mark.parametrize("restart", [60, 4])
def test_the_newton_steps_gmres_is_the_dense_solve(restart):
    """The Newton step's GMRES (newton._gmres: classical Gram-Schmidt twice, Givens
    rotations, restarted) on a nonsymmetric 120 x 120 system (I + 0.3 G / sqrt(n), G
    normal: eigenvalues in a disc of radius 0.3 about 1): at tol 1e-3 and 1e-12 the true
    residual within tol (measured 7.0e-4 / 2.8e-13 in 6 / 23 products unrestarted, 7.0e-4 /
    6.7e-13 in 7 / 28 restarted every 4), the residual it reports equal
    to the true one to 1e-10 |b| (it takes no product to check it: the products are the
    Arnoldi steps' alone, one per iteration, plus one a restart), and at 1e-12 the dense
    solve to 1e-10; with 2 products allowed it reports the residual it stopped at
    (> tol: the Newton step then raises). Fails with the earlier rotations not applied to
    a new Hessenberg column (planted, run once)."""
    rng = np.random.default_rng(0)
    n = 120
    A = np.eye(n) + 0.3 * rng.standard_normal((n, n)) / np.sqrt(n)
    b = rng.standard_normal(n)
    for tol in (1e-3, 1e-12):
        count = [0]

        def apply(v):
            count[0] += 1
            return A @ v
        y, reported = newton._gmres(apply, b, tol, restart, 40)
        true = np.linalg.norm(b - A @ y) / np.linalg.norm(b)
        assert true <= tol and reported <= tol
        assert abs(true - reported) <= 1e-10
        if restart == 60:
            assert count[0] < restart      # no product beyond the Arnoldi steps'
    assert np.allclose(y, np.linalg.solve(A, b), rtol=0, atol=1e-10 * np.max(np.abs(y)))
    y, reported = newton._gmres(lambda v: A @ v, b, 1e-12, 2, 1)
    assert reported > 1e-12
    assert abs(np.linalg.norm(b - A @ y) / np.linalg.norm(b) - reported) <= 1e-10


def test_the_chord_allows_its_slack_of_steps_that_miss_the_rate(monkeypatch):
    """newton._chord with ``slack``: a step that cuts max |Phi| by less than ``rate`` ends
    the chord (Newton takes over from the iterate of least residual) only past the first
    ``slack`` such steps. On a scripted residual sequence (the iterate's index picks it):
    1, 2 (a miss), then 1e-3, 1e-7, 1e-12 converges with slack 1 or 2 in 4 steps and
    stops at the miss with slack 0, returning the start; a sequence that keeps growing
    stops after slack + 1 misses, returning the start (least residual). Fails with the
    slack not spent on a miss (planted, run once: the growing sequence runs to max_steps)."""
    sequences = {"recovers": [1.0, 2.0, 1e-3, 1e-7, 1e-12],
                 "grows": [1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0, 128.0]}

    class Factor:
        held = np.zeros(1, bool)

        def step(self, P, phi):
            return np.ones(1)

    for name, seq in sequences.items():
        monkeypatch.setattr(newton, "_merit", lambda film, P, s, free, cav, seq=seq: (
            np.array([seq[int(P[0])]]), 1.0, np.zeros(1, bool), None))
        for slack in (0, 1, 2):
            out, steps, best = newton._chord(None, np.zeros(1), 1.0, np.arange(1), 1e-10,
                                             [Factor()], 7, 0.9, slack)
            if name == "recovers" and slack > 0:
                assert out is not None and steps == 4 and out[0][0] == 4
            else:
                assert out is None and best[0] == 0
                assert steps == slack + 1


def test_the_bush_compliance_build_is_told_once(caplog):
    """Building the bush's compliance (tens of seconds for the 3-D solid, silent before)
    is logged at INFO before and after; a second solve on the same bush reuses it and says
    nothing of it."""
    import logging
    bush = ElasticBush(model="ring", outer_radius=0.0161, modulus=109e9, poisson=0.33)
    with caplog.at_level(logging.INFO, logger="bearingfem.ehd"):
        for _ in range(2):
            solve_reynolds(SEED, HEAVY, 24, 4, bush=bush)
    told = [r.getMessage() for r in caplog.records if "compliance" in r.getMessage()]
    assert len(told) == 2 and told[0] == "bush ring: building its compliance on 24 x 5 " \
        "film nodes" and told[1].startswith("bush ring: compliance built in "), told


def test_the_newton_steps_gmres_reports_what_it_cannot_solve():
    """newton._gmres where its rotations' residual would lie: a residual it reports within
    tol is the true one. A singular system whose right-hand side leaves the range (the
    Krylov space turns invariant: 2 x 2, diag(1, 0) and b = (1, 1), and 200 x 200 with a
    5 x 5 block and b partly outside it, restart 60 < n) reports its true residual (the
    rotations gave 6e-16 and < 1e-12 against the true 0.7 and 0.5: one product taken at
    the breakdown); a product that is not finite reports inf with a finite y (the
    rotations gave 0 and y NaN); a happy breakdown (A = I) the exact solve; b = 0 gives
    y = 0 and residual 0. Fails with the code before the breakdown's product and the
    finite check (run once: the first three)."""
    rng = np.random.default_rng(1)
    small = rng.standard_normal((5, 5)) + 3 * np.eye(5)
    big = np.zeros((200, 200))
    big[:5, :5] = small
    b = np.concatenate([rng.standard_normal(5), rng.standard_normal(195) * 0.1])
    for A, rhs in ((np.diag([1.0, 0.0]), np.ones(2)), (big, b)):
        y, reported = newton._gmres(lambda v: A @ v, rhs, 1e-12, 60, 10)
        true = np.linalg.norm(rhs - A @ y) / np.linalg.norm(rhs)
        assert reported > 1e-12 and abs(reported - true) <= 1e-10 * max(true, 1.0)
    y, reported = newton._gmres(lambda v: np.full_like(v, np.nan), np.ones(6), 1e-12, 60, 10)
    assert reported == np.inf and np.all(np.isfinite(y))
    b = rng.standard_normal(6)
    y, reported = newton._gmres(lambda v: v, b, 1e-12, 60, 10)
    assert reported <= 1e-12 and np.allclose(y, b, rtol=1e-15, atol=0)
    y, reported = newton._gmres(lambda v: v, np.zeros(6), 1e-12, 60, 10)
    assert reported == 0.0 and not np.any(y)


def test_the_newton_steps_gmres_reported_residual_holds_near_a_breakdown():
    """newton._gmres on 2000 small random systems (n 2-11, singular values 1e-14-1, one
    zero in three or repeated, normal and not): a residual reported within tol 1e-12 is
    the true one within 10 tol. Near a breakdown (a basis vector within 1e-8 of the span)
    the rotations' residual is checked by a product: without it one system here reported
    5.8e-13 with a true 1.2e-10 (planted, run once)."""
    rng = np.random.default_rng(5)
    for _ in range(2000):
        n = rng.integers(2, 12)
        Q = np.linalg.qr(rng.standard_normal((n, n)))[0]
        s = 10.0 ** rng.uniform(-14, 0, n)
        s[rng.integers(n)] = 0.0 if rng.random() < 0.3 else s[0]
        A = (Q @ np.diag(s) @ np.linalg.qr(rng.standard_normal((n, n)))[0]
             if rng.random() < 0.5 else Q @ np.diag(s) @ Q.T)
        b = rng.standard_normal(n)
        y, reported = newton._gmres(lambda v: A @ v, b, 1e-12, 60, 2)
        if reported <= 1e-12:
            assert np.linalg.norm(b - A @ y) <= 1e-11 * np.linalg.norm(b)


def test_the_chord_hands_newton_its_least_residual_iterate_where_a_step_fails(monkeypatch):
    """newton._chord where its factorisation fails (GMRES unconverged or a singular LU:
    LinAlgError or splu's RuntimeError) hands Newton the iterate of least residual (None:
    no result) and raises nothing: on the scripted residuals 1, 2 (a miss, within the
    slack) a step failing at the second iterate, or its refactorisation with other held
    rows, returns the start, not the iterate of residual 2. Fails with the step's error
    let through, or the refactorisation returning the last iterate (planted, run once)."""
    seq = [1.0, 2.0, 1e-3, 1e-12]
    monkeypatch.setattr(newton, "_merit", lambda film, P, s, free, cav: (
        np.array([seq[int(P[0])]]), 1.0, np.full(1, P[0] >= 1), None))

    class Factor:
        held = np.zeros(1, bool)

        def __init__(self, error, where):
            self.error, self.where = error, where

        def step(self, P, phi):
            if self.where == "step" and P[0] >= 1:
                raise self.error("GMRES of the EHD Newton step stopped")
            return np.ones(1)

        def with_held(self, held):
            if self.where == "held":
                raise self.error("singular")
            return self

    for where in ("step", "held"):
        for error in (la.LinAlgError, RuntimeError):
            out, steps, best = newton._chord(None, np.zeros(1), 1.0, np.arange(1), 1e-10,
                                             [Factor(error, where)], 7, 0.9, 2)
            assert out is None and steps == 1 and best[0] == 0


def test_a_frames_blended_compliance_follows_its_fraction():
    """_Frame.blended keeps its table per blend fraction a: asked again with another a it
    gives that a's blend ((1 - a)^2 + a^2) c(d) + a (1 - a) (c(d - 1) + c(d + 1)), not the
    first one's (it kept the first table whatever a it was asked for)."""
    op = fe_operator(SEED, HEAVY, 16, 4, "P1", None, False, ())
    cols = np.random.default_rng(3).normal(size=(16, 5, 5))
    frame = _Frame(op, 0.3)
    for a in (0.25, 0.7, 0.25):
        want = ((1 - a) ** 2 + a * a) * cols + a * (1 - a) * (np.roll(cols, 1, axis=0)
                                                               + np.roll(cols, -1, axis=0))
        np.testing.assert_array_equal(frame.blended(cols, a), want.ravel())
