"""The transient EHD-JFO film (bearingfem.ehd.jfo_transient): rigid-bush limit against the
rigid transient JFO film, the steady limit of a journal held still, the oil balance per
step with the bush's squeeze."""
import numpy as np
import pytest

from bearingfem import JournalState, solve_reynolds
from bearingfem.bearing import seed_bearing
from bearingfem.ehd.jfo_transient import EHDJFOFilm
from bearingfem.elastic import ElasticBush
from bearingfem.fe.jfo import JFOFilm

SEED = seed_bearing(0.2)                 # R 10 mm, L 4 mm, c 20 um, mu 0.0117 Pa s
STIFF = ElasticBush(outer_radius=0.016, modulus=1e30, poisson=0.34, model="ring")
SOFT = ElasticBush(outer_radius=0.016, modulus=5e9, poisson=0.34, model="ring")
N = (48, 4)
AMBIENT = 1e5
DT = 2e-4


def moving(i):
    """A journal moving out and turning (squeeze and whirl: the step's transport 6 omega
    differs from the steady wedge 6 (omega - 2 gamma_dot))."""
    return JournalState(eps=0.6 + 0.05 * i, gamma=0.4 + 0.1 * i, omega=250.0,
                        eps_dot=0.05 / DT, gamma_dot=0.1 / DT)


def test_rigid_bush_is_the_rigid_transient_jfo_film():
    """E = 1e30 Pa: five steps equal JFOFilm's on the same whole-length mesh (P to 1e-12 of
    its peak, phi to 1e-12, force to 1e-10; measured 6e-14, 4e-16, 1e-14). Fails with the
    Couette content moved at the steady wedge speed omega - 2 gamma_dot (7 % off)."""
    e = EHDJFOFilm(SEED, moving(0), *N, STIFF, ambient_pressure=AMBIENT)
    r = JFOFilm(SEED, moving(0), *N, half=False, ambient_pressure=AMBIENT)
    for i in range(1, 6):
        a, b = e.advance(moving(i), DT), r.step(moving(i), DT)
        assert np.max(np.abs(a.P * SEED.pressure_scale - b.pressure)) <= 1e-12 * b.pressure_max
        assert np.max(np.abs(a.fraction - b.fraction)) <= 1e-12
        assert np.allclose(a.force, b.force_local, rtol=1e-10, atol=0.0)
    assert a.fraction.min() < 0.9            # a cavity is there


def test_journal_held_still_tends_to_the_steady_ehd_jfo_film():
    """The film of a still journal after 20 steps of 10 ms from a full undeformed film is
    the steady EHD-JFO film (P to 1e-9 of its peak, phi to 1e-8: the steps converge by a
    factor ~6 each to the Newton tolerance 1e-10, measured 4e-11 and 4e-10 after 14 steps).
    Fails with the deflection's share of the new content dropped (the bush's squeeze:
    the content balance then holds the rigid gap's content)."""
    s = JournalState(eps=0.8, gamma=0.4, omega=250.0)
    steady = solve_reynolds(SEED, s, *N, bush=SOFT, cavitation="jfo",
                            ambient_pressure=AMBIENT)
    e = EHDJFOFilm(SEED, s, *N, SOFT, ambient_pressure=AMBIENT)
    for _ in range(20):
        a = e.advance(s, 1e-2)
    assert np.max(np.abs(a.P * SEED.pressure_scale - steady.pressure)) \
        <= 1e-9 * steady.pressure_max
    assert np.max(np.abs(a.fraction - steady.fraction)) <= 1e-8
    assert np.allclose(a.deformation, steady.deformation, rtol=0.0,
                       atol=1e-9 * np.max(np.abs(steady.deformation)))
    assert steady.fraction.min() < 0.9 and np.max(np.abs(steady.deformation)) > 1e-7


def test_oil_balance_per_step_with_the_bush_moving():
    """Soft bush, moving journal: the change of the free volumes' content (phi Q(H) less
    the kept content, the deflection's rate in it) equals the net inflow from the fixed
    nodes (the operator's and transport's flows there: K and T conserve, so the total over
    all nodes is zero) to 1e-9 of the flows' size (measured ~1e-14). Fails with the
    deflection's share of the new content dropped from the balance."""
    e = EHDJFOFilm(SEED, moving(0), *N, SOFT, ambient_pressure=AMBIENT)
    for i in range(1, 5):
        a = e.advance(moving(i), DT)
        assert abs(a.inflow - a.content_rate) <= 1e-9 * abs(a.content_rate)
        assert np.max(np.abs(a.deformation)) > 1e-8


