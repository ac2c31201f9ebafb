"""What accuracy costs in time: every lubrication model on the paper's mechanism and on a
static film, error against the finest FE run versus wall time.

    python -m studies.accuracy_cost -o results/accuracy   # both parts, ~10 min
    python -m studies.accuracy_cost -o out --part static  # the static film only, ~1 min
    python -m studies.accuracy_cost -o out --quick        # small meshes, one turn (smoke)

Mechanism part: the paper scenes (short L/D 0.2, long L/D 2) run for ``--turns`` turns with
each model; errors over the last turn, at the same instants, against the finest FE mesh:
orbit (max |e - e_ref| / c), joint force (max |F - F_ref| / max |F_ref|) and min film
(relative). The FE rows at several meshes are the convergence study of the dynamic case.
Static part: one film state solved per model and mesh (warm caches, best of 3): error of
the force against a fine P2 solve, time, dofs, and the fitted growth time ~ N^k.
Writes mechanism.csv, static.csv, accuracy-cost.png and static-cost.png.
"""
from __future__ import annotations

import argparse
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from bearingfem import JournalState
from bearingfem.bearing import seed_bearing
from bearingfem.fe.force_table import table_force
from bearingfem.fv.fvm import fvm_force
from bearingfem.routes import fe_force
from bearingfem import long_bearing_exact_force, long_bearing_force
from bearingfem import short_bearing_exact_force, short_bearing_force
from mechanism import load_scene, simulate
from bearingfem.models import NUMERIC_MODELS
from mechanism.scene import SCENES, Lubrication
from bearingfem.outputs.tables import write_csv


# (label, model, options); the last FE entry of each list is the reference.
_ANALYTIC = {"short": [("Eq. 9 (short)", "short", dict(half_film="wedge", switch_speed=1.0)),
                       ("short exact", "short-exact", {})],
             "long": [("Eq. 10 (long)", "long", {}), ("long exact", "long-exact", {})]}
_MESHES = {"short": [(48, 4), (96, 8), (192, 8), (384, 16)],
           "long": [(24, 8), (48, 16), (96, 32), (192, 64)]}


def mechanism_models(bearing: str, quick=False):
    meshes = _MESHES[bearing][:2] if quick else _MESHES[bearing]
    models = list(_ANALYTIC[bearing])
    m = meshes[-2]
    models.append((f"FVM {m[0]}x{m[1]}", "fvm", dict(n_theta=m[0], n_z=m[1],
                                                     cavitation="gumbel")))
    models.append((f"FE table {m[0]}x{m[1]}", "fem-table",
                   dict(n_theta=m[0], n_z=m[1], element="P1", cavitation="gumbel",
                        n_eps=60, n_phi=96)))
    models.append((f"FE P2 {meshes[0][0]}x{meshes[0][1]}", "fem",
                   dict(n_theta=meshes[0][0], n_z=meshes[0][1], element="P2",
                        cavitation="gumbel")))
    for nt, nz in meshes:   # the finest last: the reference
        models.append((f"FE P1 {nt}x{nz}", "fem", dict(n_theta=nt, n_z=nz, element="P1",
                                                       cavitation="gumbel")))
    return models


def _errors(r, ref, c):
    t = ref.t
    ex, ey = np.interp(t, r.t, r.e_x), np.interp(t, r.t, r.e_y)
    fx, fy = np.interp(t, r.t, r.force_x), np.interp(t, r.t, r.force_y)
    f_ref = np.max(np.hypot(ref.force_x, ref.force_y))
    return dict(orbit_err=float(np.max(np.hypot(ex - ref.e_x, ey - ref.e_y)) / c),
                force_err=float(np.max(np.hypot(fx - ref.force_x, fy - ref.force_y)) / f_ref),
                min_film_err=float(abs(np.min(r.film_min) / np.min(ref.film_min) - 1.0)))


