"""Transient JFO journal films: settling, the content carried by the turning mesh,
convergence in the step along a load-reversing orbit."""
import numpy as np
import pytest

from bearingfem import Bearing, Groove, JournalState, solve_reynolds
from bearingfem.bearing import seed_bearing


@pytest.fixture(scope="module")
def seed():
    return seed_bearing(1.0)


def test_transient_journal_settles_on_the_steady_film(seed):
    """The transient film at a fixed state (grooves hold the mesh in the bearing) marches
    from a full film to the steady JFO film; every step balances to round-off."""
    from bearingfem.fe.jfo import JFOFilm
    s = JournalState(eps=0.6, omega=250.0, gamma=0.3)
    g = [Groove(angle=0.3 + np.pi, width=0.1, fraction=0.6)]
    steady = solve_reynolds(seed, s, 48, 8, cavitation="jfo", grooves=g)
    film = JFOFilm(seed, s, 48, 8, grooves=g)
    for _ in range(120):
        sol = film.step(s, 2 * np.pi / 250.0 / 10)
        assert abs(sol.mass_balance) <= 1e-10 * max(abs(sol.flow_in), abs(sol.side_leakage))
    assert np.allclose(sol.force_local, steady.force_local, rtol=1e-6)
    assert np.allclose(sol.fraction, steady.fraction, atol=1e-6)


def test_transient_content_stays_with_the_line_of_centres(seed):
    """A journal whirling at half the shaft speed (w = omega - 2 gamma_dot = 0) drags the
    oil around with its line of centres: in the mesh that follows it the content does not
    move. The rotating mesh carries the content by the turn of each step; without that the
    content would lag by the whole turn (here pi/2)."""
    from bearingfem.fe.jfo import JFOFilm
    omega = 200.0
    s0 = JournalState(eps=0.3, omega=omega, gamma_dot=omega / 2)
    film = JFOFilm(seed, s0, 64, 4, ambient_pressure=1e4, fraction=1.0)
    op = film._operator(s0)
    th = np.mod(op.mesh.theta, 2 * np.pi)
    phi0 = np.where((th > 2.0) & (th < 3.0), 0.5, 1.0)       # a band of thinner content
    film = JFOFilm(seed, s0, 64, 4, ambient_pressure=1e4, fraction=phi0)
    n, turn = 50, np.pi / 2
    for k in range(1, n + 1):
        gamma = turn * k / n
        film.step(JournalState(eps=0.3, omega=omega, gamma=gamma, gamma_dot=omega / 2),
                  turn / n / (omega / 2))
    lack = 1.0 - film.fraction
    centre = np.angle(np.sum(lack * np.exp(1j * th)))
    assert abs(centre - 2.5) < 2 * np.pi / 64      # within a cell of where it started


def test_whirling_full_film_carry_is_second_order_in_the_mesh(seed):
    """A full film whirling at constant eps: one backward-Euler step in which the mesh
    turns against the steady full film of that state (wedge speed omega - 2 gamma_dot).
    The step divides the error of the carry between the turned meshes by its dt: with a
    tiny step (1/1000 of a cell) that is all the gap, second order in the cell (measured
    9.9e-4, 2.4e-4, 6.9e-5 of the peak at 64, 128, 256 cells; a donor-cell carry gave
    0.134, 0.067, 0.0335 whatever the step); a step of half a cell adds backward Euler's
    first-order error in the step (0.067, 0.0335, 0.0168)."""
    from bearingfem.fe.jfo import JFOFilm
    gamma_dot, gaps = 60.0, {}
    for n in (64, 128):
        for cells in (0.5, 1e-3):
            s0 = JournalState(eps=0.5, omega=250.0, gamma=0.2, gamma_dot=gamma_dot)
            dt = cells * 2 * np.pi / n / gamma_dot
            s1 = JournalState(eps=0.5, omega=250.0, gamma=0.2 + gamma_dot * dt,
                              gamma_dot=gamma_dot)
            film = JFOFilm(seed, s0, n, 8, ambient_pressure=1e7)      # full everywhere
            step = film.step(s1, dt)
            steady = solve_reynolds(seed, s1, n, 8, cavitation="jfo", ambient_pressure=1e7)
            assert np.all(step.fraction == 1.0)
            gaps[n, cells] = (np.max(np.abs(step.pressure - steady.pressure))
                              / (steady.pressure.max() - 1e7))
    assert gaps[64, 1e-3] < 0.0015 and 3.5 < gaps[64, 1e-3] / gaps[128, 1e-3] < 4.5
    assert gaps[64, 0.5] < 0.07 and 1.9 < gaps[64, 0.5] / gaps[128, 0.5] < 2.1


