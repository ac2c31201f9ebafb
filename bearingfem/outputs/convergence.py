"""Mesh-convergence study of a film solve: observed order, Richardson extrapolation and
Roache's grid-convergence index (GCI), for P1, P2 and finite volumes.

For three meshes refined by a constant ratio r (fine f1, medium f2, coarse f3):

    p = ln|(f3 - f2) / (f2 - f1)| / ln r,      f_ext = f1 + (f1 - f2) / (r^p - 1),
    GCI_fine = 1.25 |(f1 - f2) / f1| / (r^p - 1).
"""
from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..bearing import Bearing, JournalState
from ..reynolds import fvm_reynolds, solve_reynolds
from ..validation import check_int
from .tables import write_csv

__all__ = ["convergence_study", "richardson", "ConvergenceStudy", "QUANTITIES", "UNITS"]

QUANTITIES = ("force", "F_r", "F_t", "pressure_max", "cavitated_fraction", "friction_force",
              "side_leakage")
#: each quantity's SI unit (the summary's "unit" column; the order and GCI are pure numbers)
UNITS = {"force": "N", "F_r": "N", "F_t": "N", "pressure_max": "Pa", "cavitated_fraction": "1",
         "friction_force": "N", "side_leakage": "m^3/s"}
METHODS = ("P1", "P2", "fvm")


def richardson(f1, f2, f3, r=2.0):
    """(observed order p, extrapolated value, GCI of the fine value) from fine..coarse values.
    Non-monotone, stalled or growing sequences give p = nan and no extrapolation (a
    difference that does not shrink gives p <= 0: a negative GCI, no convergence)."""
    e21, e32 = f1 - f2, f2 - f3
    if e21 == 0.0 or e32 == 0.0 or np.sign(e21) != np.sign(e32) or abs(e21) >= abs(e32):
        return float("nan"), float("nan"), float("nan")
    p = float(np.log(abs(e32 / e21)) / np.log(r))
    ext = f1 + e21 / (r ** p - 1.0)
    gci = 1.25 * abs(e21 / f1) / (r ** p - 1.0) if f1 != 0.0 else float("nan")
    return p, float(ext), float(gci)


@dataclass(frozen=True)
class ConvergenceStudy:
    """Rows (one per method and mesh) and a summary per method and quantity."""

    rows: list
    summary: list
    case: str = ""            # what was solved, for titles: "L/D 1, eps 0.6, reynolds"

    def write_csv(self, path):
        path = Path(path)
        write_csv(self.rows, path)
        write_csv(self.summary, path.with_name(path.stem + "_summary.csv"))

    def plot(self, path, quantity="force"):
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 4.8))
        for m in METHODS:
            rows = [r for r in self.rows if r["method"] == m]
            s = [x for x in self.summary if x["method"] == m and x["quantity"] == quantity]
            if not rows or not s:
                continue
            n = np.array([r["dofs"] for r in rows], float)
            if np.isfinite(s[0]["extrapolated"]):
                ref, label = s[0]["extrapolated"], (
                    f"{m}: observed order {s[0]['order']:.2f} (in h), "
                    f"GCI {100 * s[0]['gci']:.2g} %")
            else:   # no order (oscillating, stalled or growing): against the finest mesh
                ref, label = rows[-1][quantity], f"{m}: no order; vs its finest"
                n, rows = n[:-1], rows[:-1]
            err = np.array([abs(r[quantity] / ref - 1.0) for r in rows]) if ref else n * 0
            ax.loglog(n, np.maximum(err, 1e-16), "o-", label=label)
        ax.set(xlabel="unknowns (degrees of freedom) [-]",
               ylabel=f"relative error of {quantity} [-]")
        # the case on a line of its own: one line was cut at the figure's edge
        ax.set_title(f"mesh convergence of {quantity}" + (f"\n{self.case}" if self.case else ""),
                     fontsize=10)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(path, dpi=100)
        plt.close(fig)


def convergence_study(bearing: Bearing, state: JournalState, *, levels: int = 4,
                      n_theta: int = 24, n_z: int = 4, cavitation: str = "reynolds",
                      methods=METHODS, supply_angle=None, ambient_pressure=0.0,
                      progress=None, on_row=None) -> ConvergenceStudy:
    """Solve on ``levels`` meshes (n_theta x n_z, doubled each level) with each method;
    ``supply_angle`` and ``ambient_pressure`` [Pa] as :func:`bearingfem.solve_reynolds`
    takes them (a JFO film's supply). ``on_row(row)``: called with each mesh's row as it
    is solved (a caller keeps what an interrupted study had done)."""
    levels = check_int("levels", levels, 3)
    for m in methods:
        if m not in METHODS:
            raise ValueError(f"methods must be among {', '.join(METHODS)}, got {m!r}")
    rows = []
    for m in methods:
        for k in range(levels):
            nt, nz = n_theta * 2 ** k, n_z * 2 ** k
            t0 = time.perf_counter()
            if m == "fvm":
                sol = fvm_reynolds(bearing, state, nt, nz, cavitation, supply_angle=supply_angle,
                                   ambient_pressure=ambient_pressure)
            else:
                sol = solve_reynolds(bearing, state, nt, nz, m, cavitation,
                                     supply_angle=supply_angle,
                                     ambient_pressure=ambient_pressure)
            dt = time.perf_counter() - t0
            fr, ft = sol.force_local
            rows.append({"method": m, "n_theta": nt, "n_z": nz, "dofs": sol.n_dofs,
                         "force": float(np.hypot(fr, ft)), "F_r": fr, "F_t": ft,
                         "pressure_max": sol.pressure_max,
                         "cavitated_fraction": sol.cavitated_fraction,
                         "friction_force": sol.friction_force, "side_leakage": sol.side_leakage,
                         "film_min": sol.film_min, "iterations": sol.iterations,
                         "seconds": dt})
            if on_row:
                on_row(rows[-1])
            if progress:
                progress(f"{m} {nt}x{nz}: |F| = {rows[-1]['force']:.6g} N ({dt:.2f} s)")
    summary = []
    for m in methods:
        rm = [r for r in rows if r["method"] == m]
        for q in QUANTITIES:
            f3, f2, f1 = (rm[-3][q], rm[-2][q], rm[-1][q])
            p, ext, gci = richardson(f1, f2, f3)
            summary.append({"method": m, "quantity": q, "unit": UNITS[q], "finest": f1,
                            "order": p, "extrapolated": ext, "gci": gci})
    case = (f"L/D {bearing.length_ratio:g}, eps {state.eps:g}, eps_dot {state.eps_dot:g} 1/s, "
            f"omega {state.omega:g} rad/s, {cavitation}")
    return ConvergenceStudy(rows, summary, case)
