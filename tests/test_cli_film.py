"""The film commands on the command line: solve prints the force, attitude, Sommerfeld
number (and a JFO film's fraction and balance) and exports the film; convergence and
render write their files."""
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def run(*args):
    return subprocess.run([sys.executable, "-m", "bearingfem_app", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)


def test_solve_prints_forces_and_exports(tmp_path):
    r = run("solve", "--ld", "0.5", "--eps", "0.7", "--n-theta", "48", "--n-z", "8",
            "-o", str(tmp_path / "film.vtu"))
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "film.vtu").is_file()
    for named in ("|F|", "N", "attitude angle", "deg", "cavitated area", "%", "Pa", "um",
                  "m^3/s", "Sommerfeld number"):
        assert named in r.stdout, named


@pytest.mark.slow   # 5 s; convergence and render are tested directly by default
def test_convergence_and_render_commands(tmp_path):
    r = run("convergence", "--ld", "1.0", "--eps", "0.6", "--levels", "3", "--methods", "P1,fvm",
            "-o", str(tmp_path / "conv"))
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "conv" / "convergence.csv").is_file()
    assert (tmp_path / "conv" / "convergence.png").is_file()
    r = run("render", "--ld", "1.0", "--eps", "0.6", "--n-theta", "48", "--n-z", "8",
            "-o", str(tmp_path / "film.png"))
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "film.png").stat().st_size > 5000
    r = run("render", "--field", "vorticity", "-o", str(tmp_path / "x.png"))
    assert r.returncode == 2 and "field must be one of" in r.stderr
    r = run("render", "--field", "temperature", "-o", str(tmp_path / "x.png"))
    assert r.returncode == 2 and "--field temperature is a thermal film's" in r.stderr


def test_solve_prints_load_attitude_and_sommerfeld():
    r = run("solve", "--eps", "0.6", "--n-theta", "48", "--n-z", "8")
    assert r.returncode == 0
    assert "|F|" in r.stdout and "attitude angle" in r.stdout and "Sommerfeld number" in r.stdout


def test_solve_jfo_prints_fraction_and_balance(tmp_path):
    r = run("solve", "--cavitation", "jfo", "--ambient-pressure", "1e5", "--n-theta", "48",
            "--n-z", "8", "-o", str(tmp_path / "film.vtu"))
    assert r.returncode == 0, r.stderr
    assert "JFO film fraction" in r.stdout and "mass balance" in r.stdout
