import numpy as np
import pytest

from bearingfem.bearing import seed_bearing as table1_bearing  # noqa: F401 (the tests' name)


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
