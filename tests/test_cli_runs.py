"""The run commands on the command line: simulate writes its result and figure (and
--turns runs and records that many turns); sweep runs and resumes."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def run(*args):
    return subprocess.run([sys.executable, "-m", "bearingfem_app", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)


def test_simulate_writes_result_and_figure(tmp_path):
    scene = tmp_path / "quick.toml"
    scene.write_text((ROOT / "scenes" / "paper-long-analytic.toml").read_text()
                     .replace("turns = 5", "turns = 0.5").replace("record_from_turn = 4",
                                                                  "record_from_turn = 0"))
    r = run("simulate", str(scene), "-o", str(tmp_path / "out"), "-q")
    assert r.returncode == 0, r.stderr
    meta = json.loads((tmp_path / "out" / "result.json").read_text())
    assert meta["partial"] is False and meta["stats"]["film_solves"] > 0
    assert (tmp_path / "out" / "run.png").stat().st_size > 10_000


def test_simulate_turns_runs_and_records_that_many_turns(tmp_path):
    """--turns 0.25 on a shipped scene of five turns recorded from the fourth: the run ends
    after a quarter turn of the crank (from top dead centre, 90 deg) and records it all
    (its first time is 0). Old: no --turns; the scene's turns and recording only."""
    r = run("simulate", "paper-long-analytic", "--turns", "0.25", "-o", str(tmp_path / "o"),
            "-q")
    assert r.returncode == 0, r.stderr
    import numpy as np
    data = np.load(tmp_path / "o" / "result.npz")
    turned = np.degrees(data["crank_angle"][-1] - data["crank_angle"][0])
    assert data["t"][0] == 0.0 and abs(turned - 90.0) < 1.0
    r = run("simulate", "paper-long-analytic", "--turns", "0", "-o", str(tmp_path / "p"))
    assert r.returncode == 2 and "--turns" in r.stderr and not (tmp_path / "p").exists()


@pytest.mark.slow   # 5 s; the sweep runner is tested on a real cluster in test_sweep.py
def test_sweep_command_runs_and_resumes(tmp_path):
    sweep = tmp_path / "s.toml"
    sweep.write_text('name = "s"\n[base]\nmodel = "short"\n[vary]\neps = [0.2, 0.8]\n')
    r = run("sweep", str(sweep), "-o", str(tmp_path / "out"), "--workers", "1", "-q")
    assert r.returncode == 0, r.stderr
    assert "2 computed, 0 already done, 0 failed" in r.stdout
    r = run("sweep", str(sweep), "-o", str(tmp_path / "out"), "--workers", "1", "-q")
    assert "0 computed, 2 already done" in r.stdout
