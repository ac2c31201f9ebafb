"""The command line's help and version: every command listed, each option's default and
checked range said truthfully, --version for citing, and `python -m bearingfem`
pointing to the command."""
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


def test_version_is_printed_for_citing():
    """`bearingfem --version` prints the package version, exit 0 (it said 'the following
    arguments are required: command')."""
    from bearingfem import __version__
    r = run("--version")
    assert r.returncode == 0 and r.stdout.strip() == f"bearingfem {__version__}"
