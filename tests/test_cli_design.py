"""The designer's commands on the command line (equilibrium, coefficients, design): what
they print and write, against the Python API's numbers and closed forms."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def run(*args):
    return subprocess.run([sys.executable, "-m", "bearingfem_app", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)


def test_equilibrium_and_coefficients_print_and_write(tmp_path):
    r = run("equilibrium", "--ld", "1", "--load", "381.439", "--element", "P2",
            "--n-theta", "48", "--n-z", "8", "-o", str(tmp_path / "eq.json"))
    assert r.returncode == 0, r.stderr
    assert "Sommerfeld number" in r.stdout and "deg" in r.stdout
    eq = json.loads((tmp_path / "eq.json").read_text())
    # `solve --eps 0.6` carries 381.4 N on this bearing (Table 1, L/D 1, 250 rad/s)
    # the API's names (Equilibrium.eps, ...), each with its unit; the printed names kept
    # beside them for one version (docs/cli.md). Old: only the printed names
    assert eq["eps"]["value"] == pytest.approx(0.6, abs=2e-3)
    assert eq["friction_force"]["unit"] == "N" and eq["attitude_deg"]["unit"] == "deg"
    assert {"sommerfeld", "film_min", "friction_coefficient", "e_x", "e_y",
            "side_outflow"} <= set(eq)
    assert eq["eccentricity ratio"] == eq["eps"]
    r = run("coefficients", "--model", "short", "--eps", "0.5", "--frame", "load",
            "-o", str(tmp_path / "kc.csv"))
    assert r.returncode == 0, r.stderr
    import csv
    with open(tmp_path / "kc.csv") as fh:
        header = fh.readline().strip().split(",")
        fh.seek(0)
        rows = {row["key"]: row for row in csv.DictReader(fh)}
    # 0.1.0's columns first, in their order (a positional reader unpacks three), the key after
    assert header == ["quantity", "value", "unit", "key"]
    assert rows["K_11"]["unit"] == "N/m" and rows["C_12"]["unit"] == "N s/m"
    assert rows["critical_mass"]["unit"] == "kg" and float(rows["eps"]["value"]) == 0.5
    assert rows["critical_mass"]["quantity"] == "critical mass"


def test_coefficients_gamma_is_degrees(tmp_path):
    """--gamma is in degrees (its help says so): the command's inertial K and C equal the
    Python API's at the state's attitude in radians, and differ from those at gamma = 0
    by the rotation through it. Fails with --gamma taken as radians."""
    import math

    import numpy as np

    from bearingfem import Bearing, JournalState
    from bearingfem.design import coefficients
    r = run("coefficients", "--model", "short", "--eps", "0.5", "--gamma", "30",
            "-o", str(tmp_path / "kc.json"))
    assert r.returncode == 0, r.stderr
    got = json.loads((tmp_path / "kc.json").read_text())
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    kc = coefficients(b, JournalState(0.5, omega=250.0, gamma=math.radians(30)), "short")
    for name, value in zip(("xx", "xy", "yx", "yy"), kc.K.ravel()):
        assert got[f"K_{name}"]["value"] == pytest.approx(value, rel=1e-6)
    for name, value in zip(("xx", "xy", "yx", "yy"), kc.C.ravel()):
        assert got[f"C_{name}"]["value"] == pytest.approx(value, rel=1e-6)
    k0 = coefficients(b, JournalState(0.5, omega=250.0), "short").K   # the same film at 0
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    rot = np.array([[c, -s], [s, c]])
    assert np.allclose(kc.K, rot @ k0 @ rot.T, rtol=1e-9, atol=1e-9 * abs(k0).max())


def test_design_answers_the_designers_question_in_one_command(tmp_path):
    """50 mm, L/D 0.5, c 50 um, 0.028 Pa s, 3000 rpm, 2 kN: least film, attitude, friction
    power, flow, K and C in the load frame with its axes named, and stability, in one
    command; the numbers are the Python API's at 3000 rpm = 100 pi rad/s (converted here)."""
    import math

    from bearingfem import Bearing
    from bearingfem.design import coefficients, equilibrium
    r = run("design", "--diameter", "0.05", "--ld", "0.5", "--clearance", "50e-6",
            "--viscosity", "0.028", "--rpm", "3000", "--load", "2000", "--model", "short",
            "-o", str(tmp_path / "d.json"))
    assert r.returncode == 0, r.stderr
    for words in ("minimum film", "attitude angle", "power loss", "side leakage (outflow)", "K_11",
                  "C_22", "axis 1 at -90 deg", "1 along the load", "critical mass",
                  "Lund stability of a rigid journal"):
        assert words in r.stdout
    got = json.loads((tmp_path / "d.json").read_text())
    b = Bearing(radius=0.025, length=0.025, clearance=50e-6, viscosity=0.028)
    eq = equilibrium(b, 2000.0, 100 * math.pi, "short", direction=-math.pi / 2)
    kc = coefficients(b, eq.state, "short", frame="load")
    assert got["minimum film"]["value"] == pytest.approx(eq.film_min, rel=1e-9)
    assert got["power loss"]["value"] == pytest.approx(eq.power_loss, rel=1e-9)
    assert got["K_12"]["value"] == pytest.approx(kc.K[0, 1], rel=1e-9)
    assert got["C_21"]["value"] == pytest.approx(kc.C[1, 0], rel=1e-9)
    # the least film also in um, as a designer reads it (the files keep SI)
    assert f"({eq.film_min * 1e6:.4g} um)" in r.stdout


