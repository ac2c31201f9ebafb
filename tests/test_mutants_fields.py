"""The film's fields (bearingfem.fields) against independent references: mutants of the
tilted gap's rate, the nodal-field route, the rigid fast path's test and the gap's refusal
survived the manufactured-field and misalignment tests (docs/mutation.md)."""
import numpy as np
import pytest

from bearingfem import JournalState, solve_reynolds
from bearingfem.fe.kernel import fe_operator
from bearingfem.fields import FilmFields, tilted_gap
from conftest import table1_bearing

B = table1_bearing(1.0)
S = JournalState(0.5, 3.0, 0.4, 0.0, 250.0)


def test_tilted_gap_rate_is_the_time_derivative_at_fixed_theta():
    """The rate of the tilted gap at a fixed film angle theta, with the attitude turning
    (gamma_dot = 40 rad/s) and the tilt changing, against the central difference in time
    of the gap itself (step 1e-6 s: truncation ~1e-12, measured 3e-10 relative). Fails
    with the gamma_dot term's sign flipped or d(dH)/dtheta's tilt_y term divided
    (fields.py:148-149)."""
    tilt, rate, gamma_dot = np.array([2e-4, -3e-4]), np.array([0.05, 0.08]), 40.0
    theta, zeta = np.meshgrid(np.linspace(0, 2 * np.pi, 13), np.linspace(-1, 1, 5))

    def gap(t):
        s = JournalState(0.5, 0.0, 0.4 + gamma_dot * t, gamma_dot, 250.0)
        return tilted_gap(B, s, theta, zeta, tuple(tilt + rate * t))[0]
    s0 = JournalState(0.5, 0.0, 0.4, gamma_dot, 250.0)
    dt = 1e-6
    reference = (gap(dt) - gap(-dt)) / (2 * dt)
    got = tilted_gap(B, s0, theta, zeta, tuple(tilt), tuple(rate))[1]
    assert got == pytest.approx(reference, rel=1e-7, abs=1e-9 * np.abs(reference).max())


def _force(fields, state=S):
    return np.array(solve_reynolds(B, state, 48, 8, "P1", "none", fields=fields).force)


def test_nodal_viscosity_field_scales_the_pressure():
    """A viscosity given as nodal values, mu/mu0 = 2 at every dof, doubles the full film's
    pressure and force (the film equation is linear in P/mu): against twice the rigid
    film: the general assembly and the fast path agree to 2.3e-10 (their quadratures of
    H^3 differ at round-off of the element sums), hence 1e-8. Fails when nodal arrays
    are not recognised as such (fields.py:113, then refused as a wrong shape)."""
    ndofs = fe_operator(B, S, 48, 8, "P1", None, False).mesh.ndofs
    rigid = _force(FilmFields())
    assert _force(FilmFields(viscosity=np.full(ndofs, 2.0))) == pytest.approx(
        2.0 * rigid, rel=1e-8)


def test_gap_rate_off_the_rigid_one_takes_the_general_path():
    """A gap rate 1.5 eps_dot cos(theta) on the rigid gap is the rigid film of a state
    squeezing 1.5 times faster: the general assembly must give that film's force, to
    1e-8 (measured 1.1e-10, as above), not the fast path's at the original eps_dot (1.5 % off
    here). Fails when the fast path's test accepts a relative difference (the rate's
    rtol 0 -> 1, fields.py:97)."""
    rate = FilmFields(gap_rate=lambda th, ze: 1.5 * S.eps_dot * np.cos(th))
    faster = JournalState(S.eps, 1.5 * S.eps_dot, S.gamma, S.gamma_dot, S.omega)
    ref, slow = _force(FilmFields(), faster), _force(FilmFields())
    got = _force(rate)
    assert np.linalg.norm(got - ref) < 1e-8 * np.linalg.norm(ref)
    assert np.linalg.norm(slow - ref) > 1e-3 * np.linalg.norm(ref)   # the test can tell


def test_a_gap_touching_zero_is_refused():
    """A gap field that is 0 over part of the film (the journal touching the bush) is
    refused before any work, naming the field. Fails with the refusal's test v > 0
    relaxed to v >= 0 (fields.py:73)."""
    touching = FilmFields(gap=lambda th, ze: np.where(th < 1.0, 0.0, 1.0))
    with pytest.raises(ValueError, match="film field gap must be > 0"):
        solve_reynolds(B, S, 48, 8, "P1", "none", fields=touching)