def test_steps_warm_from_the_kept_film_need_no_continuation(monkeypatch):
    """Each step of a journal moving out and turning (the film-step benchmark's sequence,
    bronze ring bush, 8 modes, 24 x 2) converges by Newton at s = 1 from the kept film
    (the solve's ``warm``), in at most 6 iterations (measured 3-5), where a fallback to
    the load continuation takes 20 or more. Fails without the watchdog of the Newton's
    line search: step 11 then moves two volumes across the cavity's boundary, |R| rises,
    the backtracking creeps and stalls, and the step takes 29 iterations."""
    import bearingfem.ehd.jfo_transient as transient
    from benchmarks.ehd_jfo_run import DT as BENCH_DT, RING as BENCH_RING, state
    from bearingfem.bearing import Bearing
    from bearingfem.elastic import bush_compliance
    warm, original = [], transient.solve_ehd_jfo

    def solve(*args, **kwargs):
        out = original(*args, **kwargs)
        warm.append(out.warm)
        return out
    monkeypatch.setattr(transient, "solve_ehd_jfo", solve)
    b = Bearing(radius=0.01, length=0.01, clearance=20e-6, viscosity=0.0117)
    modes = bush_compliance(BENCH_RING, b.radius, b.length, 24, 3).reduced(8)
    e = EHDJFOFilm(b, state(0), 24, 2, modes, ambient_pressure=AMBIENT)
    iterations = [e.advance(state(i), BENCH_DT).iterations for i in range(1, 13)]
    assert all(warm) and len(warm) == 12, warm
    assert max(iterations) <= 6, iterations
    assert e.fraction.min() < 0.9            # a cavity is there


def test_bad_step_raises():
    e = EHDJFOFilm(SEED, moving(0), *N, SOFT, ambient_pressure=AMBIENT)
    with pytest.raises(ValueError, match="dt"):
        e.advance(moving(1), 0.0)


# --- the "fem-ehd" model with cavitation="jfo" in the mechanism -------------------------

RING = dict(outer_radius=0.016, modulus=110e9, poisson=0.34, model="ring")


def _quarter_scene(model, **lub):
    """A tenth of a turn of a short pin (L/D 0.5), coarse film (32 x 4)."""
    from mechanism import parse_scene
    return parse_scene({"name": "ehd-jfo", "bearing": {"diameter": 0.02, "length_ratio": 0.5,
                                                       "clearance": 20e-6,
                                                       "viscosity": 0.0117},
                        "run": {"turns": 0.1, "record_from_turn": 0, "samples_per_turn": 400},
                        "effects": {"lubrication": {"model": model, "n_theta": 32, "n_z": 4,
                                                    "film_step": 2e-4, **lub}}})


def test_model_option_picks_the_run_film():
    from bearingfem.ehd.jfo_run import TransientEHDJFO
    from bearingfem.ehd.transient import TransientEHD
    from bearingfem.models import film_model
    m = film_model("fem-ehd")
    assert isinstance(m.along_run(SEED, dict(n_theta=24, n_z=4, bush=SOFT, modes=8)),
                      TransientEHD)
    assert isinstance(m.along_run(SEED, dict(n_theta=24, n_z=4, bush=SOFT, modes=8,
                                             cavitation="jfo")), TransientEHDJFO)
    with pytest.raises(ValueError, match="bush"):
        m.along_run(SEED, dict(n_theta=24, n_z=4, cavitation="jfo"))


def test_rigid_bush_run_is_the_fem_jfo_run(monkeypatch):
    """E = 1e25 Pa: the mechanism's run with fem-ehd cavitation "jfo" follows fem-jfo's.
    With the rigid film's early-step policy the two runs are the same film (centre within
    1e-11 m, measured 1.6e-13 m: half and whole meshes); with the EHD-JFO film's own
    (early steps >= film_step / 4) within the run's absolute tolerance 2e-9 m (1.3e-9 m
    measured). Fails with the kept cavities dropped between film steps (the instant film
    then the Reynolds film everywhere)."""
    from mechanism import simulate
    from bearingfem.ehd.jfo_run import TransientEHDJFO
    from bearingfem.transient import EARLY
    stiff = dict(RING, modulus=1e25)
    jfo = simulate(_quarter_scene("fem-jfo"), progress=False)
    ehd = simulate(_quarter_scene("fem-ehd", bush=stiff, modes=0, cavitation="jfo"),
                   progress=False)
    assert not jfo.partial and not ehd.partial, ehd.message
    assert np.max(np.hypot(jfo.e_x - ehd.e_x, jfo.e_y - ehd.e_y)) < 2e-9
    monkeypatch.setattr(TransientEHDJFO, "early_fraction", EARLY)
    same = simulate(_quarter_scene("fem-ehd", bush=stiff, modes=0, cavitation="jfo"),
                    progress=False)
    assert np.max(np.hypot(jfo.e_x - same.e_x, jfo.e_y - same.e_y)) < 1e-11


