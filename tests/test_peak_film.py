"""The film at a run's peak joint load, kept by the run (SimulationResult.peak_film): the
committed film step with the largest film + summits force in the recorded turns, against
the run's own film record and against the film replayed to that step; a stopped run keeps
the one it had; saved beside the arrays; drawn (mechanism.figures.render_deflection). And
the implicit film's replay tolerance: a scene that is not the run's is still refused.

The run: the crowned seed pin with the implicit-step EHD film (benchmarks/ehd_implicit.py's)
on 24 x 4, 5 deg of crank from top dead centre, recorded from 3.1 deg: its run-up from the
bearing's centre peaks at 9.9e3 N near 2 deg, before the recorded window, whose own peak
(4.7e3 N near 4.6 deg) lies inside it. A second, the rigid JFO film on 16 x 4 (0.01 turn),
checks that a kept film is not changed by the later steps and that a round-off replay
tolerance refuses a scene 0.01 % off. Each run is made once (module fixtures)."""
import copy
import dataclasses
import types

import numpy as np
import pytest

from bearingfem.fields import EdgeProfile
from benchmarks.ehd_implicit import implicit_scene, peak_figure
from mechanism import load_result, load_scene, simulate
from mechanism.effects import FilmEffect
from mechanism.figures import render_deflection
from mechanism.film_history import film_history
from mechanism.result import film_column

TURNS, RECORD_FROM = 0.014, 0.0085


def _scene(**changes):
    sc = implicit_scene(TURNS, 24, 4, 1e-5, 1e-6, record_from_turn=RECORD_FROM)
    lub = dataclasses.replace(sc.lubrication, options=dict(sc.lubrication.options, **changes))
    return dataclasses.replace(sc, lubrication=lub)


def _kept_copies(sc):
    """(the run of ``sc``, {id of a kept film: its deep copy made when it was kept}): what
    a film that reuses or updates its solution in place would change after the fact."""
    copies, flags = {}, []
    keep, commit = FilmEffect._keep_peak, FilmEffect.commit

    def logging(self, k, recording=True):
        flags.append((k.t, recording))
        return commit(self, k, recording)

    def copying(self, step, *args):
        keep(self, step, *args)
        if self.peak is step:
            copies[id(step.solution)] = (step.solution, copy.deepcopy(step.solution))
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(FilmEffect, "_keep_peak", copying)
        mp.setattr(FilmEffect, "commit", logging)
        r = simulate(sc, progress=False)
    copies["recording"] = np.array(flags)
    return r, copies


def test_the_run_records_its_commits_from_its_first_saved_sample(kept):
    """The commits' recording flag (simulate's, by the crank angle) against the saved
    samples' first time (mechanism.sampling.output_times', by the dense output): off
    before it, on from it. Fails when the two rules part (e.g. recording a degree late)."""
    r, copies = kept
    t, recording = copies["recording"].T
    assert 0 < np.count_nonzero(recording) < len(t)
    assert np.all(recording == (t >= r.t[0]))


def _unchanged(sol, copies):
    """The names of ``sol``'s array fields that differ from its copy made when kept."""
    _, kept = copies[id(sol)]
    return [f.name for f in dataclasses.fields(kept)
            if isinstance(getattr(kept, f.name), np.ndarray)
            and not np.array_equal(getattr(kept, f.name), getattr(sol, f.name), equal_nan=True)]


@pytest.fixture(scope="module")
def kept():
    return _kept_copies(_scene())


@pytest.fixture(scope="module")
def run(kept):
    return kept[0]


def _jfo_scene(**changes):
    """The seed pin's rigid JFO film on 16 x 4, a film step at each accepted step, 0.01
    turn recorded from 0.005 (0.6 s CPU, 142 film steps)."""
    sc = load_scene("paper-short-jfo")
    lub = dataclasses.replace(sc.lubrication, options=dict(
        sc.lubrication.options, n_theta=16, n_z=4, film_step=0.0, **changes))
    return dataclasses.replace(sc, lubrication=lub, run=dataclasses.replace(
        sc.run, turns=0.01, record_from_turn=0.005))


@pytest.fixture(scope="module")
def jfo_kept():
    return _kept_copies(_jfo_scene())


def _forces(r):
    rec = r.film_record
    return film_column(rec, "t"), np.hypot(film_column(rec, "force_x"),
                                          film_column(rec, "force_y"))


