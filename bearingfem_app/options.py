"""What the ``bearingfem`` commands read from their options and how they write: the
bearing, the journal state, the film model and its options, an accuracy, the output's
checks and the rows of numbers (:mod:`bearingfem_app.commands`,
:mod:`bearingfem_app.design_commands`). Every check raises ValueError with one line
naming the option, before any work."""
from __future__ import annotations

import math
import sys
from pathlib import Path

from .bush import bush_from_args
from .checks import check_writable

__all__ = ["bearing_from_args", "supply_angle", "ambient_pressure", "film_state",
           "MODEL_OPTIONS", "model_options", "accuracy_options", "check_rtol_mesh",
           "check_film_options", "refuse_bush_film",
           "check_cache", "coarse_film_note", "note_coarse_film", "estimate_options",
           "RESOLVED_SPACINGS",
           "check_output", "make_dir", "write_numbers", "print_rows"]


def bearing_from_args(args):
    from bearingfem import Bearing
    from bearingfem.bearing import check_positive
    check_positive("--length-ratio/--ld (L/D)", args.length_ratio)   # name what was typed
    return Bearing(radius=args.diameter / 2, length=args.length_ratio * args.diameter,
                   clearance=args.clearance, viscosity=args.viscosity)


def supply_angle(args, gamma=0.0):
    """--supply-angle: degrees from the maximum film (or max-film) -> inertial [rad], or
    None. The maximum film lies opposite the eccentricity, at gamma + pi."""
    text = args.supply_angle
    if text is None:
        return None
    if text == "max-film":
        return gamma + math.pi
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"--supply-angle must be degrees from the maximum film or max-film, "
                         f"got {text!r}") from None
    if not math.isfinite(value):
        raise ValueError(f"--supply-angle must be finite, got {text!r}")
    return gamma + math.pi + math.radians(value)


def ambient_pressure(args):
    return 0.0 if args.ambient_pressure is None else args.ambient_pressure


def film_state(args):
    """The bearing and the journal state the film options describe."""
    from bearingfem import JournalState
    s = JournalState(eps=args.eps, eps_dot=args.eps_dot, gamma=0.0, gamma_dot=0.0,
                     omega=args.omega)
    return bearing_from_args(args), s


#: command-line options that are film-model options (dest -> option as typed)
MODEL_OPTIONS = {"n_theta": "--n-theta", "n_z": "--n-z", "element": "--element",
                 "cavitation": "--cavitation", "ambient_pressure": "--ambient-pressure"}


def model_options(args):
    """The film model named on the command line and the options of it given there; an
    option typed that the model does not take is refused (it would be ignored)."""
    from bearingfem.models import film_model
    m = film_model(args.model, "--model")
    refused = [o for k, o in MODEL_OPTIONS.items() if k in args.given and k not in m.defaults]
    if refused:
        takes = ", ".join(MODEL_OPTIONS[k] for k in m.defaults if k in MODEL_OPTIONS)
        raise ValueError(f"{', '.join(refused)} {'does' if len(refused) == 1 else 'do'} not "
                         f"apply to --model {args.model} (its options: {takes or 'none'})")
    if m.disk_cache:      # tables are built once and kept: the cache must take them
        check_cache()
    given = {k: getattr(args, k) for k in MODEL_OPTIONS}
    opts = {k: v for k, v in given.items()
            if k in m.defaults and (v is not None and (k != "ambient_pressure"
                                                       or k in args.given))}
    if "ambient_pressure" in m.defaults and "ambient_pressure" in args.given \
            and not args.ambient_pressure > 0.0:
        raise ValueError(f"--model {args.model} needs --ambient-pressure > 0 [Pa]: the oil at "
                         f"the ends is its only supply here (default "
                         f"{m.defaults['ambient_pressure']:g}), got {args.ambient_pressure:g}")
    bush = bush_from_args(args)
    if bush is not None:
        refuse_bush_film(opts.get("element") if "element" in args.given else None,
                         opts.get("cavitation"), "none or reynolds")
    if bush is not None and "bush" not in m.defaults:
        raise ValueError(f"--bush applies to a film model that takes a bush (--model fem: "
                         f"the steady elastic film; fem-ehd: beyond the clearance and along "
                         f"a run), not --model {args.model}")
    return args.model, opts if bush is None else dict(opts, bush=bush)


def check_film_options(args) -> None:
    """The film options of ``solve`` and ``render`` that need one another, refused before
    any work in the options' own names (the library's message names its keywords):
    --cavitation jfo needs a supply (--ambient-pressure > 0 or --supply-angle),
    --ambient-pressure is the JFO film's, a --bush needs --element P1 and a cavitation
    other than gumbel."""
    cav = args.cavitation
    supplied = (args.ambient_pressure or 0.0) > 0.0 or args.supply_angle is not None
    if cav == "jfo" and not supplied:
        raise ValueError("--cavitation jfo needs a supply of oil: --ambient-pressure > 0 [Pa] "
                         "(oil at the ends) or --supply-angle (a supply line); without one "
                         "nothing refills the film")
    if args.ambient_pressure is not None and cav != "jfo":
        raise ValueError(f"--ambient-pressure is the mass-conserving film's end pressure: "
                         f"give --cavitation jfo with it, not --cavitation {cav}")
    if getattr(args, "bush", None) is not None:
        refuse_bush_film(args.element if args.element_given else None, cav,
                         "none, reynolds or jfo")


