"""The clearance-joint mechanism: effects built on demand, the ideal-joint limit, staying in
the film, and clean stops."""
import numpy as np
import pytest

from mechanism import parse_scene, simulate
from mechanism.rigid import simulate_rigid
from mechanism.parameters import Mechanism
from mechanism.simulate import build_effects
from mechanism.effects import FilmEffect, HertzContact


def scene(effects, turns=1.0, ld=0.2, viscosity=0.0117, **run):
    return parse_scene({"name": "t", "bearing": {"diameter": 0.02, "length_ratio": ld,
                                                 "clearance": 20e-6, "viscosity": viscosity},
                        "run": {"turns": turns, **run}, "effects": effects})


def test_only_called_effects_are_built():
    dry = scene({"contact": {}})
    effects, film, contact = build_effects(dry)
    assert film is None and isinstance(contact, HertzContact) and len(effects) == 1
    wet = scene({"lubrication": {"model": "long"}})
    effects, film, contact = build_effects(wet)
    assert isinstance(film, FilmEffect) and contact is None and len(effects) == 1


def test_lubricated_run_makes_no_contact_check_and_counts_solves():
    r = simulate(scene({"lubrication": {"model": "long"}}, turns=0.5, ld=2.0), progress=False)
    assert not r.partial
    assert r.stats["contact_evals"] == 0 and r.stats["film_solves"] == r.stats["rhs_evals"]


def _rigid_speed_at(q):
    t, qq, qd = simulate_rigid(Mechanism(), 250.0, 6.0, 9.81, samples_per_turn=4000)
    return np.interp(q, qq, qd)


def test_stiff_spring_joint_tends_to_ideal_joint():
    """Crank speed against the ideal mechanism's, at the same crank angles: the difference
    falls roughly as 1/k (the joint's deflection ~ load / k)."""
    errs = []
    for k in (1e8, 1e9, 1e10):
        # critically damped pin on the slider mass keeps the joint mode from ringing
        d = 2 * np.sqrt(k * 0.91)
        r = simulate(scene({"spring": {"stiffness": k, "damping": d}}, turns=1.0, rtol=1e-8),
                     progress=False)
        errs.append(np.max(np.abs(r.crank_speed - _rigid_speed_at(r.crank_angle))))
    assert errs[1] < errs[0] / 5 and errs[2] < errs[1] / 5, errs
    assert errs[2] < 0.01


@pytest.mark.parametrize("model,ld", [("short", 0.2), ("short-exact", 0.2), ("long", 2.0),
                                      pytest.param("long-exact", 2.0, marks=pytest.mark.slow)])
def test_lubricated_paper_cases_stay_in_the_film(model, ld):
    """The paper: no contact in any lubricated case; the crank speed follows the ideal
    mechanism's. It trails slightly because the film dissipates energy (the ideal mechanism
    conserves it): measured 0.4-0.8 rad/s over the second turn out of a 40 rad/s swing."""
    lub = {"model": model}
    if model == "short":
        lub["switch_speed"] = 1.0
    r = simulate(scene({"lubrication": lub}, turns=2.0, ld=ld, record_from_turn=1.0),
                 progress=False)
    assert not r.partial, r.message
    assert np.all(np.isfinite(r.eps)) and r.eps.max() < 1.0
    assert np.max(np.abs(r.crank_speed - _rigid_speed_at(r.crank_angle))) < 1.0


def test_wall_without_contact_stops_cleanly_and_keeps_results():
    """A film capped at eps = 0.98 cannot hold the paper's short bearing (it needs ~0.987),
    and there is no contact effect: the run stops at eps = 1 mid-turn with a message
    naming the time, and what was computed is kept, marked partial."""
    r = simulate(scene({"lubrication": {"model": "short", "eps_max": 0.98}}), progress=False)
    assert r.partial
    assert "eps = 1" in r.message and "no contact effect" in r.message and "t = 0.0176" in r.message
    assert len(r.t) > 400 and np.all(np.isfinite(r.force_x))
    assert r.t[-1] <= 0.01764


@pytest.mark.parametrize("integrator", ["lsoda", "bdf"])
def test_film_and_contact_pass_to_contact_and_back(integrator):
    """Thin oil and a film capped at eps = 0.99: the pin reaches the bush, rebounds into the
    film and back; both integrators give the same peak penetration."""
    r = simulate(scene({"lubrication": {"model": "short", "eps_max": 0.99}, "contact": {},
                        "friction": {"coefficient": 0.05, "v_reg": 1e-3}}, viscosity=1e-4,
                       integrator=integrator), progress=False)
    assert not r.partial, r.message
    assert r.stats["contact_evals"] > 0
    assert r.eps.max() > 1.0 and r.eps.min() < 1.0
    assert np.all(np.isfinite(r.force_x)) and np.all(np.isfinite(r.slider_acceleration))
    assert np.all(r.film_min >= 0.0)
    assert r.eps.max() == pytest.approx(1.2169, abs=2e-3)


