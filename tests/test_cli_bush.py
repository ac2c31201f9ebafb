"""The elastic bush on the command line (--bush, --bush-outer-radius, --bush-modulus,
--bush-poisson on solve, equilibrium and coefficients): the film is the Python API's, bad
input is one line with exit status 2."""
import re

import numpy as np
import pytest

from bearingfem import Bearing, ElasticBush, JournalState, solve_reynolds
from bearingfem.bearing import SEED_TABLE1
from bearingfem_app.cli import main

MESH = ("--n-theta", "48", "--n-z", "4")


def test_solve_with_a_bush_is_the_api_film(capsys):
    """solve --bush ring with a soft bush prints the EHD film's force, the one
    solve_reynolds(..., bush=ElasticBush(...)) gives (to the printed 6 digits). Fails if
    a bush option is dropped (the bronze default's force differs in the 3rd digit)."""
    assert main(["solve", "--ld", "0.5", "--eps", "0.8", *MESH, "--bush", "ring",
                 "--bush-outer-radius", "0.015", "--bush-modulus", "5e9",
                 "--bush-poisson", "0.3"]) == 0
    out = capsys.readouterr().out
    assert "ehd-newton" in out
    d = SEED_TABLE1["diameter"]
    b = Bearing(radius=d / 2, length=0.5 * d, clearance=SEED_TABLE1["clearance"],
                viscosity=SEED_TABLE1["viscosity"])
    sol = solve_reynolds(b, JournalState(eps=0.8, omega=250.0), 48, 4, "P1", "reynolds",
                         bush=ElasticBush(outer_radius=0.015, modulus=5e9, poisson=0.3,
                                          model="ring"))
    printed = float(re.search(r"\|F\| ([\d.e+-]+) N", out).group(1))
    assert printed == pytest.approx(float(f"{abs(complex(*sol.force_local)):.6g}"), rel=1e-12)
    # the bush as the options name it, and the film's largest deflection (1.9 um here)
    line = [x for x in out.splitlines() if x.startswith("  bush: ")]
    assert len(line) == 1 and line[0].startswith(
        "  bush: --bush ring, --bush-outer-radius 0.015 m, --bush-modulus 5e+09 Pa, "
        "--bush-poisson 0.3; largest deflection "), out
    i = int(np.argmax(np.abs(sol.deformation)))
    w = float(re.search(r"largest deflection ([\d.e+-]+) um at theta ([\d.]+) deg",
                        line[0]).group(1))
    assert w == float(f"{sol.deformation[i] * 1e6:.4g}") and w > 1.0
    assert f"at theta {np.degrees(sol.theta[i]) % 360:.1f} deg" in line[0]


def test_solve_without_a_bush_prints_no_bush(capsys):
    """The rigid film's output has no bush line."""
    assert main(["solve", "--ld", "0.5", "--eps", "0.8", *MESH]) == 0
    assert "bush" not in capsys.readouterr().out


def test_equilibrium_takes_the_bush(capsys):
    """equilibrium --model fem-ehd --bush liner finds where the elastic film carries the
    load (its eccentricity printed)."""
    assert main(["equilibrium", "--ld", "0.5", "--load", "200", "--model", "fem-ehd",
                 *MESH, "--bush", "liner", "--bush-outer-radius", "0.0105",
                 "--bush-modulus", "5e9"]) == 0
    out = capsys.readouterr().out
    assert "eccentricity ratio" in out
    # the header names the bush as solve does, in the options' names
    assert "cavitation reynolds, --bush liner, --bush-outer-radius 0.0105 m, --bush-modulus " \
        "5e+09 Pa, --bush-poisson 0.34): load 200 N" in out.splitlines()[0], out