def refuse_bush_film(element, cavitation, cavitations: str) -> None:
    """A --bush's film needs --element P1 (``element`` as typed, None if not) and a
    cavitation among ``cavitations`` (gumbel is never one): refused in the options' names."""
    if element is not None and element != "P1":
        raise ValueError(f"--bush needs --element P1 (the bush acts on the film's vertex "
                         f"grid), got --element {element}")
    if cavitation == "gumbel":
        raise ValueError(f"--bush needs --cavitation {cavitations} (the elastic film is "
                         f"solved with its cavitation, not clipped after), got --cavitation "
                         f"gumbel")


def check_rtol_mesh(args) -> None:
    """--rtol asks the toolkit to choose the mesh: --n-theta or --n-z typed beside it is
    refused by name (it would be dropped unseen); --element is kept."""
    if getattr(args, "rtol", None) is None:
        return
    typed = [MODEL_OPTIONS[k] for k in ("n_theta", "n_z") if k in args.given]
    if typed:
        raise ValueError(f"{' and '.join(typed)} {'is' if len(typed) == 1 else 'are'} not "
                         f"taken with --rtol (the mesh is chosen to reach it): give --rtol "
                         f"or the mesh, not both")


def accuracy_options(args, opts):
    """With --rtol the mesh options are the toolkit's to choose (the element too unless
    given): (options without them, {"rtol": ...}); with --estimate, (options,
    {"estimate": True}): the mesh given and its error; neither, (options, {}). A mesh typed
    beside --rtol is refused (:func:`check_rtol_mesh`)."""
    check_rtol_mesh(args)
    if getattr(args, "estimate", False):
        # the library takes both and estimates rtol's mesh: the flag would do nothing
        if args.rtol is not None:
            raise ValueError("--estimate is not taken with --rtol (--rtol chooses the mesh "
                             "and gives its estimated error): give one of them")
        from bearingfem.accuracy import half_mesh
        mesh = (opts.get("n_theta"), opts.get("n_z"))
        if None not in mesh and half_mesh(mesh) == mesh:
            # the library's refusal named n_theta and n_z, not the options typed
            raise ValueError(f"--estimate needs a mesh finer than --n-theta {mesh[0]} --n-z "
                             f"{mesh[1]} (its own half mesh: no pair to estimate from); "
                             f"give --n-theta > {mesh[0]} or --n-z > {mesh[1]}")
        return opts, {"estimate": True}
    if args.rtol is None:
        return opts, {}
    drop = ("n_theta", "n_z") + (() if args.element_given else ("element",))
    return {k: v for k, v in opts.items() if k not in drop}, {"rtol": args.rtol}


def check_cache():
    """The fem-table cache folder takes a file (tried, not guessed from permissions)."""
    import tempfile

    from bearingfem.fe.force_table import cache_dir
    folder = cache_dir()
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=folder):
            pass
    except OSError as err:
        raise ValueError(f"--model fem-table: cannot write its table cache {str(folder)!r} "
                         f"({err.strerror}); set BEARINGFEM_CACHE to a writable folder") \
            from None


#: the command that writes a file of this kind, named when another command is given it
#: ('solve -o film.png' said only which suffixes solve takes)
WRITTEN_BY = {**{s: "a picture of the film: bearingfem render ... -o FILE"
                 for s in (".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff")},
              **{s: "the film's fields: bearingfem solve ... -o FILE"
                 for s in (".vtu", ".xdmf", ".vtk")},
              **{s: "the numbers: bearingfem equilibrium|coefficients|design ... -o FILE"
                 for s in (".json", ".csv")}}


def check_output(path, suffixes):
    """Refuse an output file of an unknown kind, or in a folder that cannot be made, before
    any work (the folder is made when the file is written)."""
    if path is None:
        return None
    out = Path(path)
    if out.suffix.lower() not in suffixes:
        other = WRITTEN_BY.get(out.suffix.lower())
        raise ValueError(f"-o/--output must end in {' or '.join(suffixes)}, got {path!r}"
                         + (f" ({other})" if other else ""))
    check_writable(out.parent, "-o/--output")
    return out


def make_dir(path, option):
    """Create an output folder before any work, or say in one line why it cannot be."""
    try:
        Path(path).mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise ValueError(f"{option}: cannot create folder {str(path)!r} ({err.strerror})") \
            from None
    return Path(path)


