"""The library's progress on stderr while a command runs: a mesh search's estimates,
repeated lines counted, --quiet silencing them."""
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def run(*args):
    return subprocess.run([sys.executable, "-m", "bearingfem_app", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)


def test_a_mesh_search_shows_its_progress_on_stderr():
    """A film solved to --rtol reports each mesh pair's estimate on stderr as it goes (a
    search can take tens of seconds), the answer on stdout; --quiet silences it. Old: the
    search printed nothing until the answer."""
    r = run("solve", "--ld", "0.2", "--eps", "0.6", "--rtol", "1e-3")
    assert r.returncode == 0, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) >= 2 and all(x.startswith("bearingfem: rtol 0.001: ") for x in lines)
    assert "refining" in lines[0] and "estimated error" in lines[-1]
    assert "bearingfem:" not in r.stdout
    quiet = run("solve", "--ld", "0.2", "--eps", "0.6", "--rtol", "1e-3", "--quiet")
    assert quiet.returncode == 0 and quiet.stderr == ""
    assert quiet.stdout == r.stdout


def test_repeated_progress_lines_are_counted_not_copied():
    """An equilibrium on an elastic bush solves the film tens of times, each logging the
    same continuation line: stderr shows it once and then '(the line above N more times)'
    (it showed 37 copies of one line on a 50 mm bearing)."""
    r = run("equilibrium", "--diameter", "0.05", "--ld", "0.5", "--clearance", "50e-6",
            "--load", "2000", "--rpm", "3000", "--bush", "ring", "--n-theta", "24",
            "--n-z", "4")
    assert r.returncode == 0
    lines = r.stderr.strip().splitlines()
    assert len(lines) == len(set(lines)), lines
    assert re.fullmatch(r"bearingfem: \(the line above \d+ more times\)", lines[-1]), lines
