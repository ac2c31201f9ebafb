"""The JFO complementarity solver (bearingfem.solvers.jfo): a mutant of the
Fischer-Burmeister fallback survived the JFO tests, none of which reaches the fallback
(docs/mutation.md)."""
import numpy as np

import bearingfem.solvers.jfo as sj
from bearingfem import JournalState, solve_reynolds
from bearingfem.bearing import seed_bearing


def test_fischer_burmeister_fallback_finds_the_active_set_film(monkeypatch):
    """The balance of a steady journal film (captured from a solve) by the fallback alone
    (no active-set iteration allowed) against the active set's answer: a second method on
    the same complementarity problem, equal to its tolerance (measured 3e-15 of max P).
    The pressure is rescaled (K times 1000) so that the fallback's pressure scale s is
    far from 1, where P/s and P*s would coincide. Fails with the FB residual's scaling P/s written P*s
    (solvers/jfo.py:167)."""
    systems = []
    real = sj.jfo_solve

    def capture(K, A, b, **kw):
        systems.append((K, A, b))
        return real(K, A, b, **kw)
    monkeypatch.setattr(sj, "jfo_solve", capture)
    s = JournalState(0.6, 0.0, 0.3, 0.0, 250.0)
    solve_reynolds(seed_bearing(1.0), s, 24, 4, "P1", "jfo", ambient_pressure=1e5)
    K, A, b = systems[-1]
    K = 1e3 * K          # pressure in other units: the FB scale s moves off 1 (s -> s/1000)
    ref = real(K, A, b)
    fb = real(K, A, b, max_iter=0, warm_iterations=0)
    assert ref.cavitated.any() and not ref.cavitated.all()     # a real front
    assert np.abs(fb.pressure - ref.pressure).max() < 1e-9 * ref.pressure.max()
    assert np.abs(fb.fraction - ref.fraction).max() < 1e-9
