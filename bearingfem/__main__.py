"""``python -m bearingfem``: the library has no command of its own. The command line is
the application layer's, above the library (``bearingfem`` once installed, or
``python -m bearingfem_app`` from a checkout); this points there in one line on stderr and
exits with status 2, the command line's status for what it refuses. Asked for help
(``-h``/``--help``), it prints that usage on stdout and exits 0, as any command's help
does. No import of the application layer: the library imports nothing above it.
Importing this module (a walk over the package's modules) does nothing."""
import sys

POINTER = ("bearingfem: error: the command line is 'bearingfem COMMAND' (from a checkout: "
           "'python -m bearingfem_app COMMAND'); 'bearingfem --help' lists the commands")

USAGE = """usage: bearingfem COMMAND [options]
       python -m bearingfem_app COMMAND [options]   (from a checkout)

The library has no command of its own: 'python -m bearingfem' only points to the command
line above it. 'bearingfem --help' lists the commands, 'bearingfem COMMAND --help' their
options (docs/cli.md)."""

if __name__ == "__main__":
    if any(a in ("-h", "--help") for a in sys.argv[1:]):
        print(USAGE)
        raise SystemExit(0)
    sys.stderr.write(POINTER + "\n")
    raise SystemExit(2)
