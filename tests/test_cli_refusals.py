"""The command line refuses before any work: one line, exit status 2, no folder left behind.

Each test names what the old command line did instead (run against it before the fix)."""
import os
import re
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from bearingfem_app.cli import main

ROOT = Path(__file__).resolve().parent.parent


def refused(capsys, *argv):
    """Run ``bearingfem argv`` in-process; the one stderr line of a refusal (exit 2)."""
    assert main(list(argv)) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("bearingfem: error: "), lines
    return lines[0]


@pytest.fixture
def here(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_every_bad_number_is_named_at_once(capsys):
    """Old: only '--clearance' was named; the viscosity and the mesh waited for a rerun."""
    line = refused(capsys, "solve", "--viscosity", "-1", "--clearance", "0", "--n-theta", "2")
    for name in ("--viscosity", "--clearance", "--n-theta"):
        assert name in line


def test_negative_load_is_refused_not_flipped(capsys):
    """Old: --load -100 pushed the journal up while the header said '-100 N at -90 deg'."""
    assert "--load" in refused(capsys, "equilibrium", "--load", "-100")


@pytest.mark.parametrize("argv, needle", [
    (("equilibrium", "--load", "100", "--model", "fvm", "--element", "P2"), "--element"),
    (("equilibrium", "--load", "100", "--model", "long", "--n-theta", "60"), "--n-theta"),
    (("coefficients", "--eps", "0.5", "--model", "fem", "--ambient-pressure", "1e5"),
     "--ambient-pressure"),
])
def test_options_a_model_does_not_take_are_refused(capsys, argv, needle):
    """Old: --element P2 with --model fvm was silently ignored (a P1-free FV answer)."""
    line = refused(capsys, *argv)
    assert needle in line and "does not apply to --model" in line


def test_model_help_lists_every_model_and_the_jfo_supply_exists():
    """Old: fem-jfo worked but was not listed; the help named a missing --ambient-pressure."""
    from bearingfem.models import FILM_MODELS
    from bearingfem_app.cli import DESIGN_MODELS, build_parser
    p = build_parser()
    sub = p._subparsers._group_actions[0].choices
    # every model but the thermal film, which the command line refuses by name
    assert set(FILM_MODELS) - set(DESIGN_MODELS) == {"fem-thd"}
    for cmd in ("equilibrium", "coefficients"):
        text = sub[cmd].format_help()
        for name in DESIGN_MODELS:
            assert name in text
        assert "--ambient-pressure" in text
    for cmd in ("solve", "render", "convergence", "equilibrium", "coefficients"):
        helps = " ".join(a.help or "" for a in sub[cmd]._actions)
        options = {o for a in sub[cmd]._actions for o in a.option_strings}
        for named in re.findall(r"--[a-z-]+[a-z]", helps):
            assert named in options, (cmd, named)


def test_fraction_of_a_reynolds_film_is_refused_before_the_solve(capsys, here):
    """Old: render --field fraction solved, then failed on the missing field."""
    assert "--cavitation jfo" in refused(capsys, "render", "--field", "fraction", "-o",
                                         "pics/film.png")
    assert not (here / "pics").exists()


@pytest.mark.parametrize("argv", [
    ("sweep", str(ROOT / "sweeps" / "capacity.toml"), "-o", "out", "--workers", "0"),
    ("sweep", str(ROOT / "sweeps" / "capacity.toml"), "-o", "out", "--scheduler",
     "notanaddress"),
    ("solve", "--eps", "2", "-o", "out/film.vtu"),
    ("coefficients", "--eps", "0.5", "--load", "3", "-o", "out/kc.json"),
])
def test_refused_runs_leave_no_folder(capsys, here, argv):
    """Old: each of these left an empty out/ behind."""
    refused(capsys, *argv)
    assert not (here / "out").exists()


def test_a_sweep_with_one_bad_case_is_refused_whole(capsys, here):
    """Old: the bad mesh (n_theta 2) was found by a worker, after the folder was made."""
    (here / "bad.toml").write_text('name = "bad"\nkind = "film"\n[vary]\n'
                                   'n_theta = [24, 2]\nmodel = ["fem"]\n')
    assert "n_theta" in refused(capsys, "sweep", "bad.toml", "-o", "out")
    assert not (here / "out").exists()


def test_unreachable_scheduler_is_one_line_within_seconds(here):
    """Old: 30 s of waiting, a 48-line chained traceback and an empty cases/ left behind."""
    t0 = time.perf_counter()
    r = subprocess.run([sys.executable, "-m", "bearingfem_app", "sweep", "capacity", "-o",
                        "out", "--scheduler", "tcp://127.0.0.1:1"], capture_output=True,
                       text=True, timeout=120, env={**os.environ, "PYTHONPATH": str(ROOT)})
    wall = time.perf_counter() - t0
    assert r.returncode == 2
    assert r.stderr.strip().splitlines() == [
        "bearingfem: error: --scheduler: no Dask scheduler answers at tcp://127.0.0.1:1 "
        "within 5 s (OSError)"]
    assert not (here / "out").exists()
    assert wall < 25.0     # 5 s timeout + imports on a loaded machine (was 30 s + imports)


def test_shipped_sweeps_are_found_by_name():
    """Old: 'sweeps/capacity.toml' existed only in the checkout."""
    from bearingfem_app.sweep import load_sweep, shipped_sweeps, sweep_path
    assert {"capacity", "design-chart", "mechanism-clearance"} <= set(shipped_sweeps())
    assert load_sweep("capacity").name == "capacity"
    assert sweep_path("sweeps/capacity.toml").is_file()
    assert "bearingfem_app" in sweep_path("capacity").parts


def test_unwritable_fem_table_cache_is_one_line(capsys, monkeypatch, tmp_path):
    """Old: the table was built (17 s) and its save failed silently."""
    blocker = tmp_path / "file"
    blocker.write_text("")
    monkeypatch.setenv("BEARINGFEM_CACHE", str(blocker / "cache"))
    assert "BEARINGFEM_CACHE" in refused(capsys, "equilibrium", "--load", "100", "--model",
                                         "fem-table")


def test_supply_at_the_maximum_film_gives_raimondi_boyd(capsys):
    """R&B's film starts at the maximum film: L/D 1, eps 0.6 has attitude 50.6 deg (their
    table); the periodic film gives 52.0 deg. Measured 50.53 deg at 120 x 20 and 50.53 at
    240 x 40 (the table's 3 digits bound the gap). Fails without --supply-angle."""
    assert main(["solve", "--ld", "1", "--eps", "0.6", "--supply-angle", "max-film"]) == 0
    out = capsys.readouterr().out
    attitude = float(re.search(r"attitude angle ([\d.]+) deg", out).group(1))
    assert attitude == pytest.approx(50.6, abs=0.15)


def test_broken_pipe_is_quiet(here):
    """Old: '... | head' ended in a BrokenPipeError traceback."""
    p = subprocess.Popen([sys.executable, "-m", "bearingfem_app", "solve", "--n-theta", "24",
                          "--n-z", "4"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         env={**os.environ, "PYTHONPATH": str(ROOT)})
    p.stdout.close()                    # the reader is gone before the first line
    err = p.stderr.read().decode()
    p.wait(timeout=120)
    assert "Error" not in err and "Traceback" not in err
    assert p.returncode == 141


@pytest.fixture(scope="module")
def analytic_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("run") / "long"
    assert main(["simulate", "paper-long-analytic", "-o", str(out), "-q"]) == 0
    return out


def test_frames_refuse_the_fraction_of_a_reynolds_run(capsys, here, analytic_run):
    """Old: 12 VTU files, then a 30-line TypeError."""
    line = refused(capsys, "frames", "paper-long-analytic", str(analytic_run), "-o", "fr",
                   "--field", "fraction")
    assert "fem-jfo" in line
    assert not (here / "fr").exists()


@pytest.mark.parametrize("extra", [("--angles=-30,400",), ("--frames", "0")])
def test_frames_bad_angles_are_refused(capsys, here, analytic_run, extra):
    """Old: -30 and 400 were accepted (times out of order); --frames 0 left fr/ behind."""
    refused(capsys, "frames", "paper-long-analytic", str(analytic_run), "-o", "fr", *extra)
    assert not (here / "fr").exists()


def test_frames_series_is_in_time_order(capsys, here, analytic_run):
    """Old: the PVD listed the frames in the order typed (200 deg before 10 deg)."""
    assert main(["frames", "paper-long-analytic", str(analytic_run), "-o", "fr",
                 "--angles", "200,10", "--no-render"]) == 0
    times = [float(d.get("timestep")) for d in ET.parse(here / "fr" / "film.pvd").iter("DataSet")]
    assert len(times) == 2 and times == sorted(times)


def test_ctrl_c_exits_130(here):
    """Old: an interrupted simulate exited 1 (a failure), its figure's axis still said
    'recorded turn'. The scene runs 200 turns and the interrupt waits for the progress
    line, so it always finds the run going (a first stderr byte from an import let it land
    in the import, after which five turns could finish: exit 0)."""
    scene = (ROOT / "scenes" / "paper-long-fem.toml").read_text()
    assert "turns = 5\n" in scene
    (here / "long.toml").write_text(scene.replace("turns = 5\n", "turns = 200\n"))
    p = subprocess.Popen([sys.executable, "-m", "bearingfem_app", "simulate",
                          "long.toml", "-o", "out"], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, env={**os.environ, "PYTHONPATH": str(ROOT)})
    seen = b""     # the progress line (its percentage) has come: the run is on. The first
    while b"%" not in seen:     # byte alone may be an import's notice (a fresh venv's font
        byte = p.stderr.read(1)     # cache), and a Ctrl-C then lands in the import
        if not byte:
            break
        seen += byte
    time.sleep(1.0)
    p.send_signal(signal.SIGINT)
    out, _ = p.communicate(timeout=120)      # reads both pipes: a full one would block it
    assert p.returncode == 130
    assert "PARTIAL" in out.decode()


def test_provenance_names_the_git_commit(analytic_run):
    """Old: a run said which version made it but not which commit of a checkout."""
    import json
    prov = json.loads((analytic_run / "result.json").read_text())["provenance"]
    assert re.fullmatch(r"[0-9a-f]{40}(-dirty)?", prov["git_commit"])
    from mechanism.result import _git_commit
    assert _git_commit(Path("/")) is None          # no checkout: the version says it


@pytest.mark.parametrize("argv, needles", [
    (("equilibrium", "--diameter", "50", "--load", "2000", "--omega", "314"),
     ("--diameter 50 m", "typed in mm", "0.05 m")),
    (("equilibrium", "--viscosity", "32", "--load", "2000"), ("--viscosity 32", "cSt")),
    (("solve", "--clearance", "0.05"), ("--clearance 0.05", "typed in mm")),
    (("solve", "--diameter", "0.05", "--omega", "30000"), ("--omega", "surface speed", "rpm")),
    (("coefficients", "--eps", "0.5", "--ld", "50"), ("--length-ratio/--ld (L/D) 50",)),
])
def test_a_bearing_no_journal_bearing_has_is_refused_naming_the_unit(capsys, here, argv,
                                                                      needles):
    """Old: --diameter 50 ended in a root finder's 'f(a) and f(b) must have different
    signs'; --viscosity 32 (cSt) ran silently to a friction coefficient of 19.7."""
    line = refused(capsys, *argv, "-o", "out/numbers.json") if argv[0] != "solve" else \
        refused(capsys, *argv, "-o", "out/film.vtu")
    for n in needles:
        assert n in line
    assert not (here / "out").exists()


def test_a_scene_no_journal_bearing_has_is_refused_and_leaves_nothing(capsys, here):
    """Old: a scene with diameter = 20 (mm) ran, LSODA failed at t = 0 and an output
    folder with an empty result was left behind."""
    text = (ROOT / "scenes" / "paper-short-fem.toml").read_text()
    (here / "d20.toml").write_text(text.replace("diameter = 0.020", "diameter = 20"))
    line = refused(capsys, "simulate", "d20.toml", "-o", "out")
    assert "scene.bearing.diameter 20 m" in line and "typed in mm" in line
    assert not (here / "out").exists()


def test_word_options_are_named_with_the_numbers(capsys):
    """Old: a misspelt --cavitation was reported alone, after the numbers' refusal had been
    fixed, as 'cavitation must be ...' (no option named); --element likewise."""
    line = refused(capsys, "solve", "--clearance", "-1", "--cavitation", "reynold",
                   "--element", "p2")
    for name in ("--clearance", "--cavitation must be one of", "'reynold'",
                 "--element must be one of", "'p2'"):
        assert name in line


def test_design_commands_point_the_jfo_film_to_its_model(capsys):
    """Old: 'cavitation must be one of 'none', 'gumbel', 'reynolds', got 'jfo'' with no
    word of the fem-jfo model that solves it."""
    assert "--model fem-jfo" in refused(capsys, "equilibrium", "--load", "100",
                                        "--cavitation", "jfo")


def test_jfo_convergence_refuses_p2_before_any_solve(capsys, here):
    """Old: the P1 meshes were solved (their lines printed), then the P2 film refused."""
    assert main(["convergence", "--cavitation", "jfo", "--supply-angle", "max-film",
                 "--levels", "3", "-o", "conv"]) == 2
    out, err = capsys.readouterr()
    assert out == "" and "--methods P1,fvm" in err and not (here / "conv").exists()


def test_jfo_convergence_takes_the_ambient_pressure_its_help_offers(capsys, here):
    """--cavitation jfo's help names --ambient-pressure > 0 as a supply; convergence refused
    it ('does not apply to convergence (Reynolds-family films ...)') and, without a supply,
    answered in the library's keywords (supply_angle, ambient_pressure)."""
    assert main(["convergence", "--cavitation", "jfo", "--ambient-pressure", "1e5",
                 "--methods", "P1,fvm", "--levels", "3", "--n-theta", "16", "--n-z", "2",
                 "-o", "conv"]) == 0
    assert "P1 64x8" in capsys.readouterr().out and (here / "conv" / "convergence.csv").exists()
    line = refused(capsys, "convergence", "--cavitation", "jfo", "--methods", "P1",
                   "-o", "conv2")
    assert "--ambient-pressure > 0" in line and "--supply-angle" in line
    assert "--cavitation jfo" in refused(capsys, "convergence", "--ambient-pressure", "1e5",
                                         "-o", "conv3")
    assert not (here / "conv2").exists() and not (here / "conv3").exists()


def test_convergence_says_what_an_order_nan_means(capsys, here):
    """A P2 force that oscillates at the finest meshes has no observed order; the table
    says why instead of leaving a bare nan. Old: the nan alone."""
    assert main(["convergence", "--ld", "1", "--eps", "0.6", "--levels", "3",
                 "--methods", "P2", "--n-theta", "48", "--n-z", "8", "-o", "conv"]) == 0
    out = capsys.readouterr().out
    assert " nan " in out and "order nan: the three finest values do not change" in out


@pytest.mark.parametrize("command", ["solve", "render", "convergence"])
def test_an_eps_dot_no_journal_reaches_is_refused_with_its_range(capsys, here, command):
    """--eps-dot is checked like --omega / --rpm: the journal centre's speed c |eps_dot|
    against any journal's in its bearing (10 m/s), named with its unit and the range for
    this clearance. Old: --eps-dot 1e12 (and -6e5) solved and printed a Sommerfeld number
    of 3e-12; only a non-finite rate was refused."""
    out = {"solve": "film.vtu", "render": "film.png", "convergence": "conv"}[command]
    for value in ("1e12", "-6e5"):
        line = refused(capsys, command, "--eps-dot", value, "--n-theta", "24", "--n-z", "4",
                       "-o", f"out/{out}")
        for needle in ("--eps-dot", "1/s", "m/s", "[-5e+05, 5e+05] 1/s"):
            assert needle in line, line
    # the range is the clearance's: 4e5 1/s is 8 m/s at 20 um, 16 m/s at 40 um
    line = refused(capsys, command, "--eps-dot", "4e5", "--clearance", "40e-6",
                   "-o", f"out/{out}")
    assert "[-2.5e+05, 2.5e+05] 1/s" in line
    assert not (here / "out").exists()


def test_an_eps_dot_inside_the_range_is_solved(capsys):
    """The check refuses nothing a journal does: 4e5 1/s at c = 20 um (8 m/s) is solved."""
    assert main(["solve", "--eps-dot", "4e5", "--n-theta", "24", "--n-z", "4"]) == 0
    assert "Sommerfeld number" in capsys.readouterr().out


@pytest.mark.parametrize("argv, needles", [
    (("solve", "--cavitation", "jfo"), ("--cavitation jfo", "--ambient-pressure > 0",
                                         "--supply-angle")),
    (("render", "--cavitation", "jfo", "-o", "out/f.png"), ("--cavitation jfo",
                                                           "--ambient-pressure > 0")),
    (("solve", "--ambient-pressure", "1e5"), ("--ambient-pressure", "--cavitation jfo",
                                              "not --cavitation reynolds")),
    (("solve", "--bush", "ring", "--element", "P2"), ("--bush needs --element P1",)),
    (("solve", "--bush", "ring", "--cavitation", "gumbel"), ("--bush needs --cavitation",
                                                            "gumbel")),
    (("equilibrium", "--load", "100", "--model", "fem-ehd", "--bush", "ring",
      "--cavitation", "gumbel"), ("--bush needs --cavitation",)),
    (("equilibrium", "--load", "100", "--model", "fem", "--bush", "ring",
      "--element", "P2"), ("--bush needs --element P1",)),
    (("coefficients", "--model", "fem", "--bush", "ring", "--element", "P2"),
     ("--bush needs --element P1",)),
    (("equilibrium", "--load", "100", "--model", "fem-jfo", "--ambient-pressure", "0"),
     ("--model fem-jfo needs --ambient-pressure > 0",)),
    (("render", "--field", "temperature", "-o", "out/f.png"),
     ("--field temperature is a thermal film's", "'pressure', 'film_thickness', 'fraction'")),
])
def test_film_options_that_need_each_other_are_named_as_typed(capsys, here, argv, needles):
    """Options that need one another are refused in the command line's own names before
    any work. Old: the library's keywords (cavitation='jfo' needs ... supply_angle or
    ambient_pressure > 0; bush needs element='P1'; render's field 'temperature' needs
    thermal=Thermal(...), which render does not take)."""
    line = refused(capsys, *argv)
    for n in needles:
        assert n in line, line
    assert not re.search(r"\w='", line) and "Thermal(" not in line, line
    assert not (here / "out").exists()


@pytest.mark.parametrize("argv", [
    ("solve", "--n-theta", "100000", "--n-z", "10000"),
    ("render", "--n-theta", "4000", "--n-z", "1000", "-o", "out/f.png"),
    ("convergence", "--n-theta", "480", "--n-z", "160", "--levels", "4", "-o", "out/c")])
def test_a_mesh_beyond_memory_is_named_as_typed(capsys, here, argv):
    """Old: solve built a 1e9-node mesh until the process was killed for memory; the
    library now refuses it in its own names, the command line in the options'. A
    convergence study's finest level (480 x 160 doubled three times, P2) is what counts."""
    line = refused(capsys, *argv)
    assert "--n-theta x --n-z" in line and "unknowns" in line
    assert not (here / "out").exists()


@pytest.mark.parametrize("argv, noted", [
    (("solve", "--eps", "0.999"), True),                     # 1.7 spacings: 44 % measured
    (("solve", "--eps", "0.999", "--model", "fvm"), True),
    (("solve", "--eps", "0.999", "--n-theta", "480"), False),  # 6.8 spacings
    (("solve", "--eps", "0.999", "--element", "P2", "--n-theta", "240", "--n-z", "4"), False),
    (("solve", "--eps", "0.6"), False),
    (("solve", "--eps", "0.999", "--rtol", "1e-2", "-q"), False),
    (("coefficients", "--eps", "0.999", "--n-theta", "60", "--n-z", "4"), True),
    (("equilibrium", "--load", "1.5e4", "--n-theta", "48", "--n-z", "4"), True),
    (("equilibrium", "--load", "1.5e4", "--model", "short"), False)])
def test_a_film_too_coarse_for_its_least_film_is_noted(capsys, argv, noted):
    """solve --eps 0.999 on the default 120 cells gave |F| 44 % below the converged film
    (P1 force errors of 6-86 % measured under 4 node spacings across the arc where the film
    is under twice its least) and said nothing; now a note on stderr, the answer unchanged."""
    assert main(list(argv)) == 0
    err = capsys.readouterr().err
    assert ("note: the film under twice its least" in err) == noted, err


def test_sweep_workers_are_checked_against_the_cores(monkeypatch, tmp_path, capsys):
    """--workers above 4 per core is refused before any process starts (--workers 200
    started 200 on a 2-core machine), and --workers beside --scheduler is refused by name
    (it was ignored: the cluster's own workers run the cases). The cores are those the
    process may run on (its affinity: a container pinned to 2 of 64 cores), not the
    machine's count; without an affinity call, the machine's count."""
    import bearingfem_app.sweep

    def started(*args, **kwargs):
        raise AssertionError("the sweep started")
    monkeypatch.setattr(bearingfem_app.sweep, "run_sweep", started)
    monkeypatch.setattr(os, "cpu_count", lambda: 64)
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0, 1}, raising=False)
    assert main(["sweep", "capacity", "-o", str(tmp_path / "s"), "--workers", "9"]) == 2
    assert capsys.readouterr().err.strip() == (
        "bearingfem: error: --workers 9 local processes on 2 cores: at most 8 (more only "
        "share the cores; --scheduler runs on a larger cluster)")
    assert main(["sweep", "capacity", "-o", str(tmp_path / "s"), "--workers", "2",
                 "--scheduler", "tcp://127.0.0.1:1"]) == 2
    assert "--workers starts a local cluster" in capsys.readouterr().err
    assert not (tmp_path / "s").exists()
    with pytest.raises(SystemExit):                       # the help says the cap
        main(["sweep", "--help"])
    assert "(>= 1, at most 4 per core; not with --scheduler)" in " ".join(
        capsys.readouterr().out.split())
    monkeypatch.delattr(os, "sched_getaffinity")
    monkeypatch.setattr(os, "cpu_count", lambda: 1)
    assert main(["sweep", "capacity", "-o", str(tmp_path / "s"), "--workers", "5"]) == 2
    assert "--workers 5 local processes on 1 cores: at most 4" in capsys.readouterr().err


