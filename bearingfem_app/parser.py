"""The ``bearingfem`` command's parser: its commands, their options, help texts and
defaults (:func:`build_parser`); each command's work is in :mod:`bearingfem_app.commands`
and :mod:`bearingfem_app.design_commands`, what is done with the words typed before it runs
in :mod:`bearingfem_app.cli`."""
from __future__ import annotations

import argparse
import functools

from bearingfem import __version__
from bearingfem.bearing import SEED_TABLE1
from bearingfem.fe.jfo_balance import JFO_AMBIENT
from bearingfem.models import FILM_MODELS
from bearingfem.oil_range import CELSIUS, OIL_TEMPERATURE_RANGE
from bearingfem.outputs.convergence import QUANTITIES, UNITS
from bearingfem.routes.problem import OPTION_DEFAULTS
from mechanism.scene import shipped_scenes

from .bush import add_bush_args
from .checks import range_words
from .commands import (WORKERS_PER_CORE, command_convergence, command_frames, command_render,
                       command_simulate, command_solve, command_sweep)
from .design_commands import command_coefficients, command_design, command_equilibrium

EXAMPLES = """examples:
  bearingfem simulate scenes/paper-short-fem.toml -o results/short-fem
  bearingfem design --diameter 0.05 --ld 0.5 --clearance 50e-6 --oil 'ISO VG 32' \\
      --rpm 3000 --load 2000
  bearingfem solve --ld 1.0 --eps 0.6 --cavitation reynolds --supply-angle max-film
  bearingfem render --ld 1.0 --eps 0.6 --cavitation reynolds -o film.png
  bearingfem convergence --ld 1.0 --eps 0.6 -o results/convergence
  bearingfem sweep capacity -o results/capacity --workers 2
  bearingfem frames scenes/paper-long-fem.toml results/long-fem -o results/long-frames --gif
  bearingfem equilibrium --ld 1 --load 1000 --model fem --element P2
  bearingfem coefficients --ld 0.5 --load 500 --frame load -o kc.csv
"""


#: the journal speed when neither --omega nor --rpm is given [rad/s]
DEFAULT_OMEGA = 250.0


class _HelpFormatter(argparse.ArgumentDefaultsHelpFormatter):
    """Shows an option's default where it has one that its help does not already state
    (no "(default: None)" on required options or options whose absence means something)."""

    def _get_help_string(self, action):
        text = action.help or ""
        if (action.required or action.default is None or action.default is False
                or action.default == argparse.SUPPRESS
                or "default" in text or not action.option_strings):
            return text
        return super()._get_help_string(action)


#: --ambient-pressure's defaults differ, each the library's: solve (and render,
#: convergence) solve the film of solve_reynolds, whose ends sit at the cavitation pressure
#: (0) and whose oil comes from --supply-angle; the designer's fem-jfo model takes no supply
#: line, so the ends are its only supply, at atmospheric pressure above a cavity near zero
#: absolute (docs/cli.md)
AMBIENT_FILM = (f"with --cavitation jfo (default {OPTION_DEFAULTS['ambient_pressure']:g}, "
                f"solve_reynolds's: the ends at the cavitation pressure, the oil fed by "
                f"--supply-angle; equilibrium's fem-jfo model, which takes no supply "
                f"line, defaults to {JFO_AMBIENT:g} Pa)")
AMBIENT_MODEL = (f"with --model fem-jfo (default {JFO_AMBIENT:g} Pa: atmospheric oil at the "
                 f"ends, its only supply here, above a cavity near zero absolute; solve's "
                 f"jfo film defaults to {OPTION_DEFAULTS['ambient_pressure']:g} and takes a "
                 f"supply line)")


