"""render on the command line takes the film options of solve (--model, --rtol, --bush
and its options) and draws the bush's deflection; off screen (matplotlib Agg, pyvista
off_screen). Each test fails on the old render, which refused these options."""
import re

import matplotlib
import pytest

from bearingfem.accuracy import clear_memo
from bearingfem_app.cli import main

matplotlib.use("Agg")

BUSH = ("--ld", "0.5", "--eps", "0.8", "--n-theta", "48", "--n-z", "4", "--bush", "ring",
        "--bush-outer-radius", "0.015", "--bush-modulus", "5e9", "--bush-poisson", "0.3")


def _force(out):
    return re.search(r"\|F\| ([\d.e+-]+) N", out).group(1)


@pytest.mark.parametrize("surface", ["unwrapped", "journal"])
def test_render_draws_the_bush_deflection_of_the_film_solve_solves(capsys, tmp_path, surface):
    """render --bush ... --field deformation solves the film solve --bush solves (the same
    printed force, every bush option kept) and writes its deflection's picture."""
    assert main(["solve", *BUSH, "-q"]) == 0
    solved = _force(capsys.readouterr().out)
    png = tmp_path / f"{surface}.png"
    assert main(["render", *BUSH, "-q", "--field", "deformation", "--surface", surface,
                 "-o", str(png)]) == 0
    out = capsys.readouterr().out
    assert _force(out) == solved and "ehd-newton" in out
    assert png.stat().st_size > 5000


def test_render_takes_rtol_and_the_fvm_film_as_solve_does(capsys, tmp_path):
    """The same grid chosen and force as solve's (each search cold: a repeated search in
    one process starts from the mesh that sufficed before, bearingfem.accuracy)."""
    args = ("--ld", "0.5", "--eps", "0.6", "--model", "fvm", "--rtol", "1e-2", "-q")
    clear_memo()
    assert main(["solve", *args]) == 0
    solved = capsys.readouterr().out
    clear_memo()
    assert main(["render", *args, "-o", str(tmp_path / "f.png")]) == 0
    out = capsys.readouterr().out
    assert out.startswith("film fvm/") and "chosen for rtol 0.01" in out
    assert out.splitlines()[:2] == solved.splitlines()[:2]


@pytest.mark.parametrize("argv, needle", [
    (("--field", "deformation"), "--field deformation is the elastic bush's deflection: "
                                 "give --bush"),
    (("--field", "temperature"), "--field temperature is a thermal film's"),
    (("--model", "fvm", "--bush", "ring"), "--bush applies to --model fem"),
    (("--bush-modulus", "5e9"), "--bush-modulus needs --bush"),
    (("--rtol", "1e-3", "--n-theta", "48"), "--n-theta is not taken with --rtol"),
])
def test_render_refuses_what_it_cannot_draw_before_any_work(capsys, tmp_path, argv, needle):
    assert main(["render", *argv, "-o", str(tmp_path / "out" / "f.png")]) == 2
    err = capsys.readouterr().err
    assert needle in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "out").exists()
