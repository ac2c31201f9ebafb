"""The fade of a film step's change of force (bearingfem.transient) sampled inside the
fade, against the C1 cubic it must be.

The force the integrator sees after a routine film step is the instant film plus
left(x) x jump, x = (t - t_step) / fade. The documented contract (continuous, with
continuous slope, in time; the whole change taken one fade later) fixes left to the
Hermite cubic with left(0) = 1, left(1) = 0, left'(0) = left'(1) = 0, i.e.
1 - (3 x^2 - 2 x^3), and fade = max(film_step, dt of the step).
"""
import numpy as np

from bearingfem import JournalState
from bearingfem.bearing import seed_bearing
from bearingfem.transient import TransientJFO


def _stepped(film_step, dt):
    """A film settled at s0, then one routine film step at a moved, turned state s1."""
    b = seed_bearing(0.5)
    f = TransientJFO(b, n_theta=48, n_z=4, grooves=(), ambient_pressure=1e5,
                     film_step=film_step)
    s0 = JournalState(eps=0.6, omega=250.0)
    f.force(s0, 0.0)
    for k in range(1, 21):
        f.commit(s0, k * dt)
    s1 = JournalState(eps=0.6, omega=250.0, eps_dot=-20.0, gamma=0.1, gamma_dot=50.0)
    t1 = 21 * dt
    assert not f.film.refilled(s1)
    assert f.commit(s1, t1) is not None
    return f, s1, t1


def _left(f, s1, t1, ts):
    """The fraction of the step's change of force still to come at times ts."""
    settled = np.array(f.film.instant(s1)[0])
    jump = np.array(f.force(s1, t1)) - settled
    assert np.linalg.norm(jump) > 0.05 * np.linalg.norm(settled)
    return np.array([np.dot(np.array(f.force(s1, t)) - settled, jump) / np.dot(jump, jump)
                     for t in ts])


def test_fade_is_the_c1_cubic_over_the_step():
    """Inside the fade (dt = 2e-4 s > film_step = 1e-4 s, so fade = dt) the remaining
    fraction is 1 - 3x^2 + 2x^3 to 1e-9, with zero slope at both ends (one-sided
    differences at h = 1e-3 fade: slope < 1e-2). Fails with a linear fade (0.094 off at
    x = 0.25), with the fade over film_step instead of the step (0 left at
    x = 0.5) and with any other length (the interior samples move)."""
    dt = 2e-4
    f, s1, t1 = _stepped(film_step=1e-4, dt=dt)
    x = np.array([0.1, 0.25, 0.5, 0.75, 0.9, 1.0, 1.5])
    exact = np.where(x < 1.0, 1.0 - (3.0 * x ** 2 - 2.0 * x ** 3), 0.0)
    np.testing.assert_allclose(_left(f, s1, t1, t1 + x * dt), exact, rtol=0, atol=1e-9)
    h = 1e-3
    ends = _left(f, s1, t1, t1 + np.array([0.0, h, 1.0 - h, 1.0]) * dt)
    assert abs(ends[1] - ends[0]) / h < 1e-2 and abs(ends[3] - ends[2]) / h < 1e-2


def test_force_is_continuous_across_a_film_step():
    """The force the integrator sees at (s1, t1) is the same just before and just after
    the film step taken there (to 1e-9 of the force), while that step changed the settled
    film by > 5 %. Fails with the jump's sign flipped in the fade (faded_force adding
    -left * jump: the force then jumps by twice the step's change)."""
    dt = 2e-4
    b = seed_bearing(0.5)
    f = TransientJFO(b, n_theta=48, n_z=4, grooves=(), ambient_pressure=1e5, film_step=1e-4)
    s0 = JournalState(eps=0.6, omega=250.0)
    f.force(s0, 0.0)
    for k in range(1, 21):
        f.commit(s0, k * dt)
    s1 = JournalState(eps=0.6, omega=250.0, eps_dot=-20.0, gamma=0.1, gamma_dot=50.0)
    t1 = 21 * dt
    before = np.array(f.force(s1, t1))
    assert f.commit(s1, t1) is not None
    after = np.array(f.force(s1, t1))
    settled = np.array(f.film.instant(s1)[0])
    assert np.linalg.norm(after - settled) > 0.05 * np.linalg.norm(settled)
    np.testing.assert_allclose(after, before, rtol=0, atol=1e-9 * np.linalg.norm(before))