def test_the_kept_film_is_the_records_largest_force_in_the_recorded_turns(run):
    """From the film record alone: the row of largest |F| among those at or after the
    first saved sample. The run-up's larger peak (before the window) is not it. Fails
    with the peak kept over the whole run, or with the film's force alone (no summits)."""
    r = run
    t, f = _forces(r)
    inside = np.flatnonzero(t >= r.t[0])
    j = inside[np.argmax(f[inside])]
    assert f.max() > 1.5 * f[j]                      # the run-up's peak lies before
    step = r.peak_film
    assert step.t == t[j]
    assert np.hypot(*step.force_local) == pytest.approx(f[j], rel=1e-12)
    assert step.solution.total_force == pytest.approx(
        (film_column(r.film_record, "force_x")[j], film_column(r.film_record, "force_y")[j]),
        rel=1e-12)
    assert step.solution.deformation is not None


def test_the_kept_film_is_the_replayed_film_at_its_step(run):
    """The run's film steps replayed (mechanism.film_history) to the kept step give its
    film: pressure, deflection and gap to 1e-7 of their largest (the implicit film's
    replay agrees with its run to its Newton tolerance: 4e-11 of the force measured)."""
    r = run
    step = r.peak_film
    frame, = film_history(r, _scene(), [np.degrees(r.crank_angle_at(step.t))])
    assert frame.t == step.t
    for name in ("pressure", "deformation", "film_thickness"):
        a, b = np.asarray(getattr(frame.solution, name)), np.asarray(getattr(step.solution, name))
        assert np.max(np.abs(a - b)) <= 1e-7 * np.max(np.abs(b)), name


def test_a_scene_not_the_runs_is_refused_by_the_replay(run):
    """The implicit film's replay tolerance (its Newton tolerance's, not round-off) still
    refuses a replay with a crown (2.002 um for 2) or relaxation time (1.001e-5 s for
    1e-5) 0.1 % off: they depart by up to 1.3e-4 and 1.5e-4 of the peak force, 2.8e-7 and
    1.1e-7 at their first steps (0.01 % off: 1.3e-7 and 1.2e-7, refused too). Fails with
    a tolerance of 2e-4 or more."""
    q = np.degrees(run.crank_angle_at(run.peak_film.t))
    for changes in (dict(profile=EdgeProfile("crown", 2.002e-6)), dict(relaxation=1.001e-5)):
        with pytest.raises(ValueError, match="departs from the run's record"):
            film_history(run, _scene(**changes), [q])


@pytest.mark.parametrize("n", [130, 250])
def test_a_stopped_run_keeps_the_film_it_had(ctrl_c_at_film_force, tmp_path, n):
    """A Ctrl-C in the rigid JFO run at its n-th film force: at the 130th in the run-up,
    after its peak and before the recorded turns (the run is partial, its samples the
    whole run from t = 0, its kept film the record's largest force over them, not its
    last step); at the 250th inside the recorded turns (its samples from where they
    begin, its kept film the largest force from there, not the run-up's). Saved by
    save(). Fails when a stopped run's film is dropped or not saved, or the kept film's
    window is not its samples'."""
    forces = ctrl_c_at_film_force(n)
    r = simulate(_jfo_scene(), progress=False)
    assert forces["n"] >= n and r.partial
    t, f = _forces(r)
    inside = np.flatnonzero(t >= r.t[0])
    j = inside[np.argmax(f[inside])]
    assert r.peak_film.t == t[j]
    if n == 130:
        assert r.t[0] == 0.0 and 10 < j < len(t) - 1
    else:
        assert r.t[0] > 0.0 and f.max() > f[j]       # the run-up's peak lies before
    import meshio                             # optional: the VTU writer's
    d = r.save(tmp_path)                      # a stopped run's film is saved too
    m = meshio.read(d / "peak_film.vtu")
    assert np.all(m.point_data["time [s]"] == r.peak_film.t)


