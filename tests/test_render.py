"""Off-screen renders, checked against stored baselines with a tolerance for renderer noise.

pyvista.compare_images gives the mean absolute pixel difference; re-rendering the same
film gives 0, a different film (eps 0.6 -> 0.8) ~3000-3500: the threshold of 300 (within
pyvista's own 200-500 defaults) leaves room for other VTK builds' noise. Baselines:
tests/baseline/film-*.png, made by this test's _render (review them when they change).
"""
from pathlib import Path

import pytest

pv = pytest.importorskip("pyvista")

from bearingfem import JournalState, solve_reynolds  # noqa: E402
from bearingfem.outputs.render import render_film  # noqa: E402
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


def test_render_rejects_unknown_field(tmp_path):
    sol = solve_reynolds(table1_bearing(1.0), JournalState(0.6, omega=250.0), 24, 4)
    with pytest.raises(ValueError, match="field"):
        render_film(sol, tmp_path / "x.png", field="temperature")
