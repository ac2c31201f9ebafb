"""Published finite-bearing coefficient tables against ours: the layout the studies share.

A study (studies/someya.py, studies/lund_thomsen.py) is one :class:`Published` record: its
table (L/D -> rows of S, eps, attitude [deg], K, B as printed), its grooves and which
damping entries the table gives. For every row we find the equilibrium at the table's
Sommerfeld number (the "fem" model, the load down: -y) and the coefficients there, in the
load frame and dimensionless (K c / W, B c omega / W); K both with the grooves fixed in the
bearing (``kc.K``, the force's exact Jacobian) and turning with the line of centres
(``kc.K - kc.K_groove_shift``). ``main`` prints each row against the table, writes the CSV,
prints the mesh convergence of a few rows and draws the figure.
"""
from __future__ import annotations

import argparse
import math
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Callable

import numpy as np

from bearingfem import Bearing, Groove
from bearingfem.design import coefficients, equilibrium
from bearingfem.design.groups import load_from_sommerfeld
from bearingfem.outputs.tables import write_csv

K_NAMES = ("Kxx", "Kxy", "Kyx", "Kyy")
B_NAMES = ("Bxx", "Bxy", "Byx", "Byy")
LOAD_DIRECTION = -0.5 * math.pi          # the load pulls the journal down (-y)
OMEGA = 100.0                            # [rad/s]; the groups make the answer independent
#: What the other form of K is called in a study's CSV (suffix) and figure (label).
OTHER_K = {"fixed": "ours, grooves fixed in the bearing",
           "turning": "ours, grooves turning with the line of centres"}


def axial_grooves(width: float) -> tuple:
    """Two ambient axial grooves ``width`` [rad] wide at the horizontal split (0 and 180 deg),
    across the load."""
    return (Groove(angle=0.0, width=width), Groove(angle=math.pi, width=width))


def bearing(ld: float) -> Bearing:
    """Any bearing of this L/D: the dimensionless groups do not see the others."""
    return Bearing(radius=0.05, length=0.1 * ld, clearance=1e-4, viscosity=0.01)


def mesh(ld: float, n_theta: int, grooves: tuple, element: str = "P1") -> dict:
    """FE options with cells of about equal sides."""
    return dict(grooves=grooves, n_theta=n_theta, n_z=max(4, round(n_theta * ld / 3)),
                element=element, cavitation="reynolds")


def case(ld: float, sommerfeld: float, n_theta: int, grooves: tuple, element: str = "P1",
         b_names: tuple = B_NAMES) -> dict:
    """eps, attitude [deg], dimensionless K (grooves fixed in the bearing), K of grooves
    turning with the line of centres, and the ``b_names`` entries of B, in the load frame,
    at the load that gives ``sommerfeld``."""
    b = bearing(ld)
    opts = mesh(ld, n_theta, grooves, element)
    eq = equilibrium(b, load_from_sommerfeld(b, sommerfeld, OMEGA), OMEGA, "fem",
                     direction=LOAD_DIRECTION, **opts)
    kc = coefficients(b, eq.state, "fem", frame="load", **opts)
    K, B = kc.dimensionless()
    K_t, _ = replace(kc, K=kc.K - kc.K_groove_shift).dimensionless()
    return dict(eps=eq.eps, phi=math.degrees(eq.attitude), K=K.ravel(), K_turning=K_t.ravel(),
                B=B.ravel()[[B_NAMES.index(n) for n in b_names]])


def largest_entry_error(ours, table) -> float:
    """max |ours - table| / max |table| over a matrix's entries: entries near zero (Kyx by
    eps 0.7) make per-entry relative errors meaningless."""
    return float(np.max(np.abs(np.subtract(ours, table))) / np.max(np.abs(table)))


