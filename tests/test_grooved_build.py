"""The grooved film's operator built by numpy (bearingfem.fe.grooved_build) against the
scikit-fem assembly it replaces (bearingfem.fe.assembly.build_operator for the pattern,
the four cos^k terms and the loads; the general-field tables for the seven harmonics)."""
import math

import numpy as np
import pytest

from bearingfem import Bearing, Groove, JournalState
from bearingfem.fe.assembly import film_operator
from bearingfem.fe.grooved import (bearing_fixed_operator, groove_operator_for,
                                   grooved_derivatives, grooved_operator)

B = Bearing(radius=0.05, length=0.1, clearance=100e-6, viscosity=0.02)
#: odd widths and places, three grooves, one pressurised
GROOVES = (Groove(angle=0.3, width=math.radians(17.0)),
           Groove(angle=2.4, width=math.radians(11.0), pressure=3e4),
           Groove(angle=4.1, width=math.radians(23.0)))
MESHES = [("P1", 41, 8), ("P2", 23, 4), ("P2", 30, 6)]
#: cells far longer along z than around: the weakest real couplings 3e-4 (P1) and 1.4e-6
#: (P2) of the largest table entry, below any threshold but round-off's
STRETCHED = [("P1", 241, 2), ("P2", 201, 1)]


def both(element, n, z):
    """(numpy-built, scikit-fem-built) grooved operators of one mesh."""
    new = groove_operator_for(B, n, z, element, GROOVES)
    m = new.op.mesh
    old = film_operator(n, z, element, B.length_ratio, m.theta0, True, m.arcs)
    return new, grooved_operator(old)


@pytest.mark.parametrize("element, n, z", MESHES + STRETCHED)
def test_the_numpy_operator_is_scikit_fems_to_round_off(element, n, z):
    """Same pattern and free-free selection (exactly), the same seven harmonic tables,
    four cos^k terms and two loads to round-off (measured: harmonics identical, terms
    <= 6e-16, loads <= 2e-17 of their largest entry). Fails with sin and cos swapped in
    a harmonic weight, with a wrong factor in cos^3 = (3 cos + cos 3 phi) / 4, with the
    metric's off-diagonal dropped or with the loads' sin and cos swapped (each tried); on
    the stretched meshes, with the round-off cut at 1e-3 of the largest entry instead of
    1e-12 (tried: their weak couplings dropped, 1448 of 1932 entries kept at P1 241 x 2)."""
    new, old = both(element, n, z)
    a, b = new.op, old.op
    for name in ("indptr", "indices", "ff_indptr", "ff_indices", "ff_select"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)
    for x, y in ((new.harmonics, old.harmonics), (a.terms, b.terms), (a.b_sin, b.b_sin),
                 (a.b_cos, b.b_cos), (a.qp_theta, b.qp_theta), (a.qp_weight, b.qp_weight)):
        np.testing.assert_allclose(x, y, rtol=0, atol=1e-14 * np.abs(y).max())
    assert (a.qp_interp != b.qp_interp).nnz == 0


@pytest.mark.parametrize("element, n, z", MESHES[:2])
def test_the_numpy_operators_film_and_partials_are_the_old_ones(element, n, z):
    """The Reynolds-condition film and its exact partials (the designer's path) on both
    operators agree to the solver's round-off (measured <= 5e-15 relative). Fails with
    the load's b_sin and b_cos swapped in the build (tried)."""
    s = JournalState(0.55, 0.2, 0.9, -0.7, 100.0 * math.pi)
    new, old = both(element, n, z)
    d_new = grooved_derivatives(B, s, new, GROOVES)
    d_old = grooved_derivatives(B, s, old, GROOVES)
    for f in ("force", "d_eps", "d_eps_dot", "d_wedge", "d_gamma"):
        y = np.asarray(getattr(d_old, f))
        np.testing.assert_allclose(getattr(d_new, f), y, rtol=0, atol=1e-12 * np.abs(y).max(),
                                   err_msg=f)


def test_the_bearing_fixed_operator_is_built_once_per_mesh():
    """Cached per mesh: a second journal state (or a second call) reuses the tables."""
    a = groove_operator_for(B, 23, 4, "P2", GROOVES)
    assert groove_operator_for(B, 23, 4, "P2", GROOVES) is a
    assert bearing_fixed_operator.cache_info().hits >= 1


def test_a_small_films_coarse_level_is_built_from_its_second_cold_start():
    """The first cold start on a small operator begins from no cavity and builds nothing;
    the second builds the coarse level and starts from it. Both reach the same film (the
    active set's answer does not depend on its start: measured 1e-16 apart) and it is the
    complementarity solution (residual below the solver's tolerance); no scikit-fem
    operator is built on the way. Fails with the rule inverted (the levels built on the
    first cold start) or with no first set returned (the periodic film's scikit-fem
    coarse levels then start it) (both tried)."""
    from bearingfem.fe.grooved import FIRST_COLD_START_DOFS, grooved_pressure
    bearing_fixed_operator.cache_clear()
    film_operator.cache_clear()
    gop = groove_operator_for(B, 23, 4, "P2", GROOVES)
    assert len(gop.op.mesh.free) <= FIRST_COLD_START_DOFS
    s = JournalState(0.7, 0.0, 1.0, 0.4, 100.0 * math.pi)
    first = grooved_pressure(gop, B, s, GROOVES)
    assert "coarse" not in gop.levels and gop.levels["cold_starts"] == 1
    gop.last.clear()
    second = grooved_pressure(gop, B, s, GROOVES)
    assert gop.levels["coarse"] is not None and gop.levels["cold_starts"] == 2
    assert first.residual <= 1e-10 and second.residual <= 1e-10
    np.testing.assert_allclose(first.pressure, second.pressure, rtol=0,
                               atol=1e-12 * second.pressure.max())
    np.testing.assert_array_equal(first.active, second.active)
    assert film_operator.cache_info().currsize == 0


def test_each_groove_set_gets_the_operator_of_its_own_arcs():
    """The grooves' arcs are cached per groove set (a design asks at every evaluation):
    alternating sets, and a set equal to an earlier one built anew, each get the mesh of
    their own edges. Fails when the cache answers a set with another's arcs (e.g. keyed
    by the number of grooves)."""
    one = (Groove(angle=1.0, width=math.radians(30.0)),)
    two = (Groove(angle=0.0, width=math.radians(20.0)),
           Groove(angle=math.pi, width=math.radians(20.0)))
    other_two = GROOVES[:2]
    for grooves in (one, two, other_two, one, tuple(Groove(g.angle, g.width) for g in two)):
        arcs = groove_operator_for(B, 24, 4, "P2", grooves).op.mesh.arcs
        np.testing.assert_allclose(np.ravel(arcs), np.ravel([g.arc(0.0) for g in grooves]),
                                   rtol=0, atol=1e-11)