def test_the_kept_film_is_saved_and_drawn(run, tmp_path):
    """save() writes it beside the arrays (peak_film.vtu: its pressure and time); the
    benchmark's figure file is written and its line says where the peak was; a film
    without a bush is refused by the drawing."""
    import meshio                             # optional: the VTU writer's
    r = run
    d = r.save(tmp_path / "run")
    m = meshio.read(d / "peak_film.vtu")
    assert np.allclose(m.point_data["pressure [Pa]"], r.peak_film.solution.pressure)
    assert np.all(m.point_data["time [s]"] == r.peak_film.t)
    assert load_result(d).peak_film is None
    line = peak_figure(r, tmp_path / "fig" / "peak.png")
    assert (tmp_path / "fig" / "peak.png").stat().st_size > 10_000
    angle = np.degrees(r.crank_angle_at(r.peak_film.t))
    assert f"crank {angle:.2f} deg of turn 1" in line and "least film" in line
    assert f"force {np.hypot(*r.peak_film.force_local):.1f} N" in line
    # the force it names is the step's, film + summits (no summits' load at this peak)
    step = r.peak_film
    summits = dataclasses.replace(step, force_local=(step.force_local[0] + 50.0,
                                                     step.force_local[1]))
    line = peak_figure(dataclasses.replace(r, peak_film=summits), tmp_path / "fig" / "s.png")
    assert f"force {np.hypot(*summits.force_local):.1f} N" in line
    rigid = dataclasses.replace(r.peak_film.solution, deformation=None)
    with pytest.raises(ValueError, match="deformation"):
        render_deflection(rigid, r.peak_film.state, tmp_path / "no.png")


def test_the_kept_step_is_the_largest_film_and_summits_force_once_the_run_records():
    """Scripted film steps through FilmEffect.commit: a run-up step (not recording) of
    500 N, then recorded steps of 100 N (film), 80 N film + 50 N summits, 120 N film, and
    a step of 1000 N without a whole film. The kept step is the 130 N one: the run-up's is
    forgotten once the run records, the summits count, a step without its film is not
    kept. Fails with the peak over the whole run or ranked by the film's force alone."""
    from mechanism.effects import JointKinematics
    from mechanism.result import FILM_COLUMNS
    from mechanism.simulate import build_effects
    from bearingfem import JournalState
    from bearingfem.contract import FilmStep

    def step(t, film, summits, whole=True):
        sol = types.SimpleNamespace(force_local=(film, 0.0), **dict.fromkeys(
            ("pressure_max", "cavitated_fraction", "friction_force", "mass_balance",
             "film_min", "asperity_load"), 0.0)) if whole else None
        return FilmStep(t, JournalState(eps=0.5, omega=250.0), (film + summits, 0.0), sol)

    script = [step(1e-5, 500.0, 0.0), step(2e-5, 100.0, 0.0), step(3e-5, 80.0, 50.0),
              step(4e-5, 120.0, 0.0), step(5e-5, 1000.0, 0.0, whole=False)]
    _, film, _ = build_effects(load_scene("paper-short-analytic"))
    film.run = types.SimpleNamespace(commit=lambda state, t: script.pop(0))
    for k, recording in enumerate((False, True, True, True, True)):
        film.commit(JointKinematics(1e-6, 0.0, 0.0, 0.0, 250.0, (k + 1) * 1e-5), recording)
    assert len(film.history) == 5 and len(FILM_COLUMNS) == len(film.history[0])
    assert film.peak.t == 3e-5 and film.peak.force_local == (130.0, 0.0)


def test_a_film_without_memory_keeps_none():
    sc = load_scene("paper-short-analytic")
    sc = dataclasses.replace(sc, run=dataclasses.replace(sc.run, turns=0.01,
                                                         record_from_turn=0.0))
    assert simulate(sc, progress=False).peak_film is None


def test_the_kept_film_is_not_changed_by_the_later_steps(kept, jfo_kept):
    """The kept film's arrays as they were when it was kept, after the run's later film
    steps (a film that reused or updated its solution in place would change them); the
    rigid JFO film (TransientJFO, its film fraction carried) too."""
    r, copies = kept
    assert r.peak_film.t < film_column(r.film_record, "t")[-1]     # later steps were taken
    assert _unchanged(r.peak_film.solution, copies) == []
    r, copies = jfo_kept
    assert r.peak_film.t < film_column(r.film_record, "t")[-1]
    assert _unchanged(r.peak_film.solution, copies) == []


def test_a_round_off_replay_refuses_a_scene_0_01_percent_off(jfo_kept):
    """The rigid JFO film declares round-off (StatelessRun's REPLAY_TOLERANCE, 1e-9): its
    replay of its own run passes (it departs by 0: the same solves), one with the ambient
    pressure 0.01 % off (1.0001e5 Pa for 1e5) is refused (1.4e-8 of the peak force at its
    third step; 0.1 % off: 1.4e-7). Fails with a tolerance of 1.4e-8 or more."""
    r, _ = jfo_kept
    q = np.degrees(r.crank_angle_at(r.peak_film.t))
    frame, = film_history(r, _jfo_scene(), [q])
    assert frame.t == r.peak_film.t
    with pytest.raises(ValueError, match="departs from the run's record"):
        film_history(r, _jfo_scene(ambient_pressure=1.0001e5), [q])


