"""The command line's errors: bad input and options are one line with exit status 2, a
typo or an old spelling is named with its fix, an unconverged solve is one line with exit
status 1, a load beyond the film's capacity says when the mesh is the cause
(test_cli_refusals.py: what a refused run leaves behind)."""
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def run(*args):
    return subprocess.run([sys.executable, "-m", "bearingfem_app", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)


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
