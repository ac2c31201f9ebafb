"""The built package is what a user gets: a wheel holds the libraries, the app layer and the
shipped scenes (not studies/ or benchmarks/), and its ``bearingfem`` command runs a shipped
scene from a directory outside the checkout."""
import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    out = tmp_path_factory.mktemp("wheel")
    # build from a copy: an in-tree build would leave build/ in the checkout
    src = out / "src"
    shutil.copytree(ROOT, src, symlinks=True, ignore=shutil.ignore_patterns(
        ".git", ".venv*", "results", "build", "*.egg-info", "__pycache__", ".pytest_cache"))
    r = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--quiet", "-w",
                        str(out), str(src)], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    return next(out.glob("bearingfem-*.whl"))


def test_wheel_holds_what_users_import(wheel):
    names = zipfile.ZipFile(wheel).namelist()
    tops = {n.split("/")[0] for n in names if not n.split("/")[0].endswith(".dist-info")}
    assert tops == {"bearingfem", "mechanism", "bearingfem_app"}
    assert "mechanism/scenes/paper-short-fem.toml" in names
    assert "bearingfem_app/sweeps/capacity.toml" in names       # bearingfem sweep capacity
    meta = next(n for n in names if n.endswith("METADATA"))
    text = zipfile.ZipFile(wheel).read(meta).decode()
    assert "License-Expression: BSD-3-Clause" in text and "Requires-Dist: pillow" in text


def test_installed_command_runs_a_shipped_scene_outside_the_checkout(wheel, tmp_path):
    site = tmp_path / "site"
    r = subprocess.run([sys.executable, "-m", "pip", "install", "--no-deps", "--quiet",
                        "--target", str(site), str(wheel)], capture_output=True, text=True,
                       timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    work = tmp_path / "elsewhere"
    work.mkdir()
    env = {**os.environ, "PYTHONPATH": str(site), "MPLBACKEND": "Agg"}
    code = ("import bearingfem, mechanism, sys; from bearingfem_app.cli import main; "
            "print(bearingfem.__file__); sys.exit(main(sys.argv[1:]))")
    r = subprocess.run([sys.executable, "-c", code, "simulate", "paper-long-analytic", "-o",
                        "out", "-q"], cwd=work, env=env, capture_output=True, text=True,
                       timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.splitlines()[0].startswith(str(site))   # the installed copy ran
    assert (work / "out" / "result.npz").is_file()