def test_headers_name_the_films_options_in_words(capsys):
    """The designer's commands' first line names the film model's options as words (before:
    a Python dict, "fem {'n_theta': 120, ...}"); the help's design example is one shell
    command over two lines (before: the continuation swallowed, a run of spaces)."""
    from bearingfem_app.cli import build_parser, main
    assert main(["coefficients", "--ld", "1", "--eps", "0.5", "--n-theta", "24",
                 "--n-z", "4"]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert first.startswith("coefficients, fem (n_theta 24, n_z 4, element P1, "
                            "cavitation reynolds)") and "{" not in first
    assert "--oil 'ISO VG 32' \\\n      --rpm 3000" in build_parser().format_help()


def test_equilibrium_prints_one_flow_the_short_bearings_side_leakage(tmp_path):
    """The equilibrium prints one flow line, the side leakage, and it is the short bearing's
    closed form, U c eps L (the Couette flow into the pressurised half less the one out of
    it: Raimondi & Boyd's side-flow variable 2 pi eps), at L/D 1/8. The film's gap to it
    falls as (L/D)^2: 0.95, 0.26, 0.076 % at L/D 1/4, 1/8, 1/16 (120 x 20 P1), so 0.5 %.
    Old: a second line "inflow" printed the same number (flow_in was the side leakage)."""
    out = tmp_path / "eq.json"
    r = run("equilibrium", "--ld", "0.125", "--load", "100", "-o", str(out))
    assert r.returncode == 0, r.stderr
    assert "side leakage (outflow)" in r.stdout and "inflow" not in r.stdout
    rows = json.loads(out.read_text())
    assert "inflow" not in rows
    eps = rows["eps"]["value"]
    leakage = rows["side_outflow"]["value"]
    radius, clearance, length, omega = 0.01, 20e-6, 0.125 * 0.02, 250.0
    assert leakage == pytest.approx(omega * radius * clearance * eps * length, rel=5e-3)


def test_equilibrium_of_a_film_fed_at_its_ends_prints_what_leaves_there(tmp_path):
    """fem-jfo, oil at 1 bar at the ends: the side leakage printed is what leaves through
    the ends (the solution's side_outflow, checked against the Poiseuille field in
    test_independent_jfo), not the net leakage, zero to round-off (1e-20 m^3/s was printed
    as the film's side leakage)."""
    out = tmp_path / "eq.json"
    r = run("equilibrium", "--ld", "1", "--load", "1000", "--model", "fem-jfo", "-q",
            "-o", str(out))
    assert r.returncode == 0, r.stderr
    leakage = json.loads(out.read_text())["side leakage (outflow)"]["value"]
    assert 1e-7 < leakage < 1e-6       # 3.8e-7 m^3/s; the net is ~1e-20


@pytest.mark.parametrize("command", [("equilibrium", "--load", "500"),
                                     ("coefficients", "--eps", "0.5")])
def test_designer_headers_name_the_oils_viscosity(capsys, command):
    """--oil 'ISO VG 46' --oil-temperature 80: equilibrium and coefficients named neither
    the oil nor the viscosity it gave (design did); now their first line does."""
    from bearingfem_app.cli import main
    assert main([*command, "--oil", "ISO VG 46", "--oil-temperature", "80", "--n-theta",
                 "24", "--n-z", "4"]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert "viscosity 0.009614 Pa s (ISO VG 46 at 80 degC)" in first, first   # ~11 cSt


def test_coefficients_without_rotation_print_the_damping(capsys, tmp_path):
    """--omega 0 (a squeeze-film damper): K = 0 and C > 0, printed and written, with no
    stability verdict. Old: 'bearingfem: error: the film has no stiffness (K = 0): no
    stability verdict', exit 2, after the work, and K and C lost."""
    from bearingfem_app.cli import main
    out = tmp_path / "kc.csv"
    assert main(["coefficients", "--omega", "0", "--eps", "0.5", "--n-theta", "24",
                 "--n-z", "4", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "no stability verdict" in text and "C_xx" in text and "critical mass" not in text
    rows = {r.split(",")[0]: r.split(",")[1] for r in out.read_text().splitlines()[1:]}
    assert float(rows["K_xx"]) == 0.0 and float(rows["C_xx"]) > 0.0
    assert rows["stability"] == "none (K = 0)"
