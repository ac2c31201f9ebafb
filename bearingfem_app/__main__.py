"""``python -m bearingfem_app``: the same as the ``bearingfem`` command."""
from .cli import main

raise SystemExit(main())
