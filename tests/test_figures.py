"""Run figures: minimum film on a log axis, one legend for all panels, the orbit from the
integrator's dense output."""
from dataclasses import replace

import numpy as np

from mechanism import load_scene, simulate
from mechanism.figures import plot_comparison


def test_run_figure_reads_at_a_glance(tmp_path):
    sc = load_scene("paper-short-analytic")
    sc = replace(sc, run=replace(sc.run, turns=0.5, record_from_turn=0.0))
    r = simulate(sc, progress=False)
    assert len(r.dense_t) == 10 * (len(r.t) - 1) + 1
    fig = plot_comparison([r, r], ["a", "b"], sc.bearing.clearance)
    film, orbit = fig.axes[0], fig.axes[1]
    assert film.get_yscale() == "log"
    assert len(fig.legends) == 1 and [t.get_text() for t in fig.legends[0].get_texts()] == ["a", "b"]
    assert all(a.get_legend() is None for a in fig.axes)
    x, y = orbit.lines[0].get_data()
    assert len(x) == len(r.dense_t)
    np.testing.assert_allclose(x[::10], r.e_x / sc.bearing.clearance, rtol=1e-9, atol=1e-12)
    r.save(tmp_path / "run")
    from mechanism import load_result
    back = load_result(tmp_path / "run")
    np.testing.assert_array_equal(back.dense_e_y, r.dense_e_y)
    # where the integrator's steps went: one time per accepted step, kept with the run
    assert len(r.step_t) == r.stats["steps"] and np.all(np.diff(r.step_t) > 0)
    assert r.t[-1] <= r.step_t[-1] < r.t[-1] + 2 * np.pi / sc.crank_speed / sc.run.samples_per_turn
    np.testing.assert_array_equal(back.step_t, r.step_t)
