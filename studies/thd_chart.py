"""A design chart with temperature: the designer's bearing against load, isothermal and THD.

    python -m studies.thd_chart -o docs/img          # table + thd-chart.png, ~1 min

The bearing of studies/thd_designer.py (50 mm, L/D 0.5, c 50 um, ISO VG 32 at 40 C, two
20 deg grooves, 3000 rpm) under 0.5 .. 8 kN down, 96 x 16 P1, Reynolds' condition: the
isothermal film at the supply temperature against the adiabatic thermal film with
carry-over 0.8. Columns: eps, least film [um], power loss [W], maximum film temperature
[C]. (A thermal film has no Sommerfeld collapse: the chart is for this bearing and speed.)
"""
from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from bearingfem.design import equilibrium
from bearingfem.thermal import Thermal

from .thd_designer import BEARING, GROOVES, OIL, OMEGA, SUPPLY

LOADS = (500.0, 1000.0, 2000.0, 3000.0, 4000.0, 6000.0, 8000.0)     # [N]
MESH = dict(n_theta=96, n_z=16, grooves=GROOVES, cavitation="reynolds")
THERMAL = Thermal(SUPPLY, carry_over=0.8)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--out", type=Path, default=Path("."))
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    rows = []
    print(f"{'load N':>7} {'eps iso':>8} {'eps THD':>8} {'h_min iso':>9} {'h_min THD':>9} "
          f"{'loss iso W':>10} {'loss THD W':>10} {'Tmax THD C':>10}")
    for W in LOADS:
        iso = equilibrium(BEARING, (0.0, -W), OMEGA, "fem", **MESH)
        thd = equilibrium(BEARING, (0.0, -W), OMEGA, "fem", lubricant=OIL, thermal=THERMAL,
                          **MESH)
        row = (W, iso.eps, thd.eps, iso.film_min * 1e6, thd.film_min * 1e6,
               abs(iso.solution.friction_torque * OMEGA),
               abs(thd.solution.friction_torque * OMEGA),
               thd.solution.temperature_max - 273.15)
        rows.append(row)
        print(f"{row[0]:7.0f} {row[1]:8.4f} {row[2]:8.4f} {row[3]:9.2f} {row[4]:9.2f} "
              f"{row[5]:10.1f} {row[6]:10.1f} {row[7]:10.1f}", flush=True)
    r = np.array(rows)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(12, 3.8), constrained_layout=True)
    kn = r[:, 0] / 1e3
    for a, (i, j), label in zip(ax[:2], ((3, 4), (5, 6)), ("least film [um]",
                                                            "power loss [W]")):
        a.plot(kn, r[:, i], "o-", label="isothermal at 40 C")
        a.plot(kn, r[:, j], "s-", label="THD, adiabatic, carry-over 0.8")
        a.set_xlabel("load [kN]")
        a.set_ylabel(label)
        a.grid(True, alpha=0.3)
    ax[0].legend()
    ax[2].plot(kn, r[:, 7], "s-", color="C1")
    ax[2].set_xlabel("load [kN]")
    ax[2].set_ylabel("maximum film temperature [C]")
    ax[2].grid(True, alpha=0.3)
    fig.suptitle("50 mm bearing, L/D 0.5, c 50 um, ISO VG 32 at 40 C, 3000 rpm")
    fig.savefig(args.out / "thd-chart.png", dpi=100)
    print(f"wrote {args.out / 'thd-chart.png'}")


if __name__ == "__main__":
    main()
