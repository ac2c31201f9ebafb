"""The FE JFO film (bearingfem.fe.jfo): mutants of the transient film's step cut and of its
starting fraction's refusal survived the JFO tests (docs/mutation.md)."""
import numpy as np
import pytest

from bearingfem import JournalState
from bearingfem.bearing import seed_bearing
from bearingfem.errors import ConvergenceError
from bearingfem.fe import jfo
from bearingfem.fe.jfo import JFOFilm
from bearingfem.fe.jfo_balance import _between

B = seed_bearing(1.0)
S0 = JournalState(0.5, 0.0, 0.3, 0.0, 250.0)
S1 = JournalState(0.6, 20.0, 0.3, 0.0, 250.0)
DT = 1e-3


def test_cut_journal_step_is_two_half_steps(monkeypatch):
    """A journal step whose first solve fails is cut in two (substeps = 2): its film is the
    one two explicit half steps give, the first to the state halfway, to round-off.
    Fails with the second half taking the whole step (jfo.py:302)."""
    film, ref = (JFOFilm(B, S0, 48, 4, ambient_pressure=1e5) for _ in range(2))
    real, calls = jfo._step_balance, []

    def fails_once(*args, **kw):
        calls.append(1)
        if len(calls) == 1:
            raise ConvergenceError("test balance", 1, 1.0)
        return real(*args, **kw)
    monkeypatch.setattr(jfo, "_step_balance", fails_once)
    s = film.step(S1, DT)
    monkeypatch.setattr(jfo, "_step_balance", real)
    ref.step(_between(S0, S1), 0.5 * DT)
    r = ref.step(S1, 0.5 * DT)
    assert film.substeps == 2 and film.time == pytest.approx(DT, rel=1e-14)
    assert np.allclose(s.pressure, r.pressure, rtol=1e-12, atol=1e-9 * r.pressure.max())
    assert np.allclose(film.fraction, ref.fraction, rtol=0, atol=1e-12)


def test_a_partly_filled_start_is_accepted_and_bad_fractions_refused():
    """A film may start partly filled (0 <= phi <= 1: 0.5 here, kept as given), not outside
    [0, 1]. Fails with the lower bound of the check raised to 1 (jfo.py:176)."""
    film = JFOFilm(B, S0, 48, 4, ambient_pressure=1e5, fraction=0.5)
    assert np.all(film.fraction == 0.5)
    for bad in (-0.1, 1.1):
        with pytest.raises(ValueError, match="fraction"):
            JFOFilm(B, S0, 48, 4, ambient_pressure=1e5, fraction=bad)
