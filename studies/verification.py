"""Verification table of the film models: what each reference says and how close we are.

    python -m studies.verification -o results/verification

Prints a markdown table (reference, quantity, tolerance, worst error) and writes
``verification.csv`` and ``raimondi_boyd.png`` (our curves over the published points).
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from bearingfem.bearing import seed_bearing
from bearingfem import (JournalState, fvm_reynolds, long_bearing_force,
                        short_bearing_exact_force, short_bearing_force, solve_reynolds)

from bearingfem.outputs.tables import write_csv
from studies.raimondi_boyd import TABLE, bearing_numbers
from studies import someya as sy


def table1(ld):
    return seed_bearing(ld)


def rel(a, b):
    return float(np.linalg.norm(np.subtract(a, b)) / np.linalg.norm(b))


def raimondi_boyd(out):
    rows, curves = [], {}
    for ld, data in TABLE.items():
        errs = {"S": [], "phi": [], "f": [], "Qs": []}
        for eps, S0, phi0, f0, Q0, r0 in data:
            S, phi, fv, qs = bearing_numbers(ld, eps)
            errs["S"].append(abs(S / S0 - 1))
            errs["phi"].append(abs(phi - phi0))
            errs["f"].append(abs(fv / f0 - 1))
            errs["Qs"].append(abs(qs / (Q0 * r0) - 1))
        for k, tol in (("S", "2 %"), ("phi", "1 deg"), ("f", "2 %"), ("Qs", "2 %")):
            worst = max(errs[k])
            rows.append(("Raimondi & Boyd 1958", f"L/D={ld:g} {k}", tol,
                         f"{worst:.2f} deg" if k == "phi" else f"{100 * worst:.2f} %"))
        eps_fine = np.array([0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.97])
        curves[ld] = np.array([bearing_numbers(ld, e)[:2] for e in eps_fine])
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
        for ld, data in TABLE.items():
            d = np.array(data)
            l, = ax[0].loglog(eps_fine, curves[ld][:, 0], label=f"FE P2, L/D={ld:g}")
            ax[0].loglog(d[:, 0], d[:, 1], "o", color=l.get_color(), mfc="none")
            ax[1].plot(eps_fine, curves[ld][:, 1], color=l.get_color(), label=f"L/D={ld:g}")
            ax[1].plot(d[:, 0], d[:, 2], "o", color=l.get_color(), mfc="none")
        ax[0].set(xlabel="eccentricity ratio", ylabel="Sommerfeld number S",
                  title="lines: bearingfem, circles: Raimondi & Boyd (1958)")
        ax[1].set(xlabel="eccentricity ratio", ylabel="attitude angle [deg]")
        ax[0].legend(fontsize=8)
        for a in ax:
            a.grid(alpha=0.3, which="both")
        fig.tight_layout()
        fig.savefig(out / "raimondi_boyd.png", dpi=100)
    except ImportError:
        pass
    return rows


def someya():
    """Someya's data book, two-axial-groove bearing, eps 0.3-0.9 (studies/someya.py)."""
    rows = []
    for ld in (0.5, 1.0):
        e = {"eps": [], "phi": [], "K": [], "B": []}
        for S, eps, phi, *book in sy.TABLE[ld]:
            if not 0.3 <= eps <= 0.9:
                continue
            r = sy.databook_case(ld, S)
            e["eps"].append(abs(r["eps"] / eps - 1))
            e["phi"].append(abs(r["phi"] - phi))
            e["K"].append(sy.largest_entry_error(r["K_turning"], book[:4]))
            e["B"].append(sy.largest_entry_error(r["B"], book[4:]))
        rows.append(("Someya 1989, two-axial-groove", f"L/D={ld:g} eps, phi, K, C (eps 0.3-0.9)",
                     "0.6 %, 0.5 deg, 3 %, 5 %" if ld == 0.5 else "reported, not tested",
                     f"{100 * max(e['eps']):.2f} %, {max(e['phi']):.2f} deg, "
                     f"{100 * max(e['K']):.1f} %, {100 * max(e['B']):.1f} %"))
    return rows


