"""Symmetries the film must respect, whatever the model."""
import numpy as np
import pytest

from bearingfem import (JournalState, fvm_reynolds, long_bearing_exact_force, long_bearing_force,
                        short_bearing_exact_force, short_bearing_force, solve_reynolds)
from conftest import rel, table1_bearing

EXACT_MIRROR = [
    lambda b, s: fvm_reynolds(b, s, 48, 8, "reynolds").force_local, short_bearing_force,
    long_bearing_force, short_bearing_exact_force, long_bearing_exact_force,
]
MODELS = EXACT_MIRROR + [lambda b, s: solve_reynolds(b, s, 48, 8, "P1", "reynolds").force_local]
MIRROR = (JournalState(0.6, 12.0, 0.0, 20.0, 250.0), JournalState(0.6, 12.0, 0.0, -20.0, -250.0))


def _mirror_gap(model, b):
    fr, ft = model(b, MIRROR[0])
    mr, mt = model(b, MIRROR[1])
    return abs(mr - fr) / abs(fr), abs(mt + ft) / abs(ft)


@pytest.mark.parametrize("model", EXACT_MIRROR)
def test_reversing_rotation_mirrors_the_film(model):
    """omega -> -omega (and gamma_dot -> -gamma_dot) mirrors theta: F_r kept, F_t flips."""
    assert max(_mirror_gap(model, table1_bearing(0.5))) < 1e-9


@pytest.mark.parametrize("element,order", [("P1", 2), ("P2", 3)])
def test_fe_mirror_gap_is_discretisation_error(element, order):
    """The triangulation has one diagonal direction, so the mirrored film sits on another
    mesh: the gap must vanish with the mesh at (at least) the element's L2 order."""
    b = table1_bearing(0.5)
    gaps = [max(_mirror_gap(lambda b_, s_: solve_reynolds(
        b_, s_, 24 * k, 4 * k, element, "gumbel").force_local, b)) for k in (1, 2, 4)]
    assert gaps[2] < gaps[1] / 2 ** (order - 0.5) or gaps[2] < 1e-6, gaps


def test_literal_eq9_is_not_mirror_symmetric():
    """Eq. 9 applied literally integrates theta in [0, pi] even when omega < 0 puts the
    pressure in [pi, 2 pi]: it then pulls the journal outward (F_r > 0). The default
    half_film="wedge" turns the half film toward the wedge and equals Eq. 9 for omega > 0."""
    b = table1_bearing(0.2)
    fwd = JournalState(0.6, 3.0, 0.0, 0.0, 250.0)
    rev = JournalState(0.6, 3.0, 0.0, 0.0, -250.0)
    assert short_bearing_force(b, fwd) == short_bearing_force(b, fwd, half_film="fixed")
    assert short_bearing_force(b, fwd)[0] < 0.0 < short_bearing_force(b, rev, half_film="fixed")[0]
    assert short_bearing_force(b, rev)[0] < 0.0


@pytest.mark.parametrize("model", MODELS)
def test_local_force_does_not_depend_on_gamma(model):
    """Every film is periodic and turns with the line of centres: gamma only turns the frame."""
    b = table1_bearing(0.5)
    base = model(b, JournalState(0.6, 3.0, 0.0, 10.0, 250.0))
    for g in (0.7, 2.5, -2.0):
        assert model(b, JournalState(0.6, 3.0, g, 10.0, 250.0)) == pytest.approx(base, rel=1e-12)


@pytest.mark.parametrize("solver", [
    lambda b, s: fvm_reynolds(b, s, 48, 8, "reynolds"),
    lambda b, s: solve_reynolds(b, s, 48, 8, "P1", "reynolds")], ids=["fvm", "fem"])
def test_rotating_gamma_rotates_inertial_force(solver):
    b = table1_bearing(0.5)
    base = solver(b, JournalState(0.6, 0, 0.0, 0, 250.0))
    for g in (0.7, 2.5, -2.0):
        s = solver(b, JournalState(0.6, 0, g, 0, 250.0))
        c, si = np.cos(g), np.sin(g)
        fx, fy = base.force
        assert s.force == pytest.approx((c * fx - si * fy, si * fx + c * fy), rel=1e-9)


def test_contract_signs_under_steady_load():
    b = table1_bearing(0.2)
    s = JournalState(0.6, 0.0, 0.0, 0.0, 250.0)
    for f in (short_bearing_force(b, s), long_bearing_force(b, s),
              solve_reynolds(b, s, 48, 8).force_local, fvm_reynolds(b, s, 48, 8).force_local):
        assert f[0] < 0 < f[1]


@pytest.mark.parametrize("element,order", [("P1", 2), ("P2", 3)])
def test_half_domain_equals_full_domain(element, order):
    """Half and full meshes differ in the lower half's diagonals only: the results agree to
    discretisation error, which vanishes at the element's order."""
    b = table1_bearing(0.5)
    s = JournalState(0.7, -10.0, 0.0, 5.0, 250.0)
    gaps = []
    for k in (1, 2, 4):
        h = solve_reynolds(b, s, 24 * k, 4 * k, element, "reynolds", half=True)
        f = solve_reynolds(b, s, 24 * k, 4 * k, element, "reynolds", half=False)
        gaps.append(max(rel(h.force_local, f.force_local),
                        abs(h.friction_force / f.friction_force - 1)))
    assert gaps[2] < gaps[1] / 2 ** (order - 0.5) or gaps[2] < 1e-6, gaps


def test_velocity_homogeneity():
    """Reynolds complementarity is positively homogeneous in the velocities."""
    b = table1_bearing(0.5)
    s1 = JournalState(0.6, 12.0, 0.0, 20.0, 250.0)
    s3 = JournalState(0.6, 36.0, 0.0, 60.0, 750.0)
    a = solve_reynolds(b, s1, 48, 8).force_local
    c = solve_reynolds(b, s3, 48, 8).force_local
    assert c == pytest.approx((3 * a[0], 3 * a[1]), rel=1e-9)


@pytest.mark.parametrize("model", MODELS)
def test_zero_velocity_zero_force(model):
    assert model(table1_bearing(0.5), JournalState(0.5)) == pytest.approx((0.0, 0.0), abs=1e-12)
