"""The transient JFO film (JFOFilm, TransientJFO) on fields and with a tilted journal:
its steady limit, a tilting squeeze film, today's film at zero tilt."""
import numpy as np
import pytest

from bearingfem import Bearing, JournalState, solve_reynolds
from bearingfem.fe.jfo import JFOFilm
from bearingfem.fields import FilmFields
from bearingfem.transient import TransientJFO

B = Bearing(radius=0.01, length=0.01, clearance=20e-6, viscosity=0.0117)
S = JournalState(eps=0.6, gamma=0.3, omega=250.0)
AMBIENT = 2e4
TILT = (5e-4, 3e-4)
FIELDS = FilmFields(viscosity=lambda t, z: 1.0 + 0.3 * np.cos(t) * z,
                    density=lambda t, z: 1.0 + 0.1 * np.sin(t))


@pytest.mark.parametrize("kwargs", [dict(tilt=TILT), dict(fields=FIELDS)],
                         ids=["tilt", "fields"])
def test_transient_film_settles_on_the_steady_film(kwargs):
    """Backward Euler at a fixed journal state has the steady balance as its fixed point:
    steps of 0.01 ... 1000 s from a full film end on the steady JFO film of the same
    fields or tilt (cavitating: min fraction < 0.5) to round-off. Measured: the gap
    falls as 1/dt (6e-6 at 10 s, 6e-10 at 100 s) to 4e-15 at 1000 s. Fails with the
    transient's transport taken from the rigid cylinder (its content cancels at the fixed
    point: the squeeze test below sees it)."""
    steady = solve_reynolds(B, S, 48, 8, cavitation="jfo", ambient_pressure=AMBIENT,
                            **kwargs)
    film = JFOFilm(B, S, 48, 8, ambient_pressure=AMBIENT, **kwargs)
    for dt in [1e-2, 1e-1, 1.0, 10.0, 100.0, 1000.0]:
        sol = film.step(S, dt)
    assert np.max(np.abs(sol.pressure - steady.pressure)) <= 1e-12 * steady.pressure_max
    assert np.max(np.abs(sol.fraction - steady.fraction)) <= 1e-12
    assert np.min(steady.fraction) < 0.5
    assert np.allclose(sol.moment, steady.moment, rtol=1e-11, atol=0.0)


def test_tilting_squeeze_film_is_the_steady_squeeze():
    """A journal tilting at a constant rate (tilt a function of time, no spin) in a full
    film (ambient 1e6 Pa holds every node full): the gap is linear in time, so a
    backward-Euler step's change of content over dt is its exact rate and every step is
    the steady film with that tilt and tilt rate, to round-off (1e-10 of the peak
    pressure: pressure differences of ambient-sized numbers). Fails with the step's
    fields taken at the start of the step (then no squeeze at all), the tilt's content
    left out or the step's content taken from the rigid cylinder."""
    rate = np.array([0.4, -0.3])
    state = JournalState(eps=0.3, gamma=0.2)
    film = JFOFilm(B, state, 32, 8, ambient_pressure=1e6,
                   tilt=lambda t: tuple(rate * t), tilt_rate=lambda t: tuple(rate))
    for k in range(1, 4):
        sol = film.step(state, 1e-3)
        t = 1e-3 * k
        steady = solve_reynolds(B, state, 32, 8, cavitation="jfo", ambient_pressure=1e6,
                                tilt=tuple(rate * t), tilt_rate=tuple(rate))
        assert np.min(sol.fraction) == 1.0
        squeeze = np.max(np.abs(steady.pressure - 1e6))
        assert squeeze > 1e3                              # the squeeze is there
        assert np.max(np.abs(sol.pressure - steady.pressure)) <= 1e-10 * steady.pressure_max
        assert np.allclose(sol.moment, steady.moment, rtol=1e-8, atol=0.0)


def test_zero_tilt_transient_is_todays_film():
    """tilt=(0, 0), tilt_rate=(0, 0) given: the same film, bit for bit, on a moving
    journal (JFOFilm steps and TransientJFO forces and commits)."""
    states = [JournalState(eps=0.5 + 0.02 * k, eps_dot=2.0, gamma=0.1 * k, gamma_dot=100.0,
                           omega=250.0) for k in range(4)]
    a = JFOFilm(B, states[0], 48, 4, ambient_pressure=AMBIENT)
    b = JFOFilm(B, states[0], 48, 4, ambient_pressure=AMBIENT, tilt=(0.0, 0.0),
                tilt_rate=(0.0, 0.0))
    for s in states[1:]:
        sa, sb = a.step(s, 1e-3), b.step(s, 1e-3)
        assert sa.force == sb.force and np.array_equal(sa.fraction, sb.fraction)
    ta = TransientJFO(B, 48, 4, ambient_pressure=AMBIENT)
    tb = TransientJFO(B, 48, 4, ambient_pressure=AMBIENT, tilt=(0.0, 0.0))
    for k, s in enumerate(states):
        assert ta.force(s, 1e-3 * k) == tb.force(s, 1e-3 * k)
        ca, cb = ta.commit(s, 1e-3 * k), tb.commit(s, 1e-3 * k)
        assert (ca is None and cb is None) or ca.solution.force == cb.solution.force


def test_transient_jfo_on_a_tilted_journal():
    """TransientJFO with a tilt given as a function of the integrator's time: its film
    steps carry the moment, mirrored tilts give the same force and opposite moments
    (to 1e-10), and the tilt reaches the instant force the integrator sees. Fails with
    the tilt left out of the instant (then the tilted and aligned forces agree)."""
    def run(sign):
        f = TransientJFO(B, 48, 8, ambient_pressure=AMBIENT,
                         tilt=lambda t: (sign * 5e-4, sign * 3e-4 * (1.0 + t)))
        f.start(S, 0.0)
        step = f.commit(S, 2e-3)
        return f.force(S, 2e-3), step.solution
    fp, sp_ = run(1.0)
    fm, sm = run(-1.0)
    aligned = TransientJFO(B, 48, 8, ambient_pressure=AMBIENT)
    aligned.start(S, 0.0)
    aligned.commit(S, 2e-3)
    assert np.allclose(fp, fm, rtol=1e-10, atol=0.0)
    assert np.allclose(sp_.moment, -np.array(sm.moment), rtol=1e-10, atol=0.0)
    assert np.hypot(*sp_.moment) > 1e-4
    assert abs(fp[0] - aligned.force(S, 2e-3)[0]) > 1e-3 * abs(fp[0])


def test_transient_fields_bad_input():
    with pytest.raises(ValueError, match="fields"):
        JFOFilm(B, S, 24, 4, ambient_pressure=AMBIENT, fields=2.0)
    with pytest.raises(ValueError, match="tilt"):
        JFOFilm(B, S, 24, 4, ambient_pressure=AMBIENT, tilt=(1.0,))
