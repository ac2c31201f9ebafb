"""Lund & Thomsen's (1978) two-axial-groove bearing: their coefficients and ours.

Reference: J. W. Lund and K. K. Thomsen, "A calculation method and data for the dynamic
coefficients of oil-lubricated journal bearings", in *Topics in Fluid Film Bearing and Rotor
Bearing System Design and Optimization*, ASME (1978), pp. 1-28: the cylindrical bearing with
two axial grooves, each 20 deg wide, at the horizontal split (two 160 deg pads), the load
vertical (through the middle of the lower pad); isoviscous, laminar, Reynolds' (Swift-Stieber)
condition at the film's rupture. Rows as transcribed (10 of them, five at L/D 0.5 and five at
L/D 1; their L/D 1 row at S = 0.358 prints a Kyy off its column's trend and is left out).

Dimensionless groups (the same as Someya's): S = mu N L D (R/c)^2 / W, N in rev/s; eps =
e/c; phi the attitude angle from the load line [deg]; K_ij c / W and B_ij c omega / W in the
load frame (x along the load, y turned +90 deg with the rotation). The table gives Bxx, Bxy
and Byy (their damping is symmetric, Byx = Bxy).

What it shows (``python -m studies.lund_thomsen -o out``, table + CSV + figure):

- eps, attitude, K and B agree with the table to about 1 % of each matrix's largest entry
  (largest gaps printed by the study), on meshes whose nodes fall on the grooves' edges.
- Their stiffness is ours with the grooves *fixed in the bearing* (``kc.K``, the force's
  exact Jacobian). The turning-grooves form ``kc.K - kc.K_groove_shift``, which Someya's data
  book matches (studies/someya.py), misses theirs by up to ~180 % of an entry (Kyx at light
  load). Published tables differ in this convention: check which one before comparing.
"""
from __future__ import annotations

import argparse
import math
from dataclasses import replace
from pathlib import Path

import numpy as np

from bearingfem import Bearing, Groove
from bearingfem.design import coefficients, equilibrium
from bearingfem.design.groups import load_from_sommerfeld
from bearingfem.outputs.tables import write_csv

#: L/D -> rows (S, eps, phi [deg], Kxx, Kxy, Kyx, Kyy, Bxx, Bxy, Byy), as published
TABLE = {
    0.5: [(1.656, 0.244, 65.85, 1.69, 5.06, -2.20, 1.95, 9.93, 2.15, 4.80),
          (0.917, 0.372, 57.45, 2.12, 4.01, -1.30, 1.85, 7.70, 2.06, 3.23),
          (0.580, 0.477, 51.01, 2.67, 3.70, -0.78, 1.75, 6.96, 1.94, 2.40),
          (0.379, 0.570, 45.43, 3.33, 3.64, -0.43, 1.68, 6.76, 1.87, 1.89),
          (0.244, 0.655, 40.25, 4.21, 3.74, -0.13, 1.64, 6.87, 1.82, 1.54)],
    1.0: [(0.991, 0.150, 70.58, 1.56, 7.29, -2.16, 1.52, 14.66, 1.58, 4.49),
          (0.635, 0.224, 63.54, 1.62, 5.33, -1.57, 1.56, 10.80, 1.70, 3.41),
          (0.235, 0.460, 49.27, 2.19, 3.57, -0.80, 1.55, 7.36, 1.89, 2.19),
          (0.159, 0.559, 44.33, 2.73, 3.36, -0.48, 1.48, 6.94, 1.78, 1.74),
          (0.108, 0.650, 39.72, 3.45, 3.34, -0.23, 1.44, 6.89, 1.72, 1.43)],
}
K_NAMES = ("Kxx", "Kxy", "Kyx", "Kyy")
B_NAMES = ("Bxx", "Bxy", "Byy")
GROOVE_WIDTH = math.radians(20.0)
LOAD_DIRECTION = -0.5 * math.pi          # the load pulls the journal down (-y)
#: the grooves at the horizontal split, across the load
GROOVES = (Groove(angle=0.0, width=GROOVE_WIDTH), Groove(angle=math.pi, width=GROOVE_WIDTH))
OMEGA = 100.0                            # [rad/s]; the groups make the answer independent


def bearing(ld: float) -> Bearing:
    """Any bearing of this L/D: the dimensionless groups do not see the others."""
    return Bearing(radius=0.05, length=0.1 * ld, clearance=1e-4, viscosity=0.01)


def mesh(ld: float, n_theta: int, element: str = "P1") -> dict:
    """FE options with cells of about equal sides (n_z over the whole length)."""
    return dict(grooves=GROOVES, n_theta=n_theta, n_z=max(4, round(n_theta * ld / 3)),
                element=element, cavitation="reynolds")


