"""Create .venv-ross31: ROSS's main branch with its compiled (numba) fluid-film engine.

    python -m benchmarks._ross31_env            # once; benchmarks/ross31.py calls it too

ROSS is not a dependency of bearingfem. The source is the public snapshot of ROSS's main
(petrobras/ross) at ``ROSS_COMMIT`` (2026-08-18), the newest public source carrying the
engine ``ross/bearings/fluid_film/`` that ROSS 3.1 ships; PyPI here has only 2.3.0 (the old
FluidFlow, see .venv-ross). The snapshot is exported from a local bare mirror of the
repository (``--mirror``, or $ROSS_MIRROR) and pip-installed with its own requirements
(numba and the rest from PyPI). ``.venv-ross31/ross31.json`` records what was installed.
"""
from __future__ import annotations

import argparse
import io
import json
import os
import subprocess
import sys
import tarfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
VENV = ROOT / ".venv-ross31"
# a bare mirror: git clone --mirror https://github.com/petrobras/ross .ross-mirror
MIRROR = Path(os.environ.get("ROSS_MIRROR", ROOT / ".ross-mirror"))
ROSS_COMMIT = "631a249adbae414d5f5f986479b58f1a4c47935e"
# the package and its build files only (the repository's notebooks are not needed)
SOURCE_PATHS = ("ross", "pyproject.toml", "requirements.txt", "setup.cfg", "MANIFEST.in",
                "README.md", "LICENSE.md")


def python() -> Path:
    return VENV / "bin" / "python"


def record() -> dict:
    """What .venv-ross31 measured: ROSS's commit and numba's version."""
    return json.loads((VENV / "ross31.json").read_text())


def install(mirror: Path = MIRROR, commit: str = ROSS_COMMIT) -> dict:
    """Build .venv-ross31 (no-op when it exists); returns the install record."""
    if (VENV / "ross31.json").exists():
        return record()
    if not (mirror / "HEAD").exists():
        raise FileNotFoundError(f"no git mirror of petrobras/ross at {mirror}: make one with "
                                f"'git clone --mirror https://github.com/petrobras/ross "
                                f"{mirror}', or give --mirror / $ROSS_MIRROR")
    print(f"installing ROSS main @ {commit[:10]} into {VENV.name} (once) ...", flush=True)
    src = VENV / "src"
    src.mkdir(parents=True, exist_ok=True)
    tar = subprocess.run(["git", f"--git-dir={mirror}", "archive", commit, *SOURCE_PATHS],
                         capture_output=True, check=True).stdout
    with tarfile.open(fileobj=io.BytesIO(tar)) as t:
        t.extractall(src)
    subprocess.run([sys.executable, "-m", "venv", str(VENV)], check=True)
    subprocess.run([str(python()), "-m", "pip", "install", "--quiet", "--upgrade", "pip"],
                   check=True)
    # ROSS themes plotly with "scattermapbox", which plotly 6 removed (as for ROSS 2.3)
    subprocess.run([str(python()), "-m", "pip", "install", "--quiet", str(src), "plotly<6"],
                   check=True)
    versions = subprocess.run(
        [str(python()), "-c", "import json, numba, numpy, scipy; print(json.dumps(dict("
         "numba=numba.__version__, numpy=numpy.__version__, scipy=scipy.__version__)))"],
        capture_output=True, text=True, check=True).stdout
    rec = dict(ross_commit=commit, ross_date="2026-08-18", **json.loads(versions))
    (VENV / "ross31.json").write_text(json.dumps(rec, indent=1))
    return rec


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mirror", type=Path, default=MIRROR)
    print(json.dumps(install(ap.parse_args().mirror)))
