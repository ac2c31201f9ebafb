"""The "fem-ehd" film model: registered with checked options, its rigid-bush limit, its
film with memory in the mechanism (kept deflection between film steps) and film-step
convergence."""
import numpy as np
import pytest

from bearingfem import ElasticBush, JournalState
from bearingfem.bearing import seed_bearing
from bearingfem.ehd.transient import TransientEHD, ehd_solution
from bearingfem.lubricant import Lubricant
from bearingfem.models import FILM_MODELS, film_model
from mechanism import load_scene, parse_scene, simulate

B = seed_bearing(0.2)
S = JournalState(eps=0.95, gamma=0.3, omega=250.0)
RING = ElasticBush(outer_radius=0.016, modulus=110e9, poisson=0.34, model="ring")
OIL = Lubricant(viscosity=0.0117, barus=2e-8, density="dowson-higginson")
STIFF = ElasticBush(outer_radius=0.016, modulus=1e25, poisson=0.34, model="ring")


def test_model_is_registered_with_memory_and_the_scene_loads():
    m = FILM_MODELS["fem-ehd"]
    assert m.memory and m.numeric
    sc = load_scene("paper-short-ehd")
    opts = sc.lubrication.options
    assert isinstance(opts["bush"], ElasticBush) and opts["bush"].modulus == 110e9
    assert isinstance(opts["lubricant"], Lubricant) and opts["lubricant"].roelands == 0.751
    # Z = 0.751 is the Barus 2e-8 /Pa it replaces, at p = 0 (the scene's comments)
    assert abs(opts["lubricant"].pressure_viscosity - 2e-8) < 1e-11
    assert isinstance(m.along_run(B, dict(n_theta=24, n_z=4, bush=RING, modes=8)),
                      TransientEHD)


@pytest.mark.parametrize("options, name", [
    (dict(bush="bronze"), "bush"), (dict(lubricant=0.0117), "lubricant"),
    (dict(modes=-1), "modes"), (dict(modes=2.5), "modes"), (dict(n_theta=4), "n_theta"),
    (dict(film_step=-1e-4), "film_step"), (dict(cavitation="gumbel"), "cavitation"),
])
def test_bad_options_raise_naming_the_option(options, name):
    """The registry refuses each before any work, naming it after where it was given.
    Fails with the "instance" rule (lubricant, bush) left unchecked: the film's own
    checks downstream would name the parameter without the scene's path."""
    m = film_model("fem-ehd")
    with pytest.raises(ValueError, match=f"lubrication.{name}"):
        m.options(options, where="scene.effects.lubrication")
    with pytest.raises(ValueError, match=name):
        m.film_force(B, S, **options)


def test_more_modes_than_the_film_grid_has_nodes_is_refused():
    """More compliance vectors than the film grid has nodes: refused by the steady force
    naming ``modes`` (roughness with a bush is the mixed EHD film, tests/test_ehd_mixed.py)."""
    m = film_model("fem-ehd")
    with pytest.raises(ValueError, match="modes"):
        m.film_force(B, S, **dict(n_theta=8, n_z=2, bush=RING, modes=100))


def test_scene_tables_are_checked():
    base = {"name": "e", "bearing": {"diameter": 0.02, "length_ratio": 0.2,
                                     "clearance": 20e-6, "viscosity": 0.0117}}
    for key, table in (("bush", {"modulus": -1.0}), ("lubricant", {"viscosity": 0.01,
                                                                    "barus": -1.0})):
        with pytest.raises(ValueError, match=f"lubrication.{key}"):
            parse_scene(dict(base, effects={"lubrication": {"model": "fem-ehd",
                                                            key: table}}))


def test_rigid_bush_limit_is_the_fem_reynolds_film():
    """A bush of modulus 1e25 Pa (deflection ~1e-16 of the film) and no lubricant: the
    model's force equals the "fem" model's under the Reynolds condition on the same mesh
    (1.2e-9 relative measured: Newton's tolerance; the fem film is solved on the half
    mesh, this one on the whole length). Fails with the model's film under Gumbel's
    condition or on another mesh."""
    ehd = film_model("fem-ehd").film_force(B, S, n_theta=48, n_z=4, bush=STIFF, modes=0)
    fem = film_model("fem").film_force(B, S, n_theta=48, n_z=4, cavitation="reynolds")
    assert np.allclose(ehd, fem, rtol=1e-7, atol=0.0)


def _lamb_scene(model, **lub):
    """A quarter of a turn of a short pin (L/D 0.5), coarse film."""
    return parse_scene({"name": "ehd", "bearing": {"diameter": 0.02, "length_ratio": 0.5,
                                                   "clearance": 20e-6, "viscosity": 0.0117},
                        "run": {"turns": 0.1, "record_from_turn": 0, "samples_per_turn": 400},
                        "effects": {"lubrication": {"model": model, "n_theta": 32, "n_z": 4,
                                                    **lub}}})


