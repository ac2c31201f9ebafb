"""A scene that asks for an accuracy instead of a mesh ([effects.lubrication] rtol): the
mesh is chosen when the run starts, the run reports the film's estimated error."""
import tomllib
from pathlib import Path

import pytest

from mechanism import simulate
from mechanism.scene import parse_scene

SCENE = Path(__file__).resolve().parents[1] / "scenes" / "paper-short-fem.toml"


def _scene(**lubrication):
    d = tomllib.loads(SCENE.read_text())
    lub = d["effects"]["lubrication"]
    for k in ("n_theta", "n_z", "element"):
        lub.pop(k)
    lub.update(lubrication)
    d["run"].update(turns=0.05, record_from_turn=0)
    return parse_scene(d)


def test_a_run_to_an_accuracy_reports_the_films_error():
    """The mesh chosen meets rtol at the probe states; the run's own states are checked
    after it and reported (it may exceed rtol where the pin passes the deepest probe,
    eps 0.97: over 0.25 turn, 0.022 at rtol 0.01 on P2 96 x 8)."""
    res = simulate(_scene(rtol=1e-2), progress=False)
    n_theta, n_z, element = res.stats["film_mesh"]
    assert element == "P2" and n_theta >= 24
    assert res.stats["film_rtol"] == 1e-2
    assert 0.0 < res.stats["film_force_error"] < 0.1


@pytest.mark.parametrize("extra, needle", [
    (dict(rtol=1e-3, n_theta=48), "give rtol or the mesh"),
    (dict(rtol=0.5), "rtol must lie in"),
    (dict(rtol=1e-3, model="short", cavitation=None), "needs a film model on a mesh")])
def test_bad_rtol_in_a_scene_is_refused_by_name(extra, needle):
    extra = {k: v for k, v in extra.items() if v is not None}
    d = tomllib.loads(SCENE.read_text())
    lub = d["effects"]["lubrication"]
    for k in ("n_theta", "n_z", "element") + (("cavitation",) if "model" in extra else ()):
        lub.pop(k)
    lub.update(extra)
    with pytest.raises(ValueError, match=needle):
        parse_scene(d)
