"""The two complementarity solvers solve the same discrete problem."""
import numpy as np
import pytest

from bearingfem import JournalState, solve_reynolds, fvm_reynolds
from bearingfem.cavitation import graph_colouring
from bearingfem.assembly import film_operator
from conftest import rel, table1_bearing

STATES = [JournalState(0.6, 0.0, 0.0, 0.0, 250.0), JournalState(0.95, 0.0, 0.0, 0.0, 250.0),
          JournalState(0.4, -20.0, 0.0, 30.0, 250.0), JournalState(0.3, 40.0, 0.0, 0.0, 0.0)]


@pytest.mark.parametrize("state", STATES)
@pytest.mark.parametrize("element", ["P1", "P2"])
def test_psor_matches_active_set(state, element):
    b = table1_bearing(0.5)
    a = solve_reynolds(b, state, 60, 10, element, "reynolds", method="active-set", tol=1e-12)
    p = solve_reynolds(b, state, 60, 10, element, "reynolds", method="psor", tol=1e-12)
    assert a.converged and p.converged
    assert a.residual < 1e-9 and p.residual < 1e-9
    assert np.max(np.abs(a.pressure - p.pressure)) < 1e-8 * a.pressure_max
    assert rel(a.force_local, p.force_local) < 1e-8


def test_fvm_psor_matches_active_set():
    b = table1_bearing(1.0)
    s = JournalState(0.8, 5.0, 0.0, 0.0, 250.0)
    a = fvm_reynolds(b, s, 60, 10, "reynolds", tol=1e-12)
    p = fvm_reynolds(b, s, 60, 10, "reynolds", method="psor", tol=1e-12)
    assert np.max(np.abs(a.pressure - p.pressure)) < 1e-8 * a.pressure_max


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_colouring_is_proper(element):
    op = film_operator(24, 6, element, 0.5, None, True)
    K = op.free_stiffness(0.5).tocsr()
    colours = graph_colouring(K)
    colour = np.empty(K.shape[0], int)
    for c, idx in enumerate(colours):
        colour[idx] = c
    coo = K.tocoo()
    off = coo.row != coo.col
    assert np.all(colour[coo.row[off]] != colour[coo.col[off]])
    assert sum(len(c) for c in colours) == K.shape[0]


@pytest.mark.parametrize("state", STATES)
def test_reynolds_pressure_is_complementary(state):
    sol = solve_reynolds(table1_bearing(1.0), state, 60, 10, "P1", "reynolds")
    assert np.all(sol.pressure >= 0.0)
    assert sol.residual < 1e-9
    # Swift-Stieber carries more load than Gumbel's clipped full solution never less than 0
    g = solve_reynolds(table1_bearing(1.0), state, 60, 10, "P1", "gumbel")
    assert np.all(g.pressure >= 0.0)
