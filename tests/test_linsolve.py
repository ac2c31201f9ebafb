"""Factorisation reuse: CG preconditioned by old factors gives the direct answer, and a
warm-started film solve is the cold one (the warm start changes the cost, not the result)."""
import numpy as np
import pytest

from bearingfem import JournalState
from bearingfem.solvers.cavitation import active_set
from bearingfem.solvers.linsolve import factorise, pcg, solve_spd
from bearingfem.fe.kernel import fe_operator, fe_pressure
from bearingfem.routes import fe_force
from conftest import table1_bearing


def _system(eps, n_theta=96, n_z=16):
    s = JournalState(eps, 3.0, 0.0, 0.0, 250.0)
    op = fe_operator(table1_bearing(1.0), s, n_theta, n_z)
    return op, s, op.free_stiffness(eps), op.load(eps, 3.0, 250.0)[op.mesh.free]


def test_pcg_with_exact_factors_takes_one_step():
    _, _, K, b = _system(0.7)
    x, ok, it = pcg(K, b, np.zeros_like(b), factorise(K).solve)
    assert ok and it == 1
    assert np.allclose(K @ x, b, rtol=0, atol=1e-11 * np.abs(b).max())


def test_stale_factors_precondition_a_nearby_matrix():
    _, _, K0, _ = _system(0.70)
    _, _, K1, b = _system(0.71)
    x, factor, fresh = solve_spd(K1, b, factorise(K0))
    assert not fresh                                        # CG sufficed
    assert np.max(np.abs(x - factorise(K1).solve(b))) < 1e-10 * np.abs(x).max()


def test_unrelated_factors_fall_back_to_factorising():
    _, _, K0, _ = _system(0.05)
    _, _, K1, b = _system(0.97)
    x, _, fresh = solve_spd(K1, b, factorise(K0), max_iter=3)
    assert fresh
    assert np.allclose(x, factorise(K1).solve(b))
    # factors of another size are ignored, not misused
    _, _, K2, _ = _system(0.97, 48, 8)
    assert solve_spd(K1, b, factorise(K2))[2]


@pytest.mark.parametrize("step", [1e-4, 1e-2, 0.2])
def test_warm_active_set_matches_cold(step):
    op, s, K, b = _system(0.8)
    prev = fe_pressure(op, JournalState(0.8 - step, 3.0, 0.0, 0.0, 250.0), "reynolds")
    cold = active_set(K, b)
    warm = active_set(K, b, active0=prev.active[op.mesh.free], factor=prev.factor)
    assert warm.converged
    assert np.max(np.abs(warm.pressure - cold.pressure)) < 1e-9 * cold.pressure.max()
    if step <= 1e-2:
        assert warm.factorisations == 0 and warm.iterations <= 2


@pytest.mark.parametrize("cavitation", ["gumbel", "reynolds"])
def test_warm_fe_force_matches_cold_along_a_path(cavitation):
    b = table1_bearing(0.5)
    warm = None
    for t in np.linspace(0.0, 1.0, 12):
        s = JournalState(0.3 + 0.6 * t, 20.0 * np.cos(7 * t), 0.0, 5.0, 250.0)
        f_warm, warm = fe_force(b, s, 96, 12, cavitation=cavitation, warm=warm)
        f_cold, _ = fe_force(b, s, 96, 12, cavitation=cavitation)
        assert np.allclose(f_warm, f_cold, rtol=1e-9, atol=0)


def test_quadrature_interpolation_matches_the_basis():
    for element in ("P1", "P2"):
        op = fe_operator(table1_bearing(0.5), JournalState(0.5), 24, 6, element)
        P = np.cos(op.mesh.theta) * (1.0 + op.mesh.zeta ** 2)
        assert np.allclose(op.at_quadrature(P), np.asarray(op.mesh.basis.interpolate(P)),
                           rtol=0, atol=1e-14)