@pytest.mark.parametrize("args, needle", [
    (("solve", "--bush-modulus", "5e9"), "--bush-modulus needs --bush ring|solid|liner"),
    (("solve", "--bush", "ring", "--bush-poisson", "0.6"),
     "--bush-poisson must be in (-1, 0.5), got 0.6"),
    (("solve", "--bush", "ring", "--bush-modulus", "-1"), "--bush-modulus must be"),
    (("solve", "--bush", "ring", "--bush-outer-radius", "0.001"),
     "--bush-outer-radius must exceed the film radius"),
    (("solve", "--bush", "ring", "--model", "fvm"), "--bush applies to --model fem"),
    (("equilibrium", "--load", "100", "--bush", "solid", "--model", "short"),
     "--bush applies to a film model that takes a bush"),
    (("coefficients", "--eps", "0.5", "--bush-poisson", "0.3"), "needs --bush"),
    # a modulus typed in GPa was a ConvergenceError traceback from the EHD Newton solve
    (("solve", "--bush", "ring", "--bush-modulus", "110", *MESH),
     "--bush-modulus 110 Pa is below any bush material's (>= 1e+05 Pa; rubber ~1e6 Pa): "
     "typed in GPa? (110 GPa = 1.1e+11 Pa)"),
    (("solve", "--bush", "ring", "--bush-modulus", "1e15", *MESH),
     "--bush-modulus 1e+15 Pa is above any solid's"),
    # a metal in MPa: only the unit that brings it into range is named ('50000 GPa' was)
    (("solve", "--bush", "ring", "--bush-modulus", "5e4", *MESH),
     "(>= 1e+05 Pa; rubber ~1e6 Pa): typed in MPa? (50000 MPa = 5e+10 Pa); a softer solid: "
     "the library's ElasticBush takes any positive modulus"),
])
def test_bad_bush_input_is_one_line(args, needle, capsys):
    assert main(list(args)) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and needle in err[0], err


def test_unknown_bush_model_is_refused(capsys):
    with pytest.raises(SystemExit) as e:
        main(["solve", "--bush", "rubber"])
    assert e.value.code == 2
    assert "--bush: invalid choice" in capsys.readouterr().err


def test_the_default_outer_radius_scales_with_the_diameter(capsys):
    """--bush without --bush-outer-radius on a 50 mm journal is a bush held at 1.6 R (the
    seed pin's 16 mm at R 10 mm): the API's film with ElasticBush(outer_radius=0.04). A fixed
    16 mm default was refused ('must exceed the film radius R = 0.025 m') from D = 32 mm on."""
    assert main(["solve", "--diameter", "0.05", "--ld", "0.5", "--clearance", "50e-6",
                 "--eps", "0.7", *MESH, "--bush", "ring", "--bush-modulus", "5e9"]) == 0
    out = capsys.readouterr().out
    b = Bearing(radius=0.025, length=0.025, clearance=50e-6,
                viscosity=SEED_TABLE1["viscosity"])
    sol = solve_reynolds(b, JournalState(eps=0.7, omega=250.0), 48, 4, "P1", "reynolds",
                         bush=ElasticBush(outer_radius=0.04, modulus=5e9, model="ring"))
    printed = float(re.search(r"\|F\| ([\d.e+-]+) N", out).group(1))
    assert printed == pytest.approx(float(f"{abs(complex(*sol.force_local)):.6g}"), rel=1e-12)
    # the library's default, printed as resolved
    assert "  bush: --bush ring, --bush-outer-radius 0.04 m, --bush-modulus 5e+09 Pa, " \
        "--bush-poisson 0.34; largest deflection " in out, out


def test_the_modulus_help_says_its_range(capsys):
    """--bush-modulus is refused outside [1e5, 1.2e12] Pa: its help says so."""
    from bearingfem_app.bush import MODULUS_RANGE
    with pytest.raises(SystemExit):
        main(["solve", "--help"])
    help_text = " ".join(capsys.readouterr().out.split())
    assert (f"Young's modulus [Pa] in [{MODULUS_RANGE[0]:g}, {MODULUS_RANGE[1]:g}]"
            in help_text)


@pytest.mark.parametrize("diameter, outer", [(0.05, 0.04), (0.02, 0.016), (0.03, 0.024)])
def test_the_default_outer_radius_is_printed_as_typed(diameter, outer):
    """1.6 R is rounded to 12 digits, so that a header prints outer_radius=0.04 for a 50 mm
    journal (1.6 * 0.025 is 0.04000000000000001); it is the library's own default,
    ElasticBush's 1.6 R, the seed's 16 mm at the default --diameter."""
    import argparse
    from bearingfem_app.bush import BUSH_OPTIONS, bush_from_args
    args = argparse.Namespace(bush="ring", diameter=diameter,
                              **{dest: None for dest in BUSH_OPTIONS})
    bush = bush_from_args(args)
    assert bush.outer_radius == outer and f"outer_radius={outer!r}," in repr(bush)
    assert bush == ElasticBush(model="ring").at_radius(diameter / 2)    # the library's rule
    assert diameter != SEED_TABLE1["diameter"] or outer == 0.016