@dataclass(frozen=True)
class Published:
    """A published coefficient table and how its study shows it.

    name : the study's module and file stem; source : the legend's citation
    table : L/D -> rows (S, eps, phi [deg], the K entries, the ``b_names`` entries of B)
    grooves, element : the bearing's grooves and the FE element
    tag : suffix of the table's columns in the CSV ("book", "table")
    other : the form of K in the CSV's suffixed columns ("fixed" or "turning"; the other
        form fills the plain columns)
    errors : the CSV also carries each matrix's largest entry error (K_error, ...)
    line : formats one CSV row for the progress print; header : the line above them
    convergence_rows, convergence_column : the L/D 0.5 rows whose mesh convergence is
        printed, each named by its S (0) or eps (1)
    panels, symlog : the figure's panels (K, B names or "phi") and those on a symlog scale
    title : the figure's title
    """

    name: str
    source: str
    table: dict
    grooves: tuple
    tag: str
    other: str
    line: Callable
    header: str
    convergence_rows: tuple
    convergence_column: int
    panels: tuple
    title: str
    b_names: tuple = B_NAMES
    element: str = "P1"
    errors: bool = False
    symlog: tuple = ()

    def case(self, ld: float, sommerfeld: float, n_theta: int = 144) -> dict:
        return case(ld, sommerfeld, n_theta, self.grooves, self.element, self.b_names)

    def ours(self, r: dict) -> np.ndarray:
        """The form of K in the plain columns."""
        return r["K_turning"] if self.other == "fixed" else r["K"]

    def compare(self, ld: float, n_theta: int = 144, progress=print) -> list:
        """One CSV row per table row at L/D ``ld``."""
        names, rows = K_NAMES + self.b_names, []
        for S, eps0, phi0, *ref in self.table[ld]:
            r = self.case(ld, S, n_theta)
            other = r["K"] if self.other == "fixed" else r["K_turning"]
            row = dict(ld=ld, S=S, **{f"eps_{self.tag}": eps0}, eps=r["eps"],
                       **{f"phi_{self.tag}": phi0}, phi=r["phi"],
                       **{f"{n}_{self.tag}": v for n, v in zip(names, ref)},
                       **dict(zip(K_NAMES, self.ours(r))),
                       **{f"{n}_{self.other}": v for n, v in zip(K_NAMES, other)},
                       **dict(zip(self.b_names, r["B"])))
            if self.errors:
                row.update(K_error=largest_entry_error(r["K"], ref[:4]),
                           K_turning_error=largest_entry_error(r["K_turning"], ref[:4]),
                           B_error=largest_entry_error(r["B"], ref[4:]))
            rows.append(row)
            progress(self.line(rows[-1]))
        return rows

    def convergence(self, ld: float = 0.5, meshes=(72, 144, 288)) -> list:
        """Our numbers at three meshes for a few rows (how far the mesh moves them)."""
        out = []
        for i in self.convergence_rows:
            row = self.table[ld][i]
            for n in meshes:
                r = self.case(ld, row[0], n)
                out.append((ld, row[self.convergence_column], n, r["eps"], r["phi"],
                            *self.ours(r), *r["B"]))
        return out

    def figure(self, rows, path):
        import matplotlib.pyplot as plt
        fig, axes = plt.subplots(2, 4, figsize=(14, 6.5), sharex=True)
        for ax, n in zip(axes.ravel(), self.panels):
            for ld, colour in ((0.5, "C0"), (1.0, "C1")):
                sel = [r for r in rows if r["ld"] == ld]
                eps = [r["eps"] for r in sel]
                ax.plot(eps, [r[n] for r in sel], "-", color=colour, label=f"ours, L/D = {ld:g}")
                if n in K_NAMES:
                    ax.plot(eps, [r[f"{n}_{self.other}"] for r in sel], ":", color=colour,
                            label=OTHER_K[self.other])
                ax.plot([r[f"eps_{self.tag}"] for r in sel], [r[f"{n}_{self.tag}"] for r in sel],
                        "o", mfc="none", color=colour, label=f"{self.source}, L/D = {ld:g}")
            ax.set_title(n if n != "phi" else "attitude [deg]")
            if n in self.symlog:
                ax.set_yscale("symlog", linthresh=1.0)
            ax.grid(alpha=0.3)
        for ax in axes[1]:
            ax.set_xlabel("eccentricity ratio")
        axes[0, 0].legend(fontsize=7)
        fig.suptitle(self.title)
        fig.tight_layout()
        fig.savefig(path, dpi=100)
        plt.close(fig)

    def main(self, argv=None, description: str = ""):
        p = argparse.ArgumentParser(description=description)
        p.add_argument("-o", "--out", type=Path, default=Path(f"results/{self.name}"))
        p.add_argument("--n-theta", type=int, default=144, help="cells around the film")
        a = p.parse_args(argv)
        a.out.mkdir(parents=True, exist_ok=True)
        print(self.header)
        rows = self.compare(0.5, a.n_theta) + self.compare(1.0, a.n_theta)
        write_csv(rows, a.out / f"{self.name}.csv")
        named = ("S", f"eps_{self.tag}")[self.convergence_column]
        form = "turning" if self.other == "fixed" else "fixed"
        print(f"\nmesh convergence (L/D 0.5): {named}, n_theta, eps, phi, K ({form} grooves), B")
        for c in self.convergence():
            print(" ".join(f"{v:9.4f}" if isinstance(v, float) else f"{v:>5}" for v in c))
        self.figure(rows, a.out / f"{self.name}.png")
        print(f"wrote {a.out / f'{self.name}.csv'} and {a.out / f'{self.name}.png'}")
