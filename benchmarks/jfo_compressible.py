"""The compressible (Elrod) JFO film: its incompressible limit and what it costs coupled.

    python -m benchmarks.jfo_compressible [--part limits|coupled|all] [--turns N]
                                          [--moduli B ...] [--quick] [-o results/benchmarks]

limits: the steady film (seed bearing L/D 1, eps 0.6, 250 rad/s, flooded groove at the
maximum film, 120x20) and the transient film (L/D 2, 24x8, the load-reversing orbit of
tests/test_jfo_transient.py, 64 steps a turn) against the incompressible JFO film for B =
1e7 ... 1e11 Pa: relative force difference, times B (constant at the rate 1/B), and the
local order log10 of successive differences.

coupled: the long bearing's scene (paper-long-jfo: L/D 2, 48x16, film step 1e-4 s,
LSODA rtol 1e-6) run with Reynolds' condition ("fem", cavitation reynolds), the
incompressible JFO film and the compressible one at several B, each once in one run:
accepted steps, wall and CPU time (the process's: on a shared machine the
wall time also counts other jobs) and their ratios to the Reynolds run, minimum film of the last
turn and its difference to the incompressible JFO run. Writes jfo_compressible_*.csv.
"""
from __future__ import annotations

import argparse
import dataclasses
from pathlib import Path

import numpy as np

from bearingfem import Bearing, Groove, JournalState, Lubricant, solve_reynolds
from bearingfem.bearing import seed_bearing
from bearingfem.fe.jfo import JFOFilm
from bearingfem.fe.jfo_compressible import CompressibleJFOFilm
from bearingfem.outputs.tables import write_csv

from .common import best_of

MODULI = (1e7, 1e8, 1e9, 1e10, 1e11)
COUPLED_MODULI = (1e8, 1.5e9, 1e11)


def _rel(a, b) -> float:
    return float(np.hypot(*np.subtract(a, b)) / np.hypot(*b))


def _orbit():
    """The load-reversing orbit through the centre of tests/test_jfo_transient.py."""
    w = 250.0

    def state(t):
        ex, ey = 0.75 * np.sin(w * t), 0.1 * np.sin(2 * w * t) + 0.02
        dx, dy = 0.75 * w * np.cos(w * t), 0.2 * w * np.cos(2 * w * t)
        eps = np.hypot(ex, ey)
        return JournalState(eps=eps, eps_dot=(ex * dx + ey * dy) / eps,
                            gamma=np.arctan2(ey, ex), gamma_dot=(ex * dy - ey * dx) / eps**2,
                            omega=60.0 * np.cos(w * t))
    return state, 2 * np.pi / w


def _forces(film, state, turn, m):
    return np.array([film.step(state(k * turn / m), turn / m).force
                     for k in range(1, m + 1)])


def limits(moduli=MODULI):
    b, s = seed_bearing(1.0), JournalState(eps=0.6, omega=250.0)
    g = [Groove(angle=np.pi, width=0.1)]
    ref = solve_reynolds(b, s, 120, 20, cavitation="jfo", grooves=g)
    tb = Bearing(radius=0.01, length=0.04, clearance=20e-6, viscosity=0.0117)
    state, turn = _orbit()
    m = 64
    f_ref = _forces(JFOFilm(tb, state(0.0), 24, 8, ambient_pressure=1e5), state, turn, m)
    peak = np.max(np.hypot(*f_ref.T))
    rows = []
    for B in moduli:
        c = solve_reynolds(b, s, 120, 20, cavitation="jfo", grooves=g,
                           lubricant=Lubricant(viscosity=b.viscosity, bulk_modulus=B))
        f = _forces(CompressibleJFOFilm(tb, state(0.0), 24, 8, ambient_pressure=1e5,
                                        bulk_modulus=B), state, turn, m)
        rows.append(dict(bulk_modulus_Pa=B, steady_diff=_rel(c.force_local, ref.force_local),
                         steady_peak_density=float(c.density.max()),
                         transient_diff=float(np.max(np.hypot(*(f - f_ref).T)) / peak)))
    print("| B [Pa] | steady: force diff | x B [MPa] | order | peak rho/rho0 | "
          "transient: max force diff / peak | x B [MPa] | order |")
    print("|---|---|---|---|---|---|---|---|")
    for i, r in enumerate(rows):
        o = ["-", "-"] if i == 0 else [
            f"{np.log10(rows[i - 1][k] / r[k]):.3f}" for k in ("steady_diff", "transient_diff")]
        print(f"| {r['bulk_modulus_Pa']:.0e} | {r['steady_diff']:.3e} | "
              f"{r['steady_diff'] * r['bulk_modulus_Pa'] / 1e6:.3f} | {o[0]} | "
              f"{r['steady_peak_density']:.5f} | {r['transient_diff']:.3e} | "
              f"{r['transient_diff'] * r['bulk_modulus_Pa'] / 1e6:.2f} | {o[1]} |", flush=True)
    print(f"(steady 120x20: incompressible peak pressure {ref.pressure_max / 1e6:.3f} MPa; "
          f"transient: peak force {peak:.0f} N)")
    return rows


