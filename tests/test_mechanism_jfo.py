"""The mechanism on the mass-conserving film: the film advances at accepted steps only."""
import numpy as np
import pytest

from bearingfem import JournalState
from bearingfem.bearing import seed_bearing
from mechanism import parse_scene, simulate
from bearingfem.transient import TransientJFO
from mechanism.simulate import build_effects


def scene(turns=0.25, **lub):
    return parse_scene({"name": "jfo", "bearing": {"diameter": 0.02, "length_ratio": 0.5,
                                                   "clearance": 20e-6, "viscosity": 0.0117},
                        "run": {"turns": turns, "record_from_turn": 0},
                        "effects": {"lubrication": {"model": "fem-jfo", "n_theta": 48,
                                                    "n_z": 4, **lub}}})


def test_jfo_film_is_built_only_when_named_and_carries_its_state():
    effects, film, _ = build_effects(scene())
    assert film.memory and isinstance(film.run, TransientJFO)
    effects, film, _ = build_effects(parse_scene({
        "name": "r", "bearing": {"diameter": 0.02, "length_ratio": 0.5, "clearance": 20e-6,
                                 "viscosity": 0.0117},
        "effects": {"lubrication": {"model": "fem"}}}))
    assert not film.memory


def test_jfo_run_commits_each_step_and_balances_mass():
    """A quarter turn: one film step per accepted integrator step, finite forces, the
    journal inside the clearance."""
    r = simulate(scene(), progress=False)
    assert not r.partial, r.message
    assert r.stats["film_steps"] == r.stats["steps"] > 50
    assert np.all(np.isfinite(r.force_x)) and np.all(np.isfinite(r.force_y))
    assert r.eps.max() < 1.0


def test_film_history_rows_balance():
    from mechanism.effects import JointKinematics
    effects, film, _ = build_effects(scene())
    c = film.bearing.clearance
    for k in range(1, 40):
        t = 1e-4 * k
        e = 0.5 * c * np.sin(2e3 * t)
        film.force(JointKinematics(e, 0.3 * e, 1e3 * c * np.cos(2e3 * t), 0.0, 50.0, t))
        film.commit(JointKinematics(e, 0.3 * e, 1e3 * c * np.cos(2e3 * t), 0.0, 50.0, t))
    h = np.array(film.history)
    assert len(h) == 38 and np.all(np.diff(h[:, 0]) > 0)   # the first call starts the film
    # mass balance per step against the squeeze flow scale e_dot R L
    scale = 1e3 * c * film.bearing.radius * film.bearing.length
    assert np.max(np.abs(h[:, 6])) < 1e-10 * scale
    assert np.any(h[:, 4] > 0.0)        # a cavity formed


def test_restored_snapshot_goes_back():
    """Going back to a snapshot (an integrator cutting its step) and committing an earlier
    time gives what one step from the snapshot gives; a commit before the last film step
    without a restore is refused (fails if restore leaves any kept field behind)."""
    b = seed_bearing(0.5)
    opts = dict(n_theta=32, n_z=4, grooves=(), ambient_pressure=1e5)
    s = [JournalState(eps=0.3 + 0.1 * k, eps_dot=40.0, omega=100.0) for k in range(3)]
    a, ref = TransientJFO(b, **opts), TransientJFO(b, **opts)
    for f in (a, ref):
        f.force(s[0], 0.0)
        f.commit(s[0], 0.0)
        f.commit(s[1], 1e-3)
    kept = a.snapshot()
    a.commit(s[2], 2e-3)
    with pytest.raises(ValueError, match="before the last film step"):
        a.commit(s[2], 1.5e-3)
    a.restore(kept)
    a.commit(s[2], 1.5e-3)                     # back inside the last step
    ref.commit(s[2], 1.5e-3)
    assert np.array_equal(a.film.fraction, ref.film.fraction)
    assert a.film.solution.force_local == pytest.approx(ref.film.solution.force_local)
    assert a.steps == ref.steps == 2 and a.snapshot().t == ref.snapshot().t


def test_coefficients_refuse_a_film_with_memory():
    from bearingfem import coefficients
    b = seed_bearing(1.0)
    with pytest.raises(ValueError, match="has memory"):
        coefficients(b, JournalState(eps=0.5, omega=100.0), model="fem-jfo")


def test_film_history_replays_a_film_with_memory(tmp_path):
    """A fem-jfo film depends on its past: film_history replays the run's film steps from
    their recorded states, so each frame is the film the run had (force equal to the
    record to round-off), with its film fraction; through save / load too."""
    from mechanism import load_result
    from mechanism.film_history import film_history
    sc = scene(turns=0.1)
    r = simulate(sc, progress=False)
    assert r.film_record.shape[1] == 14 and len(r.film_record) == r.stats["film_steps"]
    frames = film_history(load_result(r.save(tmp_path)), sc, [10, 20, 30])
    assert len(frames) == 3
    for f in frames:
        row = r.film_record[r.film_record[:, 0] == f.t][0]
        assert f.solution.force == pytest.approx(tuple(row[1:3]), rel=1e-12, abs=1e-9)
        assert min(abs(f.crank_angle_deg - a) for a in (10, 20, 30)) < 1.0
    assert min(f.solution.fraction.min() for f in frames) < 0.99    # a cavity to show
    with pytest.raises(ValueError, match="departs from the run's record"):
        film_history(r, scene(turns=0.1, ambient_pressure=2e5), [20])
    with pytest.raises(ValueError, match="n_theta"):
        film_history(r, sc, [20], n_theta=24)


