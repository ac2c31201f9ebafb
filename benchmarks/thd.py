"""What a thermal film costs beside the isothermal film of the same mesh.

    python -m benchmarks.thd [--profile | --parts | --calls]

The 50 mm bearing of studies/thd_designer.py (ISO VG 32 at 40 C, two 20 deg grooves,
3000 rpm) at eps 0.7: the isothermal grooved film (``solve_reynolds``, its default route)
and the thermal film (``solve_thd``, adiabatic, carry-over 0.8; cold start, and warm from
the film at eps 0.69, as an equilibrium's steps are), one process, best of 5 CPU times
(caches built first; OMP_NUM_THREADS=1). Columns: time [ms], film solves of the thermal
film, ratio to the isothermal solve; then the same film by the coupled Newton
(``solve_thd_newton``, cold and warm; "steps": its film solve plus its Newton steps).
``--calls``: each film, energy solve and the outputs of one cold and one warm fixed-point
solve at each mesh, timed inside the solve (CPU ms; the solve of the least total of 9),
with the isothermal solve's (best of 30): the count times the cost of each part, the
ratio's make-up. ``--profile``: where one cold 96 x 16 thermal solve of each spends its time (cProfile,
CPU clock, functions above 3 % of the total). ``--parts``: one thermal step's parts at
each mesh, best of 11 CPU times on the film after three steps of a cold solve: the film
(factors kept), the energy step's inputs (flow, mixing, viscosity), the energy solve
(``solve_energy``) and, within it, the SUPG system's assembly; with the points of the
arcs' quadrature.
"""
from __future__ import annotations

import argparse
import cProfile
import pstats
import time

from bearingfem import JournalState, solve_reynolds
from bearingfem.routes.thd import ThermalIteration, solve_thd
from bearingfem.routes.thd_newton import solve_thd_newton
from bearingfem.thermal import Thermal
from bearingfem.thermal.energy import energy_system, solve_energy
from studies.thd_designer import BEARING, GROOVES, OIL, OMEGA, SUPPLY

from .common import best_of

MESHES = ((48, 8), (96, 16), (192, 32))
THERMAL = Thermal(SUPPLY, carry_over=0.8)
STATE = JournalState(eps=0.7, omega=OMEGA, gamma=-1.0)
NEAR = JournalState(eps=0.69, omega=OMEGA, gamma=-1.0)


def cpu(f, repeat=5):
    """(best CPU time [s], result) of ``repeat`` calls."""
    t = best_of(f, repeat)
    return t.cpu, t.out


def profile(n=(96, 16)):
    thd = dict(lubricant=OIL, thermal=THERMAL, grooves=GROOVES)
    for solve in (solve_thd, solve_thd_newton):
        solve(BEARING, STATE, *n, **thd)
        pr = cProfile.Profile(time.process_time)
        pr.runcall(solve, BEARING, STATE, *n, **thd)
        stats = pstats.Stats(pr)
        total = stats.total_tt
        print(f"one thermal solve ({solve.__name__}) {n[0]}x{n[1]}: {1e3 * total:.1f} ms "
              f"CPU under the profiler")
        rows = sorted(((v[3], f"{k[0].split('/')[-1]}:{k[2]}")
                       for k, v in stats.stats.items()), reverse=True)
        for cum, name in rows:
            if cum >= 0.03 * total:
                print(f"  {1e3 * cum:8.1f} ms {100 * cum / total:5.1f} %  {name}")


def parts():
    """One thermal step's parts [ms] at each mesh (module docstring)."""
    print(f"{'mesh':>7} {'points':>6} {'iso':>6} {'film':>6} {'step':>6} {'energy':>6} "
          f"{'system':>6}")
    for n in MESHES:
        it = ThermalIteration(BEARING, STATE, *n, lubricant=OIL, thermal=THERMAL,
                              grooves=GROOVES)
        for _ in range(3):
            it.film(STATE)
            it.energy(STATE)
        it.film(STATE)
        step = it.energy_step(STATE)
        s = step.linearised[0]
        times = [cpu(f, 11)[0] for f in (
            lambda: solve_reynolds(BEARING, STATE, *n, grooves=GROOVES),
            lambda: it.film(STATE),
            lambda: it.energy_step(STATE),
            lambda: solve_energy(BEARING, it.eop, step.flow, step.mixing, THERMAL.walls,
                                 linearised=step.linearised),
            lambda: energy_system(it.eop, step.flow, -s, step.flow.dissipation,
                                  BEARING.radius))]
        print(f"{n[0]:>3}x{n[1]:<3} {it.eop.dx.size:6d} "
              + " ".join(f"{1e3 * t:6.2f}" for t in times), flush=True)


