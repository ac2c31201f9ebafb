"""The finite-volume film (bearingfem.fv.fvm): a mutant of the JFO supply line's face
conductance survived the FE-vs-FV, manufactured and JFO tests (docs/mutation.md)."""
import numpy as np
import pytest

from bearingfem import JournalState, fvm_reynolds
from conftest import table1_bearing


@pytest.mark.parametrize("supply_film_angle", [0.0, 0.5 * np.pi])
def test_jfo_supply_line_without_a_cavity_is_the_full_film_raised_by_the_ambient(
        supply_film_angle):
    """At an ambient pressure (40 bar) above the full film's suction (-21 bar here) the JFO
    film never cavitates: it is the full (Reynolds, "none") film on the same cells with
    every pressure raised by the ambient (a constant solves the source-free equation), and
    its force is the full film's (sum of cos, sin over a whole turn of cells is zero). The
    two routes build the supply line's faces separately; measured 4e-15. Fails with the
    JFO supply faces' conductance 2 H^3 dzeta/dtheta written 2 dzeta/(H^3 dtheta)
    (fvm.py:229). The line at film angle 0 and pi / 2: the friction's ghost columns
    beside the line mirror the JFO film's ambient, not 0 (planted: friction 2.4 % off at
    pi / 2, yet exact at 0, where the gap is even about the line and the two edge
    columns' errors cancel; measured 5.6e-16)."""
    b = table1_bearing(1.0)
    s = JournalState(0.6, 0.0, 0.3, 0.0, 250.0)
    pa, supply = 4e6, s.gamma + np.pi + supply_film_angle
    jfo = fvm_reynolds(b, s, 48, 8, "jfo", supply_angle=supply, ambient_pressure=pa)
    full = fvm_reynolds(b, s, 48, 8, "none", supply_angle=supply)
    assert full.pressure.min() + pa > 0.0          # the case has no cavity
    scale = np.abs(full.pressure).max()
    assert np.abs(jfo.pressure - (full.pressure + pa)).max() < 1e-12 * scale
    assert np.linalg.norm(np.subtract(jfo.force_local, full.force_local)) < 1e-12 * np.linalg.norm(
        full.force_local)
    assert jfo.friction_force == pytest.approx(full.friction_force, rel=1e-12)
