"""The general path (films on fields) is the rigid cylinder's fast path to round-off on
every model when the fields are the rigid cylinder's: FE P1/P2 none/gumbel/reynolds on a
periodic film and with a supply line, the steady and the transient JFO film, the finite
volumes (Reynolds family and JFO)."""
import numpy as np
import pytest

from bearingfem import Bearing, JournalState
from bearingfem.fe.general import film_system
from bearingfem.fe.jfo import JFOFilm
from bearingfem.fe.kernel import fe_operator, fe_pressure
from bearingfem.fields import FilmFields
from bearingfem.film import film_thickness
from bearingfem.fv.fvm import _assemble, _assemble_gap, _jfo, fvm_grid

B = Bearing(radius=0.01, length=0.01, clearance=20e-6, viscosity=0.0117)
S = JournalState(eps=0.6, eps_dot=0.1, gamma=0.3, gamma_dot=0.0, omega=250.0)


def rigid_gap(t, z):
    return film_thickness(t, S.eps)


def rigid_rate(t, z):
    return S.eps_dot * np.cos(t)


@pytest.mark.parametrize("element", ["P1", "P2"])
@pytest.mark.parametrize("cavitation", ["none", "gumbel", "reynolds"])
@pytest.mark.parametrize("supply_angle", [None, 2.0])
def test_fe_reynolds_family(element, cavitation, supply_angle):
    """Pressure to 1e-12 of its peak (measured <= 9.5e-14 P1, 1.8e-13 P2 at 120x20 with a
    supply line; 1e-14 at 30x6). Fails with the reference cylinder's load left out."""
    op = fe_operator(B, S, 30, 6, element, supply_angle, False)
    system = film_system(op, FilmFields(gap=rigid_gap).on(op, S), S.wedge_speed, S.eps)
    fast = fe_pressure(op, S, cavitation)
    general = fe_pressure(op, S, cavitation, system=system)
    assert np.max(np.abs(general.pressure - fast.pressure)) <= \
        1e-12 * np.max(np.abs(fast.pressure))


def test_transient_jfo():
    """The transient JFO film with the rigid cylinder of each state given as fields (a
    function of the state) is today's whole-length film to round-off over moving steps
    (attitude turning, eps and its rate changing): 1e-12 of the peak pressure, fraction
    to 1e-12. Fails with the content's departure not taken from the state's own
    cylinder (its eps sign flipped)."""
    def fields(state, t):
        return FilmFields(gap=lambda th, z: film_thickness(th, state.eps),
                          gap_rate=lambda th, z: state.eps_dot * np.cos(th))
    states = [JournalState(eps=0.5 + 0.03 * k, eps_dot=30.0, gamma=0.02 * k, gamma_dot=20.0,
                           omega=250.0) for k in range(4)]
    fast = JFOFilm(B, states[0], 48, 8, ambient_pressure=2e4, half=False)
    general = JFOFilm(B, states[0], 48, 8, ambient_pressure=2e4, fields=fields)
    for s in states[1:]:
        a, b = fast.step(s, 1e-3), general.step(s, 1e-3)
        assert np.max(np.abs(a.pressure - b.pressure)) <= 1e-12 * a.pressure_max
        assert np.max(np.abs(a.fraction - b.fraction)) <= 1e-12
    assert np.min(a.fraction) < 0.9


def test_fv_reynolds_balance():
    """The FV balance on the rigid gap given as functions: matrix and right-hand side to
    1e-14 (measured 1.6e-16, 4.3e-15; the squeeze's rigid part integrated exactly as on
    the fast path). Fails with the squeeze by the midpoint rule alone (1e-3 at 30x6)."""
    g = fvm_grid(30, 6, B.length_ratio, None)
    A0, r0 = _assemble(g, S.eps, S.eps_dot, S.wedge_speed)
    A1, r1, _ = _assemble_gap(g, rigid_gap, rigid_rate, S.wedge_speed, S.eps_dot)
    assert abs(A1 - A0).max() <= 1e-14 * abs(A0).max()
    assert np.max(np.abs(r1 - r0)) <= 1e-14 * np.max(np.abs(r0))


@pytest.mark.parametrize("supply_angle", [None, 2.0])
def test_fv_jfo(supply_angle):
    """The FV JFO film on the rigid gap given as functions: pressure and fraction to
    1e-12. Fails with the gap's squeeze by the midpoint rule alone."""
    theta0 = supply_angle       # a film angle: any line serves
    g = fvm_grid(40, 8, B.length_ratio, theta0)
    P0, phi0, _, _ = _jfo(B, g, S, (), 2e4)
    P1, phi1, _, _ = _jfo(B, g, S, (), 2e4, rigid_gap, rigid_rate)
    assert np.max(np.abs(P1 - P0)) <= 1e-12 * np.max(P0)
    assert np.max(np.abs(phi1 - phi0)) <= 1e-12
    assert np.min(phi0) < 0.9