def limits():
    s = JournalState(0.6, 0.0, 0.0, 0.0, 250.0)
    rows = []
    e_short = [rel(solve_reynolds(table1(ld), s, 120, 8, "P2", "gumbel").force_local,
                   short_bearing_force(table1(ld), s)) for ld in (0.25, 0.125, 0.0625)]
    rows.append(("Frene short bearing (Eq. 9), L/D -> 0", "FE error at L/D=1/4,1/8,1/16",
                 "rate 2", ", ".join(f"{100 * e:.2f} %" for e in e_short)
                 + f"; rate {np.log2(e_short[-2] / e_short[-1]):.2f}"))
    e_long = [rel(solve_reynolds(table1(ld), s, 120, int(8 * ld), "P2", "gumbel").force_local,
                  long_bearing_force(table1(ld), s)) for ld in (2.0, 4.0, 8.0)]
    rows.append(("half-Sommerfeld long bearing, L/D -> inf", "FE error at L/D=2,4,8", "rate 1",
                 ", ".join(f"{100 * e:.2f} %" for e in e_long)
                 + f"; rate {np.log2(e_long[-2] / e_long[-1]):.2f}"))
    b = table1(0.0625)
    sq = JournalState(0.5, 25.0, 0.0, 0.0, 250.0)
    fe = solve_reynolds(b, sq, 240, 16, "P2", "gumbel").force_local
    rows.append(("squeeze eps_dot=0.1 omega, L/D=1/16", "FE vs exact quadrature / vs Eq. 9",
                 "< 1 % / > 10 %", f"{100 * rel(fe, short_bearing_exact_force(b, sq)):.2f} % / "
                 f"{100 * rel(fe, short_bearing_force(b, sq)):.1f} %"))
    return rows


def fe_vs_fvm():
    b = table1(1.0)
    s = JournalState(0.6, 10.0, 0.0, 20.0, 250.0)
    gaps = []
    for k in (1, 2, 4, 8):
        fe = solve_reynolds(b, s, 30 * k, 6 * k, "P2", "reynolds").force_local
        fv = fvm_reynolds(b, s, 30 * k, 6 * k, "reynolds").force_local
        gaps.append(rel(fe, fv))
    return [("FE (P2) vs finite volumes, Reynolds BC", "force gap at 30x6 ... 240x48",
             "-> 0 at order 2", ", ".join(f"{g:.1e}" for g in gaps))]


def psor_vs_active_set():
    rows = []
    b = table1(1.0)
    s = JournalState(0.95, 0.0, 0.0, 0.0, 250.0)
    for nt, nz in ((120, 20), (480, 80)):
        t0 = time.perf_counter()
        a = solve_reynolds(b, s, nt, nz, "P1", "reynolds", method="active-set")
        ta = time.perf_counter() - t0
        t0 = time.perf_counter()
        p = solve_reynolds(b, s, nt, nz, "P1", "reynolds", method="psor")
        tp = time.perf_counter() - t0
        d = np.max(np.abs(a.pressure - p.pressure)) / a.pressure_max
        rows.append(("PSOR vs active set, eps=0.95, P1", f"{nt}x{nz} ({a.n_dofs} dofs)",
                     "same pressure", f"max diff {d:.1e}; active set {ta * 1e3:.0f} ms "
                     f"({a.iterations} it), PSOR {tp * 1e3:.0f} ms ({p.iterations} sweeps)"))
    return rows


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("-o", "--output", default="results/verification")
    out = Path(p.parse_args(argv).output)
    out.mkdir(parents=True, exist_ok=True)
    rows = raimondi_boyd(out) + someya() + limits() + fe_vs_fvm() + psor_vs_active_set()
    header = ("reference", "quantity", "tolerance", "achieved")
    write_csv([dict(zip(header, r)) for r in rows], out / "verification.csv")
    print("| reference | quantity | tolerance | achieved |\n|---|---|---|---|")
    for r in rows:
        print("| " + " | ".join(r) + " |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
