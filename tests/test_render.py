"""Off-screen renders: stored baselines (renderer noise tolerated), and checks a test can
see - orientation marks, a smooth cavitation boundary, a colour bar from 0, the whole body
in view, one colour scale for a series.

pyvista.compare_images gives the mean absolute pixel difference; re-rendering the same
film gives 0, a different film (eps 0.6 -> 0.8) several thousand: the threshold of 300
(within pyvista's own 200-500 defaults) leaves room for other VTK builds' noise. Baselines:
tests/baseline/film-*.png, made by this test's _render (review them when they change).
"""
from pathlib import Path

import numpy as np
import pytest

pv = pytest.importorskip("pyvista")

from bearingfem import JournalState, solve_reynolds  # noqa: E402
from bearingfem.outputs.render import _boundary_lines, render_film, unwrapped_figure  # noqa: E402
from conftest import table1_bearing  # noqa: E402

BASE = Path(__file__).parent / "baseline"
THRESHOLD = 300.0


def _render(tmp, eps, surface):
    sol = solve_reynolds(table1_bearing(1.0), JournalState(eps, omega=250.0), 48, 8)
    return render_film(sol, tmp / f"{surface}-{eps}.png", surface=surface, window_size=(400, 300))


@pytest.mark.parametrize("surface", ["journal", "unwrapped"])
def test_render_matches_baseline(tmp_path, surface):
    img = _render(tmp_path, 0.6, surface)
    base = BASE / f"film-{surface}.png"
    assert base.is_file(), f"missing baseline {base}"
    assert pv.compare_images(str(img), str(base)) < THRESHOLD
    other = _render(tmp_path, 0.8, surface)
    assert pv.compare_images(str(other), str(base)) > THRESHOLD


@pytest.mark.parametrize("surface", ["journal", "unwrapped"])
def test_a_film_without_pressure_renders(tmp_path, surface):
    """A centred journal (eps 0) carries no pressure: no cavity boundary to draw. It
    stopped in pyvista ('negative dimensions are not allowed') drawing an empty line."""
    sol = solve_reynolds(table1_bearing(1.0), JournalState(0.0, omega=250.0), 24, 4)
    assert sol.pressure_max == 0.0 and _boundary_lines(sol) == []
    path = render_film(sol, tmp_path / f"{surface}.png", surface=surface,
                       window_size=(200, 150))
    assert Path(path).stat().st_size > 0


def test_render_rejects_unknown_field(tmp_path):
    sol = solve_reynolds(table1_bearing(1.0), JournalState(0.6, omega=250.0), 24, 4)
    with pytest.raises(ValueError, match="field"):
        render_film(sol, tmp_path / "x.png", field="temperature")


def test_unwrapped_map_is_oriented_and_its_cavity_boundary_is_smooth():
    sol = solve_reynolds(table1_bearing(1.0), JournalState(0.6, omega=250.0), 48, 8)
    fig = unwrapped_figure(sol)
    ax, cax = fig.axes
    assert "theta from the maximum film [deg]" in ax.get_xlabel() and ax.get_ylabel() == "z [mm]"
    # a margin either side: the maximum film (theta = 0 and 360, the seam) is not on the edge
    assert ax.get_xlim() == (-6.0, 366.0)
    seam = [ln for ln in ax.get_lines() if list(ln.get_xdata()) in ([0.0, 0.0], [360.0, 360.0])]
    assert len(seam) == 2
    names = [t.get_text() for t in ax.get_legend().get_texts()]
    for name in ("maximum film", "minimum film (eccentricity)", "load line",
                 "cavitation boundary (p = 0)", "cavitated", "peak pressure"):
        assert name in names
    assert "inertial" in ax.get_title() and "attitude" in ax.get_title()
    ticks = [t.get_text() for t in cax.get_yticklabels()]
    assert ticks[0] == "0" and "e-0" not in "".join(ticks)      # no 2.32e-06 crowding 0
    # the free boundary is an isoline, not the element staircase: few of its segments run
    # along the mesh lines (the staircase of the old render had nothing else)
    lines = _boundary_lines(sol)
    seg = np.concatenate([np.diff(line, axis=0) for line in lines])
    seg = seg[np.hypot(*seg.T) > 1e-9]
    aligned = (np.abs(seg[:, 0]) < 1e-6) | (np.abs(seg[:, 1]) < 1e-6)
    assert len(seg) > 50 and aligned.mean() < 0.2


