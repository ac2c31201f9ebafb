"""The JFO complementarity solver's linear algebra: low-rank set changes, free blocks."""
import numpy as np
import pytest

from bearingfem import JournalState
from bearingfem.bearing import seed_bearing


@pytest.fixture(scope="module")
def seed():
    return seed_bearing(1.0)


def test_set_changes_solved_by_low_rank_correction_equal_a_new_factorisation(seed):
    """A set a few volumes away from the factorised one is solved by the Woodbury
    correction of the old factors: same solution as factorising its own matrix, no new
    factorisation; beyond BORDERED_MAX_CHANGES volumes it factorises again."""
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla
    from bearingfem.fe.jfo_balance import transport, film_volumes
    from bearingfem.solvers.blocksolve import BORDERED_MAX_CHANGES
    from bearingfem.solvers.jfo import SetSolver, set_matrix
    from bearingfem.solvers.linsolve import principal_block
    from bearingfem.fe.assembly import fe_operator
    state = JournalState(eps=0.6, omega=250.0)
    op = fe_operator(seed, state, 48, 8, "P1", None, True, ())
    free = op.mesh.free
    K = op.free_stiffness(state.eps)          # CSR, as the balance gives them
    A = (principal_block(transport(film_volumes(op.mesh), state.eps, state.wedge_speed),
                         free) + 0.3 * sp.eye(len(free))).tocsr()
    rng = np.random.default_rng(1)
    rhs = rng.standard_normal(len(free))
    base = rng.random(len(free)) < 0.4
    sets = SetSolver(K, A)
    sets.solve(base, rhs)
    for k in (1, 5, BORDERED_MAX_CHANGES):
        cav = base.copy()
        cav[rng.choice(len(free), k, replace=False)] ^= True
        x = sets.solve(cav, rhs)
        exact = spla.spsolve(set_matrix(sets.K, sets.A, cav), rhs)
        assert np.max(np.abs(x - exact)) < 1e-10 * np.max(np.abs(exact))
    assert sets.factorisations == 1
    cav = base.copy()
    cav[:BORDERED_MAX_CHANGES + 1] ^= True
    sets.solve(cav, rhs)
    assert sets.factorisations == 2


def test_principal_block_is_the_submatrix():
    import scipy.sparse as sp
    from bearingfem.solvers.linsolve import principal_block
    M = sp.random(40, 40, density=0.2, random_state=3, format="csr")
    rows = np.flatnonzero(np.random.default_rng(3).random(40) < 0.6)
    want = M.toarray()[np.ix_(rows, rows)]
    np.testing.assert_array_equal(principal_block(M, rows).toarray(), want)
    mask = np.zeros(40, bool)
    mask[rows] = True
    np.testing.assert_array_equal(principal_block(M.tocsc(), mask).toarray(), want)


def test_balance_is_refined_to_round_off(seed):
    """A short time step's storage (~1/dt) dominates the balance's right-hand side, so the
    flows' balance is its small difference: the converged set is refined once on the same
    factors, leaving a residual at round-off of |b| (without: ~6e-14 here, which in a
    1e-7 s film step of the long seed bearing is 3e-7 of the throughput)."""
    import scipy.sparse as sp
    from bearingfem.fe.assembly import fe_operator
    from bearingfem.fe.jfo_balance import transport, film_volumes
    from bearingfem.solvers.jfo import jfo_solve
    from bearingfem.solvers.linsolve import principal_block
    state = JournalState(eps=0.6, omega=250.0)
    op = fe_operator(seed, state, 48, 8, "P1", None, True, ())
    free = op.mesh.free
    T = principal_block(transport(film_volumes(op.mesh), state.eps, state.wedge_speed),
                        free)
    rng = np.random.default_rng(2)
    n = len(free)
    worst = 0.0
    for storage in (1e2, 1e4, 1e6):
        A = (T + storage * sp.eye(n)).tocsr()
        phi_old = np.clip(1.2 - 0.5 * rng.random(n), 0, 1)
        b = storage * phi_old * (1 + 0.01 * rng.standard_normal(n))
        warm = phi_old < 1.0
        warm[rng.choice(n, 8, replace=False)] ^= True       # a few volumes off: Woodbury
        res = jfo_solve(op.free_stiffness(state.eps), A, b, cavitated0=warm)
        assert res.converged
        worst = max(worst, res.residual)
    assert worst < 1e-14
