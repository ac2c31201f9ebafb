"""Exact FE sensitivities (bearingfem.fe.sensitivity): mutants of the generalised forces'
weights, the default tilt and the grooves' gamma partial survived the tilt-coefficient and
centred-journal tests (docs/mutation.md)."""
from dataclasses import replace

import numpy as np
import pytest

from bearingfem import Bearing, Groove, JournalState, solve_reynolds
from bearingfem.fe.sensitivity import fe_force_derivatives, fe_tilt_coefficients

B = Bearing(radius=0.01, length=0.01, clearance=20e-6, viscosity=0.0117)
S = JournalState(eps=0.6, gamma=0.3, omega=250.0)


@pytest.mark.parametrize("cavitation", ["none", "reynolds"])
def test_generalised_forces_are_the_film_force_and_moment(cavitation):
    """Q = c int p dH/dq (virtual work) against the film's own force and moment of the
    tilted journal, integrated directly (p (cos, sin)(theta + gamma), lever arm z) on the
    same mesh: equal to round-off (measured 1e-15). Fails with the weights dH/dq negated
    (sensitivity.py:127: K and C, products of two weights, stay unchanged)."""
    tilt = (1.0e-3, -0.5e-3)
    Q = fe_tilt_coefficients(B, S, tilt, 48, 8, "P1", cavitation).force
    sol = solve_reynolds(B, S, 48, 8, "P1", cavitation, tilt=tilt)
    assert Q == pytest.approx(np.r_[sol.force, sol.moment], rel=1e-10, abs=1e-12)


def test_default_tilt_is_the_aligned_journal():
    """Without a tilt the coefficients linearise the aligned journal: its force is the
    aligned film's (the whole length on the general assembly against the half film's
    fast path: measured 1.6e-10, hence 1e-8) and its moments vanish (mid-plane symmetry,
    measured 1e-17 N m). Fails with the default tilt non-zero (sensitivity.py:145)."""
    Q = fe_tilt_coefficients(B, S, n_theta=48, n_z=8).force
    sol = solve_reynolds(B, S, 48, 8, "P1", "reynolds")
    assert Q[:2] == pytest.approx(sol.force, rel=1e-8)
    assert np.abs(Q[2:]).max() < 1e-12 * np.hypot(*sol.force) * B.length


def test_groove_gamma_partial_against_a_wider_central_difference():
    """With a pressurised groove fixed in the inertial frame the force depends on gamma at
    fixed (eps, eps_dot, w): its partial against a central difference of solve_reynolds
    with a 100 times wider step (1e-4 rad; measured agreement 2e-7 relative). Fails with
    the difference divided by the step written times it (sensitivity.py:76)."""
    grooves = [Groove(angle=1.0, width=0.3, pressure=1e5)]
    d = fe_force_derivatives(B, S, 48, 8, "P1", "reynolds", grooves=grooves).d_gamma
    h = 1e-4

    def force(gamma):
        return np.array(solve_reynolds(B, replace(S, gamma=gamma), 48, 8, "P1", "reynolds",
                                       grooves=grooves).force_local)
    reference = (force(S.gamma + h) - force(S.gamma - h)) / (2 * h)
    assert np.linalg.norm(np.subtract(d, reference)) < 1e-5 * np.linalg.norm(reference)
