"""The film along a run: re-solved films agree with the run's own joint force, and the
series exports (PVD + VTU) and renders (PNG + GIF) off screen."""
import xml.etree.ElementTree as ET
from dataclasses import replace
from pathlib import Path

import meshio
import numpy as np
import pytest

from mechanism import load_scene, simulate
from mechanism.film_history import film_history, render_history, write_history

SCENES = Path(__file__).resolve().parent.parent / "scenes"


@pytest.fixture(scope="module")
def long_run():
    sc = load_scene(SCENES / "paper-long-fem.toml")
    sc = replace(sc, run=replace(sc.run, turns=0.5, record_from_turn=0.0))
    return sc, simulate(sc, progress=False)


def test_refilmed_force_matches_the_run(long_run):
    """The run's joint force is this film's force; re-solving it from the saved records
    (rates by central differences of 720-per-turn samples) gives it to 4e-3 (measured)."""
    sc, r = long_run
    frames = film_history(r, sc, [45, 90, 135, 170])
    for f in frames:
        i = int(np.argmin(np.abs(r.t - f.t)))
        F = np.array([r.force_x[i], r.force_y[i]])
        assert np.linalg.norm(np.array(f.solution.force) - F) < 1e-2 * np.linalg.norm(F)


def test_series_exports_and_renders(long_run, tmp_path):
    sc, r = long_run
    frames = film_history(r, sc, [60, 120, 170], n_theta=24, n_z=4)
    pvd = write_history(frames, tmp_path)
    ds = ET.parse(pvd).getroot().find("Collection").findall("DataSet")
    assert [float(d.get("timestep")) for d in ds] == [f.t for f in frames]
    m = meshio.read(tmp_path / ds[1].get("file"))
    assert np.allclose(m.point_data["pressure"].max(), frames[1].solution.pressure_max)
    paths = render_history(frames, tmp_path, gif=True)
    assert [p.name for p in paths] == ["frame-000.png", "frame-001.png", "frame-002.png",
                                       "film.gif"]
    from PIL import Image
    assert Image.open(tmp_path / "film.gif").n_frames == 3


def test_bad_requests_are_named(long_run):
    sc, r = long_run
    with pytest.raises(ValueError, match="n_frames must be an integer >= 1"):
        film_history(r, sc, n_frames=0)
    with pytest.raises(ValueError, match="fewer than 3 saved samples"):
        film_history(replace(r, t=r.t[:2]), sc)


def test_frames_command(long_run, tmp_path):
    import subprocess
    import sys
    sc, r = long_run
    r.save(tmp_path / "run")
    cmd = [sys.executable, "-m", "bearingfem_app", "frames", str(SCENES / "paper-long-fem.toml"),
           str(tmp_path / "run"), "-o", str(tmp_path / "fr"), "--angles", "30,150",
           "--no-render"]
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert len(list((tmp_path / "fr").glob("film-*.vtu"))) == 2
    bad = subprocess.run(cmd[:5] + [str(tmp_path / "nothing"), "-o", str(tmp_path / "x")],
                         capture_output=True, text=True, timeout=300)
    assert bad.returncode == 2 and "no run result in" in bad.stderr
    assert len(bad.stderr.strip().splitlines()) == 1
    # a run of another scene is refused by name, before any film is solved
    other = subprocess.run(cmd[:4] + [str(SCENES / "paper-short-fem.toml")] + cmd[5:],
                           capture_output=True, text=True, timeout=300)
    assert other.returncode == 2 and "was made from scene 'paper-long-fem'" in other.stderr
