"""FE (Gumbel) against the closed forms in their limits, with the rates of the limits.

Mesh errors here are < 1e-4 relative (P2, tests below check it), far below the model errors
being measured, so the observed rates are those of the short/long approximations:
short: error ~ (L/D)^2; long: error ~ D/L.
"""
import numpy as np
import pytest

from bearingfem import (JournalState, long_bearing_exact_force, long_bearing_force,
                        short_bearing_exact_force, short_bearing_force, solve_reynolds)
from conftest import rel, table1_bearing

STEADY = JournalState(0.6, 0.0, 0.0, 0.0, 250.0)


def _fe(ld, state, n_theta, n_z, **kw):
    return solve_reynolds(table1_bearing(ld), state, n_theta, n_z, "P2", "gumbel", **kw).force_local


def test_short_limit_rate():
    lds = (0.25, 0.125, 0.0625)
    errs = [rel(_fe(ld, STEADY, 120, 8), short_bearing_force(table1_bearing(ld), STEADY))
            for ld in lds]
    # mesh error of the finest case is negligible against its model error
    fine = _fe(0.0625, STEADY, 240, 16)
    assert rel(_fe(0.0625, STEADY, 120, 8), fine) < 0.02 * errs[-1]
    rates = np.log2(np.array(errs[:-1]) / errs[1:])
    # asymptotic rate 2, approached from below as higher-order terms fade
    assert rates[0] < rates[1] and rates[-1] == pytest.approx(2.0, abs=0.1), (errs, rates)
    assert errs[-1] < 0.01


def test_long_limit_rate():
    lds = (2.0, 4.0, 8.0)
    errs = [rel(_fe(ld, STEADY, 120, int(8 * ld)), long_bearing_force(table1_bearing(ld), STEADY))
            for ld in lds]
    rates = np.log2(np.array(errs[:-1]) / errs[1:])
    assert np.all(np.abs(rates - 1.0) < 0.1), (errs, rates)


@pytest.mark.parametrize("eps_dot", [25.0, -25.0, 60.0])
def test_short_squeeze_follows_exact_quadrature_not_fixed_half_film(eps_dot):
    b = table1_bearing(0.0625)
    s = JournalState(0.5, eps_dot, 0.0, 0.0, 250.0)
    fe = _fe(0.0625, s, 240, 16)
    # Model error of the short approximation at this L/D is 0.76 % in steady state.
    assert rel(fe, short_bearing_exact_force(b, s)) < 0.01
    assert rel(fe, short_bearing_force(b, s)) > 0.1


@pytest.mark.parametrize("state", [JournalState(0.5, 25.0, 0.0, 0.0, 250.0),
                                   JournalState(0.5, -25.0, 0.0, 0.0, 250.0),
                                   JournalState(0.5, 30.0, 0.0, 0.0, 0.0)])
def test_long_squeeze_follows_exact_quadrature(state):
    """Eq. 10 holds p = 0 at the maximum film: with the supply line there the FE film
    approaches its exact quadrature at the long-bearing rate D/L; the closed form stalls."""
    lds = (4.0, 8.0)
    pi_line = state.gamma + np.pi
    exact = [rel(_fe(ld, state, 120, int(8 * ld), supply_angle=pi_line),
                 long_bearing_exact_force(table1_bearing(ld), state)) for ld in lds]
    closed = rel(_fe(8.0, state, 120, 64, supply_angle=pi_line),
                 long_bearing_force(table1_bearing(8.0), state))
    assert exact[0] / exact[1] == pytest.approx(2.0, abs=0.2)
    assert exact[1] < 0.11
    assert closed > 0.04
