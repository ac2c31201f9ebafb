"""Command line: ``bearingfem COMMAND ...``; bad input prints one line and exits 2.

What is typed is read here before a command runs (negative numbers as values, an unknown
option named with its nearest, old spellings, --rpm and --oil), the library's progress shown
while it runs, and its errors printed as one line with an exit status; the parser (commands,
options, help) is :mod:`bearingfem_app.parser`."""
from __future__ import annotations

import argparse
import contextlib
import difflib
import logging
import math
import os
import re
import sys

from bearingfem.errors import ConvergenceError

from .checks import check_numbers, given_options, oil_viscosity
from .parser import (AMBIENT_FILM, AMBIENT_MODEL, DEFAULT_OMEGA,  # noqa: F401 (importable here)
                     DESIGN_MODELS, EXAMPLES, build_parser)


_NEGATIVE = re.compile(r"^-(\d+\.?\d*|\.\d+)(e[-+]?\d+)?$", re.IGNORECASE)


def _negative_values(argv):
    """``--opt -20e-6`` -> ``--opt=-20e-6``: argparse would read the value as an option,
    so that the range check could not speak."""
    out, i = [], 0
    while i < len(argv):
        a = argv[i]
        if (a.startswith("--") and "=" not in a and i + 1 < len(argv)
                and _NEGATIVE.match(argv[i + 1])):
            out.append(f"{a}={argv[i + 1]}")
            i += 2
        else:
            out.append(a)
            i += 1
    return out


#: words a user may try for an option spelt otherwise here
SYNONYMS = {"--speed": "--omega [rad/s] or --rpm [1/min]", "--mu": "--viscosity",
            "--method": "--model", "--length": "--ld (L/D)", "--oil-temp": "--oil-temperature"}


def _options(sub) -> list:
    """A command's visible long options."""
    return [o for a in sub._actions for o in a.option_strings if o.startswith("--")
            and a.help != argparse.SUPPRESS]


def _unrecognized(sub, unknown, commands=None) -> str:
    """argparse's message for options a command does not take: an option of other
    commands (``commands``: name -> subparser) is named as theirs, since a look-alike of
    this command's would mislead (``convergence --rtol`` was 'did you mean --oil?');
    otherwise the nearest of its own options (difflib), so that a typo names its fix."""
    known = _options(sub)
    parts = []
    for u in unknown:
        name = u.split("=", 1)[0]
        owners = [c for c, p in (commands or {}).items()
                  if p is not sub and name in _options(p)] if u.startswith("--") else []
        near = ([SYNONYMS[name]] if name in SYNONYMS else
                difflib.get_close_matches(name, known, n=1, cutoff=0.6)) \
            if u.startswith("-") else []
        parts.append(f"{u} (an option of {', '.join(owners)}, not of {sub.prog.split()[-1]})"
                     if owners else f"{u} (did you mean {near[0]}?)" if near else u)
    return "unrecognized arguments: " + " ".join(parts)


#: old option -> the one that now carries its idea, per command
OLD_SPELLINGS = {"solve": {"method": "model"}}


def _old_spellings(args) -> None:
    """An old option name is taken as its new one, with a note on stderr."""
    for old, new in OLD_SPELLINGS.get(args.command, {}).items():
        if old in args.given:
            if new in args.given:
                raise ValueError(f"--{old} is the old name of --{new}: give one of them")
            setattr(args, new, getattr(args, old))
            args.given = (args.given - {old}) | {new}
            print(f"bearingfem: note: --{old} is now --{new}", file=sys.stderr)


def _speed(args) -> None:
    """--rpm [1/min] -> args.omega [rad/s]; neither: the default speed."""
    if not hasattr(args, "omega"):
        return
    if getattr(args, "rpm", None) is not None:
        if not math.isfinite(args.rpm):
            raise ValueError(f"--rpm must be finite, got {args.rpm!r}")
        args.omega = args.rpm * math.pi / 30.0
    elif args.omega is None:
        args.omega = DEFAULT_OMEGA


def _oil(args) -> None:
    """--oil GRADE at --oil-temperature [degC] -> args.viscosity [Pa s]."""
    if getattr(args, "oil", None) is None:
        if getattr(args, "oil_temperature", None) is not None:
            raise ValueError("--oil-temperature is the --oil's temperature: give --oil "
                             "(e.g. 'ISO VG 32'), or the viscosity at that temperature "
                             "with --viscosity")
        return
    temperature = 40.0 if args.oil_temperature is None else args.oil_temperature
    args.viscosity = oil_viscosity(args.oil, temperature)


@contextlib.contextmanager
def _progress(args):
    """The library's progress (INFO on the ``bearingfem`` loggers: a mesh search's
    estimates, an elastic film's continuation) as lines on stderr while a film or designer
    command runs (not with --quiet; simulate and sweep have progress bars of their own)."""
    if not hasattr(args, "n_theta") or getattr(args, "quiet", False):
        yield
        return
    log = logging.getLogger("bearingfem")
    level = log.level
    shown = _Repeats(sys.stderr)                  # this call's stderr
    shown.setFormatter(logging.Formatter("bearingfem: %(message)s"))
    log.addHandler(shown)
    log.setLevel(logging.INFO)
    try:
        yield
    finally:
        shown.flush_repeats()
        log.removeHandler(shown)
        log.setLevel(level)


class _Repeats(logging.StreamHandler):
    """Progress lines, a run of identical ones shown once and then counted: an equilibrium
    on an elastic bush solves the film some forty times, each logging the same
    continuation line, which filled the terminal with copies of one line."""

    def __init__(self, stream):
        super().__init__(stream)
        self.last, self.repeats = None, 0

    def emit(self, record):
        message = record.getMessage()
        if message == self.last:
            self.repeats += 1
            return
        self.flush_repeats()
        self.last = message
        super().emit(record)

    def flush_repeats(self):
        if self.repeats:
            self.stream.write(f"bearingfem: (the line above {self.repeats} more "
                              f"time{'s' if self.repeats > 1 else ''})\n")
            self.flush()
        self.repeats = 0


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    parser = build_parser()
    args, unknown = parser.parse_known_args(_negative_values(argv))
    # options whose meaning depends on others: was it typed, or is it the default?
    commands = parser._subparsers._group_actions[0].choices
    sub = commands[args.command]
    if unknown:
        sub.error(_unrecognized(sub, unknown, commands))
    args.given = given_options(sub, argv)
    try:
        _old_spellings(args)
        args.element_given = "element" in args.given
        _speed(args)
        _oil(args)
        check_numbers(args)
        with _progress(args):
            return args.func(args)
    except ValueError as err:
        print(f"bearingfem: error: {err}", file=sys.stderr)
        return 2
    except ConvergenceError as err:
        # the work ran and did not succeed: one line naming what did not converge (it was
        # a traceback), status 1 as for a simulation that stopped early
        print(f"bearingfem: error: {err}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("bearingfem: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        # the reader went away (``| head``): say nothing more; stdout is closed quietly
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 141


if __name__ == "__main__":
    sys.exit(main())
