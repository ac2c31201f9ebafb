"""What the command line checks before any work, so that a refused run leaves nothing behind.

Every number option is checked against its range at once (one message naming every bad
option, joined by "; "); folders are checked writable without being made; the options a
film model does not take are refused by name.
"""
from __future__ import annotations

import math
import os
import re
from pathlib import Path

from bearingfem.accuracy import RTOL_RANGE
from bearingfem.bearing import check_squeeze_speed, check_surface_speed, plausibility_errors
from bearingfem.validation import MAX_UNKNOWNS, MIN_N_THETA, MIN_N_Z, estimated_unknowns
from mechanism.scene import oil_viscosity as scene_oil_viscosity

__all__ = ["check_numbers", "range_words", "given_options", "check_writable", "parse_angles",
           "check_scheduler_address", "oil_viscosity", "RULES"]

#: dest -> (option as typed, low, low included, high, high included); None: open end.
RULES = {
    "length_ratio": ("--length-ratio/--ld (L/D)", 0.0, False, None, False),
    "diameter": ("--diameter", 0.0, False, None, False),
    "clearance": ("--clearance", 0.0, False, None, False),
    "viscosity": ("--viscosity", 0.0, False, None, False),
    "omega": ("--omega", None, False, None, False),
    "rpm": ("--rpm", None, False, None, False),
    "eps": ("--eps: eps", 0.0, True, 1.0, False),
    "eps_dot": ("--eps-dot", None, False, None, False),
    "ambient_pressure": ("--ambient-pressure", 0.0, True, None, False),
    "load": ("--load (a magnitude; --direction turns it)", 0.0, False, None, False),
    # degrees, within a turn either way (the library takes radians and refuses more)
    "direction": ("--direction [deg]", -360.0, True, 360.0, True),
    "gamma": ("--gamma [deg]", -360.0, True, 360.0, True),
    "n_theta": ("--n-theta", MIN_N_THETA, True, None, False),
    "n_z": ("--n-z", MIN_N_Z, True, None, False),
    "levels": ("--levels", 3, True, None, False),
    "frames": ("--frames", 1, True, None, False),
    "workers": ("--workers", 1, True, None, False),
    "turns": ("--turns", 0.0, False, 1000.0, True),
    # named as typed with the others (the library's message said "rtol", after the setup)
    "rtol": ("--rtol (a relative accuracy)", RTOL_RANGE[0], True, RTOL_RANGE[1], True),
}

#: dest -> (option as typed, allowed words): named with the bad numbers, before any work
CHOICES = {
    "cavitation": ("--cavitation", ("none", "gumbel", "reynolds", "jfo")),
    "element": ("--element", ("P1", "P2")),
}
#: the commands whose films are Reynolds-family only (the JFO film is a model of its own)
NO_JFO = {"equilibrium": "--model fem-jfo", "coefficients": "--model fem-jfo",
          "design": "--model fem-jfo"}


def _range(lo, lo_in, hi, hi_in):
    if lo is None and hi is None:
        return "finite"
    if hi is None:
        return (f">= {lo:g}" if lo_in else "positive" if lo == 0 else f"> {lo:g}")
    return f"in {'[' if lo_in else '('}{lo:g}, {hi:g}{']' if hi_in else ')'}"


def range_words(dest: str) -> str:
    """The range :func:`check_numbers` holds option ``dest`` to, as its help says it (one
    table, RULES, for the check and the help)."""
    return _range(*RULES[dest][1:])


def check_numbers(args) -> None:
    """Every number option of ``args`` in its range; ValueError naming all bad ones."""
    errors = []
    for dest, (name, lo, lo_in, hi, hi_in) in RULES.items():
        v = getattr(args, dest, None)
        if v is None:
            continue
        ok = math.isfinite(v)
        if ok and lo is not None:
            ok = v >= lo if lo_in else v > lo
        if ok and hi is not None:
            ok = v <= hi if hi_in else v < hi
        if not ok:
            rule = _range(lo, lo_in, hi, hi_in)
            rule = "positive (> 0)" if rule == "positive" else rule
            if rule != "finite" and not math.isfinite(v):
                rule = f"finite and {rule}"         # 'inf must be positive' said nothing
            verb = "lie" if rule.startswith("in") else "be"
            errors.append(f"{name} must {verb} {rule}, got {v!r}")
    errors += choice_errors(args)
    errors += mesh_size_errors(args)
    if getattr(args, "command", None) in ("equilibrium", "design") and \
            getattr(args, "omega", None) == 0.0:
        errors.append(f"{_speed_option(args)} must be non-zero for {args.command}: without "
                      "rotation a film carries no steady load")
    if errors:
        raise ValueError("; ".join(errors))
    check_plausible(args)


def mesh_size_errors(args) -> list:
    """--n-theta x --n-z beyond what a film solve takes (the library's MAX_UNKNOWNS), named
    as typed; convergence's finest level (doubled --levels - 1 times) is the one solved."""
    nt, nz = getattr(args, "n_theta", None), getattr(args, "n_z", None)
    if not (isinstance(nt, int) and isinstance(nz, int) and nt > 0 and nz > 0):
        return []
    levels = getattr(args, "levels", None)
    # every level counts (--levels 40 passed as one level and ran until the library refused
    # its 12th); past 64 doublings the count is beyond any machine all the same
    scale = 2 ** (min(levels, 64) - 1) if isinstance(levels, int) and levels > 0 else 1
    methods = str(getattr(args, "methods", "") or getattr(args, "element", "P1") or "P1")
    element = "P2" if "P2" in methods else "P1"
    unknowns = estimated_unknowns(nt * scale, nz * scale, element)
    if unknowns <= MAX_UNKNOWNS:
        return []
    where = "" if scale == 1 else f" at the finest of --levels {levels}"
    return [f"--n-theta x --n-z = {nt} x {nz} ({element}{where}) is ~{unknowns:.2g} "
            f"unknowns, above the {MAX_UNKNOWNS:.0e} a film solve takes: "
            + ("a coarser mesh" if scale == 1 else "fewer --levels or a coarser mesh")]