JFO_SCENE = """name = "jfo-cli"
[bearing]
diameter = 0.02
length_ratio = 0.5
clearance = 20e-6
viscosity = 0.0117
[run]
turns = 0.1
record_from_turn = 0
[effects.lubrication]
model = "fem-jfo"
n_theta = 48
n_z = 4
"""


def test_frames_command_renders_a_jfo_runs_film_fraction(tmp_path):
    from bearingfem_app.cli import main
    (tmp_path / "jfo.toml").write_text(JFO_SCENE)
    assert main(["simulate", str(tmp_path / "jfo.toml"), "-o", str(tmp_path / "run")]) == 0
    assert main(["frames", str(tmp_path / "jfo.toml"), str(tmp_path / "run"), "-o",
                 str(tmp_path / "fr"), "--angles", "15,30", "--field", "fraction",
                 "--surface", "unwrapped"]) == 0
    assert len(list((tmp_path / "fr").glob("frame-*.png"))) == 2
    assert len(list((tmp_path / "fr").glob("film-*.vtu"))) == 2


def test_film_step_spaces_the_content_updates():
    """With film_step, accepted steps closer than it to the last film step leave the
    content alone; the orbit moves by far less than the film's own resolution (measured:
    min film 0.17219 vs 0.17216 um over half a seed turn at 1/1000 turn)."""
    every = simulate(scene(turns=0.1), progress=False)
    spaced = simulate(scene(turns=0.1, film_step=2.5e-5), progress=False)
    assert spaced.stats["film_steps"] < 0.6 * every.stats["film_steps"]
    assert np.min(np.diff(spaced.film_record[:, 0])) > 2.5e-5
    assert spaced.film_min.min() == pytest.approx(every.film_min.min(), rel=0.01)


def test_interrupted_jfo_run_keeps_results_and_film_record(monkeypatch):
    """Ctrl-C in the middle of a fem-jfo run: the finished segments come back, marked
    partial, with the film steps committed up to the stop."""
    from tests.test_mechanism import _interrupt_at
    _interrupt_at(monkeypatch, 2500)     # after the first quarter-turn segment
    r = simulate(scene(turns=1.0), progress=False)
    assert r.partial and r.message.startswith("interrupted at t = ")
    assert len(r.t) > 10 and np.all(np.isfinite(r.eps)) and np.all(np.isfinite(r.force_x))
    assert len(r.film_record) > 10 and r.film_record[-1, 0] >= r.t[-1]


def test_film_step_fades_its_change_of_force_in():
    """A routine film step moves the cavities at once; the force the integrator sees does
    not jump there (before and after the commit, same state and time: equal) and has taken
    the whole change one film step (here the 2e-4 s since the last one) later. A refill
    acts at once."""
    b = seed_bearing(0.5)
    opts = dict(n_theta=48, n_z=4, grooves=(), ambient_pressure=1e5, film_step=1e-4)
    f = TransientJFO(b, **opts)
    s0 = JournalState(eps=0.6, omega=250.0)
    f.force(s0, 0.0)
    for k in range(1, 21):                   # settle a cavity at s0
        f.commit(s0, k * 2e-4)
    s1 = JournalState(eps=0.6, omega=250.0, eps_dot=-20.0, gamma=0.1, gamma_dot=50.0)
    t1 = 21 * 2e-4
    assert not f.film.refilled(s1)           # turned and moving, no cavity refilled
    before = np.array(f.force(s1, t1))
    assert f.commit(s1, t1) is not None
    after = np.array(f.force(s1, t1))
    settled = np.array(f.film.instant(s1)[0])
    assert np.linalg.norm(settled - before) > 0.05 * np.linalg.norm(before)
    np.testing.assert_allclose(after, before, rtol=1e-9)
    np.testing.assert_allclose(f.force(s1, t1 + 2e-4), settled, rtol=1e-12)
    s2 = JournalState(eps=0.7, omega=250.0, gamma=0.1)
    assert f.film.refilled(s2)
    f.commit(s2, t1 + 2e-4)
    np.testing.assert_allclose(f.force(s2, t1 + 2e-4), f.film.instant(s2)[0],
                               rtol=1e-12)


def test_film_step_comes_early_when_the_kept_film_no_longer_fits():
    """Within film_step the content stays, unless the kept film no longer describes the
    journal: a cavity the closing gap has refilled, or the line of centres turned by half
    a cell (48 cells: 3.75 deg)."""
    b = seed_bearing(0.5)
    opts = dict(n_theta=48, n_z=4, grooves=(), ambient_pressure=1e5, film_step=0.1)
    f = TransientJFO(b, **opts)
    s0 = JournalState(eps=0.6, omega=250.0)
    f.force(s0, 0.0)
    f.film_step = 2e-4
    for k in range(1, 21):
        f.commit(s0, k * 3e-4)
    assert f.film.cavitated.any()
    f.film_step = 0.1
    t = 21 * 3e-4
    assert f.commit(JournalState(eps=0.6, omega=250.0, gamma=0.05), t) is None
    assert f.commit(JournalState(eps=0.6, omega=250.0, gamma=0.07), t) is not None
    s = JournalState(eps=0.6, omega=250.0, gamma=0.07)
    assert f.commit(s, t + 1e-4) is None
    assert f.commit(JournalState(eps=0.9, omega=250.0, gamma=0.07), t + 2e-4) is not None
