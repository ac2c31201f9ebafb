"""Film mesh: boundary dof counts (the scikit-fem periodic get_dofs pitfall) and geometry."""
import numpy as np
import pytest
from skfem import Functional

from bearingfem.fe.mesh import film_mesh


@Functional
def _cos2(w):
    return np.cos(w.x[0]) ** 2


@pytest.mark.parametrize("element,per_cell", [("P1", 1), ("P2", 2)])
@pytest.mark.parametrize("half", [True, False])
def test_periodic_end_dofs_count(element, per_cell, half):
    n_theta = 12
    m = film_mesh(n_theta, 6, element, 0.5, None, half)
    ends = 1 if half else 2
    # One row of dofs per end, each of n_theta * per_cell distinct dofs (seam counted once).
    assert len(m.end) == ends * n_theta * per_cell
    assert len(m.fixed) == len(m.end)
    assert len(m.free) + len(m.fixed) == m.ndofs


@pytest.mark.parametrize("element,per_cell", [("P1", 1), ("P2", 2)])
def test_supply_line_dofs(element, per_cell):
    m = film_mesh(12, 6, element, 0.5, 0.3, True)
    n_z_half = 3
    supply = per_cell * n_z_half + 1   # dofs on one theta line
    assert len(m.end) == 12 * per_cell + 1
    assert len(m.fixed) == len(m.end) + 2 * supply - 2
    assert np.isclose(m.theta.min(), 0.3) and np.isclose(m.theta.max(), 0.3 + 2 * np.pi)


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_periodic_geometry_integrates_exactly(element):
    m = film_mesh(16, 4, element, 0.5, None, True)
    # Elements at the seam must keep their true coordinates: int cos^2 = pi * lam.
    assert _cos2.assemble(m.basis) == pytest.approx(np.pi * 0.5, rel=1e-12)