def _speed_option(args) -> str:
    """The speed option as typed: --rpm when given (args.omega is then its value in rad/s)."""
    return "--rpm" if getattr(args, "rpm", None) is not None else "--omega"


def choice_errors(args) -> list:
    """The word options (--cavitation, --element) outside their choices, named as typed."""
    errors = []
    for dest, (name, allowed) in CHOICES.items():
        v = getattr(args, dest, None)
        command = getattr(args, "command", None)
        if dest == "cavitation" and str(getattr(args, "model", "")).startswith("fem-jfo"):
            continue        # the JFO models refuse --cavitation themselves, by name
        if dest == "cavitation" and command in NO_JFO:
            allowed = allowed[:-1]
            if v == "jfo":
                errors.append(f"--cavitation jfo is not a choice of {command} (none, gumbel, "
                              f"reynolds): the mass-conserving film is {NO_JFO[command]}")
                continue
        if v is not None and v not in allowed:
            errors.append(f"{name} must be one of {', '.join(allowed)}, got {v!r}")
    return errors


#: the bearing's options as typed, for the plausibility messages
BEARING_OPTIONS = ("--diameter", "--length-ratio/--ld (L/D)", "--clearance", "--viscosity")


def check_plausible(args) -> None:
    """The bearing and the journal's rates the options describe lie in the range of any
    journal bearing (:data:`bearingfem.bearing.PLAUSIBLE`: the surface speed of --omega /
    --rpm, the squeeze speed of --eps-dot); else ValueError naming the likely mistake."""
    values = [getattr(args, k, None) for k in ("diameter", "length_ratio", "clearance",
                                                "viscosity")]
    if any(v is None for v in values):
        return
    errors = plausibility_errors(*values, names=BEARING_OPTIONS)
    if errors:
        raise ValueError("; ".join(errors))
    if getattr(args, "omega", None) is not None:
        # named as typed: --rpm 3e6 is 3.1e5 rad/s, a mistake of its own
        check_surface_speed(args.diameter / 2, args.omega, _speed_option(args),
                            rpm=getattr(args, "rpm", None) is not None)
    if getattr(args, "eps_dot", None) is not None:
        check_squeeze_speed(args.clearance, args.eps_dot, "--eps-dot")


def given_options(subparser, argv) -> set:
    """The dests of the options typed in ``argv`` (not left at their defaults)."""
    typed = {a.split("=", 1)[0] for a in argv if a.startswith("-")}
    return {a.dest for a in subparser._actions if typed & set(a.option_strings)}


def check_writable(path, option) -> Path:
    """A folder that can be made (or exists and takes files), without leaving it made: a
    scratch folder is made and removed in its nearest existing parent (permissions alone
    do not tell, e.g. for root or on /proc)."""
    import tempfile
    probe = Path(path).absolute()
    while not probe.exists():
        probe = probe.parent
    try:
        if not probe.is_dir():
            raise NotADirectoryError(20, "Not a directory")
        os.rmdir(tempfile.mkdtemp(dir=probe, prefix=".bearingfem-probe-"))
    except OSError as err:
        raise ValueError(f"{option}: cannot create folder {str(path)!r} "
                         f"({err.strerror} in {probe})") from None
    return Path(path)


def parse_angles(text: str) -> list:
    """``--angles``: comma-separated crank angles [deg] in [0, 360), returned sorted and
    without repeats (the VTU series is in time order)."""
    try:
        angles = [float(a) for a in text.split(",")]
    except ValueError:
        raise ValueError(f"--angles must be comma-separated degrees, got {text!r}") from None
    bad = [a for a in angles if not (math.isfinite(a) and 0.0 <= a < 360.0)]
    if bad:
        shown = ", ".join(f"{a:g}" for a in bad)
        raise ValueError(f"--angles must lie in [0, 360) deg, got {shown}")
    return sorted(set(angles))


def oil_viscosity(grade: str, temperature_c: float) -> float:
    """``--oil`` 'ISO VG 32' (or 'VG32', '32') at ``temperature_c`` [degC] -> its dynamic
    viscosity [Pa s] (as a scene's ``oil``: :func:`mechanism.scene.oil_viscosity`)."""
    return scene_oil_viscosity(grade, temperature_c, ("--oil", "--oil-temperature"))


_ADDRESS = re.compile(r"^(?:(tcp|tls|ws|wss|ucx)://)?(\[[0-9a-fA-F:]+\]|[\w.-]+):(\d{1,5})$")


def check_scheduler_address(address: str) -> str:
    """``--scheduler``: [protocol://]host:port."""
    m = _ADDRESS.match(address)
    if not m or not 0 < int(m.group(3)) < 65536:
        raise ValueError(f"--scheduler must be a Dask scheduler address "
                         f"[tcp://]host:port, got {address!r}")
    return address