def calls():
    """Each part of a cold and a warm fixed-point solve [ms] at each mesh (module
    docstring): the iteration's methods timed as solve_thd calls them."""
    spent = []

    def timed(method):
        def call(self, *args, **kwargs):
            t = time.process_time()
            out = method(self, *args, **kwargs)
            spent.append((method.__name__, time.process_time() - t))
            return out
        return call

    kept = {name: getattr(ThermalIteration, name) for name in ("film", "energy", "solution")}
    thd = dict(lubricant=OIL, thermal=THERMAL, grooves=GROOVES)
    try:
        for name, method in kept.items():
            setattr(ThermalIteration, name, timed(method))
        for n in MESHES:
            t_iso, _ = cpu(lambda: solve_reynolds(BEARING, STATE, *n, grooves=GROOVES), 30)
            start = solve_thd(BEARING, NEAR, *n, **thd)
            for label, kw in (("cold", {}), ("warm", dict(start=start))):
                best = None
                for _ in range(9):
                    spent.clear()
                    t = time.process_time()
                    solve_thd(BEARING, STATE, *n, **thd, **kw)
                    t = time.process_time() - t
                    if best is None or t < best[0]:
                        best = (t, list(spent))
                t, parts = best
                row = {k: [1e3 * s for m, s in parts if m == k] for k in kept}
                print(f"{n[0]:>3}x{n[1]:<3} {label}: iso {1e3 * t_iso:.2f} ms, solve "
                      f"{1e3 * t:.2f} ms ({t / t_iso:.1f}x); films "
                      + " ".join(f"{x:.2f}" for x in row["film"]) + "; energy "
                      + " ".join(f"{x:.2f}" for x in row["energy"])
                      + f"; outputs {sum(row['solution']):.2f}", flush=True)
    finally:
        for name, method in kept.items():
            setattr(ThermalIteration, name, method)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--profile", action="store_true")
    ap.add_argument("--parts", action="store_true",
                    help="one thermal step's parts at each mesh instead of the table")
    ap.add_argument("--calls", action="store_true",
                    help="each part of a cold and a warm solve instead of the table")
    args = ap.parse_args(argv)
    if args.parts:
        parts()
        return
    if args.calls:
        calls()
        return
    print(f"{'mesh':>7} {'iso ms':>8} {'THD cold ms':>11} {'films':>5} {'ratio':>6} "
          f"{'THD warm ms':>11} {'films':>5} {'ratio':>6} | {'Newton cold':>11} {'steps':>5} "
          f"{'ratio':>6} {'Newton warm':>11} {'steps':>5} {'ratio':>6}")
    for n in MESHES:
        kw = dict(grooves=GROOVES)
        solve_reynolds(BEARING, STATE, *n, **kw)
        t_iso, _ = cpu(lambda: solve_reynolds(BEARING, STATE, *n, **kw), 10)
        thd = dict(lubricant=OIL, thermal=THERMAL, grooves=GROOVES)
        solve_thd(BEARING, STATE, *n, **thd)
        t_cold, cold = cpu(lambda: solve_thd(BEARING, STATE, *n, **thd))
        start = solve_thd(BEARING, NEAR, *n, **thd)
        t_warm, warm = cpu(lambda: solve_thd(BEARING, STATE, *n, start=start, **thd))
        solve_thd_newton(BEARING, STATE, *n, **thd)
        t_nc, nc = cpu(lambda: solve_thd_newton(BEARING, STATE, *n, **thd))
        t_nw, nw = cpu(lambda: solve_thd_newton(BEARING, STATE, *n, start=start, **thd))
        print(f"{n[0]:>3}x{n[1]:<3} {1e3 * t_iso:8.1f} {1e3 * t_cold:11.1f} "
              f"{cold.thermal.iterations:5d} {t_cold / t_iso:6.1f} {1e3 * t_warm:11.1f} "
              f"{warm.thermal.iterations:5d} {t_warm / t_iso:6.1f} | {1e3 * t_nc:11.1f} "
              f"{nc.thermal.iterations:5d} {t_nc / t_iso:6.1f} {1e3 * t_nw:11.1f} "
              f"{nw.thermal.iterations:5d} {t_nw / t_iso:6.1f}", flush=True)
    if args.profile:
        profile()


if __name__ == "__main__":
    main()