def run_mechanism(turns=2.0, quick=False, rtol=1e-8):
    """``rtol``: the scenes' 1e-6 alone moves the short-bearing orbit by 4 % of c (FE
    192x16, rtol 1e-6 vs 1e-8), which would hide every film model's own error."""
    rows = []
    for bearing in ("short", "long"):
        base = load_scene(SCENES / f"paper-{bearing}-fem.toml")
        base = replace(base, run=replace(base.run, turns=turns, rtol=rtol,
                                         record_from_turn=max(0.0, turns - 1.0)))
        c = base.bearing.clearance
        runs = []
        for label, model, opts in mechanism_models(bearing, quick):
            eps_max = base.lubrication.eps_max if model in NUMERIC_MODELS else 1.0 - 1e-6
            scene = replace(base, lubrication=Lubrication(model, opts, eps_max))
            t0 = time.perf_counter()
            r = simulate(scene, progress=False)
            wall = time.perf_counter() - t0    # includes a table's build when not cached
            runs.append((label, model, opts, r, wall))
            print(f"  {bearing:5s} {label:24s} {wall:7.2f} s  {r.message}", flush=True)
        ref = runs[-1][3]
        for label, model, opts, r, wall in runs:
            row = dict(bearing=bearing, model=label, wall_s=round(wall, 3),
                       film_solves=r.stats.get("film_solves", 0), completed=not r.partial)
            row.update(_errors(r, ref, c) if len(r.t) else {})
            rows.append(row)
    return rows


def _static_models(bearing, state, quick):
    levels = [(24, 4), (48, 8), (96, 16)] + ([] if quick else [(192, 32), (384, 64)])
    for nt, nz in levels:
        m = f"{nt}x{nz}"
        yield "FE P1", m, nt * (nz // 2 + 1), lambda nt=nt, nz=nz: fe_force(
            bearing, state, nt, nz, "P1", "gumbel")[0]
        if nt <= (96 if quick else 192):
            yield "FE P2", m, 4 * nt * (nz // 2 + 1), lambda nt=nt, nz=nz: fe_force(
                bearing, state, nt, nz, "P2", "gumbel")[0]
        yield "FVM", m, nt * nz, lambda nt=nt, nz=nz: fvm_force(bearing, state, nt, nz, "gumbel")
    for nt, nz in levels[1:4]:
        yield "FE table", f"{nt}x{nz}", 0, lambda nt=nt, nz=nz: table_force(bearing, state, nt, nz,
                                                                             element="P1")
    yield "Eq. 9 (short)", "-", 0, lambda: short_bearing_force(bearing, state)
    yield "short exact", "-", 0, lambda: short_bearing_exact_force(bearing, state)
    yield "Eq. 10 (long)", "-", 0, lambda: long_bearing_force(bearing, state)
    yield "long exact", "-", 0, lambda: long_bearing_exact_force(bearing, state)


def run_static(quick=False, ld=1.0, eps=0.8):
    bearing = seed_bearing(ld)
    state = JournalState(eps, 20.0, 0.0, 0.0, 250.0)
    ref = np.array(fe_force(bearing, state, 192 if quick else 384, 32 if quick else 64, "P2",
                            "gumbel")[0])
    rows = []
    for name, mesh, dofs, solve in _static_models(bearing, state, quick):
        f = np.array(solve())                     # warms the caches (operator, table)
        times = []
        for _ in range(3):
            t0 = time.perf_counter()
            solve()
            times.append(time.perf_counter() - t0)
        rows.append(dict(model=name, mesh=mesh, dofs=dofs, time_s=min(times),
                         force_err=float(np.linalg.norm(f - ref) / np.linalg.norm(ref))))
    return rows


def cost_exponents(rows):
    """Fitted k in time ~ dofs^k per numerical model, over its three largest meshes."""
    out = {}
    for name in ("FE P1", "FE P2", "FVM"):
        pts = sorted((r["dofs"], r["time_s"]) for r in rows if r["model"] == name)[-3:]
        if len(pts) >= 2:
            n, t = np.log(np.array(pts)).T
            out[name] = float(np.polyfit(n, t, 1)[0])
    return out