def _bearing_args(p, film=True):
    p.add_argument("--length-ratio", "--ld", dest="length_ratio", type=float, default=1.0,
                   help="L/D, the bearing's length over its diameter")
    speed = p.add_mutually_exclusive_group()
    speed.add_argument("--omega", type=float, default=None,
                       help=f"journal speed [rad/s] (default {DEFAULT_OMEGA:g})")
    speed.add_argument("--rpm", type=float, default=None,
                       help="journal speed [1/min], instead of --omega")
    p.add_argument("--diameter", type=float, default=SEED_TABLE1["diameter"],
                   help="journal diameter D [m] (seed Table 1)")
    p.add_argument("--clearance", type=float, default=SEED_TABLE1["clearance"],
                   help="radial clearance c [m], bush radius minus journal radius "
                        "(seed Table 1)")
    oil = p.add_mutually_exclusive_group()
    oil.add_argument("--viscosity", type=float, default=SEED_TABLE1["viscosity"],
                     help="dynamic viscosity [Pa s] (seed Table 1)")
    oil.add_argument("--oil", help="the oil by grade, e.g. 'ISO VG 32' (a VI 100 mineral "
                     "oil, ISO 3448), instead of --viscosity")
    p.add_argument("--oil-temperature", type=float, default=None,
                   help="the --oil's temperature [degC] in [{:g}, {:g}] (default 40)".format(
                       *(t - CELSIUS for t in OIL_TEMPERATURE_RANGE)))
    p.add_argument("--cavitation", default="reynolds",
                   help="none | gumbel | reynolds | jfo (mass-conserving; needs a supply: "
                        "--ambient-pressure > 0 or --supply-angle)" if film else
                        "none | gumbel | reynolds (the mass-conserving film: --model fem-jfo)")
    p.add_argument("-q", "--quiet", action="store_true",
                   help="no progress lines on stderr (a mesh search's estimates, an elastic "
                        "film's Newton steps)")
    p.add_argument("--n-theta", type=int, default=120,
                   help=f"cells around the film ({range_words('n_theta')})")
    p.add_argument("--n-z", type=int, default=20,
                   help=f"cells along the length ({range_words('n_z')})")
    p.add_argument("--element", default="P1", help="P1 | P2 (finite elements only)")
    p.add_argument("--ambient-pressure", type=float, default=None,
                   help="the JFO film's oil pressure at the ends above the cavitation "
                        "pressure [Pa], >= 0; " + (AMBIENT_FILM if film else AMBIENT_MODEL))


def _film_discretisation(name: str) -> str:
    """solve's --model: fem or fvm; a designer's model name (fem-jfo, short, ...) is
    answered with the options that ask for that film here."""
    if name in ("fem", "fvm"):
        return name
    hint = ""
    if name.endswith("-jfo") and name[:-4] in ("fem", "fvm"):
        hint = f": for the {name} film give --model {name[:-4]} --cavitation jfo"
    elif name in FILM_MODELS:
        hint = (f": {name!r} is a model of equilibrium, coefficients and scenes; solve "
                "solves the film on a mesh")
    raise argparse.ArgumentTypeError(
        f"invalid choice {name!r} (choose fem or fvm; the cavitation model is "
        f"--cavitation){hint}")


def _film_args(p):
    _bearing_args(p)
    p.add_argument("--eps", type=float, default=0.6,
                   help=f"eccentricity ratio {range_words('eps')}")
    p.add_argument("--eps-dot", type=float, default=0.0, help="d(eps)/dt [1/s]")
    p.add_argument("--supply-angle", default=None,
                   help="an axial supply line at ambient pressure: its angle [deg] from "
                        "the maximum film, or max-film (0: Raimondi & Boyd's film starts "
                        "there); default: none, a fully periodic film")


def _load_args(p, required):
    p.add_argument("--load", type=float, required=required,
                   help="load magnitude [N], > 0" + ("" if required else
                                                ": K, C at the equilibrium under it"))
    p.add_argument("--direction", type=float, default=-90.0,
                   help=f"load direction [deg] {range_words('direction')}, inertial, "
                        "counter-clockwise from x (-90: downward)")


def _rtol_arg(p):
    p.add_argument("--rtol", type=float, default=None,
                   help=f"a requested relative accuracy {range_words('rtol')} (e.g. 1e-3): "
                        "the mesh (and element, P2 unless --element) is chosen to reach it; "
                        "not with --n-theta, --n-z")


def _estimate_arg(p):
    p.add_argument("--estimate", action="store_true",
                   help="also estimate the error on the mesh given (the library's "
                        "estimate=True: the same answer on the half mesh, a quarter's cost); "
                        "not with --rtol, which gives its own estimate")


#: the designer's film models the command line can build (the thermal film needs an
#: oil's heat properties, grooves and walls, which it does not take)
DESIGN_MODELS = tuple(m for m in FILM_MODELS if m != "fem-thd")