def test_an_output_of_another_commands_kind_names_that_command(capsys):
    """solve -o film.png names render, which draws the film (it listed solve's suffixes
    alone); render -o film.vtu names solve; a kind no command writes only the suffixes."""
    assert refused(capsys, "solve", "-o", "film.png").endswith(
        "got 'film.png' (a picture of the film: bearingfem render ... -o FILE)")
    assert "(the film's fields: bearingfem solve ... -o FILE)" in refused(
        capsys, "render", "-o", "film.vtu")
    assert refused(capsys, "design", "--load", "10", "-o", "d.txt").endswith("got 'd.txt'")


@pytest.mark.parametrize("argv", [
    ("solve", "--eps", "0.999"),
    ("coefficients", "--eps", "0.999", "--n-theta", "60", "--n-z", "4"),
    ("coefficients", "--eps", "0.999", "--n-theta", "60", "--n-z", "4", "--estimate"),
    ("equilibrium", "--load", "1.5e4", "--n-theta", "48", "--n-z", "4"),
    ("design", "--load", "1.5e4", "--n-theta", "48", "--n-z", "4")])
def test_the_coarse_film_notes_advice_names_options_the_command_takes(capsys, argv):
    """The note's advice ('a finer --n-theta, or --rtol for an estimated error') names
    only options the command takes, checked against its parser: design, which takes no
    --rtol, advised it (refused then as 'an option of solve, render, equilibrium,
    coefficients'), and an option already in use (--estimate) is not advised again.
    Planted: one advice for every command (--rtol or --estimate): fails for solve and
    design."""
    from bearingfem_app.parser import build_parser
    assert main(list(argv)) == 0
    note = next(x for x in capsys.readouterr().err.splitlines() if "note: the film" in x)
    advised = re.findall(r"--[a-z-]+", note.split("): a finer", 1)[1])
    sub = build_parser()._subparsers._group_actions[0].choices[argv[0]]
    taken = {o for a in sub._actions for o in a.option_strings}
    assert advised[0] == "--n-theta" and set(advised) <= taken, advised
    assert not set(advised[1:]) & set(argv[1:]), advised
