"""The shipped EHD scene ``paper-short-ehd`` from the command line: ``--turns`` gives a
quick look, and a Ctrl-C in its settling turns (the recorded turn is its fifth) keeps what
was computed and says where it stopped."""
import numpy as np
import pytest

from bearingfem_app.cli import main
from mechanism import load_scene
from mechanism.result import load_result


def test_turns_gives_a_quick_look_at_the_shipped_scene(tmp_path):
    """--turns 0.005 (~1 s): those turns, recorded from t = 0, with the scene's own film
    (the implicit coupling records every accepted step). Fails with --turns not applied as
    given (a run twice as long)."""
    out = tmp_path / "quick"
    assert main(["simulate", "paper-short-ehd", "--turns", "0.005", "-o", str(out), "-q"]) == 0
    r = load_result(out)
    assert not r.partial and r.t[0] == 0.0 and len(r.t) >= 3
    # 720 samples a turn: the last within one sample of the end
    turns = (r.crank_angle[-1] - r.crank_angle[0]) / (2 * np.pi)
    assert 0.005 - 1 / 720 <= turns <= 0.005
    assert len(r.film_record) == r.stats["steps"] > 0
    assert r.provenance["scene"]["lubrication"]["options"]["coupling"] == "implicit"


def test_ctrl_c_in_the_settling_turns_keeps_the_run_and_says_where_it_stopped(
        tmp_path, capsys, ctrl_c_at_film_force):
    """A real Ctrl-C (SIGINT to this process) at the 60th film force of the shipped scene's
    five turns, long before its recorded turn (from turn 4): exit 130, the run saved and
    printed as PARTIAL, its samples the whole run from t = 0 with every accepted step's
    film record, and the message says how far it got and what was kept instead of the
    recorded turn. Fails without that note (the message then said only the time)."""
    forces = ctrl_c_at_film_force(60)
    out = tmp_path / "run"
    assert main(["simulate", "paper-short-ehd", "-o", str(out), "-q"]) == 130
    assert forces["n"] >= 60
    printed = capsys.readouterr().out
    r = load_result(out)
    assert r.partial and r.message.startswith("interrupted at t = ")
    assert r.message.endswith("of 5 turns, before the recorded turns from turn 4: kept the "
                              "whole run from t = 0)")
    assert f"scene paper-short-ehd: {r.message} (PARTIAL)" in printed
    done = float(r.message.split("(after ")[1].split(" of")[0])
    # the last sample lies within a sample (1/720 turn at about the scene's speed) of the stop
    assert done == pytest.approx((r.crank_angle[-1] - r.crank_angle[0]) / (2 * np.pi),
                                 abs=2 / 720)
    assert r.t[0] == 0.0 and len(r.t) >= 2 and np.all(np.isfinite(r.eps))
    assert len(r.film_record) == r.stats["steps"] > 10


def test_one_name_per_scene():
    """The crowned implicit pin is paper-short-ehd itself; the sharp bore's modal film keeps
    its own name. The old second name is not a scene (the error lists the shipped ones)."""
    assert load_scene("paper-short-ehd-sharp").lubrication.options["modes"] == 64
    with pytest.raises(ValueError, match=r"scene file not found: paper-short-ehd-crowned "
                                         r"\(shipped scenes: .*paper-short-ehd, "):
        load_scene("paper-short-ehd-crowned")