def coupled(turns: float | None, moduli=COUPLED_MODULI):
    from mechanism import load_scene, simulate
    jfo = load_scene("paper-long-jfo")
    if turns is not None:
        jfo = dataclasses.replace(jfo, run=dataclasses.replace(
            jfo.run, turns=turns, record_from_turn=max(0.0, turns - 1.0)))
    lub = jfo.lubrication
    rey_opts = {k: lub.options[k] for k in ("n_theta", "n_z")}
    cases = [("Reynolds' condition (fem)", dataclasses.replace(
        lub, model="fem", options=dict(rey_opts, cavitation="reynolds"))),
        ("JFO (fem-jfo)", lub)]
    cases += [(f"compressible JFO, B = {B:.2g} Pa", dataclasses.replace(
        lub, model="fem-jfo-compressible", options=dict(lub.options, bulk_modulus=B)))
        for B in moduli]
    rows = []
    print("| film | steps | film steps | wall [s] | / Reynolds | CPU [s] | / Reynolds | "
          "min film [um] | vs JFO [um] | peak eps |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, l in cases:
        sc = dataclasses.replace(jfo, lubrication=l)
        t = best_of(lambda: simulate(sc, progress=False))
        r, wall, cpu = t.out, t.wall, t.cpu
        rows.append(dict(film=name, steps=int(r.stats["steps"]),
                         film_steps=int(r.stats.get("film_steps", 0)), wall_s=wall, cpu_s=cpu,
                         partial=bool(r.partial), film_min_um=1e6 * float(r.film_min.min()),
                         peak_eps=float(r.eps.max())))
        w = rows[-1]
        w["over_reynolds"] = wall / rows[0]["wall_s"]
        w["cpu_over_reynolds"] = cpu / rows[0]["cpu_s"]
        w["vs_jfo_um"] = w["film_min_um"] - rows[1]["film_min_um"] if len(rows) > 1 else 0.0
        print(f"| {name}{' (partial)' if w['partial'] else ''} | {w['steps']} | "
              f"{w['film_steps']} | {wall:.1f} | {w['over_reynolds']:.2f} | {cpu:.1f} | "
              f"{w['cpu_over_reynolds']:.2f} | "
              f"{w['film_min_um']:.3f} | {w['vs_jfo_um']:+.3f} | {w['peak_eps']:.4f} |",
              flush=True)
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--output", default="results/benchmarks")
    ap.add_argument("--part", choices=("limits", "coupled", "all"), default="all")
    ap.add_argument("--turns", type=float, default=None,
                    help="coupled runs: turns (default the scene's ten, the last recorded)")
    ap.add_argument("--moduli", type=float, nargs="*", default=COUPLED_MODULI)
    ap.add_argument("--quick", action="store_true", help="limits: B = 1e10, 1e11 only")
    a = ap.parse_args(argv)
    out = Path(a.output)
    out.mkdir(parents=True, exist_ok=True)
    rows = {}
    if a.part in ("limits", "all"):
        rows["limits"] = limits(MODULI[-2:] if a.quick else MODULI)
        write_csv(rows["limits"], out / "jfo_compressible_limits.csv")
    if a.part in ("coupled", "all"):
        rows["coupled"] = coupled(a.turns, tuple(a.moduli))
        write_csv(rows["coupled"], out / "jfo_compressible_coupled.csv")
    return rows


if __name__ == "__main__":
    main()
