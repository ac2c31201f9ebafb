"""Reynolds' condition against the mass-conserving (JFO) film for the seed's piston pin.

    python -m studies.jfo_paper -o results/jfo_paper [--ld 0.2] [--turns 5]

Runs the seed's scene (``paper-short-fem`` or ``paper-long-fem`` by L/D) with the FE film
under Reynolds' condition, and the same scene with the JFO film (``paper-*-jfo``: same
mesh, oil at atmospheric pressure around a cavity near zero absolute), both over the JFO
scene's turns (the long bearing's JFO film settles only by the ninth turn). Prints a
table over the recorded turn (peak eccentricity, minimum film, peak joint force and peak
film pressure from their smooth curves with the raw maxima beside them, the joint force's
jitter about its curve, friction power of the films at 72 crank angles, wall time,
steps), where the
JFO film's cavity forms and collapses (crank angles) and where each run's integrator spent
its steps (per 30 deg of crank over the recorded turn), and writes ``jfo_paper.csv``,
``jfo_paper_steps.csv``, ``jfo_paper.png`` (orbits, minimum film, cavitated share, peak
pressure, steps and the mass balance against the crank angle) and
``jfo_paper_films.png`` (the JFO film fraction at eight crank angles).
"""
from __future__ import annotations

import argparse
import dataclasses
from pathlib import Path

import numpy as np

from bearingfem.outputs.signal import Smoothing, jitter
from bearingfem.outputs.tables import write_csv
from mechanism import load_scene, simulate
from mechanism.film_history import film_history
from mechanism.result import film_column


def scenes(ld: float, turns: float | None):
    """The Reynolds-condition FE scene of the seed and its JFO twin (``turns``: shorter
    runs, the last turn recorded)."""
    name = "short" if ld <= 0.5 else "long"
    fem, jfo = load_scene(f"paper-{name}-fem"), load_scene(f"paper-{name}-jfo")
    lub = dataclasses.replace(fem.lubrication,
                              options=dict(fem.lubrication.options, cavitation="reynolds"))
    # the same turns and recorded turn as the JFO scene (whose film may settle later)
    fem = dataclasses.replace(fem, name=f"paper-{name}-reynolds", lubrication=lub,
                              run=jfo.run)
    if turns is None:
        return fem, jfo

    def shorter(sc):
        return dataclasses.replace(sc, run=dataclasses.replace(
            sc.run, turns=turns, record_from_turn=max(0.0, turns - 1.0)))
    return shorter(fem), shorter(jfo)


def cavity_events(record: np.ndarray, crank_at) -> tuple[list, list]:
    """Crank angles [deg] where the JFO cavity forms (its share rises from below 1 % of
    the film) and where it collapses (falls below 1 %)."""
    share = film_column(record, "cavitated_fraction")
    on = share > 0.01
    rise = np.flatnonzero(~on[:-1] & on[1:]) + 1
    fall = np.flatnonzero(on[:-1] & ~on[1:]) + 1
    deg = lambda i: float(np.mod(np.degrees(crank_at(film_column(record, "t")[i])), 360.0))  # noqa: E731
    return [deg(i) for i in rise], [deg(i) for i in fall]


def steps_by_crank_angle(r, bins: int = 12) -> np.ndarray:
    """Accepted steps of the recorded turn in ``bins`` equal crank-angle intervals."""
    t = r.step_t[(r.step_t >= r.t[0]) & (r.step_t <= r.t[-1])]
    q = np.mod(np.degrees(np.interp(t, r.t, r.crank_angle)), 360.0)
    return np.histogram(q, bins=bins, range=(0.0, 360.0))[0]


def friction_power(result, frames, radius: float) -> float:
    """Mean friction power [W] over ``frames`` (evenly spaced crank angles): the journal's
    friction force times its surface speed relative to the bearing, R omega, with omega
    minus the rod's angular velocity (the friction force alone changes sign with omega)."""
    omega = -np.gradient(result.rod_angle, result.t)
    return float(np.mean([f.solution.friction_force * radius * np.interp(f.t, result.t, omega)
                          for f in frames]))


