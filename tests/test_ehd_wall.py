"""The mechanism with a film that carries the journal beyond the clearance circle (contract
rule 15): "fem-ehd" with a solid bronze bush runs through eps = 1 at the seed's 250 rad/s;
a rigid film still stops at eps = 1 (tests/test_mechanism.py keeps that stop's message)."""
import numpy as np

from mechanism import parse_scene, simulate
from mechanism.result import film_column


def seed_pin(lubrication):
    return parse_scene({"name": "wall", "bearing": {"diameter": 0.02, "length_ratio": 0.2,
                                                    "clearance": 20e-6, "viscosity": 0.0117},
                        "initial": {"crank_speed": 250.0},
                        "run": {"turns": 0.1, "record_from_turn": 0, "samples_per_turn": 400},
                        "effects": {"lubrication": lubrication}})


BRONZE = {"outer_radius": 0.016, "modulus": 110e9, "poisson": 0.34, "model": "solid"}


def test_the_ehd_film_carries_the_seed_pin_through_the_clearance_circle():
    """The seed pin from a centred start at 250 rad/s: the start transient's squeeze
    carries the pin past the rigid circle (peak eps ~1.10 on this 24 x 4 mesh, 8 modes);
    the run completes its tenth of a turn with finite forces and film steps beyond 1.
    Fails with "fem-ehd" not declaring beyond_clearance (the run then stops at eps = 1)."""
    r = simulate(seed_pin({"model": "fem-ehd", "n_theta": 24, "n_z": 4, "modes": 8,
                           "film_step": 2e-4, "bush": BRONZE}), progress=False)
    assert not r.partial, r.message
    assert 1.02 < np.max(r.eps) < 1.3
    assert np.all(np.isfinite(r.force_x)) and np.all(np.isfinite(r.force_y))
    assert r.stats["film_steps"] > 5
    # the run's film_min is the elastic film's own (the bush opens the gap), not the rigid
    # c (1 - eps) that is 0 beyond the circle: the record's value at each film step, where
    # a film step falls on a sample (fails with the rigid column kept: 0 where eps > 1)
    beyond = r.eps > 1.0
    assert beyond.any() and np.all(r.film_min[beyond] > 0.0)
    rec_t, rec_h = film_column(r.film_record, "t"), film_column(r.film_record, "film_min")
    assert np.allclose(np.interp(rec_t, r.t, r.film_min), rec_h, rtol=0.2)


def test_a_rigid_film_on_the_same_pin_still_stops_at_the_wall():
    """The same pin with the rigid Reynolds film on the same mesh, capped at eps 0.9 so
    that it cannot hold the pin: the wall stays at eps = 1 and the run stops there, marked
    partial. Fails with the simulator's wall taken from
    the film for every model (the rigid run then goes on to a ValueError at eps >= 1 and
    its message names no wall)."""
    r = simulate(seed_pin({"model": "fem", "n_theta": 24, "n_z": 4, "eps_max": 0.9}), progress=False)
    assert r.partial and "bearing wall (eps = 1)" in r.message
    assert np.all(r.eps <= 1.0 + 1e-9)