def test_long_journal_fits_in_view_beside_its_colour_bar(tmp_path):
    from PIL import Image
    sol = solve_reynolds(table1_bearing(2.0), JournalState(0.6, omega=250.0), 48, 16)
    path = render_film(sol, tmp_path / "long.png", window_size=(600, 450))
    img = np.asarray(Image.open(path).convert("L"), float)
    h, w = img.shape
    body = img[int(0.08 * h):, : int(0.80 * w)]          # below the title, left of the bar
    assert (body[-3:] > 250).all(), "the body is cut off at the bottom"
    gap = img[int(0.2 * h):, int(0.80 * w): int(0.84 * w)]     # below the bar's title
    assert (gap > 250).all(), "body and colour bar touch"
    assert (body < 200).mean() > 0.1                      # and there is a body


def test_a_series_shares_one_colour_scale(monkeypatch, tmp_path):
    from mechanism import film_history as fh

    class Frame:
        def __init__(self, sol, t):
            self.solution, self.t, self.crank_angle_deg = sol, t, 10.0 * t
    sols = [solve_reynolds(table1_bearing(1.0), JournalState(e, omega=250.0), 24, 4)
            for e in (0.3, 0.8)]
    seen = []
    monkeypatch.setattr("bearingfem.outputs.render.render_film",
                        lambda sol, path, **kw: seen.append(kw) or path)
    fh.render_history([Frame(s, k) for k, s in enumerate(sols)], tmp_path, gif=False,
                      fixed_camera=True)
    top = max(s.pressure_max for s in sols) * 1e-6
    assert [kw["clim"] for kw in seen] == [(0.0, pytest.approx(top))] * 2
    assert seen[0]["camera_angle"] == seen[1]["camera_angle"] is not None


def test_cavity_is_shaded_over_the_end_rows():
    """The cavitated region runs to the ends of the map: the end nodes take their inside
    neighbour's value for the picture, so the shading covers the end rows (old: left out,
    they showed as dark bands across the cavity, clearest on a whole-length film with few
    rows)."""
    from bearingfem.outputs.render import _cavity, film_map
    sol = solve_reynolds(table1_bearing(1.0), JournalState(0.6, omega=250.0), 48, 4)
    tri, vals = film_map(sol, "pressure")
    fine, fine_vals, edge = _cavity(sol, tri, vals)
    zmax = float(np.max(np.abs(tri.y)))
    inside = np.sort(np.unique(np.round(np.abs(tri.y), 9)))[-2]
    deep = np.abs(fine.x - 270.0) < 20.0            # the cavity's middle (eps 0.6)
    end_rows = np.abs(fine.y) > 0.5 * (inside + zmax)
    assert np.any(deep & end_rows)
    assert np.all(fine_vals[deep & end_rows] <= edge)
    full = np.abs(fine.x - 150.0) < 10.0            # the full film: no boundary on the ends
    assert np.all(fine_vals[full & end_rows] > edge)


def test_negative_pressure_is_on_the_colour_scale(tmp_path):
    """The full Sommerfeld film (cavitation "none") has a suction half: the colour bar goes
    down to its least pressure (both surfaces) instead of drawing it as 0, as it did."""
    from bearingfem.outputs.render import color_range
    sol = solve_reynolds(table1_bearing(1.0), JournalState(0.6, omega=250.0), 24, 4,
                         cavitation="none")
    least = float(np.min(sol.pressure)) * 1e-6
    assert least < -1.0                                   # MPa: a real suction half
    fig = unwrapped_figure(sol)
    bar = fig.axes[1]                                     # the colour bar's axes
    assert bar.get_ylim()[0] == pytest.approx(least, rel=1e-9)
    assert color_range("pressure", sol.pressure * 1e-6) == pytest.approx(
        (least, sol.pressure_max * 1e-6))
    # a cavitating film and a series' fixed scale keep theirs
    cav = solve_reynolds(table1_bearing(1.0), JournalState(0.6, omega=250.0), 24, 4)
    assert color_range("pressure", cav.pressure * 1e-6)[0] == 0.0
    assert color_range("pressure", cav.pressure, clim=(0.0, 5.0)) == (0.0, 5.0)
    render_film(sol, tmp_path / "none.png", window_size=(400, 300))


def test_the_journal_view_scales_from_the_suction_pressure(tmp_path, monkeypatch):
    """The journal surface's colour scale starts at the full Sommerfeld film's least
    pressure, as the unwrapped map's does (it started at 0 there too)."""
    sol = solve_reynolds(table1_bearing(1.0), JournalState(0.6, omega=250.0), 24, 4,
                         cavitation="none")
    real, clims = pv.Plotter.add_mesh, []

    def recorded(self, mesh, *args, **kwargs):
        if "clim" in kwargs:
            clims.append(kwargs["clim"])
        return real(self, mesh, *args, **kwargs)
    monkeypatch.setattr(pv.Plotter, "add_mesh", recorded)
    render_film(sol, tmp_path / "journal.png", window_size=(300, 200))
    assert clims == [pytest.approx((np.min(sol.pressure) * 1e-6, sol.pressure_max * 1e-6),
                                   rel=1e-9)]
