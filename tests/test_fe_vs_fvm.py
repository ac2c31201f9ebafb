"""Finite elements and finite volumes converge to the same film as meshes refine."""
import pytest

from bearingfem import JournalState, fvm_reynolds, solve_reynolds
from conftest import rel, table1_bearing

STATE = JournalState(0.6, 10.0, 0.0, 20.0, 250.0)


@pytest.mark.parametrize("cavitation", ["none", "gumbel", "reynolds"])
def test_fe_and_fvm_sequences_meet(cavitation):
    b = table1_bearing(1.0)
    ks = (1, 2, 4)
    fe = [solve_reynolds(b, STATE, 30 * k, 6 * k, "P2", cavitation).force_local for k in ks]
    fv = [fvm_reynolds(b, STATE, 30 * k, 6 * k, cavitation).force_local for k in ks]
    gaps = [rel(a, c) for a, c in zip(fe, fv)]
    # FV is second order: each halving divides the gap by ~4 (>= 3 allowing the free
    # boundary of the cavitated cases); at the finest level they agree to 0.5 %.
    assert gaps[1] < gaps[0] / 3 and gaps[2] < gaps[1] / 3, gaps
    assert gaps[-1] < 5e-3
    # and the FE sequence itself has settled well below that gap
    assert rel(fe[1], fe[2]) < gaps[-1]
