"""Design charts in the style of Raimondi & Boyd, from a Dask sweep of steady films.

    python -m studies.design_charts -o results/design [--sweep sweeps/design-chart.toml]

Writes the sweep's cases and results.csv, then design-chart.png (eps, attitude angle,
friction variable (R/c) f and flow variable Q/(R c N L) against the Sommerfeld number)
and design-coefficients.png (K c / W and C c omega / W in the load frame: axis 1 along the
load, axis 2 turned +90 deg in the sense of rotation), one line per L/D, with error bars
(each entry's estimated discretisation error, ``coefficients(estimate=True)``) where they
are larger than the line (:data:`BAR_FROM`).
"""
from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from bearingfem_app.sweep import load_sweep, run_sweep

DEFAULT_SWEEP = Path(__file__).resolve().parent.parent / "sweeps" / "design-chart.toml"

PANELS = [("eps", "eccentricity ratio eps [-]", "linear"),
          ("attitude_deg", "attitude angle [deg]", "linear"),
          ("friction_variable", "friction variable (R/c) f [-]", "log"),
          ("flow_variable", "side flow Q_s / (R c N L) [-]", "linear")]


#: An entry's error bar is drawn where it is larger than the line: its relative error
#: above this (a 1.5 pt line on a panel ~4 decades over ~300 pt is ~2 % of a value)
BAR_FROM = 0.02


def error_bars(values, errors):
    """(mask, errors) of the points whose error bar would show: |error| > BAR_FROM |value|
    (rows without errors, e.g. a closed-form model's: none)."""
    v = np.abs(np.asarray(values, float))
    e = np.asarray([np.nan if x in ("", None) else x for x in errors], float)
    return np.nan_to_num(e, nan=0.0) > BAR_FROM * v, e


def _by_ld(rows):
    groups = {}
    for r in rows:
        groups.setdefault(r["length_ratio"], []).append(r)
    return {ld: sorted(rs, key=lambda r: r["sommerfeld"]) for ld, rs in sorted(groups.items())}


def plot_design_charts(rows, out) -> list[Path]:
    """The two chart figures from the sweep's rows; returns their paths."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    out = Path(out)
    groups = _by_ld(rows)
    title = (f"plain bearing, {rows[0].get('model', '')} "
             f"{rows[0].get('element', '')} {rows[0].get('cavitation', '')} "
             "(full film periodic, ambient ends)")
    fig, axes = plt.subplots(2, 2, figsize=(10, 7.5), constrained_layout=True)
    for ax, (key, label, scale) in zip(axes.ravel(), PANELS):
        for ld, rs in groups.items():
            pts = [(r["sommerfeld"], r[key]) for r in rs if r.get(key, "") != ""]
            if pts:
                ax.plot(*zip(*pts), "o-", ms=3, label=f"L/D = {ld:g}")
        ax.set(xscale="log", yscale=scale, xlabel="Sommerfeld number S = (R/c)^2 mu N / P [-]",
               ylabel=label)
        ax.grid(True, which="both", alpha=0.3)
    axes[0, 0].legend()
    fig.suptitle(title, fontsize=10)
    p1 = out / "design-chart.png"
    fig.savefig(p1, dpi=110)
    plt.close(fig)

    fig, axes = plt.subplots(2, 4, figsize=(14, 6.5), constrained_layout=True)
    for row, (name, unit) in enumerate((("K", "K c / W"), ("C", "C c omega / W"))):
        for col, ij in enumerate(("11", "12", "21", "22")):
            ax = axes[row, col]
            for ld, rs in groups.items():
                S = np.array([r["sommerfeld"] for r in rs])
                v = np.array([r[f"{name}{ij}"] for r in rs])
                line, = ax.plot(S, np.abs(v), "-", label=f"L/D = {ld:g}")
                ax.plot(S[v >= 0], v[v >= 0], "o", ms=3, color=line.get_color())
                ax.plot(S[v < 0], -v[v < 0], "o", ms=4, mfc="none", color=line.get_color())
                show, err = error_bars(v, [r.get(f"{name}{ij}_error") for r in rs])
                if show.any():    # the estimate, clipped above zero on the log axis
                    lo = np.minimum(err[show], 0.999 * np.abs(v[show]))
                    ax.errorbar(S[show], np.abs(v[show]), yerr=[lo, err[show]], fmt="none",
                                capsize=2, lw=0.8, color=line.get_color())
            ax.set(xscale="log", yscale="log", xlabel="Sommerfeld number S [-]",
                   ylabel=f"|{unit}|, {name}_{ij} [-]")
            ax.grid(True, which="both", alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    fig.suptitle(title + "; load frame: 1 along the load, 2 turned +90 deg; "
                 "open markers: negative values; bars: estimated mesh error where "
                 f"above {100 * BAR_FROM:g} %", fontsize=10)
    p2 = out / "design-coefficients.png"
    fig.savefig(p2, dpi=110)
    plt.close(fig)
    return [p1, p2]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                 formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    ap.add_argument("-o", "--output", default="results/design", help="output directory")
    ap.add_argument("--sweep", default=str(DEFAULT_SWEEP), help="design sweep TOML")
    ap.add_argument("--workers", type=int, default=2, help="local Dask workers")
    ap.add_argument("--scheduler", help="address of a running Dask scheduler")
    args = ap.parse_args(argv)
    sweep = load_sweep(args.sweep)
    if sweep.kind != "design":
        ap.error(f"--sweep must be a sweep of kind 'design', got {sweep.kind!r}")
    res = run_sweep(sweep, args.output, scheduler=args.scheduler, workers=args.workers)
    rows = [dict(r, eps=r["eps"]) for r in res.rows]
    paths = plot_design_charts(rows, args.output)
    print(f"{len(rows)} cases ({res.computed} computed); wrote "
          f"{Path(args.output) / 'results.csv'}, " + ", ".join(map(str, paths)))
    return 1 if res.failed else 0


if __name__ == "__main__":
    raise SystemExit(main())
