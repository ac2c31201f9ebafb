"""The route table: each problem goes to the route of its kind, and each route refuses,
by name and before any work, every option it does not use (rule 2 of
bearingfem.routes.base). Each refusal test fails with the route's ``uses`` widened to all
options (the option is then ignored in silence, as it was before the table)."""
import numpy as np
import pytest

from bearingfem import (Bearing, ElasticBush, Groove, JournalState, Lubricant, Roughness,
                        Thermal, fvm_reynolds, solve_reynolds)
from bearingfem.fields import FilmFields
from bearingfem.routes import OPTION_DEFAULTS, ROUTES, fe_force, film_problem, route_for

B = Bearing(radius=0.01, length=0.01, clearance=20e-6, viscosity=0.0117)
S = JournalState(eps=0.6, eps_dot=0.0, gamma=0.3, gamma_dot=0.0, omega=250.0)
G = (Groove(angle=np.pi / 2, width=0.2, pressure=1e5),)
OIL = Lubricant(viscosity=0.0117, barus=2e-8)
ELRODE = Lubricant(viscosity=0.0117, bulk_modulus=1e9)
VG32 = Lubricant.iso_vg(32)
HOT = Thermal(supply_temperature=323.0)
RING = ElasticBush(outer_radius=0.016, modulus=110e9, poisson=0.34, model="ring")
ROUGH = Roughness(sigma=0.31e-6, contact_modulus=53.3e9, elastic_factor=1e-3)

#: (cavitation, options) -> the route that must take it
KINDS = [
    ("reynolds", {}, "rigid"),
    ("gumbel", dict(supply_angle=0.2), "rigid"),
    ("reynolds", dict(grooves=G, half=False), "rigid"),
    ("reynolds", dict(grooves=G), "grooved"),
    ("none", dict(grooves=G, grading=(np.pi, 0.5)), "grooved"),
    ("reynolds", dict(grading=0.5), "rigid"),
    ("reynolds", dict(tilt=(0.0, 1e-4)), "general"),
    ("none", dict(fields=FilmFields(viscosity=2.0)), "general"),
    ("reynolds", dict(lubricant=OIL), "ehd"),
    ("none", dict(bush=RING), "ehd"),
    ("jfo", dict(ambient_pressure=1e5), "jfo"),
    ("jfo", dict(grooves=G, roughness=ROUGH), "jfo"),
    ("jfo", dict(grooves=G), "jfo-grooved"),
    ("jfo", dict(ambient_pressure=1e5, lubricant=ELRODE), "jfo-compressible"),
    ("jfo", dict(ambient_pressure=1e5, bush=RING), "ehd-jfo"),
    ("jfo", dict(ambient_pressure=1e5, bush=RING, roughness=ROUGH), "ehd-jfo"),
    ("reynolds", dict(grooves=G, lubricant=VG32, thermal=HOT), "thd"),
    ("jfo", dict(grooves=G, lubricant=VG32, thermal=HOT), "thd"),
]


@pytest.mark.parametrize("cavitation, options, route", KINDS)
def test_each_problem_takes_the_route_of_its_kind(cavitation, options, route):
    assert route_for(film_problem(B, S, 24, 4, cavitation, **options)).name == route


def test_every_route_is_in_the_table_and_takes_a_known_option():
    assert {r for _, _, r in KINDS} | {"fv"} == set(ROUTES)
    for route in ROUTES.values():
        assert route.uses <= set(OPTION_DEFAULTS), route.name


#: An option each route does not use, given away from its default: refused by name.
UNUSED = [
    ("reynolds", dict(supply_angle=0.2), "start", None),
    ("reynolds", dict(grooves=G), "start", None),
    ("gumbel", {}, "ambient_pressure", 1e5),         # refused by the shared JFO check
    ("reynolds", dict(tilt=(0.0, 1e-4)), "grading", (np.pi, 0.5)),
    ("jfo", dict(ambient_pressure=1e5), "method", "psor"),
    ("jfo", dict(ambient_pressure=1e5), "cavitated_shear", "none"),
    ("jfo", dict(ambient_pressure=1e5), "tol", 1e-8),
    ("jfo", dict(grooves=G), "start", None),
    ("jfo", dict(ambient_pressure=1e5, lubricant=ELRODE), "tilt", (0.0, 1e-4)),
    ("jfo", dict(ambient_pressure=1e5, bush=RING), "method", "psor"),
    ("jfo", dict(ambient_pressure=1e5, bush=RING), "cavitated_shear", "none"),
    ("reynolds", dict(lubricant=OIL), "grading", (np.pi, 0.5)),
    ("reynolds", dict(grooves=G, lubricant=VG32, thermal=HOT), "tilt", (0.0, 1e-4)),
    ("reynolds", dict(grooves=G, lubricant=VG32, thermal=HOT), "roughness", ROUGH),
]


@pytest.mark.parametrize("cavitation, options, name, value", UNUSED,
                         ids=[f"{c}-{n}" for c, _, n, _ in UNUSED])
