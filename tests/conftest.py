import os
import signal

import numpy as np
import pytest

from bearingfem.bearing import seed_bearing as table1_bearing  # noqa: F401 (the tests' name)
from mechanism.effects import FilmEffect


@pytest.fixture
def short_b():
    return table1_bearing(0.2)


@pytest.fixture
def long_b():
    return table1_bearing(2.0)


def rel(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return float(np.linalg.norm(a - b) / np.linalg.norm(b))


@pytest.fixture
def ctrl_c_at_film_force(monkeypatch):
    """A real Ctrl-C in a mechanism run: ``ctrl_c_at_film_force(n)`` makes the n-th film
    force evaluated from then on send SIGINT to this process (which the run's own handler
    catches, as a user's key press would be). Returns the count of film forces, so a test
    can check that the signal was sent at all (``count["n"] >= n``)."""
    def arm(n):
        count = {"n": 0}
        original = FilmEffect.force

        def force(self, kinematics):
            count["n"] += 1
            if count["n"] == n:
                os.kill(os.getpid(), signal.SIGINT)
            return original(self, kinematics)

        monkeypatch.setattr(FilmEffect, "force", force)
        return count
    return arm


# FE force tables are cached on disk: keep the suite's tables out of the user's cache.
import os as _os
import tempfile as _tempfile

_os.environ.setdefault("BEARINGFEM_CACHE", _tempfile.mkdtemp(prefix="bearingfem-tables-"))
