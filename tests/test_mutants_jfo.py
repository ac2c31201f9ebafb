"""The FE JFO film (bearingfem.fe.jfo): mutants of the transient film's step cut and of its
starting fraction's refusal survived the JFO tests (docs/mutation.md)."""
import numpy as np
import pytest

from bearingfem import JournalState
from bearingfem.bearing import seed_bearing
from bearingfem.errors import ConvergenceError
from bearingfem.fe import jfo
from bearingfem.fe.jfo import JFOFilm
from bearingfem.fe.jfo_balance import state_between

B = seed_bearing(1.0)
S0 = JournalState(0.5, 0.0, 0.3, 0.0, 250.0)
S1 = JournalState(0.6, 20.0, 0.3, 0.0, 250.0)
DT = 1e-3


def test_cut_journal_step_is_two_half_steps(monkeypatch):
    """A journal step whose first solve fails is cut in two (substeps = 2): its film is the
    one two explicit half steps give, the first to the state halfway, to round-off.
    Fails with the second half taking the whole step (jfo.py:302)."""
    film, ref = (JFOFilm(B, S0, 48, 4, ambient_pressure=1e5) for _ in range(2))
    real, calls = jfo.step_balance, []

    def fails_once(*args, **kw):
        calls.append(1)
        if len(calls) == 1:
            raise ConvergenceError("test balance", 1, 1.0)
        return real(*args, **kw)
    monkeypatch.setattr(jfo, "step_balance", fails_once)
    s = film.step(S1, DT)
    monkeypatch.setattr(jfo, "step_balance", real)
    ref.step(state_between(S0, S1), 0.5 * DT)
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


def test_half_way_state_by_hand():
    """The state half way through a cut step, by hand: every rate and speed the mean of the
    two ends, the attitude the short way round (0.1 and 2 pi - 0.1 rad meet at 0, not at
    pi). The cut-step test above takes its reference through the same helper, so this
    pins the helper itself. Fails with a mean's 1/2 divided in (jfo_balance.py:125)."""
    a = JournalState(0.2, -4.0, 0.1, 3.0, 100.0)
    b = JournalState(0.6, 10.0, 2 * np.pi - 0.1, 5.0, 300.0)
    mid = state_between(a, b)
    assert (mid.eps, mid.eps_dot, mid.gamma_dot, mid.omega) == pytest.approx(
        (0.4, 3.0, 4.0, 200.0), rel=1e-15)
    assert mid.gamma == pytest.approx(0.0, abs=1e-15)


@pytest.mark.parametrize("half", [True, False])
def test_full_content_sums_to_the_film_volume(half):
    """The full content of the control volumes (the exact integral of H over each) sums
    to the film's volume, int (1 + eps cos theta) dtheta dzeta = 2 pi times the meshed
    length in zeta (lambda for the half film, 2 lambda for the whole), to round-off; each
    volume holds between (1 - eps) and (1 + eps) times its area. Fails with the content
    negated (jfo_balance.py:35)."""
    from bearingfem.fe.assembly import fe_operator
    from bearingfem.fe.jfo_balance import full_content, film_volumes

    op = fe_operator(B, S1, 48, 8, "P1", None, half)
    cv = film_volumes(op.mesh)
    content = full_content(cv, S1.eps)
    lam = B.length / (2 * B.radius)
    assert content.sum() == pytest.approx(2 * np.pi * lam * (1 if half else 2), rel=1e-12)
    assert np.all(content >= (1 - S1.eps) * cv.area) and np.all(content <= (1 + S1.eps) * cv.area)


def test_jfo_friction_shears_only_the_oil_present():
    """The JFO film's friction against a second quadrature of the shear computed here from
    the solution's nodal fields alone: the Couette part mu omega R / h acts on the oil
    present (the fraction phi of the gap, as streamers), the Poiseuille part h/(2R) dp/dtheta
    where the film is full (p > 0); the trapezoid rule on the node grid, dp/dtheta by
    central differences. The two quadratures agree to 0.12 % at 60 x 10, 0.07 % at 120 x 20
    and 0.05 % at 240 x 40; the Couette shear over the whole gap in the cavities (phi
    ignored) moves the friction by 16 %. Fails with ``couette_share`` = 1
    (jfo_steady.py:jfo_shear)."""
    from bearingfem import solve_reynolds
    state = JournalState(0.6, omega=250.0)
    sol = solve_reynolds(B, state, 60, 10, "P1", "jfo", ambient_pressure=1e5)
    assert sol.cavitated_fraction > 0.3          # the cavities matter here
    order = np.lexsort((sol.theta, sol.z))
    nt, nz = len(np.unique(sol.theta)), len(np.unique(sol.z))
    grid = [a[order].reshape(nz, nt) for a in (sol.z, sol.pressure, sol.film_thickness,
                                                 sol.fraction)]
    Z, P, H, PHI = grid
    dth = 2 * np.pi / nt                       # periodic in theta: every node weighs dth
    dP = (np.roll(P, -1, 1) - np.roll(P, 1, 1)) / (2 * dth)
    R, mu = B.radius, B.viscosity
    tau = mu * state.omega * R / H * PHI + H / (2 * R) * dP * (P > 0)
    friction = 2 * np.trapezoid(tau.sum(axis=1) * dth * R, Z[:, 0])   # both halves
    assert sol.friction_force == pytest.approx(friction, rel=0.01)


def test_a_squeeze_film_that_never_cavitates_records_no_rupture():
    """Plates closing at a steady rate (h = 1 - t/2, h' < 0) keep the whole film above
    ambient: the exact solver must report no rupture, the front at the plate's middle, and
    the load the parallel-plate squeeze film's by hand, W = p_a l + mu |h'| l^3 / h^3 (the
    pressure p_a + 6 mu |h'| x (l - x) / h^3 integrated). Fails with the full film's exit
    test `t_open >= t_end` written `>` (a rupture recorded at t_end; docs/mutation.md left
    it without a test in the first round)."""
    from bearingfem.closed.squeeze_film import oscillating_squeeze
    l, mu, pa = 1.0, 1.0 / 12.0, 0.025
    ex = oscillating_squeeze(lambda t: 1.0 - 0.5 * t, lambda t: -0.5 + 0.0 * t, 1.0,
                             length=l, viscosity=mu, ambient_pressure=pa, n_t=201)
    assert ex.rupture_times == () and ex.collapse_times == ()
    assert np.all(ex.front == 0.5 * l)
    h = 1.0 - 0.5 * ex.t
    assert ex.load == pytest.approx(pa * l + mu * 0.5 * l ** 3 / h ** 3, rel=1e-12)