#: The smooth curve the joint force and peak pressure are measured against: a local
#: quadratic over 15 deg of crank (31 of the 720 samples a turn). Wide enough to average
#: the JFO film's film-step jitter (a film step is ~1.4 deg, a refill a single sample),
#: narrow enough not to cut the load-reversal peaks (docs/jfo.md: the residual of the
#: Reynolds-condition force and the smoothed peaks against the window).
SMOOTHING = Smoothing(window=15.0, order=2)


def crank_deg(r, t):
    """Crank angle [deg] of the recorded turn at times ``t`` (increasing, from its start)."""
    q = np.degrees(np.interp(t, r.t, r.crank_angle))
    return q - 360.0 * np.floor(q[0] / 360.0)


def away_from_reversals(q, smooth, margin: float = 10.0, level: float = 0.1):
    """Samples more than ``margin`` deg of crank from any where the smooth force is below
    ``level`` of its peak. At a load reversal the pin crosses the clearance and the squeeze
    film's impact is a real spike a degree or two wide in either film (Reynolds' condition
    too), which no 15-deg window resolves: it is left out of the jitter."""
    low = q[smooth < level * smooth.max()]
    gap = np.abs((q[:, None] - low[None, :] + 180.0) % 360.0 - 180.0)
    return ~np.any(gap <= margin, axis=1)


def force_jitter(r, smoothing: Smoothing = SMOOTHING):
    """The joint force's magnitude [N] over the saved samples about its smooth curve (a
    whole recorded turn is periodic: windows wrap), the jitter measured away from the load
    reversals."""
    q = crank_deg(r, r.t)
    period = 360.0 if q[-1] - q[0] >= 359.0 else None
    force = np.hypot(r.force_x, r.force_y)
    smooth = jitter(q, force, smoothing, period).smooth
    return jitter(q, force, smoothing, period, measured=away_from_reversals(q, smooth))


def pressure_jitter(t, pressure_max, r, smoothing: Smoothing = SMOOTHING):
    """The peak film pressure [Pa] at times ``t`` (film steps, or instants) about its
    smooth curve."""
    q = crank_deg(r, t)
    return jitter(q, pressure_max, smoothing, 360.0 if q[-1] - q[0] >= 359.0 else None)


