"""The two complementarity solvers solve the same discrete problem."""
import numpy as np
import pytest

from bearingfem import JournalState, solve_reynolds, fvm_reynolds
from bearingfem.solvers.cavitation import graph_colouring
from bearingfem.fe.assembly import film_operator
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
    """The converged residual is the complementarity check (p >= 0 itself holds by the
    solver's clipping); Gumbel's film is the full film's pressure clipped at zero,
    checked against a second solve without cavitation."""
    sol = solve_reynolds(table1_bearing(1.0), state, 60, 10, "P1", "reynolds")
    assert sol.residual < 1e-9
    g = solve_reynolds(table1_bearing(1.0), state, 60, 10, "P1", "gumbel")
    full = solve_reynolds(table1_bearing(1.0), state, 60, 10, "P1", "none")
    np.testing.assert_allclose(g.pressure, np.maximum(full.pressure, 0.0), rtol=1e-12,
                               atol=1e-12 * np.abs(full.pressure).max())


@pytest.mark.parametrize("supply", [None, 0.0])
def test_nested_start_gives_the_cold_start_answer_in_fewer_iterations(supply):
    from bearingfem.solvers.cavitation import active_set
    from bearingfem.fe.kernel import fe_operator, fe_pressure
    b = table1_bearing(1.0)
    s = JournalState(0.9, 5.0, 0.0, 0.0, 250.0)
    op = fe_operator(b, s, 240, 40, "P1", supply)
    nested = fe_pressure(op, s, "reynolds")
    free = op.mesh.free
    K = op.free_stiffness(s.eps)
    cold = active_set(K, op.load(s.eps, s.eps_dot, s.wedge_speed)[free])
    assert np.max(np.abs(nested.pressure[free] - cold.pressure)) < 1e-9 * cold.pressure.max()
    assert nested.iterations <= 5 < cold.iterations


@pytest.mark.parametrize("periodic", [True, False])
def test_prolongation_is_exact_for_bilinear_data(periodic):
    from bearingfem.fe.mesh import film_mesh
    from bearingfem.fe.multilevel import prolongation
    coarse = film_mesh(16, 4, "P1", 0.5, None if periodic else 0.0, True)
    fine = film_mesh(64, 16, "P1", 0.5, None if periodic else 0.0, True)
    # cos(theta) is not bilinear, but 1 + zeta is, and a periodic hat is piecewise linear
    f = lambda th, ze: (1.0 + ze) * (2.0 + np.interp(np.mod(th, 2 * np.pi),
                                                      [0, np.pi, 2 * np.pi], [0.0, 1.0, 0.0]))
    interp = prolongation(coarse, fine.theta, fine.zeta)
    np.testing.assert_allclose(interp @ f(coarse.theta, coarse.zeta), f(fine.theta, fine.zeta),
                               atol=1e-12)
    # rows are partitions of unity, at most 4 entries: bilinear weights
    np.testing.assert_allclose(interp.sum(axis=1).A.ravel(), 1.0, atol=1e-14)
    assert np.diff(interp.indptr).max() <= 4 and interp.data.min() >= 0.0


@pytest.mark.parametrize("solve, element", [(solve_reynolds, "P1"), (solve_reynolds, "P2"),
                                            (fvm_reynolds, None)])
@pytest.mark.parametrize("cavitation", ["reynolds", "gumbel"])
@pytest.mark.parametrize("state", [JournalState(0.0, 0.0, 0.0, 0.0, 250.0),
                                   JournalState(0.0, 0.0, 0.0, 0.0, 0.0),
                                   JournalState(0.5, 0.0, 0.0, 125.0, 250.0)],
                         ids=["centred", "still", "no-wedge"])
def test_a_film_nothing_drives_has_no_cavity(solve, element, cavitation, state):
    """A centred spinning journal (eps 0), a still one, or a whirl at half speed (no wedge)
    has no pressure anywhere and no cavity: it was reported 100 % cavitated. The summary
    (what the command line prints) says the same; a loaded film keeps its cavity."""
    b = table1_bearing(1.0)
    args = (b, state, 48, 8) + ((element,) if element else ())
    sol = solve(*args, cavitation=cavitation)
    assert sol.pressure_max == 0.0 and sol.cavitated_fraction == 0.0
    assert "no pressure in the film" in sol.summary()
    assert "cavitated area 0.0 % of the film" in sol.summary()
    loaded = solve(b, JournalState(0.6, 0.0, 0.0, 0.0, 250.0), 48, 8,
                   *((element,) if element else ()), cavitation=cavitation)
    assert 0.3 < loaded.cavitated_fraction < 0.7
