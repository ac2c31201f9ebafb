"""The command line: help, one-line errors with exit status 2, and the simulate output."""
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def run(*args):
    return subprocess.run([sys.executable, "-m", "bearingfem_app", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)


def test_help_lists_commands():
    r = run("--help")
    assert r.returncode == 0
    for cmd in ("simulate", "solve", "render", "convergence", "sweep", "examples:"):
        assert cmd in r.stdout


def test_python_m_bearingfem_points_to_the_command_in_one_line():
    # the library has no command of its own (and imports nothing of the app layer above it)
    r = subprocess.run([sys.executable, "-m", "bearingfem", "solve"], cwd=ROOT,
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and r.stdout == ""
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "python -m bearingfem_app" in lines[0]
    assert lines[0].startswith("bearingfem: error:")


@pytest.mark.parametrize("flag", ["--help", "-h"])
def test_python_m_bearingfem_help_prints_the_usage_and_exits_0(flag):
    # asked for help it answers as any command's help does (it refused with status 2)
    r = subprocess.run([sys.executable, "-m", "bearingfem", flag], cwd=ROOT,
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and r.stderr == ""
    assert r.stdout.startswith("usage: bearingfem COMMAND")
    assert "python -m bearingfem_app COMMAND" in r.stdout


@pytest.mark.parametrize("args,needle", [
    (("solve", "--eps", "1.5"), "eps must lie in [0, 1)"),
    (("solve", "--cavitation", "swift"), "cavitation must be one of"),
    (("solve", "--ld", "-1"), "--length-ratio/--ld (L/D) must be positive"),
    # inf and nan are named as not finite (it said 'must be positive (> 0), got inf')
    (("solve", "--ld", "inf"), "--length-ratio/--ld (L/D) must be finite and positive (> 0), "
                               "got inf"),
    (("solve", "--eps", "nan"), "--eps: eps must be finite and in [0, 1), got nan"),
    # degrees within a turn (1e30 ran, a load at 1.7e28 rad; the library takes radians)
    (("design", "--load", "100", "--direction", "1e30"), "--direction [deg] must lie in "
                                                          "[-360, 360], got 1e+30"),
    # every level counts (--levels 40 ran eleven levels, minutes, before the 12th's refusal)
    (("convergence", "--levels", "40", "-o", "x"), "(P2 at the finest of --levels 40) is "
                                                    "~1.2e+26 unknowns, above the 4e+06 a "
                                                    "film solve takes: fewer --levels"),
    (("simulate", "no/such/scene.toml", "-o", "x"), "scene file not found"),
    (("sweep", "no/such/sweep.toml", "-o", "x"), "sweep file not found: no/such/sweep.toml"),
    (("solve", "--cavitation", "jfo"), "needs a supply of oil"),
    (("solve", "--ambient-pressure", "1e5"), "give --cavitation jfo with it"),
    (("solve", "--speed", "300"), "did you mean --omega [rad/s] or --rpm [1/min]?"),
    (("solve", "--model", "fdm"), "invalid choice 'fdm' (choose fem or fvm"),
    (("coefficients", "--frame", "polar"), "invalid choice: 'polar'"),
    (("simulate", "paper-short-fem"), "required: -o/--output"),
    (("mesh",), "invalid choice: 'mesh'"),
    # the thermal film needs what the command line does not take (it failed after parsing)
    (("equilibrium", "--load", "100", "--model", "fem-thd"), "build it in Python"),
    # the speed named as typed (it was '--omega 314159 rad/s' and 'omega must be non-zero')
    (("solve", "--rpm", "3e6"), "--rpm 3e+06 1/min gives a surface speed of 3142 m/s at "
                                "radius 0.01 m, above any journal bearing's (300 m/s): "
                                "|--rpm| must be at most 2.8648e+05 1/min"),
    (("design", "--load", "100", "--rpm", "0"), "--rpm must be non-zero for design"),
    (("equilibrium", "--load", "100", "--omega", "0"), "--omega must be non-zero for "
                                                       "equilibrium"),
])
def test_bad_input_is_one_line_and_exit_2(args, needle):
    r = run(*args)
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and needle in lines[0] and lines[0].startswith("bearingfem: error:")


def test_solve_prints_forces_and_exports(tmp_path):
    r = run("solve", "--ld", "0.5", "--eps", "0.7", "--n-theta", "48", "--n-z", "8",
            "-o", str(tmp_path / "film.vtu"))
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "film.vtu").is_file()
    for named in ("|F|", "N", "attitude angle", "deg", "cavitated area", "%", "Pa", "um",
                  "m^3/s", "Sommerfeld number"):
        assert named in r.stdout, named


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


@pytest.mark.slow   # 5 s; the sweep runner is tested on a real cluster in test_sweep.py
def test_sweep_command_runs_and_resumes(tmp_path):
    sweep = tmp_path / "s.toml"
    sweep.write_text('name = "s"\n[base]\nmodel = "short"\n[vary]\neps = [0.2, 0.8]\n')
    r = run("sweep", str(sweep), "-o", str(tmp_path / "out"), "--workers", "1", "-q")
    assert r.returncode == 0, r.stderr
    assert "2 computed, 0 already done, 0 failed" in r.stdout
    r = run("sweep", str(sweep), "-o", str(tmp_path / "out"), "--workers", "1", "-q")
    assert "0 computed, 2 already done" in r.stdout


@pytest.mark.parametrize("args,needle", [
    (("solve", "--model", "fvm", "--element", "P2"), "--element applies to --model fem only"),
    (("solve", "-o", "film.csv"), "-o/--output must end in .vtu or .xdmf or .vtk"),
    (("render", "-o", "film.pdf"), "-o/--output must end in .png"),
    (("render", "-o", "/proc/no/film.png"), "-o/--output: cannot create folder"),
    (("simulate", "paper-long-analytic", "-o", "/proc/no/run"), "-o/--output: cannot create"),
    (("render", "--surface", "flat", "-o", "x.png"), "--surface must be one of"),
    (("convergence", "--quantity", "foo", "-o", "c"), "--quantity must be one of"),
    (("convergence", "--element", "P2", "-o", "c"), "--element does not apply to convergence"),
    (("solve", "--clearance", "-20e-6"), "clearance must be positive (> 0), got -2e-05"),
    (("equilibrium", "--load", "1e8"), "exceeds what the film carries before contact"),
    (("equilibrium", "--load", "100", "--model", "fe"), "--model must be one of"),
    (("equilibrium", "--load", "100", "-o", "eq.txt"), "-o/--output must end in .json or .csv"),
    (("coefficients", "--ld", "1"), "give exactly one of --eps"),
])
def test_bad_options_are_refused_before_any_work(args, needle):
    r = run(*args)
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and needle in lines[0]   # one line, no traceback


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


def test_solve_prints_load_attitude_and_sommerfeld():
    r = run("solve", "--eps", "0.6", "--n-theta", "48", "--n-z", "8")
    assert r.returncode == 0
    assert "|F|" in r.stdout and "attitude angle" in r.stdout and "Sommerfeld number" in r.stdout


def test_solve_jfo_prints_fraction_and_balance(tmp_path):
    r = run("solve", "--cavitation", "jfo", "--ambient-pressure", "1e5", "--n-theta", "48",
            "--n-z", "8", "-o", str(tmp_path / "film.vtu"))
    assert r.returncode == 0, r.stderr
    assert "JFO film fraction" in r.stdout and "mass balance" in r.stdout


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


def test_rpm_is_the_speed_in_revolutions_per_minute():
    """--rpm 3000 is --omega 100 pi (the same film), and one of the two is given."""
    import math
    a = run("solve", "--rpm", "3000", "--model", "fvm", "--n-theta", "24", "--n-z", "4")
    b = run("solve", "--omega", repr(100 * math.pi), "--model", "fvm", "--n-theta", "24",
            "--n-z", "4")
    assert a.returncode == 0 and a.stdout == b.stdout
    c = run("equilibrium", "--load", "100", "--rpm", "3000", "--omega", "3")
    assert c.returncode == 2 and "not allowed with argument" in c.stderr


def test_help_states_defaults_truthfully():
    """No '(default: None)' on required options or options whose absence means something,
    and no default said twice (old: '(default 1e5) (default: None)'); simulate's scene
    may be a shipped scene's name."""
    for cmd in ("simulate", "solve", "convergence", "render", "sweep", "frames",
                "equilibrium", "coefficients", "design"):
        text = " ".join(run(cmd, "--help").stdout.split())
        assert "(default: None)" not in text, cmd
        assert "default 1e5) (default" not in text and "default 0) (default" not in text
    assert "paper-short-fem" in run("simulate", "--help").stdout


def test_old_spelling_is_taken_with_a_note_and_typos_get_a_suggestion():
    """`solve --method fvm` (old) is `solve --model fvm`, with a note; `--modl` names
    --model (old: the top-level usage, no suggestion)."""
    old = run("solve", "--method", "fvm", "--n-theta", "24", "--n-z", "4")
    new = run("solve", "--model", "fvm", "--n-theta", "24", "--n-z", "4")
    assert old.returncode == 0 and old.stdout == new.stdout
    assert "note: --method is now --model" in old.stderr
    speed = run("equilibrium", "--load", "100", "--speed", "300")
    assert speed.returncode == 2 and "did you mean --omega [rad/s] or --rpm" in speed.stderr
    typo = run("solve", "--modl", "fvm")
    assert typo.returncode == 2 and "did you mean --model?" in typo.stderr
    assert typo.stderr.strip().splitlines() == [   # one line, as every refusal
        "bearingfem: error: unrecognized arguments: --modl (did you mean --model?) fvm "
        "('bearingfem solve --help' lists the options)"]
    # a designer's model name on solve names the options that ask for its film here
    jfo = run("solve", "--model", "fem-jfo")
    assert jfo.returncode == 2 and "give --model fem --cavitation jfo" in jfo.stderr


def test_oil_by_grade_is_its_viscosity_at_the_temperature():
    """--oil 'ISO VG 32' at 40 degC is 32 mm^2/s (the grade's midpoint, ISO 3448) times
    870 kg/m^3 = 0.02784 Pa s, by hand; a warmer oil is thinner; a grade that does not
    exist, both --oil and --viscosity, or a temperature without an oil are refused."""
    a = run("solve", "--oil", "ISO VG 32", "--oil-temperature", "40", "--model", "fvm",
            "--n-theta", "24", "--n-z", "4")
    b = run("solve", "--viscosity", repr(32e-6 * 870), "--model", "fvm", "--n-theta", "24",
            "--n-z", "4")
    assert a.returncode == 0 and a.stdout == b.stdout
    hot = run("solve", "--oil", "VG32", "--oil-temperature", "80", "--model", "fvm",
              "--n-theta", "24", "--n-z", "4")
    f = [float(r.stdout.split("|F| ")[1].split()[0]) for r in (a, hot)]
    assert f[1] < 0.5 * f[0]
    for argv, needle in ((("--oil", "ISO VG 33"), "--oil must be an ISO VG grade"),
                         (("--oil", "VG 32", "--viscosity", "0.03"), "not allowed with"),
                         (("--oil-temperature", "60"), "--oil-temperature is the --oil's")):
        r = run("equilibrium", "--load", "100", *argv)
        assert r.returncode == 2 and needle in r.stderr


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


def test_help_states_each_checked_range():
    """Every option the command line checks against a bound says the bound in its help
    (old: --n-theta, --n-z, --rtol, --workers, --frames, --turns and coefficients' --eps
    were refused by a range their help did not name), and --quantity lists its choices."""
    import argparse
    from bearingfem_app.checks import RULES, _range
    from bearingfem_app.cli import build_parser
    sub = next(a for a in build_parser()._actions
               if isinstance(a, argparse._SubParsersAction)).choices
    missing = []
    for cmd, parser in sub.items():
        for action in parser._actions:
            rule = RULES.get(action.dest)
            if rule is None or not action.option_strings:
                continue
            text = _range(*rule[1:])
            if text in ("finite", "positive"):
                continue
            said = text.removeprefix("in ")
            if said not in " ".join((action.help or "").split()):
                missing.append(f"{cmd} {action.option_strings[-1]}: {said}")
    assert not missing, missing
    from bearingfem.outputs.convergence import QUANTITIES
    quantity = next(a for a in sub["convergence"]._actions if a.dest == "quantity")
    assert all(q in quantity.help for q in QUANTITIES)


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


def test_ambient_pressure_help_says_each_default_and_why_they_differ():
    """solve's --ambient-pressure defaults to solve_reynolds's 0, equilibrium's to the
    fem-jfo model's 1e5 Pa: each help text gives its own default, the other's and the
    reason (the model takes no supply line), from the library's values (the helps said
    '(default 0)' and '(default 1e5)' with no word on why)."""
    import inspect

    from bearingfem import solve_reynolds
    from bearingfem.models import film_model
    film = inspect.signature(solve_reynolds).parameters["ambient_pressure"].default
    model = film_model("fem-jfo").defaults["ambient_pressure"]
    assert (film, model) == (0.0, 1e5)
    for command, own, other in (("solve", film, model), ("equilibrium", model, film)):
        text = " ".join(run(command, "--help").stdout.split())
        assert f"(default {own:g}" in text and f"defaults to {other:g}" in text, command
        assert "takes no supply line" in text or "takes a supply line" in text, command


def test_help_ranges_are_the_checks_own_table(monkeypatch):
    """The helps' ranges are read from RULES, the table check_numbers refuses by, not
    retyped: a range changed in RULES changes the help (retyped, '[1e-06, 0.1]' and
    '(0, 1000]' stayed behind)."""
    import argparse
    from bearingfem_app import checks
    from bearingfem_app.cli import build_parser
    monkeypatch.setitem(checks.RULES, "rtol", ("--rtol", 1e-5, True, 0.05, True))
    monkeypatch.setitem(checks.RULES, "turns", ("--turns", 0.0, False, 50.0, True))
    sub = next(a for a in build_parser()._actions
               if isinstance(a, argparse._SubParsersAction)).choices
    helps = {a.dest: " ".join(a.help.split()) for cmd in ("solve", "simulate")
             for a in sub[cmd]._actions if a.dest in ("rtol", "turns")}
    assert "in [1e-05, 0.05]" in helps["rtol"] and "in (0, 50]" in helps["turns"]


def test_the_oil_temperature_help_says_its_range():
    """--oil-temperature is refused outside [-50, 200] degC (an oil film's): its help says
    so (it gave the default alone)."""
    import argparse
    from bearingfem_app.cli import build_parser
    sub = next(a for a in build_parser()._actions
               if isinstance(a, argparse._SubParsersAction)).choices
    for cmd in ("solve", "equilibrium", "design"):
        (action,) = [a for a in sub[cmd]._actions if a.dest == "oil_temperature"]
        assert "[degC] in [-50, 200] (default 40)" in action.help


def test_an_option_of_other_commands_is_named_as_theirs():
    """`convergence --rtol` (convergence refines --levels meshes; --rtol is the film
    commands') says whose option it is, not 'did you mean --oil?', a look-alike of this
    command's; a typo still gets its nearest option."""
    r = run("convergence", "--rtol", "1e-3", "-o", "x")
    assert r.returncode == 2
    assert r.stderr.strip().splitlines() == [
        "bearingfem: error: unrecognized arguments: --rtol (an option of solve, render, "
        "equilibrium, coefficients, not of convergence) 1e-3 ('bearingfem convergence --help' "
        "lists the options)"]
    bush = run("design", "--load", "100", "--bush", "ring")
    assert bush.returncode == 2 and "--bush (an option of solve, render, equilibrium, " \
        "coefficients, not of design)" in bush.stderr


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


def test_a_solve_that_does_not_converge_is_one_line_and_exit_1(monkeypatch, capsys):
    """A ConvergenceError from the library is one line on stderr naming what did not
    converge, exit status 1 (the work ran and did not succeed); it was a traceback."""
    import bearingfem
    from bearingfem.errors import ConvergenceError
    from bearingfem_app.cli import main

    def unconverged(*args, **kwargs):
        raise ConvergenceError("EHD Newton (load continuation)", 0, None,
                               "coupling s = 0, step below 0.0001")
    monkeypatch.setattr(bearingfem, "solve_reynolds", unconverged)
    assert main(["solve", "--n-theta", "24", "--n-z", "4", "-q"]) == 1
    err = capsys.readouterr().err
    assert err.splitlines() == ["bearingfem: error: EHD Newton (load continuation) did not "
                                "converge at coupling s = 0, step below 0.0001: 0 iterations"]


def test_a_capacity_refusal_on_a_coarse_mesh_says_the_mesh_is_coarse(capsys):
    """'load exceeds what the film carries' on 8 x 2 cells names the mesh as surely too
    coarse at eps_max (its 1991 N is the mesh's: 120 x 20 carries 2.5e5 N); on a mesh that
    resolves the film the refusal is the bearing's and says nothing more."""
    from bearingfem_app.cli import main
    bearing = ["--diameter", "0.05", "--ld", "0.5", "--clearance", "50e-6", "--oil",
               "ISO VG 32", "--rpm", "3000"]
    for command in ("equilibrium", "design"):
        assert main([command, *bearing, "--load", "2000", "--n-theta", "8", "--n-z",
                     "2"]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and "exceeds what the film carries" in err[0], err
        assert "spans 0.36 node spacings of --n-theta 8 (P1)" in err[0], err
    assert main(["equilibrium", *bearing, "--load", "1e6", "--n-theta", "240",
                 "--n-z", "4"]) == 2
    err = capsys.readouterr().err
    assert "exceeds what the film carries" in err and "node spacings" not in err


def test_the_coarse_mesh_note_reads_the_typed_refusal_not_its_words(monkeypatch, capsys):
    """The note is added to a LoadCapacityError (it carries eps_max and the mesh), not to
    any refusal whose text says 'exceeds what the film carries': a plain ValueError with
    those words passes through as it is, and the note's mesh is the error's."""
    import bearingfem.design
    from bearingfem import LoadCapacityError
    from bearingfem_app.cli import main

    def refuse(error):
        def equilibrium(*args, **kwargs):
            raise error
        return equilibrium

    argv = ["equilibrium", "--load", "2000", "--n-theta", "8", "--n-z", "2"]
    words = "load 2000 N exceeds what the film carries before contact: 5 N"
    monkeypatch.setattr(bearingfem.design, "equilibrium", refuse(ValueError(words)))
    assert main(argv) == 2
    assert capsys.readouterr().err.strip() == f"bearingfem: error: {words}"
    monkeypatch.setattr(bearingfem.design, "equilibrium", refuse(LoadCapacityError(
        2000.0, 5.0, 0.9, "fem", dict(n_theta=8, n_z=2, element="P2"))))
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(
        "bearingfem: error: load 2000 N exceeds what the film carries before contact: 5 N "
        "at eps_max = 0.9 (fem model); the film under twice its least (eps 0.9) spans "), err
    assert "node spacings of --n-theta 8 (P2)" in err[0], err


def test_version_is_printed_for_citing():
    """`bearingfem --version` prints the package version, exit 0 (it said 'the following
    arguments are required: command')."""
    from bearingfem import __version__
    r = run("--version")
    assert r.returncode == 0 and r.stdout.strip() == f"bearingfem {__version__}"


def test_k_and_c_of_a_film_with_memory_are_refused_before_the_equilibrium(monkeypatch,
                                                                          capsys):
    """design and coefficients --load with a film that has memory (fem-jfo, fem-ehd) are
    refused before the equilibrium is solved, naming what gives each answer; they solved
    the equilibrium, then refused with 'its film fraction is carried by the flow', also
    for fem-ehd, whose memory is the bush's deflection."""
    import bearingfem.design as design
    from bearingfem_app.cli import main

    def solved(*args, **kwargs):
        raise AssertionError("the equilibrium was solved")
    monkeypatch.setattr(design, "equilibrium", solved)
    for command, model in (("design", "fem-jfo"), ("coefficients", "fem-ehd")):
        assert main([command, "--load", "100", "--model", model]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and f"--model {model} has memory" in err[0], err
        assert "film fraction" not in err[0]
