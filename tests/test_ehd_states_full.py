"""The EHD film with the bush's whole deflection integrated as states (modes 0,
bearingfem.ehd.states.FullStateEHD): the modal film with every mode kept is the same film
in another basis; a still journal relaxes to the steady EHD solve with the full
compliance; its dense tangent against differences."""
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from bearingfem import JournalState, solve_reynolds
from bearingfem.contact import Roughness
from bearingfem.ehd.states import FullStateEHD, ModalStateEHD
from bearingfem.ehd.transient import ehd_compliance
from bearingfem.models.ehd import ehd_run_film

from test_ehd_states import B, NT, NZ, SOLID, STALLED_Q, stalled_film


def _full_and_modal():
    """At :data:`STALLED_Q`'s state (past the circle, summits carrying, cavitated,
    whirling, Dowson-Higginson oil, 48 x 4): the full film and the modal film with all
    48 x 5 modes, and the deflection of STALLED_Q's 24 modes on the bush grid."""
    part, state = stalled_film()
    w = part.left @ np.asarray(STALLED_Q)
    n = w.size
    full = FullStateEHD(B, part.lubricant, SOLID, 48, 4, 1e-5, part.roughness)
    every = ModalStateEHD(B, part.lubricant, SOLID, 48, 4, n, 1e-5, part.roughness)
    return full, every, state, w


def test_every_mode_kept_is_the_full_film():
    """The modal film with all n_theta (n_z + 1) modes and the full film at the same
    deflection (q_modal = L^T w, L orthogonal): force, dq/dt (L dq/dt against dw/dt) and
    the tangent (L^T-transformed) agree to 1e-8 relative (measured on
    the heavy state: 3e-13, 2e-11, 3e-12 and 3e-13; each film converged to the Newton
    test of 1e-10). Fails with the frame shift's transpose taking w to the film nodes, or
    the whirl's squeeze dropped from the full tangent."""
    full, every, state, w = _full_and_modal()
    L = every.left
    q = L.T @ w
    Fm, rm = every.rates(state, q)
    Ff, rf = full.rates(state, w)
    assert np.allclose(Ff, Fm, rtol=1e-8, atol=1e-8 * np.hypot(*Fm))
    assert np.max(np.abs(L @ rm - rf)) < 1e-8 * np.max(np.abs(rf))
    tm, tf = every.tangent(), full.tangent()
    assert np.max(np.abs(tf.force_local @ L - tm.force_local)) < \
        1e-8 * np.max(np.abs(tm.force_local))
    assert np.max(np.abs(L @ tm.rates @ L.T - tf.rates)) < 1e-8 * np.max(np.abs(tf.rates))


def test_the_full_tangent_is_the_films_derivative():
    """The full film's tangent (dense: one LU of the Newton matrix) along four random
    directions of the deflection against central differences of the film solved at
    w +- h d (h 3e-10 m, |d|_inf = 1: the modal tangent's step), to 1e-6 of the largest
    entry (measured 2e-8 to 4e-7), at the heavy state of :func:`_full_and_modal`. Fails
    with the whirl's squeeze dropped from it."""
    full, _, state, w = _full_and_modal()
    full.rates(state, w)
    t = full.tangent()
    rng = np.random.default_rng(3)
    h = 3e-10
    for _ in range(4):
        d = rng.uniform(-1.0, 1.0, w.size)
        (fp, rp), (fm, rm) = full.rates(state, w + h * d), full.rates(state, w - h * d)
        dF, dr = np.subtract(fp, fm) / (2 * h), (rp - rm) / (2 * h)
        assert np.max(np.abs(t.force_local @ d - dF)) < 1e-6 * np.max(np.abs(dF))
        assert np.max(np.abs(t.rates @ d - dr)) < 1e-6 * np.max(np.abs(dr))


@pytest.mark.slow
def test_a_journal_held_still_relaxes_to_the_steady_full_ehd_film():
    """A still journal (eps 0.9, 24 x 4) from an undeflected bush: the whole deflection
    relaxes (dw/dt -> 0) to the steady EHD solve with the full compliance (no modes), force
    to 1e-8 and the deflection to 1e-7 of its largest. At w = 0 the bush's own squeeze
    first sucks the film down to under 5 % of the rigid force (3.3 %). Measured: force
    4e-11, dw/dt 2e-13 m/s, deflection 1e-10. Fails with the squeeze load's sign flipped or the compliance's blocks
    transposed per harmonic. (12 s: slow.)"""
    s = JournalState(eps=0.9, gamma=np.pi, omega=62.5)
    film = ehd_run_film(B, bush=SOLID, n_theta=NT, n_z=NZ, modes=0, coupling="states",
                        relaxation=1e-6)
    assert isinstance(film, FullStateEHD) and film.state_size == NT * (NZ + 1)
    F0, _ = film.rates(s, np.zeros(film.state_size))
    rigid = solve_reynolds(B, s, NT, NZ, "P1", "reynolds", half=False).force_local
    assert np.hypot(*F0) < 0.05 * np.hypot(*rigid)     # the bush's squeeze at w = 0

    def jac(t, w):
        film.rates(s, w)
        return film.tangent().rates
    sol = solve_ivp(lambda t, w: film.rates(s, w)[1], (0.0, 2e-2), np.zeros(film.state_size),
                    method="BDF", jac=jac, rtol=1e-8, atol=1e-14)
    F, wdot = film.rates(s, sol.y[:, -1])
    steady = solve_reynolds(B, s, NT, NZ, "P1", "reynolds",
                            bush=ehd_compliance(SOLID, B.radius, B.length, NT, NZ, 0))
    assert np.allclose(F, steady.force_local, rtol=1e-8, atol=0)
    assert np.max(np.abs(wdot)) < 1e-10
    w = film.solution(s, sol.y[:, -1]).deformation
    assert np.allclose(w, steady.deformation, rtol=0,
                       atol=1e-7 * np.max(np.abs(steady.deformation)))


@pytest.mark.slow
def test_the_mechanism_runs_the_full_film_as_the_modal_film_with_every_mode():
    """Contract rules 16-17 with the whole deflection: the seed pin at 250 rad/s, 1 % of a
    turn from a centred start, 24 x 4, rough (sigma 0.2 um), modes 0 (120 states) against
    the modal film with all 120 modes (another basis of the same ODE): the peak eps and
    least film agree to the integrator's tolerance (measured 1.2e-6 and 1.8e-6 c; 1e-5
    asserted, as the tangent's run check), the sampled peak joint force to 1e-2 (measured
    1.4e-3: the force is a stiff function of eps near the circle). Fails when the full
    film's states reach the film nodes through the frame shift's transpose."""
    from benchmarks.ehd_run import scene
    from mechanism import simulate
    rough = Roughness(sigma=0.2e-6, contact_modulus=80.8e9, elastic_factor=1e-3)
    runs = []
    for modes in (0, NT * (NZ + 1)):
        sc = scene("paper-short-ehd-sharp", 250.0, 0.01, n_theta=NT, n_z=NZ, modes=modes,
                   film_step=0.0, lubricant=None, coupling="states", relaxation=1e-5,
                   roughness=rough)
        runs.append(simulate(sc, progress=False))
    full, modal = runs
    assert not full.partial and full.film_z.shape[1] == NT * (NZ + 1)
    assert abs(full.eps.max() - modal.eps.max()) < 1e-5 * modal.eps.max()
    assert abs(full.film_min.min() - modal.film_min.min()) < 1e-5 * 20e-6
    force = np.hypot(full.force_x, full.force_y)
    assert abs(force.max() - np.hypot(modal.force_x, modal.force_y).max()) < 1e-2 * force.max()