def plot(mech_rows, static_rows, out: Path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    if mech_rows:
        fig, axes = plt.subplots(2, 2, figsize=(11, 8), constrained_layout=True)
        for j, bearing in enumerate(("short", "long")):
            rows = [r for r in mech_rows if r["bearing"] == bearing and r.get("orbit_err")]
            for i, key in enumerate(("orbit_err", "force_err")):
                ax = axes[i, j]
                for r in rows:
                    ax.loglog(r["wall_s"], r[key], "o", color=_colour(r["model"]))
                    ax.annotate(r["model"], (r["wall_s"], r[key]), fontsize=7,
                                xytext=(3, 3), textcoords="offset points")
                ax.set_xlabel("wall time of the run [s]")
                ax.set_ylabel({"orbit_err": "orbit error max|e - e_ref| / c",
                               "force_err": "joint force error / max |F_ref|"}[key])
                ax.set_title(f"paper mechanism, {bearing} bearing")
                ax.grid(True, which="both", alpha=0.3)
        fig.savefig(out / "accuracy-cost.png", dpi=110)
        plt.close(fig)
    if static_rows:
        fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.5), constrained_layout=True)
        k = cost_exponents(static_rows)
        for name in dict.fromkeys(r["model"] for r in static_rows):
            rs = [r for r in static_rows if r["model"] == name]
            t = [r["time_s"] for r in rs]
            e = [max(r["force_err"], 1e-12) for r in rs]
            style = "o-" if name in k else "s"
            a1.loglog(t, e, style, label=name, color=_colour(name))
            if name in k:
                a2.loglog([r["dofs"] for r in rs], t, style, color=_colour(name),
                          label=f"{name}: time ~ N^{k[name]:.2f}")
        a1.set_xlabel("time per film solve [s]")
        a1.set_ylabel("force error vs fine P2")
        a1.legend(fontsize=7)
        a2.set_xlabel("unknowns N")
        a2.set_ylabel("time per film solve [s]")
        a2.legend(fontsize=8)
        for a in (a1, a2):
            a.grid(True, which="both", alpha=0.3)
        fig.savefig(out / "static-cost.png", dpi=110)
        plt.close(fig)


def _colour(name):
    for key, c in (("table", "C3"), ("P2", "C1"), ("P1", "C0"), ("FVM", "C2"),
                   ("exact", "C4"), ("Eq.", "C5")):
        if key in name:
            return c
    return "k"


def _print(rows):
    keys = list(dict.fromkeys(k for r in rows for k in r))
    print("| " + " | ".join(keys) + " |\n|" + "---|" * len(keys))
    for r in rows:
        print("| " + " | ".join(f"{r[k]:.3g}" if isinstance(r.get(k), float) else
                                str(r.get(k, "")) for k in keys) + " |")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("-o", "--output", default="results/accuracy")
    p.add_argument("--part", choices=("all", "mechanism", "static"), default="all")
    p.add_argument("--turns", type=float, default=2.0)
    p.add_argument("--rtol", type=float, default=1e-8, help="integrator tolerance of every run")
    p.add_argument("--quick", action="store_true", help="small meshes, one turn (smoke)")
    a = p.parse_args(argv)
    out = Path(a.output)
    out.mkdir(parents=True, exist_ok=True)
    mech = static = []
    if a.part in ("all", "static"):
        static = run_static(a.quick)
        write_csv(static, out / "static.csv")
        _print(static)
        print("fitted cost exponents (time ~ N^k):",
              ", ".join(f"{n} {k:.2f}" for n, k in cost_exponents(static).items()))
    if a.part in ("all", "mechanism"):
        mech = run_mechanism(1.0 if a.quick else a.turns, a.quick, a.rtol)
        write_csv(mech, out / "mechanism.csv")
        _print(mech)
    plot(mech, static, out)
    print(f"wrote {out}")
    return mech, static


if __name__ == "__main__":
    main()
