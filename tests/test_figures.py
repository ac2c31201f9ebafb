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


def test_curves_that_agree_stay_apart(tmp_path):
    """Two runs that agree (FE and FV films: the curves overlap) are drawn each in its own
    colour, width and markers at its own crank angles, so that both can be told apart
    (old: a dashed and a dotted line of the default cycle on top of each other); the film
    axis says um as \u00b5m and has no unlabelled tick."""
    sc = load_scene("paper-short-analytic")
    sc = replace(sc, run=replace(sc.run, turns=0.5, record_from_turn=0.0))
    r = simulate(sc, progress=False)
    fig = plot_comparison([r, r, r], ["analytic", "fem", "fvm"], sc.bearing.clearance)
    film = fig.axes[0]
    a, b, c = film.lines[:3]
    assert len({ln.get_color() for ln in (a, b, c)}) == 3
    assert len({ln.get_linewidth() for ln in (a, b, c)}) == 3
    assert b.get_marker() not in ("", "None") and c.get_marker() not in ("", "None")
    assert b.get_marker() != c.get_marker() and b.get_markevery() != c.get_markevery()
    assert "\u00b5m" in film.get_ylabel()
    fig.canvas.draw()
    assert all(t.get_text() for t in film.get_yticklabels())
    import matplotlib.pyplot as plt

    from mechanism.figures import label_log_axis
    fig, ax = plt.subplots()                 # within one decade: labelled ticks only
    ax.set(yscale="log", ylim=(10.02, 20.7))
    label_log_axis(ax.yaxis)
    fig.canvas.draw()
    assert len(ax.yaxis.get_minorticklocs()) == 0
    assert [t.get_text() for t in ax.get_yticklabels()] == ["12", "14", "16", "18", "20"]
    plt.close("all")
