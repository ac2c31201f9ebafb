"""--rtol on the command line's solve, equilibrium and coefficients: the mesh is chosen,
the printed numbers carry their estimated error."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def run(*args):
    return subprocess.run([sys.executable, "-m", "bearingfem_app", *args],
                          cwd=ROOT,
                          capture_output=True, text=True, timeout=300)


def test_solve_prints_the_force_with_its_error():
    r = run("solve", "--ld", "0.2", "--eps", "0.6", "--rtol", "1e-3")
    assert r.returncode == 0, r.stderr
    assert "fem-P2" in r.stdout and "(+- 0.0" in r.stdout


def test_solve_fvm_takes_rtol_as_the_library_does():
    """--model fvm --rtol chooses the grid (fvm_reynolds(rtol=), as equilibrium --model fvm
    --rtol did); it was refused ("--rtol applies to --model fem only")."""
    r = run("solve", "--ld", "0.5", "--eps", "0.6", "--model", "fvm", "--rtol", "1e-2", "-q")
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("film fvm/") and "chosen for rtol 0.01" in r.stdout
    assert "(+- 0." in r.stdout and " %)" in r.stdout


def test_equilibrium_reports_eps_error_and_mesh(tmp_path):
    out = tmp_path / "eq.json"
    r = run("equilibrium", "--ld", "1", "--load", "1000", "--rtol", "2e-3", "-o", str(out))
    assert r.returncode == 0, r.stderr
    assert "its estimated error" in r.stdout and "mesh chosen" in r.stdout
    assert "its estimated error" in json.dumps(json.loads(out.read_text()))


def test_coefficients_print_their_error_and_the_verdicts_range():
    r = run("coefficients", "--ld", "0.2", "--eps", "0.6", "--rtol", "1e-2")
    assert r.returncode == 0, r.stderr
    assert "K, C estimated error" in r.stdout and "range" in r.stdout


@pytest.mark.parametrize("args, needle", [
    (("solve", "--rtol", "0"), "--rtol (a relative accuracy) must lie in [1e-06, 0.1]"),
    # named as typed, with the other bad numbers in one line (was the library's "rtol")
    (("equilibrium", "--load", "100", "--rtol", "1e-9"), "--rtol (a relative accuracy)"),
    (("coefficients", "--eps", "0.5", "--rtol", "0.5", "--clearance", "-1e-6"),
     "--clearance must be positive (> 0), got -1e-06; --rtol"),
    (("equilibrium", "--load", "100", "--model", "short", "--rtol", "1e-3"),
     "model 'short' has none"),
    # a mesh typed beside --rtol was dropped unseen (the search's mesh printed)
    (("solve", "--rtol", "1e-2", "--n-theta", "48"), "--n-theta is not taken with --rtol"),
    (("solve", "--rtol", "1e-2", "--n-theta", "48", "--n-z", "8"),
     "--n-theta and --n-z are not taken with --rtol"),
    (("equilibrium", "--load", "100", "--rtol", "1e-2", "--n-z", "8"),
     "--n-z is not taken with --rtol"),
    (("coefficients", "--eps", "0.5", "--rtol", "1e-2", "--n-theta", "48"),
     "--n-theta is not taken with --rtol")])
def test_bad_rtol_is_one_line_and_exit_2(args, needle):
    r = run(*args)
    assert r.returncode == 2 and needle in r.stderr and r.stderr.count("\n") == 1
