"""The bush's grid and the film's nodes (bearingfem.ehd.grid): the bilinear interpolation
and the frame shift the modal-state film uses."""
import numpy as np
import pytest

from bearingfem import JournalState
from bearingfem.ehd.grid import FrameShift, grid_interpolation, node_grid
from bearingfem.fe.assembly import fe_operator
from bearingfem.film import inertial_from_theta

from test_ehd_states import B


def test_grid_interpolation_is_bilinear_and_periodic():
    """Exact on a bilinear field, periodic in the angle (a point at 2 pi - h/2 mixes the
    last and the first columns). Fails with the wrap to the first column dropped."""
    n, nz, hw = 8, 2, 0.2
    a = np.array([0.1, 2 * np.pi - np.pi / 8, 3.0])
    z = np.array([-0.2, 0.05, 0.2])
    I = grid_interpolation(a, z, n, nz, hw)
    ga = np.repeat(2 * np.pi * np.arange(n) / n, nz + 1)
    gz = np.tile(np.linspace(-hw, hw, nz + 1), n)
    f = lambda al, ze: 1.0 + 2.0 * ze          # bilinear, periodic trivially
    assert np.allclose(I @ f(ga, gz), f(a, z))
    col = np.cos(ga)                           # at 2 pi - h/2: the mean of cos(2 pi - h), cos 0
    assert np.isclose((I @ col)[1], 0.5 * (np.cos(2 * np.pi - np.pi / 4) + 1.0))


@pytest.mark.parametrize("gamma", [0.0, 0.3, -2.0, 2 * np.pi / 12 - np.pi, 5.9])
def test_frame_shift_is_the_grid_interpolation_at_the_nodes(gamma):
    """The film's shift between the bush's grid and its nodes (two blended rolls) against
    the bilinear grid interpolation evaluated at the nodes' inertial angles, to round-off,
    one angle on a whole cell (-pi + h); its to_grid is that matrix's transpose. Fails
    with the shift's blend weights swapped or the shift one cell off."""
    n, nz = 12, 3
    op = fe_operator(B, JournalState(0.5, gamma=gamma), n, nz, "P1", None, False)
    m = op.mesh
    hw = B.length / (2 * B.radius)
    I = grid_interpolation(inertial_from_theta(m.theta, gamma), m.zeta, n, nz, hw).toarray()
    shift = FrameShift(node_grid(m), gamma)
    G = np.random.default_rng(1).standard_normal((n * (nz + 1), 3))
    assert np.allclose(shift.to_nodes(G), I @ G, rtol=0, atol=1e-13)
    F = np.random.default_rng(2).standard_normal(m.theta.size)
    assert np.allclose(shift.to_grid(F), I.T @ F, rtol=0, atol=1e-13)