def row(name, r, frames, radius, pressure):
    """One film's line of the table: peak force and pressure from the smooth curves (the
    raw maxima beside them, and the jitter: RMS and largest residual about the curve);
    friction from ``frames`` (the film at evenly spaced crank angles of the recorded turn);
    ``pressure`` the :class:`Jitter` of the peak film pressure."""
    f = force_jitter(r)
    return dict(film=name, peak_eps=float(r.eps.max()), film_min_um=1e6 * float(r.film_min.min()),
                peak_force_N=f.peak_smooth, peak_force_raw_N=f.peak_raw,
                force_jitter_rms_N=f.rms, force_jitter_max_N=f.max,
                peak_pressure_MPa=pressure.peak_smooth / 1e6,
                peak_pressure_raw_MPa=pressure.peak_raw / 1e6,
                friction_power_W=friction_power(r, frames, radius),
                wall_time_s=r.stats["wall_time"], steps=r.stats["steps"],
                film_solves=r.stats["film_solves"])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--output", default="results/jfo_paper")
    ap.add_argument("--ld", type=float, default=0.2, help="0.2 (short) or 2 (long)")
    ap.add_argument("--turns", type=float, default=None, help="shorter runs (default: "
                    "the scene's five turns, the last recorded)")
    ap.add_argument("--no-progress", action="store_true")
    a = ap.parse_args(argv)
    out = Path(a.output)
    out.mkdir(parents=True, exist_ok=True)
    fem, jfo = scenes(a.ld, a.turns)
    progress = False if a.no_progress else None
    r_fem = simulate(fem, progress=progress)
    r_jfo = simulate(jfo, progress=progress)
    for r in (r_fem, r_jfo):
        if r.partial:
            print(f"{r.scene}: {r.message}")
    # both films at the same 72 crank angles of the recorded turn (JFO: the film step
    # nearest each, its run replayed)
    frames = film_history(r_fem, fem, n_frames=72)
    frames_jfo = film_history(r_jfo, jfo, n_frames=72)
    rec = r_jfo.film_record
    rec = rec[film_column(rec, "t") >= r_jfo.t[0]] if len(r_jfo.t) else rec
    crank_at = lambda t: np.interp(t, r_jfo.t, r_jfo.crank_angle)   # noqa: E731
    R = fem.bearing.radius
    # peak pressure: Reynolds' condition (no memory) at 360 instants of the turn, the JFO
    # film at each of its film steps
    dense = film_history(r_fem, fem, n_frames=360)
    t_fem, first = np.unique([f.t for f in dense], return_index=True)   # a short run: fewer
    p_fem = pressure_jitter(t_fem, np.array([dense[i].solution.pressure_max for i in first]),
                            r_fem)
    p_jfo = pressure_jitter(film_column(rec, "t"), film_column(rec, "pressure_max"), r_jfo)
    rows = [row("FE, Reynolds' condition", r_fem, frames, R, p_fem),
            row("FE, JFO", r_jfo, frames_jfo, R, p_jfo)]
    forms, collapses = cavity_events(rec, crank_at)
    balance = float(np.max(np.abs(film_column(rec, "mass_balance")))) if len(rec) else 0.0
    print("| film | peak eps | min film [um] | peak force [N] (raw) | force jitter RMS / max "
          "[N] | peak pressure [MPa] (raw) | friction power [W] | wall time [s] | steps |")
    print("|---|---|---|---|---|---|---|---|---|")
    for w in rows:
        print(f"| {w['film']} | {w['peak_eps']:.4f} | {w['film_min_um']:.4f} | "
              f"{w['peak_force_N']:.0f} ({w['peak_force_raw_N']:.0f}) | "
              f"{w['force_jitter_rms_N']:.1f} / {w['force_jitter_max_N']:.0f} | "
              f"{w['peak_pressure_MPa']:.0f} ({w['peak_pressure_raw_MPa']:.0f}) | "
              f"{w['friction_power_W']:.3f} | {w['wall_time_s']:.1f} | {w['steps']} |")
    print(f"(peaks: of the smooth curve, a local quadratic over {SMOOTHING.window:g} deg of "
          f"crank; raw: the largest sample. Jitter: the force's residual about the curve "
          f"more than 10 deg from the load reversals. Peak pressure: Reynolds' condition at 360 "
          f"crank angles, the JFO film at its {len(rec)} film steps of the turn; friction "
          f"power over the films at 72 crank angles)")
    print(f"JFO cavity forms at crank {', '.join(f'{x:.0f}' for x in forms) or '-'} deg and "
          f"collapses at {', '.join(f'{x:.0f}' for x in collapses) or '-'} deg; largest "
          f"step mass balance {balance:.1e} m^3/s; cost JFO / Reynolds "
          f"{r_jfo.stats['wall_time'] / r_fem.stats['wall_time']:.2f}x")
    per_bin = {"Reynolds' condition": steps_by_crank_angle(r_fem),
               "JFO": steps_by_crank_angle(r_jfo)}
    print("accepted steps of the recorded turn per 30 deg of crank, from TDC:")
    for name, h in per_bin.items():
        print(f"  {name:20s} " + " ".join(f"{k:5d}" for k in h))
    write_csv(rows, out / "jfo_paper.csv")
    write_csv([dict(crank_from_deg=30 * i, reynolds_steps=int(per_bin["Reynolds' condition"][i]),
                    jfo_steps=int(per_bin["JFO"][i])) for i in range(12)],
              out / "jfo_paper_steps.csv")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(2, 3, figsize=(15, 8))
    c = fem.bearing.clearance
    for r, lab in ((r_fem, "Reynolds' condition"), (r_jfo, "JFO")):
        q = np.mod(np.degrees(r.crank_angle), 360.0)
        o = np.argsort(q)
        ax[0, 0].plot(r.e_x / c, r.e_y / c, label=lab)
        ax[0, 1].semilogy(q[o], 1e6 * np.maximum(r.film_min[o], 1e-9), label=lab)
    th = np.linspace(0, 2 * np.pi, 200)
    ax[0, 0].plot(np.cos(th), np.sin(th), "k-", lw=0.8)
    ax[0, 0].set(xlabel="e_x / c", ylabel="e_y / c", title="pin orbit (recorded turn)",
                 aspect="equal")
    ax[0, 1].set(xlabel="crank angle [deg]", ylabel="minimum film [um]",
                 title="minimum film")
    qr = np.mod(np.degrees(crank_at(film_column(rec, "t"))), 360.0)
    o = np.argsort(qr)
    ax[1, 0].plot(qr[o], 100 * film_column(rec, "cavitated_fraction")[o], "C1.", ms=2)
    for x in forms:
        ax[1, 0].axvline(x, color="g", lw=0.8)
    for x in collapses:
        ax[1, 0].axvline(x, color="r", lw=0.8)
    ax[1, 0].set(xlabel="crank angle [deg]", ylabel="cavitated share of the film [%]",
                 title="JFO cavity (green: forms, red: collapses)")
    qf = [f.crank_angle_deg for f in frames]
    ax[1, 1].semilogy(qf, [f.solution.pressure_max / 1e6 for f in frames], "C0o", ms=3,
                      label="Reynolds' condition")
    ax[1, 1].semilogy(qr[o], film_column(rec, "pressure_max")[o] / 1e6, "C1.", ms=2, label="JFO")
    ax[1, 1].set(xlabel="crank angle [deg]", ylabel="peak film pressure [MPa]",
                 title="peak pressure")
    edges = np.arange(0, 361, 30)
    for k, (name, h) in enumerate(per_bin.items()):
        ax[0, 2].bar(edges[:-1] + 15 + (k - 0.5) * 12, h, width=12, label=name)
    ax[0, 2].set(xlabel="crank angle [deg]", ylabel="accepted steps per 30 deg",
                 title="where the integrator's steps go", xticks=edges[::2])
    ax[1, 2].semilogy(qr[o], np.maximum(np.abs(film_column(rec, "mass_balance")[o]), 1e-30), "C1.", ms=2)
    ax[1, 2].set(xlabel="crank angle [deg]", ylabel="|feed - leakage - storage| [m^3/s]",
                 title="JFO mass balance of each film step")
    for a_ in (ax[0, 0], ax[0, 1], ax[1, 1], ax[0, 2]):
        a_.legend(fontsize=8)
    from mechanism.figures import label_log_axis
    for a_ in (ax[0, 1], ax[1, 1]):       # film and pressure: labels in every decade
        label_log_axis(a_.yaxis)
    fig.suptitle(f"Seed piston pin, L/D = {fem.bearing.length_ratio:g}: Reynolds' "
                 "condition vs mass-conserving film")
    fig.tight_layout()
    fig.savefig(out / "jfo_paper.png", dpi=130)
    films = film_figure(frames_jfo[::9], jfo.name, out / "jfo_paper_films.png")
    print(f"wrote {out / 'jfo_paper.csv'}, {out / 'jfo_paper_steps.csv'}, "
          f"{out / 'jfo_paper.png'} and {films}")
    return rows, forms, collapses, per_bin