def test_dry_contact_scene_is_stable():
    r = simulate(scene({"contact": {}, "friction": {"coefficient": 0.05, "v_reg": 1e-3}}),
                 progress=False)
    assert not r.partial and r.stats["film_solves"] == 0
    assert np.all(np.isfinite(r.eps)) and 1.0 < r.eps.max() < 2.0


def test_ideal_joint_scene_matches_rigid_reference():
    s = parse_scene({"name": "ideal", "joint": "ideal", "run": {"turns": 1.0}})
    r = simulate(s)
    assert np.max(np.abs(r.crank_speed - _rigid_speed_at(r.crank_angle))) < 1e-4
    # the joint reaction along the slider axis carries the slider's inertia and weight
    assert np.allclose(r.force_x, -(0.91 * r.slider_acceleration + 0.91 * 9.81))


def _interrupt_at(monkeypatch, n_calls):
    """Press Ctrl-C at the ``n_calls``-th film force evaluation."""
    calls = {"n": 0}
    original = FilmEffect.force

    def force(self, k):
        calls["n"] += 1
        if calls["n"] == n_calls:
            raise KeyboardInterrupt
        return original(self, k)

    monkeypatch.setattr(FilmEffect, "force", force)


def test_interrupted_run_keeps_results(monkeypatch):
    """Ctrl-C in the middle of a run: the finished segments come back, marked partial."""
    _interrupt_at(monkeypatch, 800)
    r = simulate(scene({"lubrication": {"model": "long"}}, ld=2.0), progress=False)
    assert r.partial and r.message.startswith("interrupted at t = ")
    assert len(r.t) > 10 and np.all(np.isfinite(r.eps))
    assert "recorded turns" not in r.message     # recorded from t = 0: nothing to add


def test_run_stopped_before_its_recorded_window_keeps_what_it_computed(monkeypatch):
    """Interrupted during the settling turns: the whole computed trajectory comes back
    (720 samples a turn from t = 0), not the one sample at the stop."""
    _interrupt_at(monkeypatch, 1500)
    sc = scene({"lubrication": {"model": "long"}}, turns=3.0, ld=2.0, record_from_turn=2.0)
    r = simulate(sc, progress=False)
    assert r.partial and r.t[0] == 0.0
    turns_done = (r.crank_angle[-1] - r.crank_angle[0]) / (2 * np.pi)
    assert 0.05 < turns_done < 2.0
    assert len(r.t) >= int(0.9 * 720 * turns_done)
    # the message says so: the samples are not the recorded turn
    assert r.message.endswith(" of 3 turns, before the recorded turns from turn 2: kept the "
                              "whole run from t = 0)")
    said = float(r.message.split("(after ")[1].split(" of")[0])
    # 3 digits (0.005 at 1-2 turns) and the samples 1/720 turn apart
    assert said == pytest.approx(turns_done, abs=7e-3)


def test_a_run_stopped_at_its_first_film_force_comes_back_empty_without_the_note(
        monkeypatch):
    """Ctrl-C at the first film force: no step was taken, nothing is kept, so the message
    is the stop alone (no 'kept the whole run' note) and the result is empty, not an
    error. Fails with the note asked of a run with no dense output (IndexError)."""
    _interrupt_at(monkeypatch, 1)
    sc = scene({"lubrication": {"model": "long"}}, turns=3.0, ld=2.0, record_from_turn=2.0)
    r = simulate(sc, progress=False)
    assert r.partial and r.message == "interrupted at t = 0 s"
    assert len(r.t) == 0 and r.stats["steps"] == 0

