"""Figures of mechanism runs (matplotlib, Agg: no display needed)."""
from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from pathlib import Path  # noqa: E402

from .result import SimulationResult  # noqa: E402

__all__ = ["plot_run", "plot_comparison", "label_log_axis", "render_deflection"]

#: Films thinner than this [um] (contact) are drawn at it on the log axis.
FILM_FLOOR_UM = 1e-3
#: One look per curve of a comparison: colour, line style, width (the first widest, so a
#: curve drawn over it leaves it visible) and marker.
COLOURS = ("0.25", "tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple")
STYLES = ("-", "--", ":", "-.")
WIDTHS = (3.0, 1.8, 1.4, 1.2)
MARKERS = ("", "o", "x", "s", "^", "D")


def label_log_axis(axis) -> None:
    """Readable labels on a log axis (``ax.yaxis``) whatever its span: 1-2-5 per decade over
    several decades, plain round numbers within one (the default labels only the powers of
    ten, often one of them, or writes 1.9 x 10^1)."""
    from matplotlib import ticker
    lo, hi = sorted(axis.get_view_interval())
    if hi / lo < 10.0:
        ticks = [t for t in ticker.MaxNLocator(6).tick_values(lo, hi) if lo <= t <= hi and t > 0]
        axis.set_minor_locator(ticker.NullLocator())   # log minor ticks here: unlabelled
    else:
        ticks = [t for t in ticker.LogLocator(subs=(1.0, 2.0, 5.0)).tick_values(lo, hi)
                 if lo <= t <= hi]
        if len(ticks) > 12:    # four decades or more: the powers of ten are enough
            ticks = [t for t in ticker.LogLocator().tick_values(lo, hi) if lo <= t <= hi]
    axis.set_major_locator(ticker.FixedLocator(ticks))
    axis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    axis.set_minor_formatter(ticker.NullFormatter())


def _crank_deg(r: SimulationResult):
    """Crank angle [deg] from the start of the first recorded turn (round-off safe)."""
    base = np.floor(r.crank_angle[0] / (2 * np.pi) + 1e-9)
    return np.degrees(r.crank_angle - 2 * np.pi * base)


def plot_comparison(results, labels, clearance, title="", path=None):
    """Seed Figs. 2-7 style: film thickness, orbit, forces X/Y, crank speed, slider
    acceleration, one curve per result, against crank angle over the recorded turn."""
    fig, ax = plt.subplots(2, 3, figsize=(15, 8.5))
    for i, (r, lab) in enumerate(zip(results, labels)):
        if len(r.t) == 0:
            continue
        deg = _crank_deg(r)
        lab = lab + (" (partial)" if r.partial else "")
        # curves that agree lie on top of each other: each its own colour, width and
        # markers at its own crank angles, so that each stays visible where they overlap
        n = max(len(deg), 1)
        every = max(n // 12, 1)
        style = dict(color=COLOURS[i % len(COLOURS)], ls=STYLES[i % len(STYLES)],
                     lw=WIDTHS[i % len(WIDTHS)], marker=MARKERS[i % len(MARKERS)], ms=5,
                     markevery=(min(i * every // max(len(results), 1), n - 1), every),
                     label=lab)
        # log scale: 0.1-0.25 um near the wall must stay readable beside 10 um
        ax[0, 0].plot(deg, np.maximum(r.film_min * 1e6, FILM_FLOOR_UM), **style)
        dense = len(r.dense_t) > len(r.t)      # the integrator's own interpolant
        ex, ey = (r.dense_e_x, r.dense_e_y) if dense else (r.e_x, r.e_y)
        ax[0, 1].plot(ex / clearance, ey / clearance,
                      **{**style, "markevery": max(len(ex) // 12, 1)})
        ax[0, 2].plot(deg, r.force_x, **style)
        ax[1, 0].plot(deg, r.force_y, **style)
        ax[1, 1].plot(deg, r.crank_speed, **style)
        ax[1, 2].plot(deg, r.slider_acceleration, **style)
    circle = np.linspace(0, 2 * np.pi, 361)
    ax[0, 1].plot(np.cos(circle), np.sin(circle), "k", lw=0.8)
    ax[0, 1].set_aspect("equal")
    ax[0, 1].set(xlabel="e_x / c (slider axis)", ylabel="e_y / c", title="pin orbit in the clearance")
    ax[0, 0].set(ylabel="minimum film thickness [\u00b5m] (log)", title="film thickness",
                 yscale="log")
    ax[0, 2].set(ylabel="joint force on pin F_x [N]", title="force, X (slider axis)")
    ax[1, 0].set(ylabel="joint force on pin F_y [N]", title="force, Y")
    ax[1, 1].set(ylabel="crank speed [rad/s]", title="crank angular speed")
    ax[1, 2].set(ylabel="slider acceleration [m/s^2]", title="slider acceleration")
    # a run stopped early has no whole recorded turn: say what the axis holds instead
    stopped = [r for r in results if r.partial]
    xlabel = ("crank angle [deg], up to where the run stopped (partial)" if stopped
              else "crank angle in the recorded turn [deg]")
    for a in (ax[0, 0], ax[0, 2], ax[1, 0], ax[1, 1], ax[1, 2]):
        a.set_xlabel(xlabel)
        a.set_xlim(0, 360)
        a.grid(alpha=0.3)
    ax[0, 1].grid(alpha=0.3)
    if any(len(r.t) for r in results):
        label_log_axis(ax[0, 0].yaxis)
    handles, names = ax[0, 0].get_legend_handles_labels()
    # one legend for all six panels, below them
    fig.legend(handles, names, loc="lower center", ncol=max(len(names), 1), fontsize=9,
               frameon=False)
    fig.suptitle(title + "".join(f"\n{r.scene}: PARTIAL, {r.message}" for r in stopped))
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    if path is not None:
        fig.savefig(path, dpi=110)
        plt.close(fig)
    return fig


def plot_run(r: SimulationResult, clearance, path=None):
    return plot_comparison([r], [r.scene], clearance or 1.0, title=r.scene, path=path)


def render_deflection(sol, state, path, title=None) -> Path:
    """The bush deflection [um] and film pressure [MPa] of the elastic film ``sol`` (a
    FilmSolution with its ``deformation``) over the unwrapped film to ``path`` (its
    folder made). ``state``: the journal state (its eps titles the figure, unless
    ``title``). Returns the path."""
    if sol.deformation is None:
        raise ValueError("sol has no deformation (a rigid film): no bush deflection to draw")
    theta, z = np.degrees(np.asarray(sol.theta)), 1e3 * np.asarray(sol.z)
    fig, ax = plt.subplots(2, 1, figsize=(7, 5), sharex=True)
    for a, v, label in ((ax[0], 1e6 * np.asarray(sol.deformation), "bush deflection w [um]"),
                        (ax[1], np.asarray(sol.pressure) / 1e6, "film pressure [MPa]")):
        c = a.tricontourf(theta, z, v, levels=20)
        fig.colorbar(c, ax=a, label=label)
        a.set_ylabel("z [mm]")
    ax[1].set_xlabel("film angle from the largest gap [deg]")
    ax[0].set_title(title or f"EHD film at the peak joint load (eps {state.eps:.4f})")
    fig.tight_layout()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