def film_figure(frames, name: str, path):
    """The JFO film's fraction on the unwrapped film in ``frames`` (from
    :func:`film_history`: the run's film steps replayed)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from bearingfem.outputs.render import film_map
    cols = (len(frames) + 1) // 2
    fig, axes = plt.subplots(2, cols, figsize=(3.6 * cols, 5.6), sharex=True, sharey=True,
                             constrained_layout=True)
    levels = np.append(np.linspace(0.0, 0.95, 20), 1.0 + 1e-9)   # full film: the top band
    for ax, f in zip(axes.flat, frames):
        tri, theta = film_map(f.solution, "fraction")
        cf = ax.tricontourf(tri, np.clip(theta, 0.0, 1.0), levels=levels, cmap="viridis")
        ax.set_title(f"crank {f.crank_angle_deg:.0f} deg, "
                     f"h_min {1e6 * f.solution.film_min:.2f} um", fontsize=9)
        ax.set_xticks(range(0, 361, 90))
    for ax in axes[-1]:
        ax.set_xlabel("theta from the maximum film [deg]")
    for ax in axes[:, 0]:
        ax.set_ylabel("z [mm]")
    fig.colorbar(cf, ax=axes, label="film fraction [1] (1: full film)", shrink=0.8)
    fig.suptitle(f"{name}: the mass-conserving film over the recorded turn")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


if __name__ == "__main__":
    main()