@pytest.mark.parametrize("n_calls, before", [(400, True), (1200, False)])
def test_the_note_counts_turns_from_the_scenes_start_angle(monkeypatch, n_calls, before):
    """A scene started at crank angle 3 rad, recorded from half a turn on, stopped at about
    a quarter turn (before the window: the note, its turns counted from 3 rad, the samples
    from t = 0) or at about three quarters (inside it: no note, the samples from the
    window). Fails with the turns counted from crank angle 0 (1.5 turns more: no note
    before the window) or the note added whatever the window."""
    _interrupt_at(monkeypatch, n_calls)
    sc = parse_scene({"name": "t", "bearing": {"diameter": 0.02, "length_ratio": 2.0,
                                               "clearance": 20e-6, "viscosity": 0.0117},
                      "initial": {"crank_angle": 3.0},
                      "run": {"turns": 1.5, "record_from_turn": 0.5},
                      "effects": {"lubrication": {"model": "long"}}})
    r = simulate(sc, progress=False)
    assert r.partial and r.crank_angle[0] == pytest.approx(3.0 if before else 3.0 + np.pi,
                                                           abs=1e-6 if before else 2e-2)
    # independent of the note: where the dense output ended, from the last sample
    done = (r.crank_angle[-1] - 3.0) / (2 * np.pi)
    assert (done < 0.5) == before
    if before:
        assert r.t[0] == 0.0 and r.message.endswith(
            " of 1.5 turns, before the recorded turns from turn 0.5: kept the whole run "
            "from t = 0)")
        said = float(r.message.split("(after ")[1].split(" of")[0])
        assert said == pytest.approx(done, abs=2 / 720)
    else:
        assert r.t[0] > 0.0 and "recorded turns" not in r.message


def test_progress_bar_reports_on_a_stream():
    import io
    from mechanism.progress import Progress
    buf = io.StringIO()
    p = Progress(2.0, "run", enabled=True, stream=buf)
    p.update(1.0)
    p.close("done")
    last = buf.getvalue().split("\r")[-1]
    assert "50.0%" in buf.getvalue() and "100.0%" in last and last.rstrip().endswith("done")
    # a run that stops early ends where it stopped, not at 0 % (or 100 %)
    buf = io.StringIO()
    p = Progress(2.0, "run", enabled=True, stream=buf)
    p.update(1.0)
    p.close("stopped at t = 1 s", complete=False)
    last = buf.getvalue().split("\r")[-1]
    assert "50.0%" in last and "stopped" in last and "0.0%" not in last.replace("50.0%", "")


def test_progress_prints_lines_when_not_a_terminal():
    import io
    from mechanism.progress import Progress
    buf = io.StringIO()                      # not a terminal
    p = Progress(4.0, "sweep", stream=buf, every=0.0)
    for v in (1.0, 2.0, 3.0):
        p.update(v)
    p.close("done")
    lines = buf.getvalue().splitlines()
    assert len(lines) == 4 and "\r" not in buf.getvalue()
    assert "25.0%" in lines[0] and lines[-1].startswith("sweep: 100.0%") and lines[-1].endswith("done")
    assert Progress(1.0, stream=io.StringIO(), enabled=False).mode == "off"


def test_ctrl_c_in_the_first_segment_keeps_the_steps_taken(ctrl_c_at_film_force):
    """A real Ctrl-C (SIGINT to this process, caught by the run's handler) during the first
    quarter turn, of a run recording from its third turn: the steps taken so far come back,
    from t = 0, marked interrupted. Old: the integration segment in progress was dropped, so
    a slow film (the EHD scene) interrupted in its first quarter turn kept nothing."""
    forces = ctrl_c_at_film_force(200)
    sc = scene({"lubrication": {"model": "long"}}, turns=3.0, ld=2.0, record_from_turn=2.0)
    r = simulate(sc, progress=False)
    assert forces["n"] >= 200
    assert r.partial and r.message.startswith("interrupted at t = ")
    assert len(r.t) > 1 and r.t[0] == 0.0 and np.all(np.isfinite(r.eps))
    assert (r.crank_angle[-1] - r.crank_angle[0]) / (2 * np.pi) < 0.25


def test_a_film_failing_inside_a_segment_is_reported_where_it_failed_and_keeps_its_steps(
        monkeypatch):
    """The integrator runs a quarter turn (6.3 ms at 250 rad/s) per segment; a film that
    fails past t = 1 ms inside the first one is reported where it was asked (the first
    right-hand side past 1 ms: 1.13 ms, within a step), not at the segment's start (t = 0 s,
    as a quarter-turn run once said after minutes of work)."""
    force = FilmEffect.force

    def failing(self, kin):
        if kin.t > 1e-3:
            raise ValueError("planted film failure")
        return force(self, kin)
    monkeypatch.setattr(FilmEffect, "force", failing)
    r = simulate(scene({"lubrication": {"model": "long"}}, turns=0.25, ld=2.0), progress=False)
    assert r.partial and "planted film failure" in r.message
    t_stop = float(r.message.split("stopped at t = ")[1].split(" s")[0])
    assert 1e-3 < t_stop < 2e-3
    # the steps before the failure are kept (they were lost with the exception: a run
    # stopped at 66.5 % of its quarter turn returned no step), up to the last accepted one
    assert r.stats["steps"] > 0 and 0.5e-3 < r.t[-1] <= 1e-3


