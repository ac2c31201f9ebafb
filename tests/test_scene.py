"""Scenes are validated before any integration; the paper scenes load."""
import copy
from pathlib import Path

import pytest

from mechanism import load_scene, parse_scene

SCENES = Path(__file__).resolve().parent.parent / "scenes"
BASE = {"name": "t", "bearing": {"diameter": 0.02, "length_ratio": 0.2, "clearance": 20e-6,
                                 "viscosity": 0.0117},
        "effects": {"lubrication": {"model": "short"}}}


@pytest.mark.parametrize("path", sorted(SCENES.glob("*.toml")), ids=lambda p: p.stem)
def test_shipped_scenes_load(path):
    s = load_scene(path)
    assert s.name == path.stem


def _with(path, value):
    d = copy.deepcopy(BASE)
    node = d
    for k in path[:-1]:
        node = node.setdefault(k, {})
    if value is KeyError:
        del node[path[-1]]
    else:
        node[path[-1]] = value
    return d


@pytest.mark.parametrize("path,value,message", [
    (("bearing", "colour"), "red", r"scene.bearing has unknown key\(s\): colour"),
    (("effects", "magnetism"), {}, r"scene.effects has unknown key\(s\): magnetism"),
    (("bearing", "clearance"), -1e-6, r"scene.bearing.clearance must lie in"),
    (("bearing", "clearance"), KeyError, r"scene.bearing.clearance is required"),
    (("bearing", "viscosity"), "thick", r"scene.bearing.viscosity must be a finite number"),
    (("run", "rtol"), 0.5, r"scene.run.rtol must lie in \[1e-13, 0.1\]"),
    (("run", "integrator"), "euler", r"scene.run.integrator must be one of"),
    (("run", "record_from_turn"), 9, r"record_from_turn must be smaller"),
    (("initial", "crank_speed"), 0.0, r"scene.initial.crank_speed must lie in \(0"),
    (("effects", "lubrication", "model"), "magic", r"lubrication.model"),
    (("effects", "lubrication", "n_theta"), 40, r"scene.effects.lubrication.n_theta is not an option of film model 'short'"),
    (("effects", "contact"), {"poisson": 0.7}, r"scene.effects.contact.poisson must lie in \[0.0, 0.5\)"),
    (("effects", "friction"), {"coefficient": 0.1}, r"friction acts at the contact"),
    (("mechanism", "rod_length"), 0.01, r"crank_length must be smaller than rod_length"),
    (("joint",), "welded", r"scene.joint must be one of"),
])
def test_bad_scene_is_rejected_naming_the_field(path, value, message):
    with pytest.raises(ValueError, match=message):
        parse_scene(_with(path, value))


def test_fem_options_validated():
    d = _with(("effects", "lubrication"), {"model": "fem", "n_theta": 4})
    with pytest.raises(ValueError, match=r"n_theta must be an integer >= 8"):
        parse_scene(d)
    d = _with(("effects", "lubrication"), {"model": "fem", "element": "Q9"})
    with pytest.raises(ValueError, match="element must be one of"):
        parse_scene(d)


def test_cavitation_jfo_points_to_the_jfo_model():
    """cavitation = "jfo" under model "fem" was refused with the allowed words alone; the
    mass-conserving film is its own model, and the message (scene and Python alike) says
    so."""
    from bearingfem import Bearing, equilibrium
    d = _with(("effects", "lubrication"), {"model": "fem", "cavitation": "jfo"})
    with pytest.raises(ValueError, match=r"lubrication.cavitation must be one of .*"
                                         r"the model 'fem-jfo'"):
        parse_scene(d)
    b = Bearing(radius=0.01, length=0.02, clearance=20e-6, viscosity=0.0117)
    with pytest.raises(ValueError, match="the model 'fem-jfo'"):
        equilibrium(b, (0.0, -100.0), 250.0, "fem", cavitation="jfo")


def test_fem_table_options_parse_with_their_defaults_and_ranges():
    sc = parse_scene(_with(("effects", "lubrication"), {"model": "fem-table", "n_phi": 48}))
    assert sc.lubrication.options == dict(n_theta=64, n_z=16, cavitation="gumbel", n_eps=60,
                                          n_phi=48, element="P2")
    with pytest.raises(ValueError, match=r"n_eps must be an integer >= 6"):
        parse_scene(_with(("effects", "lubrication"), {"model": "fem-table", "n_eps": 2}))
    with pytest.raises(ValueError, match="half_film is not an option of film model 'fem-table'"):
        parse_scene(_with(("effects", "lubrication"), {"model": "fem-table", "half_film": "x"}))


def test_unknown_model_is_named():
    with pytest.raises(ValueError, match="model must be one of .*fem-table"):
        parse_scene(_with(("effects", "lubrication", "model"), "fem-tabel"))


def test_missing_file_and_bad_toml(tmp_path):
    with pytest.raises(ValueError, match="not found"):
        load_scene(tmp_path / "nope.toml")
    p = tmp_path / "bad.toml"
    p.write_text("name = \n")
    with pytest.raises(ValueError, match="not valid TOML"):
        load_scene(p)


def test_misspelt_keys_are_named_with_the_likely_intent():
    d = _with(("bearing", "viscosty"), 0.0117)
    del d["bearing"]["viscosity"]
    with pytest.raises(ValueError, match=r"scene.bearing.viscosity is required but missing "
                                         r"\(unknown key viscosty: did you mean viscosity\?\)"):
        parse_scene(d)
    d = _with(("run", "rtoll"), 1e-6)
    with pytest.raises(ValueError, match=r"scene.run has unknown key\(s\): rtoll "
                                         r"\(did you mean rtol\?\)"):
        parse_scene(d)


