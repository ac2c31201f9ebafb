"""The modal-state EHD film's tangent in its own states (contract rule 17) and the
joint's Jacobian the mechanism builds from it."""
import numpy as np
import pytest

from bearingfem.contact import Roughness
from bearingfem.ehd.states import ModalStateEHD

from test_ehd_states import B, M, NT, NZ, SOLID, STALLED_Q, stalled_film


def _closed_film():
    """An undeflected bush nearly (q ~ 1e-7 m) past the circle, eps 1.1: the rigid gap is
    closed on an arc, where the summits carry and the flow's gap is floored."""
    from bearingfem import ElasticJournalState
    state = ElasticJournalState(eps=1.1, eps_dot=5.0, gamma=0.4, gamma_dot=-20.0,
                                omega=62.5)
    rough = Roughness(sigma=0.2e-6, contact_modulus=80.8e9, elastic_factor=1e-3)
    film = ModalStateEHD(B, None, SOLID, NT, NZ, M, 1e-5, rough)
    return film, state, 1e-7 * np.linspace(1.0, -0.5, M)


@pytest.mark.parametrize("case", ["stalled", "closed"])
def test_the_tangent_is_the_films_derivative_in_its_states(case):
    """Contract rule 17: the force and dq/dt differentiated in q by the implicit function
    theorem (one factorisation, one n-column solve) against central differences of the
    film solved at q +- h (h 3e-10 m, where the differences' error is least: 3e-8 of the
    largest entry at STALLED_Q, 4e-7 at 1e-9 m and 2e-6 at 3e-11 m), asserted to 1e-6.
    Two states: :data:`STALLED_Q` (past the clearance circle, summits carrying,
    cavitated, whirling, a Dowson-Higginson oil) and a closed gap (the flow's gap floored
    on an arc; 3e-8, 9e-8 measured there). Fails with the whirl's squeeze
    (gamma_dot dw/dalpha; 1e-3 at STALLED_Q), the summits' pressure or dq/dt's pressure
    term (V^T dP) dropped. Not with the floored points moving: at both states they lie
    in the cavity, held at P = 0, so no row the tangent solves sees them."""
    if case == "stalled":
        film, state = stalled_film()
        q = np.asarray(STALLED_Q)
    else:
        film, state, q = _closed_film()
    film.rates(state, q)
    tangent = film.tangent()
    h = 3e-10
    dF = np.empty((2, q.size))
    d_rates = np.empty((q.size, q.size))
    for k in range(q.size):
        e = np.zeros(q.size)
        e[k] = h
        (fp, rp), (fm, rm) = film.rates(state, q + e), film.rates(state, q - e)
        dF[:, k] = (np.subtract(fp, fm)) / (2 * h)
        d_rates[:, k] = (rp - rm) / (2 * h)
    assert np.max(np.abs(tangent.force_local - dF)) < 1e-6 * np.max(np.abs(dF))
    assert np.max(np.abs(tangent.rates - d_rates)) < 1e-6 * np.max(np.abs(d_rates))


def test_the_joints_jacobian_is_its_equations_derivative():
    """The Jacobian the mechanism gives its implicit integrator when the film has a tangent
    (contract rule 17: forward differences in the joint's six states, the film's tangent
    through the motion's response to the joint force in its eight modal states) against
    central differences of the same equations with every film solved (24 x 4, 8 modes,
    rough, eps 0.9 at 2 rad, a moving journal, a deflected bush), each row relative to
    its largest entry: modal columns 6e-11 measured, asserted 1e-8; the joint's columns
    9e-8, asserted 1e-5. Fails with the tangent's force left in the film's frame (not
    turned by gamma), or the motion's responses to F_x and F_y swapped."""
    from benchmarks.ehd_run import scene
    from mechanism.simulate import JointEquations, build_effects
    rough = Roughness(sigma=0.2e-6, contact_modulus=80.8e9, elastic_factor=1e-3)
    sc = scene("paper-short-ehd-sharp", 250.0, 0.01, n_theta=NT, n_z=NZ, modes=M, film_step=0.0,
               lubricant=None, coupling="states", relaxation=1e-5, roughness=rough)
    effects, film, _ = build_effects(sc)
    c = sc.bearing.clearance
    scale = np.array([1e-3, 1e-3 * c, 1e-3 * c, 1.0, 0.25 * c, 0.25 * c] + [1e-3 * c] * M)
    eq = JointEquations(sc, effects, film, scale)
    assert eq.has_jacobian
    y = np.r_[1.0, 0.9 * c * np.cos(2.0), 0.9 * c * np.sin(2.0), 250.0, 0.004, -0.003,
              1e-7 * np.linspace(1.0, -0.5, M)]
    J = eq.jacobian(0.0, y)
    fd = np.empty_like(J)
    for j in range(y.size):
        h = 3e-10 if j >= 6 else 1e-6 * max(abs(y[j]), scale[j])
        e = np.zeros(y.size)
        e[j] = h
        fd[:, j] = (np.subtract(eq.rhs(0.0, y + e), eq.rhs(0.0, y - e))) / (2 * h)
    err = np.abs(J - fd) / np.max(np.abs(fd), axis=1, keepdims=True)
    assert np.max(err[:, 6:]) < 1e-8
    assert np.max(err[:, :6]) < 1e-5


def test_a_run_with_the_films_tangent_is_the_run_without(monkeypatch):
    """The seed pin (5 % of a turn, 24 x 4, 8 modes, rough) integrated by LSODA with the
    joint's Jacobian from the film's tangent, and with LSODA's own differences (the
    tangent hidden): the same run to the integrator's tolerance (rtol 1e-6): eps 1.4e-7,
    least film 1.6e-7 and force 7.8e-7 of their largest measured on the 3-D solid; on the
    solid per harmonic eps 6.8e-7, least film 9.2e-7, the force vector 2.1e-6 of the
    largest |F| (its y component alone 3.8e-5 of its own largest); asserted 1e-5. Fails
    when the mechanism does not hand the Jacobian to the integrator (no Jacobian
    counted)."""
    from benchmarks.ehd_run import scene
    from mechanism import simulate
    from mechanism.effects import FilmEffect
    rough = Roughness(sigma=0.2e-6, contact_modulus=80.8e9, elastic_factor=1e-3)
    sc = scene("paper-short-ehd-sharp", 250.0, 0.05, n_theta=NT, n_z=NZ, modes=M, film_step=0.0,
               lubricant=None, coupling="states", relaxation=1e-5, roughness=rough)
    a = simulate(sc, progress=False)
    monkeypatch.setattr(FilmEffect, "has_tangent", property(lambda self: False))
    b = simulate(sc, progress=False)
    assert not a.partial and not b.partial
    assert a.stats["jacobians"] > 0 and b.stats["jacobians"] == 0
    assert a.eps.shape == b.eps.shape
    assert np.max(np.abs(a.eps - b.eps)) < 1e-5
    assert np.max(np.abs(a.film_min - b.film_min)) < 1e-5 * np.max(np.abs(a.film_min))
    # the force as a vector: its small component alone differs by more, relative to itself
    force = np.hypot(a.force_x - b.force_x, a.force_y - b.force_y)
    assert np.max(force) < 1e-5 * np.max(np.hypot(a.force_x, a.force_y))
