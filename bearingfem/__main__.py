"""``python -m bearingfem``: the library has no command of its own. The command line is
the application layer's, above the library (``bearingfem`` once installed, or
``python -m bearingfem_app`` from a checkout); this points there in one line on stderr and
exits with status 2, the command line's status for what it refuses. No import of the
application layer: the library imports nothing above it. Importing this module (a walk
over the package's modules) does nothing."""
import sys

POINTER = ("bearingfem: error: the command line is 'bearingfem COMMAND' (from a checkout: "
           "'python -m bearingfem_app COMMAND'); 'bearingfem --help' lists the commands")

if __name__ == "__main__":
    sys.stderr.write(POINTER + "\n")
    raise SystemExit(2)