def test_a_route_refuses_an_option_it_does_not_use(cavitation, options, name, value):
    value = object() if value is None else value        # a start that is never read
    with pytest.raises(ValueError, match=name):
        solve_reynolds(B, S, 24, 4, "P1", cavitation, **{**options, name: value})


def test_the_finite_volume_film_refuses_a_finite_element_option():
    route = ROUTES["fv"]
    with pytest.raises(ValueError, match="element.*'fv'"):
        route.check(film_problem(B, S, 24, 4, "reynolds", discretisation="fv",
                                 element="P2"))


def test_the_finite_volume_film_refuses_a_groove_narrower_than_its_cells():
    """A groove narrower than a cell may hold no cell centre: without the refusal the JFO
    film at 12 x 4 here had no supply and returned a zero force (eps 0.6) or diverged to a
    residual of 1e294 (eps 0.3). The resolved grid gives the FE film: 2.9 %, 0.57 %,
    0.046 % apart at 60 x 10, 120 x 20, 240 x 40 (both second order)."""
    with pytest.raises(ValueError, match="n_theta = 12 .* n_theta >= 18"):
        fvm_reynolds(B, S, 12, 4, "jfo", grooves=(Groove(angle=np.pi / 2, width=0.35),))
    fv = fvm_reynolds(B, S, 120, 20, "jfo", grooves=G)
    fe = solve_reynolds(B, S, 120, 20, cavitation="jfo", grooves=G)
    assert np.hypot(*fv.force) > 0.0
    assert np.hypot(*np.subtract(fv.force, fe.force)) < 0.01 * np.hypot(*fe.force)


@pytest.mark.parametrize("cavitation, options", [
    ("reynolds", {}), ("gumbel", dict(grooves=G)), ("jfo", dict(ambient_pressure=1e5)),
    ("jfo", dict(grooves=G))])
def test_the_light_path_is_the_whole_film(cavitation, options):
    """fe_force (time integration's light path) gives the whole solve's force: the same
    route, the same discrete problem (1e-9: the solver's tolerance)."""
    light = fe_force(B, S, 24, 4, "P1", cavitation, **options)[0]
    whole = solve_reynolds(B, S, 24, 4, "P1", cavitation, **options).force_local
    assert np.allclose(light, whole, rtol=1e-9, atol=0.0)


def test_the_thermal_film_refuses_what_it_does_not_use():
    """tol with the JFO thermal film (its inner JFO films have no projected iteration), a
    start in the thermal equilibrium (it starts from its own isothermal position) and a
    model with no thermal film, are refused by name (rtol with a thermal film is a mesh
    search: tests/test_thd_accuracy.py)."""
    from bearingfem import coefficients, equilibrium
    with pytest.raises(ValueError, match="tol"):
        solve_reynolds(B, S, 24, 4, "P1", "jfo", grooves=G, lubricant=VG32, thermal=HOT,
                       tol=1e-9)
    with pytest.raises(ValueError, match="start: not taken with thermal="):
        equilibrium(B, (0.0, -20.0), 250.0, "fem", grooves=G, lubricant=VG32, thermal=HOT,
                    start=(0.5, 0.5))
    with pytest.raises(ValueError, match="model 'fem'"):
        coefficients(B, S, "short", grooves=G, lubricant=VG32, thermal=HOT)


def test_rtol_takes_no_start_and_no_mesh():
    """With rtol the mesh is the search's: a start solution cannot fit it, and a mesh given
    beside it would be replaced unseen; both are refused by name before any work (the
    mesh was silently dropped before: n_theta=4, n_z=1 solved to rtol)."""
    with pytest.raises(ValueError, match="start"):
        solve_reynolds(B, S, lubricant=OIL, start=object(), rtol=1e-2)
    for call, mesh, named in [(solve_reynolds, (4, 1), "n_theta and n_z"),
                              (solve_reynolds, (48,), "n_theta is"),
                              (fvm_reynolds, (48, 8), "n_theta and n_z")]:
        with pytest.raises(ValueError, match=f"{named}.*not taken with rtol"):
            call(B, S, *mesh, cavitation="gumbel", rtol=2e-2)
    with pytest.raises(ValueError, match="n_z is not taken with rtol"):
        solve_reynolds(B, S, n_z=8, cavitation="gumbel", rtol=2e-2)
    # the element is kept: the search stays on it
    sol = solve_reynolds(B, S, element="P1", cavitation="gumbel", rtol=2e-2)
    assert sol.accuracy.element == "P1" and sol.force_error <= 2e-2


def test_the_finite_volume_search_does_not_start_from_the_fe_films_memo():
    """The accuracy memo is keyed by the discretisation: an FV search after an FE P1 search
    of the same film starts afresh (the FE mesh says nothing of the FV grid's error)."""
    from bearingfem import fvm_reynolds
    from bearingfem.accuracy import clear_memo
    clear_memo()
    solve_reynolds(B, S, element="P1", cavitation="gumbel", rtol=1e-2)
    assert not fvm_reynolds(B, S, cavitation="gumbel", rtol=1e-2).accuracy.memo
