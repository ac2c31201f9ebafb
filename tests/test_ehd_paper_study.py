"""The EHD side-by-side study's own arithmetic (studies/ehd_paper.py): the friction power
of a film known only by its record, and its refusals."""
import types

import numpy as np
import pytest

from mechanism.result import FILM_COLUMNS
from studies.ehd_paper import record_friction_power, scenes


def test_record_friction_power_is_the_time_mean_over_uneven_steps():
    """A friction force rising linearly in time, sampled at uneven steps, at a constant
    relative speed: the mean power is F at mid-time times R omega, exactly (the trapezoid
    rule is exact for a linear integrand). Fails with a plain mean over the rows (the
    steps crowd at the start)."""
    t = np.array([0.0, 0.001, 0.002, 0.004, 0.01])
    rec = np.zeros((t.size, len(FILM_COLUMNS)))
    cols = list(FILM_COLUMNS)
    rec[:, cols.index("t")] = t
    rec[:, cols.index("friction_force")] = 2.0 + 300.0 * t
    omega, radius = 250.0, 0.01
    grid = np.linspace(0.0, 0.01, 11)
    r = types.SimpleNamespace(t=grid, rod_angle=-omega * grid)
    expected = (2.0 + 300.0 * 0.005) * radius * omega
    assert np.isclose(record_friction_power(r, rec, radius), expected, rtol=1e-12)


def test_an_unknown_coupling_is_named():
    with pytest.raises(ValueError, match="coupling"):
        scenes(0.01, 24, 4, coupling="tangent")
