"""Inactive-block solves: every route gives the reduced system's answer."""
import numpy as np
import pytest
import scipy.sparse as sp

from bearingfem import JournalState
from bearingfem.solvers.blocksolve import (BORDERED_MAX_CHANGES, _dense_rows, bordered_solve,
                                   dense_block_solve, pinned)
from bearingfem.solvers.cavitation import active_set
from bearingfem.solvers.linsolve import factorise
from bearingfem.fe.multilevel import coarse_guess
from bearingfem.fe.kernel import fe_operator, fe_pressure
from conftest import table1_bearing


def _film(eps=0.8, n_theta=96, n_z=16):
    s = JournalState(eps, 5.0, 0.0, 0.0, 250.0)
    op = fe_operator(table1_bearing(1.0), s, n_theta, n_z)
    free = op.mesh.free
    return op, s, op.free_stiffness(eps), op.load(s.eps, s.eps_dot, s.wedge_speed)[free]


def _reduced(K, b, inactive):
    """The reference: solve K_II x_I = b_I on the inactive dofs only."""
    i = np.flatnonzero(inactive)
    x = np.zeros(len(b))
    x[i] = factorise(K[i][:, i]).solve(b[i])
    return x


def test_pinned_matrix_solve_is_the_reduced_solve():
    _, _, K, b = _film()
    inactive = np.random.default_rng(0).random(len(b)) < 0.6
    x = factorise(pinned(K, inactive)).solve(np.where(inactive, b, 0.0))
    np.testing.assert_allclose(x, _reduced(K, b, inactive), rtol=0, atol=1e-12 * np.abs(x).max())


@pytest.mark.parametrize("left, joined", [(0, 0), (5, 0), (0, 7), (6, 9), (12, 8)])
def test_bordered_solve_is_exact(left, joined):
    op, s, K, b = _film()
    inactive0 = ~fe_pressure(op, s, "reynolds").active[op.mesh.free]
    rng = np.random.default_rng(left + 10 * joined)
    inactive = inactive0.copy()
    inactive[rng.choice(np.flatnonzero(inactive0), left, replace=False)] = False
    inactive[rng.choice(np.flatnonzero(~inactive0), joined, replace=False)] = True
    factor = factorise(pinned(K, inactive0))
    x = bordered_solve(factor, K, b, inactive0, inactive)
    ref = _reduced(K, b, inactive)
    assert np.all(x[~inactive] == 0.0)
    np.testing.assert_allclose(x, ref, rtol=0, atol=1e-10 * np.abs(ref).max())


def test_dense_block_solve_and_dense_rows():
    _, _, K, b = _film(0.6, 16, 4)
    inactive = np.arange(len(b)) % 3 != 0
    np.testing.assert_allclose(dense_block_solve(K.toarray(), b, inactive),
                               _reduced(K, b, inactive), atol=1e-12 * np.abs(b).max())
    A = sp.random(40, 30, 0.2, format="csr", random_state=1)
    for rows in (np.array([3, 7, 7, 39]), np.array([], int), np.arange(40)):
        assert np.array_equal(_dense_rows(A, rows), A[rows].toarray())


@pytest.mark.parametrize("eps", [0.3, 0.8, 0.97])
def test_nested_start_needs_one_factorisation(eps):
    """From the coarse levels' guess the fine set is a few dofs off: the first set's
    factors, with bordered solves for the rest, finish the job (deterministically)."""
    op, s, K, b = _film(eps, 240, 40)
    P0 = coarse_guess(op, s)
    nested = active_set(K, b, P0=P0)
    cold = active_set(K, b)
    assert nested.converged and cold.converged
    assert np.max(np.abs(nested.pressure - cold.pressure)) < 1e-9 * cold.pressure.max()
    assert nested.factorisations == 1 and nested.iterations <= 4
    first = P0 < (K @ np.maximum(P0, 0) - b) / K.diagonal()
    assert np.count_nonzero(first != cold.active) <= BORDERED_MAX_CHANGES


@pytest.mark.parametrize("left, joined", [(0, 0), (5, 0), (0, 7), (6, 9)])
def test_bordered_solve_of_several_columns_is_each_columns_reduced_solve(left, joined):
    """Several right-hand sides share one bordered solve (the grooved film's four partials):
    every column is its own reduced solve. Fails when a column is taken from the wrong slot
    (e.g. every column given the last one's answer, or the multipliers' correction applied
    to the first column only)."""
    op, s, K, b = _film()
    inactive0 = ~fe_pressure(op, s, "reynolds").active[op.mesh.free]
    rng = np.random.default_rng(3 + left + 10 * joined)
    inactive = inactive0.copy()
    inactive[rng.choice(np.flatnonzero(inactive0), left, replace=False)] = False
    inactive[rng.choice(np.flatnonzero(~inactive0), joined, replace=False)] = True
    factor = factorise(pinned(K, inactive0))
    B = np.column_stack([b, rng.standard_normal(len(b)), -2.0 * b, rng.random(len(b))])
    X = bordered_solve(factor, K, B, inactive0, inactive)
    assert X.shape == B.shape and np.all(X[~inactive] == 0.0)
    for j in range(B.shape[1]):
        ref = _reduced(K, B[:, j], inactive)
        np.testing.assert_allclose(X[:, j], ref, rtol=0, atol=1e-10 * np.abs(ref).max())