def test_carry_moves_a_smooth_profile_to_third_order_and_a_step_without_overshoot(seed):
    """shift_rows on its own: cell averages of sin(theta) moved by 0.3 of a column land
    within 6.9e-6, 8.4e-7 of the exact averages at 64, 128 columns (third order per
    shift); a band of thinner content moves without new extrema; the sum is kept."""
    from bearingfem.fe.jfo import JFOFilm, film_volumes
    from bearingfem.fe.volumes import shift_rows
    errs = []
    for n in (64, 128):
        cv = film_volumes(JFOFilm(seed, JournalState(eps=0.5), n, 4,
                                  ambient_pressure=1e4)._operator(JournalState(eps=0.5)).mesh)
        avg = lambda d: (np.cos(cv.x_lo + d) - np.cos(cv.x_hi + d)) / (cv.x_hi - cv.x_lo)  # noqa
        errs.append(np.max(np.abs(shift_rows(cv, avg(0.0), 0.3) - avg(0.3 * 2 * np.pi / n))))
        band = np.where((cv.x_lo > 2.0) & (cv.x_hi < 3.0), 0.5, 1.0)
        moved = shift_rows(cv, band, 2.3)
        assert moved.min() >= 0.5 - 1e-15 and moved.max() <= 1.0 + 1e-15
        assert moved.sum() == pytest.approx(band.sum(), rel=1e-14)
    assert errs[0] < 1e-5 and errs[0] / errs[1] > 7.0


def test_carried_content_keeps_each_row_total(seed):
    from bearingfem.fe.jfo import JFOFilm, film_volumes
    s0 = JournalState(eps=0.6, omega=250.0, gamma=0.2)
    turned = JournalState(eps=0.6, omega=250.0, gamma=0.2 + 0.37 * 2 * np.pi / 64)
    th = np.mod(JFOFilm(seed, s0, 64, 4, ambient_pressure=1e4)._operator(s0).mesh.theta,
                2 * np.pi)
    film = JFOFilm(seed, s0, 64, 4, ambient_pressure=1e4,
                   fraction=np.where((th > 2.0) & (th < 3.0), 0.5, 1.0))
    cv = film_volumes(film._operator(turned).mesh)
    _, content = film._carried(cv, turned, film.cavitated.astype(float), film.content)
    for r in np.unique(cv.row):
        assert np.isclose(content[cv.row == r].sum(), film.content[cv.row == r].sum(),
                          rtol=1e-13)


def test_transient_journal_film_converges_at_first_order_along_a_load_reversing_orbit():
    """The transient JFO film alone, along a prescribed orbit through the centre that
    reverses the load twice a turn (L/D 2, 24x8, ambient oil at 1 bar): the force at two
    instants after the cavity has formed converges at first order in the step, as
    backward Euler (successive differences shrink 3.6-3.9x for 4x smaller steps; measured
    with 2048 steps a turn as well: 236, 66, 17 N at 0.2 of the turn)."""
    from bearingfem.fe.jfo import JFOFilm
    b, w = Bearing(radius=0.01, length=0.04, clearance=20e-6, viscosity=0.0117), 250.0
    turn = 2 * np.pi / w

    def state(t):
        ex, ey = 0.75 * np.sin(w * t), 0.1 * np.sin(2 * w * t) + 0.02
        dx, dy = 0.75 * w * np.cos(w * t), 0.2 * w * np.cos(2 * w * t)
        eps = np.hypot(ex, ey)
        return JournalState(eps=eps, eps_dot=(ex * dx + ey * dy) / eps,
                            gamma=np.arctan2(ey, ex), gamma_dot=(ex * dy - ey * dx) / eps ** 2,
                            omega=60.0 * np.cos(w * t))

    at = np.array([0.2, 0.7]) * turn
    forces = []
    for m in (32, 128, 512):
        film = JFOFilm(b, state(0.0), 24, 8, ambient_pressure=1e5)
        t, fx = [0.0], [0.0]
        for k in range(1, m + 1):
            sol = film.step(state(k * turn / m), turn / m)
            t.append(k * turn / m)
            fx.append(sol.force[0])
        forces.append(np.interp(at, t, fx))
    f32, f128, f512 = forces
    ratio = np.abs(f32 - f128) / np.abs(f128 - f512)
    assert np.all((3.0 < ratio) & (ratio < 5.0)), ratio


def test_instant_film_is_continuous_in_the_state(seed):
    """Between film steps the film a time integrator sees has no jumps: kept cavities stay
    cavities until the next step moves them. Along a closing, turning gap the largest
    force change between neighbouring states halves when they are twice as close; a set
    carried with the turning mesh switches volumes one by one there (jumps: it stays)."""
    from bearingfem.fe.jfo import JFOFilm
    s = JournalState(eps=0.5, omega=250.0)
    film = JFOFilm(seed, s, 48, 8, ambient_pressure=1e5)
    for _ in range(30):
        film.step(s, 2 * np.pi / 250.0 / 20)
    assert 0.2 < film.cavitated.mean() < 0.8

    def largest_change(n):
        f = np.array([film.instant(JournalState(eps=0.5 + 0.05 * x, omega=250.0,
                                                gamma=0.4 * x))[0]
                      for x in np.linspace(0.0, 1.0, n + 1)])
        return np.max(np.hypot(*np.diff(f, axis=0).T))
    assert largest_change(160) < 0.6 * largest_change(80)
