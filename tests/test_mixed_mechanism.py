"""Mixed lubrication in the mechanism: a scene's film model with Greenwood-Tripp roughness
is the joint's contact (bearingfem.fe.mixed through the "fem" model's roughness option)."""
import dataclasses
from pathlib import Path

import numpy as np
import pytest

from bearingfem import JournalState, Roughness, solve_reynolds
from mechanism import load_scene, parse_scene, simulate
from mechanism.simulate import build_effects

SCENES = Path(__file__).resolve().parent.parent / "scenes"
ROUGH = dict(sigma=0.31e-6, contact_modulus=53.3e9, elastic_factor=1e-3, friction=0.02)


def scene(roughness=ROUGH, turns=0.05, **extra):
    lub = {"model": "fem", "n_theta": 48, "n_z": 4}
    if roughness is not None:
        lub["roughness"] = dict(roughness)
    return parse_scene({"name": "mixed", "bearing": {"diameter": 0.02, "length_ratio": 0.2,
                                                     "clearance": 20e-6, "viscosity": 0.0117},
                        "run": {"turns": turns, "record_from_turn": 0},
                        "effects": {"lubrication": lub, **extra}})


def test_mixed_scene_loads_with_its_roughness():
    """The shipped scene's roughness table becomes the film model's Roughness. Fails when
    the scene drops the table."""
    sc = load_scene(SCENES / "paper-short-mixed.toml")
    assert sc.lubrication.options["roughness"] == Roughness(**ROUGH)
    assert sc.contact is None


def test_scene_roughness_is_checked():
    """Bad roughness names the key; the Hertz contact and a model without roughness are
    refused alongside it."""
    with pytest.raises(ValueError, match=r"lubrication\.roughness\.sigma"):
        scene(dict(ROUGH, sigma=-1.0))
    with pytest.raises(ValueError, match=r"lubrication\.roughness has unknown key"):
        scene(dict(ROUGH, sigmaa=1e-6))
    with pytest.raises(ValueError, match="remove scene.effects.contact"):
        scene(contact={"young_modulus": 207e9})
    with pytest.raises(ValueError, match="roughness is not an option"):
        parse_scene({"name": "s", "bearing": {"diameter": 0.02, "length_ratio": 0.2,
                                              "clearance": 20e-6, "viscosity": 0.0117},
                     "effects": {"lubrication": {"model": "short", "roughness": ROUGH}}})


def test_joint_force_is_film_plus_asperities():
    """The force the mechanism's joint sees at a thin-film state is the film's plus the
    asperity force of the film solve (to the solver tolerance: 1e-9 relative). Fails when
    the warm-started force of a run drops the contact."""
    sc = scene()
    _, film, _ = build_effects(sc)
    s = JournalState(0.99, omega=250.0)
    f_r, f_t = film.run.force(s, 0.0)
    sol = solve_reynolds(sc.bearing, s, 48, 4, "P1", "gumbel", roughness=Roughness(**ROUGH))
    expected = np.add(sol.force_local, sol.asperity_force_local)
    assert sol.asperity_force_local[0] < -1.0          # the summits do press here
    assert (f_r, f_t) == pytest.approx(tuple(expected), rel=1e-9)


def test_short_run_of_the_mixed_scene():
    """0.05 turn of the shipped mixed scene (48 cells around to keep it short) runs into
    the mixed regime: the least film falls below 1.5 sigma (measured 0.354 um = 1.14
    sigma), where the asperity force on the film mesh is non-zero. The effect on the orbit
    is small this early (0.7 nm on the least film at rtol 1e-9, below the default
    integrator tolerance of 1e-3 c), so the force itself is checked in the test above."""
    sc = load_scene(SCENES / "paper-short-mixed.toml")
    lub = dataclasses.replace(sc.lubrication, options={**sc.lubrication.options, "n_theta": 48})
    sc = dataclasses.replace(sc, lubrication=lub,
                             run=dataclasses.replace(sc.run, turns=0.05, record_from_turn=0.0))
    r = simulate(sc, progress=False)
    assert np.all(np.isfinite(r.eps)) and np.all(np.isfinite(r.force_x))
    assert np.min(r.film_min) < 1.5 * ROUGH["sigma"]
