"""Film solutions export to meshio formats and read back with their point data."""
import meshio
import numpy as np
import pytest

from bearingfem import JournalState, fvm_reynolds, solve_reynolds
from bearingfem.outputs.export import FIELD_NAMES, to_meshio, write_solution
from conftest import table1_bearing


@pytest.mark.parametrize("solve", [
    lambda b, s: solve_reynolds(b, s, 24, 4, "P1"),
    lambda b, s: solve_reynolds(b, s, 24, 4, "P2", half=False),
    lambda b, s: fvm_reynolds(b, s, 24, 4),
    lambda b, s: fvm_reynolds(b, s, 24, 4, supply_angle=1.0),
])
@pytest.mark.parametrize("suffix", [".vtu", ".xdmf"])
def test_roundtrip(tmp_path, solve, suffix):
    b = table1_bearing(0.5)
    sol = solve(b, JournalState(0.6, 0.0, 0.4, 0.0, 250.0))
    path = tmp_path / f"film{suffix}"
    write_solution(sol, path)
    back = meshio.read(path)
    m = to_meshio(sol)
    assert back.points.shape == m.points.shape
    np.testing.assert_allclose(back.point_data["pressure [Pa]"], m.point_data["pressure [Pa]"])
    # points sit on the journal surface of radius R, and the mirrored half covers +-L/2
    r = np.hypot(back.points[:, 0], back.points[:, 1])
    np.testing.assert_allclose(r, b.radius)
    assert back.points[:, 2].max() <= b.length / 2 + 1e-12
    assert back.points[:, 2].min() < 0
    # the pressure peak is where the solution says it is
    i = np.argmax(back.point_data["pressure [Pa]"])
    alpha = np.arctan2(back.points[i, 1], back.points[i, 0]) % (2 * np.pi)
    assert np.isclose(np.cos(alpha - sol.pressure_max_angle), 1.0, atol=1e-9)


def test_unwrapped_export_has_no_cell_across_the_seam():
    b = table1_bearing(0.5)
    for sol in (solve_reynolds(b, JournalState(0.6, omega=250.0), 24, 4, "P2"),
                fvm_reynolds(b, JournalState(0.6, omega=250.0), 24, 4)):
        m = to_meshio(sol, surface="unwrapped")
        x = m.points[m.cells[0].data][..., 0]
        assert (x.max(axis=1) - x.min(axis=1)).max() < 0.5 * np.pi * b.radius
        assert x.max() == pytest.approx(2 * np.pi * b.radius, rel=0.05)


@pytest.mark.parametrize("suffix", [".vtu", ".xdmf", ".vtk"])
def test_exported_fields_carry_their_si_units(tmp_path, suffix):
    # ParaView shows the point-data names: each quantity with its SI unit, read back as written
    b = table1_bearing(0.5)
    sol = solve_reynolds(b, JournalState(0.6, omega=250.0), 24, 4, "P1")
    path = tmp_path / f"film{suffix}"
    write_solution(sol, path, constants={"time [s]": 0.25})
    back = meshio.read(path)
    sep = "_" if suffix == ".vtk" else " "      # legacy VTK: no spaces in names
    names = {"pressure [Pa]", "film_thickness [m]", "theta [rad]", "z [m]", "time [s]"}
    assert set(back.point_data) == {n.replace(" ", sep) for n in names}
    np.testing.assert_allclose(back.point_data[f"film_thickness{sep}[m]"].min(), sol.film_min)
    np.testing.assert_allclose(back.point_data[f"time{sep}[s]"], 0.25)
    for surface in ("journal", "unwrapped"):
        assert set(to_meshio(sol, surface).point_data) == {FIELD_NAMES[k] for k in (
            "pressure", "film_thickness", "theta", "z")}
