"""Grooves of any width and position on any mesh: every groove edge is a mesh line
(bearingfem/fe/mesh.py), so the grooved film converges at the element's order."""
import numpy as np
import pytest

from bearingfem import Bearing, Groove, JournalState, solve_reynolds
from bearingfem.fe.mesh import film_mesh

B = Bearing(radius=0.05, length=0.1, clearance=1e-4, viscosity=0.01)     # L/D = 1
W20 = np.radians(20.0)
TWO_GROOVES = [Groove(angle=0.0, width=W20), Groove(angle=np.pi, width=W20)]
STATE = JournalState(0.6, -0.9, omega=100.0)
#: (F_r, F_t) [N] of that film, P2 576x192 (its error: below 1e-9 at the orders measured
#: below; recomputed by the slow test)
FINE = np.array([-1107.1534023139434, 2139.2344950386787])


def _arcs(centres, widths, gamma=0.3):
    return tuple((float(np.round(lo, 12)), float(np.round(hi, 12))) for lo, hi in
                 (Groove(angle=c, width=w).arc(gamma) for c, w in zip(centres, widths)))


@pytest.mark.parametrize("n_theta", [8, 24, 25, 50, 97])
@pytest.mark.parametrize("element", ["P1", "P2"])
def test_every_groove_edge_is_a_mesh_line(n_theta, element):
    """Three grooves of unrelated widths and positions: n_theta cells, a grid line on each
    edge, uniform cells within each arc between edges, and a groove's held dofs exactly
    those on [start, end]. Fails with the edges snapped to a uniform grid (the former
    mesh: an edge up to half a cell off)."""
    arcs = _arcs([0.4, 2.9, 4.4], [0.05, 0.349, 1.0])
    m = film_mesh(n_theta, 6, element, 0.5, arcs[0][0], True, arcs)
    th = m.axes[0]
    assert len(th) == n_theta + 1
    assert th[-1] - th[0] == pytest.approx(2 * np.pi, abs=1e-12)
    rel = th - th[0]
    edges = np.mod(np.ravel(arcs) - th[0], 2 * np.pi)
    for e in edges:
        assert np.min(np.abs(rel - e)) < 1e-9
    h, mid = np.diff(rel), 0.5 * (rel[1:] + rel[:-1])
    breaks = np.unique(np.concatenate([edges, [0.0, 2 * np.pi]]))
    for a, b in zip(breaks[:-1], breaks[1:]):
        inside = (mid > a) & (mid < b)
        assert inside.any() and np.ptp(h[inside]) < 1e-12     # uniform within an arc
    for (lo, hi), dofs in zip(arcs, m.grooves):
        inside = np.mod(m.theta - lo + 1e-9, 2 * np.pi) <= hi - lo + 2e-9
        assert np.array_equal(np.sort(dofs), np.flatnonzero(inside))


def test_too_few_cells_for_the_grooves_raise():
    arcs = _arcs(np.arange(5) * 1.2, [0.1] * 5)
    with pytest.raises(ValueError, match="n_theta must be >= 10"):
        film_mesh(8, 4, "P1", 0.5, arcs[0][0], True, arcs)


def _error(n_theta, element):
    f = solve_reynolds(B, STATE, n_theta, n_theta // 3, element, "reynolds",
                       grooves=TWO_GROOVES).force_local
    return np.linalg.norm(np.array(f) - FINE) / np.linalg.norm(FINE)


def test_a_grooved_film_converges_at_the_elements_order_on_any_mesh():
    """20 deg grooves at n_theta = 24 ... 192 (no multiple of 18; cells of about equal sides),
    Reynolds' condition. Measured force errors: P1 5.43, 1.46, 0.359, 0.0911 % (orders 1.89,
    2.03, 1.98); P2 0.0625, 0.0048, 0.00031 % (orders 3.70, 3.97: the force superconverges).
    With the edges snapped to a uniform grid (the former mesh, run): P1 5.45, 1.75, 0.412,
    0.205 % (orders 1.64, 2.08, 1.01), P2 0.975, 0.657, 0.230 % (orders 0.57, 1.52)."""
    p1 = [_error(n, "P1") for n in (24, 48, 96, 192)]
    p2 = [_error(n, "P2") for n in (24, 48, 96)]
    assert all(1.8 < np.log2(a / b) < 2.2 for a, b in zip(p1, p1[1:]))
    assert all(np.log2(a / b) > 3.4 for a, b in zip(p2, p2[1:]))
    assert p1[-1] < 1.2e-3 and p2[0] < 1e-3


@pytest.mark.slow
def test_the_fine_value():
    f = solve_reynolds(B, STATE, 576, 192, "P2", "reynolds", grooves=TWO_GROOVES).force_local
    assert np.allclose(f, FINE, rtol=1e-9, atol=0.0)


#: (F_r, F_t) [N] of the JFO films below at 576x192 (recomputed by the slow test)
JFO_FINE = {"flooded": np.array([-1001.724890002838, 2937.4276428664493]),
            "starved": np.array([-987.7646852237564, 2936.4177692296])}


def _jfo_grooves(fraction):
    return [Groove(angle=a, width=W20, pressure=1e5, fraction=fraction) for a in (0.0, np.pi)]


def _jfo_error(n_theta, case):
    f = solve_reynolds(B, STATE, n_theta, n_theta // 3, "P1", "jfo", ambient_pressure=1e5,
                       grooves=_jfo_grooves(1.0 if case == "flooded" else 0.5)).force_local
    return np.linalg.norm(np.array(f) - JFO_FINE[case]) / np.linalg.norm(JFO_FINE[case])


def test_grooved_jfo_films_converge_on_any_mesh():
    """The same grooves in the mass-conserving film (supply at 1 bar, the ambient), 24 ... 192
    cells. Flooded: errors 4.09, 1.08, 0.26, 0.060 % (orders 1.92, 2.06, 2.10); starved
    (half-full grooves; the fronts the content reaches converge more slowly): 9.14, 3.69,
    1.28, 0.265 % (orders 1.31, 1.53, 2.27). The former snapped edges (run): flooded
    orders 1.26, 1.71, 0.91; starved 0.68, 2.60, 0.55."""
    flooded = [_jfo_error(n, "flooded") for n in (24, 48, 96, 192)]
    starved = [_jfo_error(n, "starved") for n in (24, 48, 96, 192)]
    assert all(1.8 < np.log2(a / b) < 2.3 for a, b in zip(flooded, flooded[1:]))
    assert all(np.log2(a / b) > 1.2 for a, b in zip(starved, starved[1:]))
    assert flooded[-1] < 1e-3 and starved[-1] < 4e-3


@pytest.mark.slow
@pytest.mark.parametrize("case", ["flooded", "starved"])
def test_the_fine_jfo_values(case):
    f = solve_reynolds(B, STATE, 576, 192, "P1", "jfo", ambient_pressure=1e5,
                       grooves=_jfo_grooves(1.0 if case == "flooded" else 0.5)).force_local
    assert np.allclose(f, JFO_FINE[case], rtol=1e-8, atol=0.0)
