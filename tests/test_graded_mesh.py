"""The theta-graded film mesh (bearingfem.fe.mesh ``grading``) and its use by the grooved
design chart (bearingfem.design.chart_grading)."""
import math

import numpy as np
import pytest

from bearingfem import Bearing, Groove, JournalState
from bearingfem.design import chart_grading, coefficients
from bearingfem.fe.grooved import groove_operator_for
from bearingfem.fe.mesh import film_mesh

B = Bearing(radius=0.05, length=0.1, clearance=100e-6, viscosity=0.02)
OMEGA = 100.0 * math.pi
GROOVES = (Groove(angle=0.0, width=math.radians(20.0)),
           Groove(angle=math.pi, width=math.radians(20.0)))


def test_graded_cells_follow_the_density_and_keep_the_groove_edges():
    """Periodic mesh: cell widths proportional to 1 - s cos(theta - focus) at the cells'
    middles, to the midpoint rule's O(h^2) (measured 2e-3 relative at 96 cells, s 0.8);
    grooved: every edge still a grid line. Fails with the density's sign flipped (cells
    fine opposite the focus) or the cells shared by length instead of density."""
    focus, s = 2.0, 0.8
    th = film_mesh(96, 4, "P1", 1.0, None, True, (), (focus, s)).axes[0]
    w, mid = np.diff(th), 0.5 * (th[1:] + th[:-1])
    shape = 1.0 - s * np.cos(mid - focus)
    ratio = w / shape
    assert np.ptp(ratio) / ratio.mean() < 5e-3
    assert th[0] == 0.0 and th[-1] == pytest.approx(2 * math.pi, abs=1e-12)
    gop = groove_operator_for(B, 48, 8, "P2", GROOVES, (-1.1, 0.9))
    axis = gop.op.mesh.axes[0]
    for lo, hi in gop.op.mesh.arcs:
        for edge in (lo, hi):
            rel = np.mod(axis - edge + 1e-9, 2 * math.pi) - 1e-9
            assert np.min(np.abs(rel)) < 1e-9
    # the finest cells where asked: inertial -1.1 is mesh angle -1.1 + pi
    widths = np.diff(axis)
    finest = 0.5 * (axis[1:] + axis[:-1])[np.argmin(widths)]
    assert math.remainder(finest - (-1.1 + math.pi), 2 * math.pi) == pytest.approx(0.0,
                                                                                   abs=0.1)


def test_grading_brings_a_heavy_loads_coefficients_to_the_fine_mesh():
    """eps 0.943 (S 0.01's equilibrium on the chart), P2 48x8: K and C against P2 96x16
    (itself within 0.08 % of 192x32): uniform cells err 3.6 %, graded ones 0.7 % (measured
    against 192x32); asserted: graded < 1.2 % and under a third of the uniform error.
    Fails with the density's sign flipped or the grading's angle read in the film frame
    (turned by pi)."""
    s = JournalState(0.943, omega=OMEGA, gamma=-1.245)
    opts = dict(element="P2", cavitation="reynolds", grooves=GROOVES)
    ref = coefficients(B, s, "fem", n_theta=96, n_z=16, **opts)

    def err(kc):
        return max(np.abs(kc.K - ref.K).max() / np.abs(ref.K).max(),
                   np.abs(kc.C - ref.C).max() / np.abs(ref.C).max())
    uniform = err(coefficients(B, s, "fem", n_theta=48, n_z=8, **opts))
    graded = err(coefficients(B, s, "fem", n_theta=48, n_z=8, grading=(-1.1, 0.9), **opts))
    assert graded < 0.012 and graded < uniform / 3.0, (graded, uniform)


def test_chart_grading_points_at_the_heavy_loads_minimum_film():
    """The closed form's line of centres at S ~ 0.032 (geometric mean of the chart's
    S < 0.1) for a downward load: -1.10 rad, between the load line (-pi/2) and the
    light-load limit (0); the chart's own equilibria there: -0.91 .. -1.25 rad."""
    angle, strength = chart_grading(B, OMEGA)
    assert -1.25 < angle < -0.9 and strength == 0.9


@pytest.mark.parametrize("grading", [(0.0, 1.0), (0.0, -0.1), (math.nan, 0.5), "ab", (1.0,)])
def test_bad_grading_raises_by_name(grading):
    with pytest.raises(ValueError, match="grading"):
        coefficients(B, JournalState(0.5, omega=OMEGA), "fem", grooves=GROOVES,
                     grading=grading)


def test_grading_without_grooves_raises():
    with pytest.raises(ValueError, match="grading"):
        coefficients(B, JournalState(0.5, omega=OMEGA), "fem", grading=(0.0, 0.5))