def table_case(ld: float, sommerfeld: float, n_theta: int = 144,
               element: str = "P1") -> dict:
    """eps, attitude [deg], dimensionless K (grooves fixed in the bearing), K of grooves
    turning with the line of centres, and B (Bxx, Bxy, Byy), load frame, at ``sommerfeld``."""
    b = bearing(ld)
    opts = mesh(ld, n_theta, element)
    eq = equilibrium(b, load_from_sommerfeld(b, sommerfeld, OMEGA), OMEGA, "fem",
                     direction=LOAD_DIRECTION, **opts)
    kc = coefficients(b, eq.state, "fem", frame="load", **opts)
    K, B = kc.dimensionless()
    K_t, _ = replace(kc, K=kc.K - kc.K_groove_shift).dimensionless()
    return dict(eps=eq.eps, phi=math.degrees(eq.attitude), K=K.ravel(),
                K_turning=K_t.ravel(), B=B.ravel()[[0, 1, 3]])


def largest_entry_error(ours, table) -> float:
    """max |ours - table| / max |table| over a matrix's entries (Kyx near zero makes
    per-entry relative errors meaningless)."""
    return float(np.max(np.abs(np.subtract(ours, table))) / np.max(np.abs(table)))


def compare(ld: float, n_theta: int = 144, element: str = "P1", progress=print):
    rows = []
    for S, eps0, phi0, *ref in TABLE[ld]:
        r = table_case(ld, S, n_theta, element)
        rows.append(dict(ld=ld, S=S, eps_table=eps0, eps=r["eps"], phi_table=phi0,
                         phi=r["phi"],
                         **{f"{n}_table": v for n, v in zip(K_NAMES + B_NAMES, ref)},
                         **dict(zip(K_NAMES, r["K"])),
                         **{f"{n}_turning": v for n, v in zip(K_NAMES, r["K_turning"])},
                         **dict(zip(B_NAMES, r["B"])),
                         K_error=largest_entry_error(r["K"], ref[:4]),
                         K_turning_error=largest_entry_error(r["K_turning"], ref[:4]),
                         B_error=largest_entry_error(r["B"], ref[4:])))
        progress(_line(rows[-1]))
    return rows


def _line(r) -> str:
    return (f"L/D {r['ld']:<4g} S {r['S']:<6g} eps {r['eps']:.4f} ({r['eps_table']:.3f})"
            f"  phi {r['phi']:6.2f} ({r['phi_table']:.2f})  K {100 * r['K_error']:5.2f} %"
            f"  B {100 * r['B_error']:5.2f} %  | turning K {100 * r['K_turning_error']:6.1f} %")


def convergence(ld: float = 0.5, rows=(0, 4), meshes=(72, 144, 288)):
    """eps, phi, K and B at three meshes (multiples of 18: the grooves' edges on nodes)."""
    out = []
    for i in rows:
        S = TABLE[ld][i][0]
        for n in meshes:
            r = table_case(ld, S, n)
            out.append((ld, S, n, r["eps"], r["phi"], *r["K"], *r["B"]))
    return out


def figure(rows, path):
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 4, figsize=(14, 6.5), sharex=True)
    for ax, n in zip(axes.ravel(), K_NAMES + B_NAMES + ("phi",)):
        for ld, colour in ((0.5, "C0"), (1.0, "C1")):
            sel = [r for r in rows if r["ld"] == ld]
            eps = [r["eps"] for r in sel]
            ax.plot(eps, [r[n] for r in sel], "-", color=colour, label=f"ours, L/D = {ld:g}")
            if n in K_NAMES:
                ax.plot(eps, [r[n + "_turning"] for r in sel], ":", color=colour,
                        label="ours, grooves turning with the line of centres")
            ax.plot([r["eps_table"] for r in sel], [r[n + "_table"] for r in sel], "o",
                    mfc="none", color=colour, label=f"Lund & Thomsen (1978), L/D = {ld:g}")
        ax.set_title(n if n != "phi" else "attitude [deg]")
        ax.grid(alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("eccentricity ratio")
    axes[0, 0].legend(fontsize=7)
    fig.suptitle("Two-axial-groove bearing (20 deg grooves): K c / W, B c omega / W, load frame;"
                 " solid: grooves fixed in the bearing (kc.K)")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("-o", "--out", type=Path, default=Path("results/lund_thomsen"))
    p.add_argument("--n-theta", type=int, default=144, help="cells around the film")
    a = p.parse_args(argv)
    a.out.mkdir(parents=True, exist_ok=True)
    print("ours (table); K, B: largest entry error; turning K: kc.K - kc.K_groove_shift")
    rows = compare(0.5, a.n_theta) + compare(1.0, a.n_theta)
    write_csv(rows, a.out / "lund_thomsen.csv")
    print("\nmesh convergence (L/D 0.5): S, n_theta, eps, phi, K (fixed grooves), B")
    for c in convergence():
        print(" ".join(f"{v:9.4f}" if isinstance(v, float) else f"{v:>5}" for v in c))
    figure(rows, a.out / "lund_thomsen.png")
    print(f"wrote {a.out / 'lund_thomsen.csv'} and {a.out / 'lund_thomsen.png'}")


if __name__ == "__main__":
    main()