def _design_model(name: str) -> str:
    """--model of equilibrium, coefficients and design: the thermal film is refused by
    name, with where it is built, before any work."""
    if name == "fem-thd":
        raise argparse.ArgumentTypeError(
            "'fem-thd' (the thermal film) needs the oil's density, specific heat and "
            "conductivity, grooves and walls, which the command line does not take: "
            "build it in Python, equilibrium(..., lubricant=Lubricant.iso_vg(...), "
            "thermal=Thermal(...), grooves=...) (docs/thd.md); here choose one of "
            + ", ".join(DESIGN_MODELS))
    return name


def _design_args(p):
    """Film model and mesh for the designer's commands (closed forms ignore the mesh)."""
    _bearing_args(p, film=False)
    p.add_argument("--model", default="fem", type=_design_model,
                   help="film model: " + " | ".join(DESIGN_MODELS)
                   + " (an option the model does not take is refused)")
    p.add_argument("-o", "--output", help="also write the numbers (.json or .csv)")


class _Parser(argparse.ArgumentParser):
    """argparse's parser whose refusals (an unknown option, a bad choice, a missing
    argument) are one line on stderr with exit status 2, as every other refusal of the
    command is, not the usage block followed by the error."""

    def error(self, message):
        self.exit(2, f"bearingfem: error: {message} ('{self.prog} --help' lists the "
                     f"options)\n")