def test_a_misspelt_table_is_named_with_the_likely_intent():
    """A table's name misspelt: [bearng] for [bearing] and [rnu] for [run]. Old: 'scene.bearing
    is required for joint = 'clearance'' with no word of [bearng], and 'unknown key(s): rnu'
    without the suggestion (difflib's ratio 0.67, below the cutoff 0.7 then)."""
    d = copy.deepcopy(BASE)
    d["bearng"] = d.pop("bearing")
    with pytest.raises(ValueError, match=r"scene.bearing is required for joint = 'clearance' "
                                         r"\(unknown key bearng: did you mean bearing\?\)"):
        parse_scene(d)
    d = copy.deepcopy(BASE)
    d["rnu"] = {"turns": 1.0}
    with pytest.raises(ValueError, match=r"scene has unknown key\(s\): rnu "
                                         r"\(did you mean run\?\)"):
        parse_scene(d)


@pytest.mark.parametrize("bearing, needle", [
    ({"diameter": 20}, "scene.bearing.diameter 20 m is larger than any journal bearing"),
    ({"viscosity": 46.0}, "scene.bearing.viscosity 46 Pa s"),
    ({"length_ratio": 40.0}, "scene.bearing.length_ratio 40"),
])
def test_a_bearing_no_journal_bearing_has_is_refused(bearing, needle):
    d = copy.deepcopy(BASE)
    d["bearing"].update(bearing)
    with pytest.raises(ValueError, match=needle):
        parse_scene(d)


def test_crank_speed_in_rpm():
    """initial.rpm: the crank speed in 1/min (3000 rpm = 100 pi rad/s); one of the two."""
    import math
    assert parse_scene(_with(("initial", "rpm"), 3000)).crank_speed == pytest.approx(
        100 * math.pi, rel=1e-15)
    d = _with(("initial", "rpm"), 3000)
    d["initial"]["crank_speed"] = 250.0
    with pytest.raises(ValueError, match="one of crank_speed"):
        parse_scene(d)


def test_oil_by_grade_in_a_scene():
    """bearing.oil 'ISO VG 32' (at oil_temperature, default 40 degC) is 32 mm^2/s times
    870 kg/m^3 = 0.02784 Pa s by hand; with viscosity too, or a grade that does not
    exist, it is refused."""
    d = copy.deepcopy(BASE)
    del d["bearing"]["viscosity"]
    d["bearing"]["oil"] = "ISO VG 32"
    assert parse_scene(d).bearing.viscosity == pytest.approx(32e-6 * 870, rel=1e-9)
    d["bearing"]["oil_temperature"] = 80.0
    assert parse_scene(d).bearing.viscosity < 0.5 * 32e-6 * 870
    d["bearing"]["oil"] = "VG 33"
    with pytest.raises(ValueError, match="scene.bearing.oil must be an ISO VG grade"):
        parse_scene(d)
    d["bearing"].update(oil="VG 32", viscosity=0.03)
    with pytest.raises(ValueError, match="one of viscosity"):
        parse_scene(d)


@pytest.mark.parametrize("initial, needle", [
    ({"crank_speed": 3000.0}, r"scene.initial.crank_speed 3000 rad/s drives the crank pin at "
                              r"152.4 m/s .*must lie in \(0, 1181\] rad/s .*rpm given as "
                              r"rad/s\? \(3000 rpm = 314.2 rad/s"),
    ({"rpm": 3e5}, r"scene.initial.rpm 300000 1/min .*must lie in \(0, 11279\] 1/min"),
])
def test_a_crank_speed_no_slider_crank_reaches_is_refused(initial, needle):
    """3000 meant as rpm but read as rad/s drives the seed's 50.8 mm crank pin at 152 m/s,
    2.5 times the limit PIN_SPEED_MAX = 60 m/s (a racing engine's pin: ~38 m/s); its limit
    is 60 / 0.0508 = 1181 rad/s = 11279 rpm. Also for a scene changed after loading."""
    from dataclasses import replace
    d = copy.deepcopy(BASE)
    d["initial"] = initial
    with pytest.raises(ValueError, match=needle):
        parse_scene(d)
    ok = parse_scene(_with(("initial", "crank_speed"), 1181.0))       # at the limit: taken
    assert ok.crank_speed == 1181.0
    with pytest.raises(ValueError, match=r"^crank_speed 3000 rad/s drives the crank pin"):
        replace(ok, crank_speed=3000.0)


def test_an_oil_grade_is_read_as_typed_on_a_shell():
    """'ISO-VG-32' and 'iso_vg_32' (typed so as to need no quotes on a shell) are ISO VG
    32, as 'ISO VG 32', 'VG32' and '32' are; they were refused ('--oil must be an ISO VG
    grade ... got 'ISO-VG-32''). A grade that does not exist still is."""
    from mechanism.scene import oil_viscosity
    mu = oil_viscosity("ISO VG 32", 40.0)
    for typed in ("ISO-VG-32", "iso_vg_32", "VG-32", "VG32", "32", 32):
        assert oil_viscosity(typed, 40.0) == mu
    for bad in ("ISO-VG-33", "ISO VG", "VG 32 cSt", "-32", -32, "_32"):   # -32: a number
        with pytest.raises(ValueError, match="must be an ISO VG grade"):
            oil_viscosity(bad, 40.0)
