"""What a user sees of an elastic film: the bush's deflection in files and pictures, and
the solid bush's whole field from a film solution."""
import numpy as np
import pytest

from bearingfem import ElasticBush, JournalState, solve_reynolds
from bearingfem.bearing import seed_bearing
from bearingfem.elastic.field import bush_field, film_grid_pressure
from bearingfem.outputs.export import to_meshio
from bearingfem.outputs.render import film_map, render_film

SEED = seed_bearing(0.2)
RING = ElasticBush(model="ring", outer_radius=0.016, modulus=110e9, poisson=0.34)
HEAVY = JournalState(eps=0.995, omega=250.0)


@pytest.fixture(scope="module")
def ehd():
    return solve_reynolds(SEED, HEAVY, 24, 4, bush=RING)


def test_deflection_is_exported_and_mapped(ehd):
    """The VTU point data carry the nodal deflection [m] as solved, and the map drawn by
    render_film(field="deformation") holds it in um at the same places (its largest value
    the solution's). Fails if the deflection is not exported or scaled to um twice."""
    m = to_meshio(ehd)
    assert np.array_equal(m.point_data["deformation [m]"], ehd.deformation)
    _, vals = film_map(ehd, "deformation")
    assert np.isclose(vals.max(), 1e6 * ehd.deformation.max(), rtol=1e-12)


def test_render_deformation_writes_pictures(ehd, tmp_path):
    """Both surfaces are drawn (a PNG each); a rigid film is refused with a ValueError
    naming the field. Fails when "deformation" is not a known field."""
    for surface in ("unwrapped", "journal"):
        path = tmp_path / f"w_{surface}.png"
        render_film(ehd, path, field="deformation", surface=surface)
        assert path.stat().st_size > 10_000
    rigid = solve_reynolds(SEED, JournalState(eps=0.6, omega=250.0), 24, 4)
    with pytest.raises(ValueError, match="deformation"):
        render_film(rigid, tmp_path / "x.png", field="deformation", surface="unwrapped")


def test_bush_field_takes_a_film_solution(ehd):
    """bush_field(bush, sol) is bush_field(bush, R, L, p) with the film's nodal pressure on
    its grid; the grid holds every node's pressure once (its sum is the nodes'). The solid
    bush's largest deflection under the ring film's pressure lies within 15 % of the
    ring's (the solid is stiffer: its slices hold each other; 9.7 % measured). Fails with
    the grid's angle index shifted by one node (the sum holds; the field does not)."""
    radius, length, grid = film_grid_pressure(ehd)
    assert radius == SEED.radius and np.isclose(length, SEED.length, rtol=1e-12)
    assert np.isclose(grid.sum(), ehd.pressure.sum(), rtol=1e-12)
    k = np.rint((ehd.z / length + 0.5) * 4).astype(int)
    j = np.rint(np.mod(ehd.theta, 2 * np.pi) / (2 * np.pi / 24)).astype(int) % 24
    assert np.array_equal(grid[j, k], ehd.pressure)
    a = bush_field(RING, ehd)
    b = bush_field(RING, radius, length, grid)
    assert np.array_equal(a.deflection, b.deflection)
    assert abs(a.deflection.max() / ehd.deformation.max() - 1) < 0.15
    with pytest.raises(ValueError, match="film solution"):
        bush_field(RING, ehd, SEED.length)
