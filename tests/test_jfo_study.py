"""The Reynolds-vs-JFO study of the seed's piston pin runs and says what it found."""
from types import SimpleNamespace

import numpy as np
import pytest

from studies import jfo_paper


def test_jfo_paper_study_smoke(tmp_path, capsys):
    rows, forms, collapses, per_bin = jfo_paper.main(["-o", str(tmp_path), "--turns", "0.3",
                                             "--no-progress"])
    out = capsys.readouterr().out
    assert [r["film"] for r in rows] == ["FE, Reynolds' condition", "FE, JFO"]
    assert "JFO cavity forms at crank" in out and "cost JFO / Reynolds" in out
    assert (tmp_path / "jfo_paper.png").stat().st_size > 10_000
    assert (tmp_path / "jfo_paper_films.png").stat().st_size > 10_000
    assert all(0.0 < r["peak_eps"] < 1.0 for r in rows)
    assert all(r["friction_power_W"] > 0.0 for r in rows)     # shear dissipates power
    # peaks of the smooth curve, the raw maxima beside them (0.3 turn from rest: the
    # start's impact, a few samples, is most of the raw peak)
    assert all(0.0 < r["peak_force_N"] <= 1.01 * r["peak_force_raw_N"]
               and r["force_jitter_rms_N"] > 0.0 for r in rows)
    assert "force jitter RMS / max [N]" in out
    # a run shorter than a turn is recorded whole: every accepted step up to the last
    # saved sample (within 1/720 turn of the end) is counted in its crank-angle interval
    # (0.3 turn: the first four)
    for h, r in zip(per_bin.values(), rows):
        assert 0.95 * r["steps"] <= h.sum() <= r["steps"] and h[4:].sum() == 0


def fake_run(force, n=720, omega=250.0):
    """A result-like record of one turn at ``n`` samples with joint force ``force`` [N]."""
    t = np.arange(n) * 2 * np.pi / omega / n
    return SimpleNamespace(t=t, crank_angle=omega * t + 8 * np.pi, rod_angle=0.1 * np.sin(omega * t),
                           force_x=force, force_y=np.zeros(n), eps=np.full(n, 0.5),
                           film_min=np.full(n, 1e-5),
                           stats=dict(wall_time=1.0, steps=10, film_solves=10))


def test_study_reports_peaks_of_the_smooth_curve():
    """The table's peak force and pressure are the smooth curve's (a local quadratic over
    15 deg), the raw maxima beside them: a single-sample spike of 500 N on a smooth force
    raises the raw peak by 500 N and the reported one by its share of the fit (its centre
    weight of the 31 samples, 0.073: 36 N). Fails if the study reports the raw maximum."""
    q = np.arange(720) * 0.5
    smooth = 2000 + 1000 * np.cos(np.radians(q - 180.0))
    spiked = smooth.copy()
    spiked[360] += 500.0
    r = fake_run(spiked)
    frame = SimpleNamespace(t=0.0, solution=SimpleNamespace(friction_force=1.0))
    p = jfo_paper.pressure_jitter(r.t, 1e6 * spiked, r)
    w = jfo_paper.row("test", r, [frame], 0.01, p)
    centre = 3 * (3 * 31 ** 2 - 7) / (4 * 31 * (31 ** 2 - 4))
    assert w["peak_force_raw_N"] == pytest.approx(3500.0)
    assert w["peak_force_N"] == pytest.approx(3000.0 + 500.0 * centre, rel=1e-4)
    assert w["peak_pressure_raw_MPa"] == pytest.approx(3500.0)
    assert w["peak_pressure_MPa"] == pytest.approx(3000.0 + 500.0 * centre, rel=1e-4)
    # the spike is the jitter: its residual 500 (1 - centre) N, RMS over the turn
    assert w["force_jitter_max_N"] == pytest.approx(500.0 * (1 - centre), rel=1e-3)