def test_rigid_bush_run_follows_the_fem_reynolds_run():
    """The run of the rigid-bush model (kept deflection zero: the film between film steps
    is the Reynolds film itself) against the "fem" run under the Reynolds condition:
    the orbits agree within the run's absolute tolerance on the centre, 2e-9 m (2.4e-10 m
    measured: two routes to one film take different steps). Fails with the kept film
    solved under Gumbel's condition instead of Reynolds'."""
    fem = simulate(_lamb_scene("fem", cavitation="reynolds"), progress=False)
    ehd = simulate(_lamb_scene("fem-ehd", bush=STIFF, modes=0, film_step=2e-4), progress=False)
    assert not fem.partial and not ehd.partial, ehd.message
    c = 20e-6
    assert fem.stats["atol_length"] == 1e-4 * c
    assert np.max(np.hypot(fem.e_x - ehd.e_x, fem.e_y - ehd.e_y)) < 1e-4 * c


def _orbit_end(film_step):
    r = simulate(_lamb_scene("fem-ehd", bush=dict(outer_radius=0.016, modulus=110e9,
                                                  poisson=0.34, model="ring"),
                             modes=0, film_step=film_step), progress=False)
    assert not r.partial, r.message
    assert np.all(np.isfinite(r.force_x)) and np.all(np.isfinite(r.force_y))
    return np.array([r.e_x[-1], r.e_y[-1]])


@pytest.mark.slow
def test_film_step_convergence():
    """The kept deflection lags by at most one film step: the journal's position after a
    tenth of a turn (L/D 0.5, bronze ring bush, 32 x 4) against the run with a full EHD
    solve at every accepted step (film_step 0). Measured: 5.5e-8, 9.7e-9, 1.1e-8 m at film
    steps 4e-4, 2e-4, 1e-4 s: the lag's error falls 5.7x from 4e-4 to 2e-4 s and then
    sits at ~1e-8 m, five times the run's absolute tolerance (2e-9 m) - the integrator's
    and the fade's floor, not the lag's. ~95 s, hence slow. Fails if the kept deflection
    is dropped (every film step then gives the rigid film's orbit: errors 0, and the
    test fails)."""
    ref = _orbit_end(0.0)
    err = [np.hypot(*(_orbit_end(h) - ref)) for h in (4e-4, 2e-4, 1e-4)]
    print("film-step errors [m]", err)
    assert err[0] > 3.0 * max(err[1:])
    assert max(err[1:]) < 2e-8


def test_no_nan_near_contact_and_the_bush_bounds_the_force():
    """Near the wall (eps 0.999, 0.9999, 0.99999; ring bronze bush, Barus oil, 48 x 4,
    32 modes) the film stays finite: pressure, deflection and film > 0 everywhere, and
    the force tends to a finite limit (the bush opens the gap: 880, 897, 899 N measured,
    the last step 0.2 %), 5.5x below the rigid film's on the same mesh (4875, 4929 N).
    Fails with the deflection left out of the gap (the force is then the rigid film's,
    with the oil's viscosity rise on top)."""
    forces = []
    for eps in (0.999, 0.9999, 0.99999):
        s = JournalState(eps=eps, gamma=0.3, omega=250.0)
        sol = ehd_solution(B, s, OIL, RING, None, 48, 4, 32)
        assert np.all(np.isfinite(sol.pressure)) and np.all(np.isfinite(sol.deformation))
        assert np.all(sol.film_thickness > 0.0)
        forces.append(np.hypot(*sol.force_local))
    rigid = [np.hypot(*film_model("fem").film_force(B, JournalState(eps=e, omega=250.0),
                                                    n_theta=48, n_z=4, cavitation="reynolds"))
             for e in (0.9999, 0.99999)]
    assert forces[1] < 0.25 * rigid[0] and forces[2] < 0.25 * rigid[1]
    assert forces[0] < forces[1] < forces[2] < 1.005 * forces[1]


def test_warm_start_converges_in_a_few_steps_to_the_cold_film():
    """solve_reynolds(start=) from the film of a nearby state (eps 0.9955 -> 0.995, gamma
    -0.01 -> 0; ring bush, 48 x 4, full compliance): 3 Newton steps against the cold
    start's 33 (measured), and the same film to 1e-8 of its peak. Fails if the start is
    ignored (the cold count) or read in the wrong units (Pa as dimensionless: Newton
    stalls from it and the cold route runs)."""
    from bearingfem import solve_reynolds
    from bearingfem.elastic import bush_compliance
    full = bush_compliance(RING, B.radius, B.length, 48, 5)
    heavy = JournalState(eps=0.995, omega=250.0)
    near = solve_reynolds(B, JournalState(eps=0.9955, gamma=-0.01, omega=250.0), 48, 4,
                          bush=full)
    cold = solve_reynolds(B, heavy, 48, 4, bush=full)
    warm = solve_reynolds(B, heavy, 48, 4, bush=full, start=near)
    assert warm.iterations <= 3 < cold.iterations
    assert np.max(np.abs(warm.pressure - cold.pressure)) < 1e-8 * cold.pressure_max
    with pytest.raises(ValueError, match="start"):
        solve_reynolds(B, heavy, 24, 4, bush=bush_compliance(RING, B.radius, B.length, 24, 5),
                       start=near)