#: printed name -> machine key of the designer's numbers: the API's attribute names
#: (Equilibrium, coefficients' result, LundStability; e_x, e_y the mechanism's), with the
#: unit in the key where the value is not the API's SI one (degrees)
KEYS = {"eccentricity ratio": "eps", "its estimated error": "eps_error",
        "mesh chosen": "mesh", "mesh given": "mesh", "attitude angle": "attitude_deg",
        "Sommerfeld number": "sommerfeld", "minimum film": "film_min",
        "minimum film angle": "film_min_angle_deg", "journal x": "e_x", "journal y": "e_y",
        "peak pressure": "pressure_max", "friction force": "friction_force",
        "friction coefficient": "friction_coefficient", "power loss": "power_loss",
        "side leakage (outflow)": "side_outflow", "load carried": "load",
        "critical mass": "critical_mass", "whirl frequency ratio": "whirl_ratio",
        "K, C estimated error": "error", "stability": "stability"}


def machine_key(name: str) -> str:
    """The key a printed row's name has in -o's JSON and CSV (K_xy, C_xy as printed)."""
    return KEYS.get(name.strip(), name.strip())


def write_numbers(out, rows):
    """rows: (name, value, unit) -> JSON object or a CSV table keyed by :data:`KEYS` (the
    API's names), each with its unit. The printed names (``quantity``) are kept beside them
    for one version (docs/cli.md): in the CSV a column, in the JSON the old keys."""
    if out is None:
        return
    make_dir(out.parent, "-o/--output")
    if out.suffix.lower() == ".json":
        import json
        new = {machine_key(n): {"value": v, "unit": u} for n, v, u in rows}
        old = {n: {"value": v, "unit": u} for n, v, u in rows if n not in new}
        out.write_text(json.dumps({**new, **old}, indent=1))
    else:
        from bearingfem.outputs.tables import write_csv
        # the 0.1.0 columns first, in their order, so positional readers keep working
        write_csv([dict(quantity=n, value=v, unit=u, key=machine_key(n))
                   for n, v, u in rows], out)
    print(f"wrote {out}")


#: units printed beside SI ones a designer reads more easily: unit -> (scale, name, below)
READABLE = {"m": (1e6, "um", 1e-3), "Pa": (1e-6, "MPa", float("inf"))}


def print_rows(rows):
    """Rows as ``name value unit``, in SI; films in um and pressures in MPa beside them."""
    for name, value, unit in rows:
        v = "-" if value is None else (value if isinstance(value, str) else f"{value:.6g}")
        gloss = ""
        if unit in READABLE and isinstance(value, float) and abs(value) < READABLE[unit][2]:
            scale, readable, _ = READABLE[unit]
            gloss = f"  ({value * scale:.4g} {readable})"
        print(f"  {name:24s} {v:>14s} {unit}{gloss}")


#: Fewer node spacings around than this across the arc where a rigid film is under twice
#: its least: force errors of 6-86 % (P1), 3-41 % (P2), 0.7-29 % (FV) were measured there,
#: 5.1 % and less (P1) from 5.4 on (L/D 1 and 0.2, eps 0.95-0.999, against rtol 1e-4;
#: docs/cli.md). A given mesh's error is not estimated: this says where it is surely large.
RESOLVED_SPACINGS = 4.0


def estimate_options(args) -> tuple:
    """The command's options that give an estimated error and are not in use, the ones a
    coarse-film note may advise: solve and render take --rtol, equilibrium and
    coefficients --rtol and --estimate, design neither."""
    return tuple(f"--{k}" for k in ("rtol", "estimate")
                 if hasattr(args, k) and not getattr(args, k))


def coarse_film_note(eps: float, n_theta: int, element: str = "P1",
                     advice: tuple = ("--rtol",)) -> str | None:
    """A note when ``n_theta`` puts fewer than :data:`RESOLVED_SPACINGS` node spacings
    (P2: half cells) across the arc where h = c (1 + eps cos theta) < 2 c (1 - eps); else
    None. ``advice``: the command's options that give an estimated error
    (:func:`estimate_options`)."""
    if not (1.0 / 3.0 < eps < 1.0):      # below 1/3 the whole film is under twice its least
        return None
    arc = 2.0 * (math.pi - math.acos((1.0 - 2.0 * eps) / eps))
    spacings = arc * n_theta / (2.0 * math.pi) * (2 if element == "P2" else 1)
    if spacings >= RESOLVED_SPACINGS:
        return None
    return (f"note: the film under twice its least (eps {eps:.4g}) spans {spacings:.2g} node "
            f"spacings of --n-theta {n_theta} ({element}); force errors up to 86 % were "
            f"measured below {RESOLVED_SPACINGS:g} (docs/cli.md): a finer --n-theta"
            + (f", or {' or '.join(advice)} for an estimated error" if advice else ""))


def note_coarse_film(eps: float, opts: dict, advice: tuple = ("--rtol",)) -> None:
    """Print :func:`coarse_film_note` on stderr for a rigid film on a given mesh (``opts``
    the film model's options: nothing without n_theta, with a bush or a chosen mesh)."""
    if "n_theta" not in opts or "bush" in opts:
        return
    note = coarse_film_note(eps, opts["n_theta"], opts.get("element", "P1"), advice)
    if note:
        print(f"bearingfem: {note}", file=sys.stderr)
