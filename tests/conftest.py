import numpy as np
import pytest

from bearingfem import Bearing

#: The seed's Table 1 bearing (D = 20 mm, c = 20 um, mu = 0.0117 Pa s) at a given L/D.
def table1_bearing(ld: float) -> Bearing:
    return Bearing(radius=0.01, length=0.02 * ld, clearance=20e-6, viscosity=0.0117)


@pytest.fixture
def short_b():
    return table1_bearing(0.2)


@pytest.fixture
def long_b():
    return table1_bearing(2.0)


def rel(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return float(np.linalg.norm(a - b) / np.linalg.norm(b))


# FE force tables are cached on disk: keep the suite's tables out of the user's cache.
import os as _os
import tempfile as _tempfile

_os.environ.setdefault("BEARINGFEM_CACHE", _tempfile.mkdtemp(prefix="bearingfem-tables-"))