def build_parser():
    p = _Parser(prog="bearingfem", description="Verified journal-bearing films "
                                "and the slider-crank that carries them.", epilog=EXAMPLES,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    # the version a result is cited with ('bearingfem --version' said a command was missing)
    p.add_argument("--version", action="version", version=f"bearingfem {__version__}")
    sub = p.add_subparsers(dest="command", required=True)
    add = functools.partial(sub.add_parser,   # every option shows its default in --help
                            formatter_class=_HelpFormatter)
    s = add("simulate", help="integrate a scene; write result and figure",
            epilog="example: bearingfem simulate scenes/paper-long-fem.toml -o out")
    s.add_argument("scene", help="scene TOML file, or the name of a shipped scene ("
                   + ", ".join(shipped_scenes()) + ")")
    s.add_argument("-o", "--output", required=True, help="output directory")
    s.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    s.add_argument("--turns", type=float, default=None,
                   help=f"run this many crank turns, {range_words('turns')}, all recorded "
                        "(a quick look; default: the scene's turns and record_from_turn)")
    s.set_defaults(func=command_simulate)
    f = add("solve", help="one film solve; print forces, optionally export VTU",
            epilog="example: bearingfem solve --ld 0.5 --eps 0.8 -o film.vtu")
    _film_args(f)
    _rtol_arg(f)
    f.add_argument("--model", default="fem", type=_film_discretisation,
                   help="film model: fem (finite elements) or fvm (finite volumes); the "
                        "cavitation model is --cavitation")
    f.add_argument("--method", type=_film_discretisation, help=argparse.SUPPRESS)  # old name
    f.add_argument("-o", "--output", help="write the film (.vtu, .xdmf, .vtk)")
    add_bush_args(f)
    f.set_defaults(func=command_solve)
    c = add("convergence", help="mesh-convergence study: CSV table + log-log PNG",
            epilog="example: bearingfem convergence --ld 1.0 --eps 0.6 -o conv")
    _film_args(c)
    c.set_defaults(n_theta=24, n_z=4)
    c.add_argument("--levels", type=int, default=4,
                   help=f"meshes, each twice as fine ({range_words('levels')})")
    c.add_argument("--methods", default="P1,P2,fvm", help="comma list of P1, P2, fvm")
    c.add_argument("--quantity", default="force",
                   help="quantity for the figure: " + " | ".join(
                       f"{q} [{UNITS[q]}]" for q in QUANTITIES))
    c.add_argument("-o", "--output", required=True, help="output directory")
    c.set_defaults(func=command_convergence)
    r = add("render", help="off-screen PNG of the film pressure, thickness, fraction or "
                           "bush deflection",
            epilog="example: bearingfem render --ld 1.0 --eps 0.6 -o film.png")
    _film_args(r)
    _rtol_arg(r)
    r.add_argument("--model", default="fem", type=_film_discretisation,
                   help="film model: fem (finite elements) or fvm (finite volumes); the "
                        "cavitation model is --cavitation")
    r.add_argument("--field", default="pressure",
                   help="pressure | film_thickness (the gap, with a --bush's deflection) | "
                        "fraction (--cavitation jfo) | deformation (the bush's deflection, "
                        "--bush)")
    r.add_argument("--surface", default="journal", help="journal | unwrapped")
    r.add_argument("-o", "--output", required=True, help="PNG file")
    add_bush_args(r)
    r.set_defaults(func=command_render)
    w = add("sweep", help="parameter sweep on Dask: one file per case, resumable",
            epilog="example: bearingfem sweep sweeps/capacity.toml -o out "
                   "--scheduler tcp://10.0.0.5:8786")
    w.add_argument("sweep", help="sweep TOML file, or the name of a shipped sweep "
                   "(capacity, design-chart, mechanism-clearance)")
    w.add_argument("-o", "--output", required=True, help="output directory (rerun to resume)")
    w.add_argument("--scheduler", help="address [tcp://]host:port of a running Dask "
                   "scheduler (refused if it does not answer within 5 s); default: a local "
                   "cluster")
    w.add_argument("--workers", type=int, default=2,
                   help=f"local cluster processes ({range_words('workers')}, at most "
                        f"{WORKERS_PER_CORE} per core; not with --scheduler)")
    w.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    w.set_defaults(func=command_sweep)
    fr = add("frames", help="the film along a saved run: VTU series (.pvd), PNG frames, GIF",
             epilog="example: bearingfem frames scenes/paper-long-fem.toml "
                    "results/long-fem -o frames --angles 0,90")
    fr.add_argument("scene", help="the scene the run was made from (a TOML file or a "
                    "shipped scene's name)")
    fr.add_argument("result", help="directory written by 'bearingfem simulate'")
    fr.add_argument("-o", "--output", required=True, help="output directory")
    fr.add_argument("--angles", help="crank angles [deg] in [0, 360), comma-separated; "
                    "taken in increasing order (default: evenly spaced --frames)")
    fr.add_argument("--frames", type=int, default=12,
                    help=f"number of evenly spaced frames ({range_words('frames')})")
    fr.add_argument("--field", default="pressure",
                    help="pressure | film_thickness | fraction (a fem-jfo run)")
    fr.add_argument("--surface", default="journal", help="journal | unwrapped")
    fr.add_argument("--gif", action="store_true", help="also write an animated film.gif")
    fr.add_argument("--fixed-camera", action="store_true",
                    help="journal view from one place for every frame (default: each "
                         "frame's loaded side)")
    fr.add_argument("--no-render", action="store_true", help="VTU series only, no PNG")
    fr.set_defaults(func=command_frames)
    e = add("equilibrium", help="where the journal sits under a load: eps, "
                                "attitude, Sommerfeld number, film, friction, flow",
            epilog="example: bearingfem equilibrium --ld 1 --load 1000 "
                   "--model fem --element P2")
    _design_args(e)
    _rtol_arg(e)
    _estimate_arg(e)
    _load_args(e, required=True)
    add_bush_args(e)
    e.set_defaults(func=command_equilibrium)
    k = add("coefficients", help="stiffness and damping (K, C) and Lund's "
                                 "critical mass, at an eccentricity or under a load",
            epilog="example: bearingfem coefficients --ld 0.5 --load 500 "
                   "--frame load")
    _design_args(k)
    _rtol_arg(k)
    _estimate_arg(k)
    k.add_argument("--eps", type=float,
                   help=f"steady state at this eccentricity ratio, {range_words('eps')}")
    k.add_argument("--gamma", type=float, default=0.0,
                   help=f"its attitude [deg] {range_words('gamma')} (with --eps)")
    _load_args(k, required=False)
    k.add_argument("--frame", default="inertial", choices=["inertial", "local", "load"],
                   help="axes of K and C")
    add_bush_args(k)
    k.set_defaults(func=command_coefficients)
    d = add("design", help="a design point in one go: least film, attitude, friction power, "
                           "flow, K and C in the load frame, stability",
            epilog="example: bearingfem design --diameter 0.05 --ld 0.5 --clearance 50e-6 "
                   "--viscosity 0.028 --rpm 3000 --load 2000")
    _design_args(d)
    _load_args(d, required=True)
    d.set_defaults(func=command_design)
    return p
