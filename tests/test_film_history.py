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
    assert np.allclose(m.point_data["pressure [Pa]"].max(), frames[1].solution.pressure_max)
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


def test_series_carry_coordinates_and_time(long_run, tmp_path):
    sc, r = long_run
    frames = film_history(r, sc, [60, 120], n_theta=24, n_z=4)
    write_history(frames, tmp_path, "unwrapped")
    m = meshio.read(tmp_path / "film-001.vtu")
    assert {"pressure [Pa]", "film_thickness [m]", "theta [rad]", "z [m]", "time [s]",
            "crank_angle [rad]"} <= set(m.point_data)
    assert np.allclose(m.point_data["time [s]"], frames[1].t)
    assert np.allclose(np.degrees(m.point_data["crank_angle [rad]"]), frames[1].crank_angle_deg)
    assert np.ptp(m.point_data["theta [rad]"]) > 6.0 and np.ptp(m.point_data["z [m]"]) > 0


def test_saved_run_carries_its_provenance_and_a_csv(long_run, tmp_path):
    import csv
    import json
    import bearingfem
    from mechanism import load_result
    sc, r = long_run
    r.save(tmp_path / "run")
    meta = json.loads((tmp_path / "run" / "result.json").read_text())
    prov = meta["provenance"]
    assert prov["bearingfem"] == bearingfem.__version__ and prov["created"].endswith("+00:00")
    assert prov["scene"]["lubrication"]["model"] == "fem"
    assert prov["scene"]["lubrication"]["options"]["n_theta"] == 48
    assert prov["scene"]["bearing"]["clearance"] == sc.bearing.clearance
    rows = list(csv.reader(open(tmp_path / "run" / "result.csv")))
    assert rows[0][:3] == ["t [s]", "crank_angle [rad]", "crank_speed [rad/s]"]
    assert len(rows) == len(r.t) + 1 and float(rows[-1][0]) == pytest.approx(r.t[-1])
    assert load_result(tmp_path / "run").provenance == prov


def test_frames_refuses_a_scene_whose_physics_differ(long_run, tmp_path):
    import subprocess
    import sys
    sc, r = long_run
    r.save(tmp_path / "run")
    text = (SCENES / "paper-long-fem.toml").read_text().replace("clearance = 20e-6",
                                                                "clearance = 30e-6")
    (tmp_path / "paper-long-fem.toml").write_text(text)
    out = subprocess.run([sys.executable, "-m", "bearingfem_app", "frames",
                          str(tmp_path / "paper-long-fem.toml"), str(tmp_path / "run"), "-o",
                          str(tmp_path / "fr"), "--no-render"], capture_output=True, text=True,
                         timeout=300)
    assert out.returncode == 2 and "scene.bearing.clearance" in out.stderr


def test_frames_spread_over_a_run_shorter_than_a_turn(long_run):
    """n_frames evenly spaced over what a half-turn run covers (0 to 180 deg, ends
    included), each its own sample; a turn's 0, 90, 180, 270 put two on the run's end."""
    sc, r = long_run
    frames = film_history(r, sc, n_frames=4, n_theta=24, n_z=4)
    angles = [f.crank_angle_deg for f in frames]
    assert len({f.t for f in frames}) == 4
    assert angles == pytest.approx([0.0, 60.0, 120.0, 180.0], abs=0.5)


def test_a_field_the_frames_lack_is_named_for_what_was_asked(long_run, tmp_path, capsys):
    """--field temperature (or deformation) on a run whose frames carry pressure and film
    thickness says why for that field; it said 'the film fraction needs a mass-conserving
    film' whatever was asked."""
    from bearingfem_app.cli import main
    sc, r = long_run
    r.save(tmp_path / "run")
    for field, why in (("temperature", "the frames keep no film temperature"),
                       ("deformation", "the frames keep no bush deflection"),
                       ("fraction", "the film fraction needs a mass-conserving film")):
        assert main(["frames", "paper-long-fem", str(tmp_path / "run"), "-o",
                     str(tmp_path / "fr"), "--field", field]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and why in err[0] and "carry pressure, film_thickness" in err[0]
        assert field == "fraction" or "fraction" not in err[0], err


def test_frames_of_a_recorded_turn_stay_a_turn_apart():
    """A scene's recorded turn ends a sample short of 360 deg (359.5): its frames are a
    turn's, 360 / n_frames apart, not spread over 0 .. 359.5 with the first and last at
    one crank angle."""
    sc = load_scene("paper-short-analytic")
    r = simulate(sc, progress=False)
    assert 359.0 < np.degrees(r.crank_angle[-1] - r.crank_angle[0]) < 360.0
    frames = film_history(r, sc, n_frames=4, n_theta=24, n_z=4)
    assert [f.crank_angle_deg for f in frames] == pytest.approx([0.0, 90.0, 180.0, 270.0],
                                                                 abs=0.5)
