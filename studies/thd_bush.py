"""The conducting bush beside ROSS 3.1's conducting pad: its temperature, and how much the
film -> bush coefficient and the bush's mesh move the answer.

    python -m studies.thd_bush -o docs/img          # figure + table, ~1 min

The bearing of ROSS 3.1's ``fixed_full`` fixture (benchmarks/thd_ross31.py: two 176 deg
pads, D 0.4 m, c 194.6 um, 900 rpm, 112.8 kN, oil at 323 K, carry-over 0.8), our film
with two 4 deg grooves, the bush a steel hollow cylinder R -> R + 0.1496 m (k 50.1 W/(m
K), back convection 735.9 W/(m^2 K) to the supply temperature, ROSS's pad), the journal
at zero net flux. Rows: the equilibrium with the film -> bush coefficient 2 k_oil/h (the
toolkit's), 6 k_oil/c and 1e5 W/(m^2 K) (the largest a BushConduction takes: the bush's
surface near the film's mean temperature), and the bush on a finer mesh. Figure: the bush's temperature in its
mid-plane (z = 0) and, along the inertial angle at z = 0, the film's, the bush's inner
and outer surfaces' temperatures.
"""
from __future__ import annotations

import argparse
import math
from dataclasses import replace
from pathlib import Path

import numpy as np

from bearingfem.design import equilibrium
from benchmarks.thd_ross31 import fixture, setup


def solve(bearing, load, omega, grooves, oil, thermal, mesh):
    return equilibrium(bearing, load, omega, "fem", n_theta=mesh[0], n_z=mesh[1],
                       grooves=grooves, cavitation="reynolds", lubricant=oil,
                       thermal=thermal)


def row(name, eq):
    rec = eq.solution.thermal
    print(f"{name:<34} {eq.eps:7.4f} {math.degrees(eq.attitude):7.2f} "
          f"{eq.solution.temperature_max:7.1f} {rec.bush.temperature.max():7.1f} "
          f"{rec.bush.inner_mean:7.1f} {rec.balance.bush:7.0f} "
          f"{'/'.join(f'{t:.1f}' for t in rec.inlet_temperatures):>12} "
          f"{rec.journal_temperature:7.1f}", flush=True)


def figure(eq, path: Path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    sol, rec = eq.solution, eq.solution.thermal
    bush = rec.bush
    bm = bush.mesh
    mid = bm.heights.size // 2 if bm.heights.size else 0
    on = bm.axial == mid
    nr, nt = bm.radii.size, bm.angles.size
    T = np.empty((nr, nt))
    T[bm.radial[on], bm.angular[on]] = bush.temperature[on]
    T = np.concatenate([T, T[:, :1]], axis=1)                 # close the seam
    # the bush's (and the bearing-fixed film's) angle phi = theta + gamma is the inertial
    # angle less pi (bearingfem.fields.tilted_gap): drawn at the inertial angle
    th = np.append(bm.angles, 2.0 * np.pi) + np.pi
    fig = plt.figure(figsize=(12, 5.4))
    ax = fig.add_subplot(1, 2, 1, projection="polar")
    ax.set_rorigin(0.0)
    im = ax.pcolormesh(th, bm.radii * 1e3, T - 273.15, shading="gouraud", cmap="inferno")
    ax.set_ylim(0.0, bm.radii[-1] * 1e3)
    ax.set_yticks([])
    ax.set_title(f"bush, R {bm.radii[0] * 1e3:.0f} -> {bm.radii[-1] * 1e3:.0f} mm, at z = 0 "
                 f"[C]\n(inertial angle; load along -y, journal turning counter-clockwise)",
                 fontsize=10, pad=18)
    fig.colorbar(im, ax=ax, pad=0.1, shrink=0.8)
    ax2 = fig.add_subplot(1, 2, 2)
    phi = np.mod(sol.theta + sol.gamma + np.pi, 2.0 * np.pi)
    zmid = np.isclose(sol.z, 0.0, atol=1e-9)
    order = np.argsort(phi[zmid])
    ax2.plot(np.degrees(phi[zmid][order]), sol.temperature[zmid][order] - 273.15, "k-",
             label="film (mean across it)")
    for layer, style, label in ((0, "C3-", "bush, inner surface"),
                                (nr - 1, "C0-", "bush, outer surface")):
        sel = on & (bm.radial == layer)
        a = np.mod(bm.angles[bm.angular[sel]] + np.pi, 2.0 * np.pi)
        o = np.argsort(a)
        ax2.plot(np.degrees(a[o]),
                 bush.temperature[sel][o] - 273.15, style, label=label)
    ax2.axhline(rec.journal_temperature - 273.15, color="0.5", ls="--", label="journal")
    ax2.set_xlabel("inertial angle [deg] (grooves at 0 and 180)")
    ax2.set_ylabel("temperature [C]")
    ax2.set_xlim(0, 360)
    ax2.set_xticks(range(0, 361, 45))
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=9)
    ax2.set_title(f"z = 0: eps {eq.eps:.4f}, {rec.balance.bush:.0f} W of "
                  f"{rec.balance.dissipation:.0f} W through the bush", fontsize=10)
    fig.tight_layout(rect=(0.0, 0.0, 1.0, 0.94))
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--out", type=Path, default=Path("."))
    ap.add_argument("--mesh", default="96x16", help="the film's n_thetaxn_z")
    ap.add_argument("--quick", action="store_true", help="the figure's row only")
    ap.add_argument("--no-figure", action="store_true", help="the table only")
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    mesh = tuple(int(v) for v in args.mesh.split("x"))
    inputs = fixture("fixed_full")["inputs"]
    bearing, load, omega, grooves, oil, thermals = setup(inputs)
    base = thermals["conducting bush"]
    print(f"film {mesh[0]}x{mesh[1]}; bush {base.bush.n_radial} radial x "
          f"{base.bush.n_axial} axial cells")
    print(f"{'case':<34} {'eps':>7} {'att deg':>7} {'Tmax K':>7} {'bush K':>7} "
          f"{'inner K':>7} {'bush W':>7} {'inlets K':>12} {'jrnl K':>7}")
    eq = solve(bearing, load, omega, grooves, oil, base, mesh)
    row("film -> bush 2 k_oil/h", eq)
    if not args.no_figure:
        figure(eq, args.out / "thd-bush-temperature.png")
    if args.quick:
        return
    c, k_oil = bearing.clearance, oil.conductivity
    for name, H in (("film -> bush 6 k_oil/c", 6.0 * k_oil / c),
                    ("film -> bush 1e5", 1e5)):
        th = replace(base, bush=replace(base.bush, film_coefficient=H))
        row(name, solve(bearing, load, omega, grooves, oil, th, mesh))
    fine = replace(base, bush=replace(base.bush, n_radial=16, n_axial=16,
                                      n_theta=2 * mesh[0]))
    row("bush 2 n_theta x 16 x 16", solve(bearing, load, omega, grooves, oil, fine, mesh))


if __name__ == "__main__":
    main()