def test_a_run_stopped_before_its_first_recorded_film_step_keeps_none():
    """A run-up film step of 500 N, then a recorded commit that takes no film step (a
    film step's interval not passed) and the run stops: its saved samples are the
    recorded ones, so the run-up's film is not kept. Fails when the run-up's is forgotten
    only at the first recorded film step."""
    from mechanism.effects import JointKinematics
    from mechanism.simulate import build_effects
    from bearingfem import JournalState
    from bearingfem.contract import FilmStep

    sol = types.SimpleNamespace(force_local=(500.0, 0.0), **dict.fromkeys(
        ("pressure_max", "cavitated_fraction", "friction_force", "mass_balance",
         "film_min", "asperity_load"), 0.0))
    script = [FilmStep(1e-5, JournalState(eps=0.5, omega=250.0), (500.0, 0.0), sol), None]
    _, film, _ = build_effects(load_scene("paper-short-analytic"))
    film.run = types.SimpleNamespace(commit=lambda state, t: script.pop(0))
    film.commit(JointKinematics(1e-6, 0.0, 0.0, 0.0, 250.0, 1e-5), False)
    assert film.peak is not None                  # the run-up's, while the run does not record
    film.commit(JointKinematics(1e-6, 0.0, 0.0, 0.0, 250.0, 2e-5), True)
    assert film.peak is None


def test_the_crank_angle_past_the_last_sample_follows_the_crank(run):
    """crank_angle_at half a sample's interval past the last saved sample (where the
    run's last steps, and a kept film step, may lie) against the same result with its
    last sample: to 1e-3 of the interval's crank angle (the crank's acceleration: 1.1e-4
    measured). Fails when it is held at the last sample's (0.5 of it off)."""
    r = run
    cut = dataclasses.replace(r, t=r.t[:-1], crank_angle=r.crank_angle[:-1],
                              crank_speed=r.crank_speed[:-1])
    t = 0.5 * (r.t[-2] + r.t[-1])
    step = r.crank_angle[-1] - r.crank_angle[-2]
    assert abs(cut.crank_angle_at(t) - r.crank_angle_at(t)) <= 1e-3 * step
    before = r.t[0] - 0.5 * (r.t[1] - r.t[0])
    assert r.crank_angle_at(before) < r.crank_angle[0] - 0.4 * step


def test_a_saved_run_replayed_to_its_peak_is_the_kept_peak_film(kept, tmp_path):
    """benchmarks.ehd_implicit's --replay: a saved run's film steps replayed from its start
    to the largest force in a window (replayed_peak) give the film the run kept there
    (peak_film) to the film's replay tolerance. Fails when the window is not honoured (the
    run-up's 9.9e3 N peak, before the saved samples, is taken) or another step replayed."""
    from benchmarks.ehd_implicit import replayed_peak
    r, _ = kept
    r.save(tmp_path / "run")
    step = replayed_peak(load_result(tmp_path / "run"), _scene(), RECORD_FROM)
    assert step.t == r.peak_film.t
    assert np.hypot(*step.force_local) == pytest.approx(np.hypot(*r.peak_film.force_local),
                                                        rel=1e-7)
    p, q = step.solution.pressure, r.peak_film.solution.pressure
    assert np.max(np.abs(p - q)) <= 1e-7 * np.max(q)


def test_film_steps_name_rows_of_the_film_record(jfo_kept):
    """film_history(film_steps=): a film with memory's record rows, the frame at each row's
    own time; a row outside the record, a non-integer, or a film without memory is
    refused by name before any replay."""
    r, _ = jfo_kept
    n = len(r.film_record)
    frames = film_history(r, _jfo_scene(), film_steps=[1, n - 1])
    assert [f.t for f in frames] == list(film_column(r.film_record, "t")[[1, n - 1]])
    for bad in (n, -1, 1.0):
        with pytest.raises(ValueError, match=r"film_steps must be rows of the film record, "
                                             rf"integers in \[0, {n - 1}\]"):
            film_history(r, _jfo_scene(), film_steps=[bad])
    rigid = load_scene("paper-short-fem")
    with pytest.raises(ValueError, match="film_steps names rows of a film record"):
        film_history(r, rigid, film_steps=[1])
