"""What the pictures of the command line show: checks a test can see (each run against the
old picture code, which fails it as its docstring says)."""
from dataclasses import replace

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402

from bearingfem import JournalState, solve_reynolds  # noqa: E402
from bearingfem.outputs.render import unwrapped_figure  # noqa: E402
from conftest import table1_bearing  # noqa: E402


def _pixel(fig, ax, x, y):
    fig.canvas.draw()
    img = np.asarray(fig.canvas.buffer_rgba())[..., :3]
    px, py = ax.transData.transform((x, y))
    return img[img.shape[0] - int(py), int(px)]


def test_jfo_fraction_map_colours_the_full_film():
    """The full film (fraction 1, around the load line) takes the colour bar's top colour;
    the old filled contours left it white, like missing data."""
    sol = solve_reynolds(table1_bearing(1.0), JournalState(0.6, omega=250.0), 48, 8,
                         cavitation="jfo", ambient_pressure=1e5)
    fig = unwrapped_figure(sol, "fraction", size=(9.0, 5.0))
    ax = fig.axes[0]
    theta = np.degrees(sol.pressure_max_theta)        # inside the full film
    assert sol.fraction.max() == 1.0
    rgb = _pixel(fig, ax, theta + 10.0, 0.0)
    top = np.round(255 * np.array(matplotlib.colormaps["viridis"](1.0)[:3]))
    assert np.abs(rgb.astype(float) - top).max() < 30, rgb
    names = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "film ruptures (fraction < 1)" in names


def test_convergence_title_is_not_cut(tmp_path):
    """The case went on the title's one line and ran off the figure."""
    from bearingfem.outputs.convergence import convergence_study
    import matplotlib.pyplot as plt
    st = convergence_study(table1_bearing(1.0), JournalState(0.6, omega=250.0), levels=3,
                           n_theta=12, n_z=2, methods=("P1",))
    captured = {}
    real = plt.Figure.savefig

    def keep(fig, *a, **k):
        fig.canvas.draw()
        captured["fig"] = fig
        return real(fig, *a, **k)
    plt.Figure.savefig = keep
    try:
        st.plot(tmp_path / "c.png")
    finally:
        plt.Figure.savefig = real
    fig = captured["fig"]
    box = fig.axes[0].title.get_window_extent()
    assert box.x0 >= 0 and box.x1 <= fig.bbox.width


def _run():
    from mechanism.result import SimulationResult
    t = np.linspace(0.0, 0.025, 200)
    angle = 2 * np.pi * t / 0.025
    film = 1e-5 * (1.05 + np.cos(angle)) ** 2 + 2e-8        # 20 um down to 0.02 um
    z = np.zeros_like(t)
    return SimulationResult(t=t, crank_angle=angle, crank_speed=z + 250.0, rod_angle=z,
                            slider_position=z, slider_acceleration=z, eps=z, e_x=z, e_y=z,
                            film_min=film, force_x=z, force_y=z, scene="test", stats={})


def test_log_film_axis_has_labels_in_every_decade():
    """Three decades of film had one labelled tick (the default log formatter); now 1-2-5."""
    from mechanism.figures import plot_run
    import matplotlib.pyplot as plt
    fig = plot_run(_run(), 2e-5)
    fig.canvas.draw()
    ax = fig.axes[0]
    lo, hi = ax.get_ylim()
    shown = [t.get_text() for t in ax.get_yticklabels()
             if t.get_text() and lo <= t.get_position()[1] <= hi]
    plt.close(fig)
    assert len(shown) >= 5 and "0.1" in shown and "10" in shown


def test_partial_run_axis_says_partial():
    """An interrupted run has no whole recorded turn; the axis claimed one."""
    from mechanism.figures import plot_run
    import matplotlib.pyplot as plt
    fig = plot_run(replace(_run(), partial=True, message="interrupted at t = 0.01 s"), 2e-5)
    assert "partial" in fig.axes[0].get_xlabel()
    assert "interrupted" in fig._suptitle.get_text()
    plt.close(fig)


def test_sweep_summary_one_colormap_and_the_cavitation():
    """Nine lines took nine unrelated colours, and the cavitation model was not said."""
    import matplotlib.pyplot as plt
    from bearingfem_app.sweep import load_sweep, plot_summary, sweep_cases
    sw = load_sweep("capacity")
    factor = {"fem": 1, "short": 2, "long": 3}
    rows = [{**p, "force": p["length_ratio"] * p["eps"] * factor[p["model"]]}
            for p in sweep_cases(sw)]
    fig = plot_summary(rows, sw, None)
    lines = fig.axes[0].get_lines()
    cmap = matplotlib.colormaps["viridis"]
    palette = [np.array(cmap(v)[:3]) for v in np.linspace(0, 1, 256)]
    for ln in lines:
        c = np.array(matplotlib.colors.to_rgb(ln.get_color()))
        assert min(np.abs(c - p).max() for p in palette) < 0.01
    # same L/D, same colour; the model by line style
    by_ld = {}
    for ln in lines:
        by_ld.setdefault(ln.get_label().split(",")[0], set()).add(ln.get_color())
    assert len(by_ld) == 3 and all(len(c) == 1 for c in by_ld.values())
    assert "cavitation gumbel" in fig._suptitle.get_text()
    plt.close(fig)
