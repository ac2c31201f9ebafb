"""The FE Reynolds film (bearingfem.fe.kernel): a mutant of the film at rest survived the
manufactured, FE-vs-FV and cavitation tests (docs/mutation.md)."""
import numpy as np
import pytest

from bearingfem import JournalState, fvm_reynolds, solve_reynolds
from bearingfem.routes import fe_force
from conftest import table1_bearing

B = table1_bearing(1.0)


@pytest.mark.parametrize("cavitation", ["none", "reynolds"])
def test_a_journal_at_rest_carries_no_film_pressure(cavitation):
    """No rotation, no whirl, no squeeze: the Reynolds equation has no source, so the film
    is ambient everywhere and carries no force, whatever the eccentricity (an exact limit),
    and with omega = 0 there is no shear either. FE and FV alike. Fails
    with the source-free shortcut's result negated (reynolds.py:64)."""
    rest = JournalState(0.7, 0.0, 0.3, 0.0, 0.0)
    for sol in (solve_reynolds(B, rest, 48, 8, "P1", cavitation),
                fvm_reynolds(B, rest, 48, 8, cavitation)):
        assert np.all(sol.pressure == 0.0)
        assert sol.force == (0.0, 0.0) and sol.friction_force == 0.0
        assert sol.iterations == 0          # nothing to solve: no solve was made


@pytest.mark.parametrize("cavitation", ["none", "gumbel", "reynolds"])
def test_light_force_path_is_the_full_solve(cavitation):
    """``fe_force``, the light path of time integration, against ``solve_reynolds`` (whose
    forces the closed-form and FE-vs-FV tests check) on the same mesh and state (squeezing
    and whirling): the same discrete film, so equal to round-off (measured exactly equal).
    Fails with the light path's force scale divided in (reynolds.py:120)."""
    b = table1_bearing(0.5)
    s = JournalState(0.6, 2.0, 0.3, 1.0, 250.0)
    light, _ = fe_force(b, s, 48, 8, cavitation=cavitation)
    full = solve_reynolds(b, s, 48, 8, "P1", cavitation).force_local
    assert light == pytest.approx(full, rel=1e-12)


def test_reynolds_condition_friction_fe_meets_fv():
    """Friction of the Reynolds-condition film (Couette shear of a full oil film over the
    cavity, cavitated_shear="full") against the finite volumes' midpoint sums: the gap
    closes at second order, 0.42 / 0.11 / 0.027 % at 48 / 96 / 192 cells around, hence
    0.3 % at 96; leaving the cavity's shear out moves FE by 31 %. Fails with the cavity's
    Couette share doubled (reynolds.py:273)."""
    s = JournalState(0.6, 0.0, 0.0, 0.0, 250.0)
    fe = solve_reynolds(B, s, 96, 16, "P1", "reynolds").friction_force
    fv = fvm_reynolds(B, s, 96, 16, "reynolds").friction_force
    assert fe == pytest.approx(fv, rel=3e-3)