def test_bronze_bush_run_has_no_nan_and_moves_the_orbit():
    """Bronze ring bush (8 modes): the run completes with finite forces, its orbit off the
    rigid fem-jfo run's by more than the run's tolerance (the bush: 3.1e-7 m measured) and
    within 1 um of it (a tenth of a turn)."""
    from mechanism import simulate
    jfo = simulate(_quarter_scene("fem-jfo"), progress=False)
    run = simulate(_quarter_scene("fem-ehd", bush=RING, modes=8, cavitation="jfo"),
                   progress=False)
    assert not run.partial, run.message
    assert np.all(np.isfinite(run.force_x)) and np.all(np.isfinite(run.force_y))
    d = np.max(np.hypot(jfo.e_x - run.e_x, jfo.e_y - run.e_y))
    assert 1e-8 < d < 1e-6


@pytest.mark.parametrize("dt", [1e-2, 2e-7])
def test_step_jacobian_is_exact(dt):
    """The step's dR/dP (the bush through faces and content) and dR/dphi against central
    differences at a random (P, phi), full compliance: 1e-6 of the column's size (measured
    1e-8 .. 1e-7 with h = 1e-3, truncation and round-off of a residual of size 12 Q / dt).
    Fails with the content's slope 12 phi / dt dQ/dH left out of dR/dP (3e-1 off)."""
    from bearingfem.ehd.transient import ehd_compliance
    b = seed_bearing(0.5)
    comp = ehd_compliance(ElasticBush(outer_radius=0.016, modulus=110e9, poisson=0.34,
                                      model="ring"), b.radius, b.length, 32, 4, 0)
    s = JournalState(eps=0.5, gamma=0.3, omega=250.0)
    film, _ = EHDJFOFilm(b, s, 32, 4, comp, ambient_pressure=AMBIENT).coupling(s, dt)
    n = film.op.mesh.ndofs
    rng = np.random.default_rng(0)
    P = film.P_fixed + 30.0 * np.abs(rng.normal(size=n))
    phi = 1.0 - 0.3 * rng.random(n)
    J, U, _, A = film.jacobian(P, phi, 1.0, film.evaluate(P, phi))
    dP, dphi = J.toarray() + U, A.toarray()
    h = 1e-3
    for j in (5, 17, 40):
        e = np.zeros(n)
        e[j] = h
        for exact, fd in ((dP[:, j], film.evaluate(P + e, phi).residual
                           - film.evaluate(P - e, phi).residual),
                          (dphi[:, j], film.evaluate(P, phi + e).residual
                           - film.evaluate(P, phi - e).residual)):
            fd = fd / (2 * h)
            assert np.max(np.abs(fd - exact)) <= 1e-6 * np.max(np.abs(fd))


def test_beyond_the_clearance_circle_is_refused():
    """fem-ehd declares eps up to 2 (an elastic film); the JFO one raises ValueError
    naming eps there (its load continuation starts from the rigid step) instead of a NaN."""
    from bearingfem.bearing import ElasticJournalState
    from bearingfem.models import film_model
    film = film_model("fem-ehd").along_run(SEED, dict(n_theta=24, n_z=4, bush=SOFT, modes=8,
                                                      cavitation="jfo"))
    film.start(moving(0), 0.0)
    with pytest.raises(ValueError, match="eps"):
        film.force(ElasticJournalState(eps=1.05, gamma=0.4, omega=250.0), 1e-4)


def test_steady_force_rigid_bush_is_fem_jfo():
    """The model's steady force with cavitation "jfo" and a 1e25 Pa bush equals fem-jfo's
    (half mesh, same supply) to 1e-9 (Newton's tolerance, measured in test_ehd_jfo.py's
    rigid limit). Fails with the steady route left on Reynolds' condition (fem-ehd's
    default)."""
    from bearingfem.models import film_model
    s = JournalState(eps=0.8, gamma=0.4, omega=250.0)
    stiff = ElasticBush(outer_radius=0.016, modulus=1e25, poisson=0.34, model="ring")
    ehd = film_model("fem-ehd").film_force(SEED, s, n_theta=48, n_z=4, bush=stiff, modes=0,
                                           cavitation="jfo")
    jfo = film_model("fem-jfo").film_force(SEED, s, n_theta=48, n_z=4)
    assert np.allclose(ehd, jfo, rtol=1e-9, atol=0.0)
    rey = film_model("fem-ehd").film_force(SEED, s, n_theta=48, n_z=4, bush=stiff, modes=0)
    assert not np.allclose(rey, jfo, rtol=1e-3, atol=0.0)