def test_summary_row_names_carry_units():
    """The one-row summary (studies.paper's summary.csv, a mechanism sweep's results.csv):
    every dimensional number names its unit; the crank speeds agree with the arrays."""
    r = simulate(scene({"lubrication": {"model": "long"}}, turns=0.1, ld=2.0), progress=False)
    row = r.summary_row(ideal_speed=r.crank_speed)
    assert set(row) == {"scene", "status", "wall_time_s", "steps", "rhs_evals", "film_solves",
                        "peak_eps", "min_film_um", "crank_speed_min_rad_s",
                        "crank_speed_max_rad_s", "max_dspeed_vs_ideal_rad_s",
                        "peak_slider_acc_m_s2"}
    assert row["crank_speed_max_rad_s"] == pytest.approx(r.crank_speed.max(), abs=0.01)
    # each column its own extreme (the speed falls from 250 to 229.5 rad/s in this tenth
    # of a turn: a column read from the other end of the array is 20 rad/s off)
    assert row["crank_speed_min_rad_s"] == pytest.approx(r.crank_speed.min(), abs=0.01)
    assert r.crank_speed.max() - r.crank_speed.min() > 1.0
    assert row["min_film_um"] == pytest.approx(1e6 * r.film_min.min(), abs=1e-4)
    assert row["peak_slider_acc_m_s2"] == pytest.approx(
        np.max(np.abs(r.slider_acceleration)), abs=0.1)
    assert row["max_dspeed_vs_ideal_rad_s"] == 0.0


def test_a_result_prints_as_one_line():
    """print(res) names the run (it printed every array: ~90 kB for half a turn)."""
    r = simulate(scene({"lubrication": {"model": "long"}}, turns=0.1, ld=2.0), progress=False)
    text = repr(r)
    assert "\n" not in text and len(text) < 200 and "'t'" in text
    assert f"{len(r.t)} points" in text and "completed" in text


def test_window_note_counts_turns_from_the_scenes_starting_crank_angle(monkeypatch):
    """A scene started at 270 deg (three quarters of a turn past top dead centre), recorded
    from its second turn and stopped in its first: the note says the run is before its
    recorded turns, and its turns are those the samples show (crank angle from the scene's
    start, not from zero: counted from zero the run would seem 0.75 turn further on,
    inside its recorded turns, and the note would be left out). Fails with the turns
    counted from a crank angle of zero (run once)."""
    _interrupt_at(monkeypatch, 700)
    data = {"name": "t", "bearing": {"diameter": 0.02, "length_ratio": 2.0,
                                     "clearance": 20e-6, "viscosity": 0.0117},
            "initial": {"crank_angle": 1.5 * np.pi},
            "run": {"turns": 3.0, "record_from_turn": 1.0},
            "effects": {"lubrication": {"model": "long"}}}
    r = simulate(parse_scene(data), progress=False)
    assert r.partial and r.t[0] == 0.0 and r.crank_angle[0] == pytest.approx(1.5 * np.pi)
    turns_done = (r.crank_angle[-1] - r.crank_angle[0]) / (2 * np.pi)
    assert 0.25 < turns_done < 1.0      # counted from zero: past turn 1
    assert r.message.endswith(" of 3 turns, before the recorded turns from turn 1: kept the "
                              "whole run from t = 0)")
    said = float(r.message.split("(after ")[1].split(" of")[0])
    assert said == pytest.approx(turns_done, abs=7e-3)


def test_summary_names_the_mesh_an_rtol_chose_and_its_error_over_the_run():
    """A scene's rtol chooses the film's mesh and the run estimates its error after: the
    command line's summary printed neither (they were in result.json alone), so an estimate
    above the request (the pin past the deepest probe) went unseen."""
    from dataclasses import replace
    r = simulate(scene({"lubrication": {"model": "long"}}, turns=0.1, ld=2.0), progress=False)
    assert "rtol" not in r.summary()
    over = replace(r, stats={**r.stats, "film_rtol": 0.01, "film_mesh": [96, 8, "P2"],
                             "film_force_error": 0.022})
    assert ("film mesh 96 x 8 P2 chosen for rtol 0.01; estimated force error over the run "
            "0.022 (above the request") in over.summary()
    within = replace(r, stats={**r.stats, "film_rtol": 0.01, "film_mesh": [96, 8, "P2"],
                               "film_force_error": 0.004})
    assert "error over the run 0.004\n" in within.summary() + "\n"
    assert "above the request" not in within.summary()
