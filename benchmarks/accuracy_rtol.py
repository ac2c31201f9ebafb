"""What a film solve to a requested accuracy costs against one solve on the cheapest
uniform mesh that reaches the same accuracy (found by search here).

    python -m benchmarks.accuracy_rtol            # ~5 min: four states x three tolerances
    python -m benchmarks.accuracy_rtol --quick    # one state, one tolerance (smoke)
    python -m benchmarks.accuracy_rtol --lund-thomsen   # the ten rows, ROSS beside (~3 min)
    python -m benchmarks.accuracy_rtol --lund-thomsen --profile   # where their time goes

For each state the true error of every uniform mesh of a grid (P1 and P2; n_theta from 8
to 256, n_z half, once or twice n_theta (L/D) / pi, at least 2) is measured against a
converged film (P2 384 x 64 graded toward the least film at 0.6); an ``rtol`` solve reports
its estimate and is measured too, twice: as the search runs it (``graded``: the plain film
graded toward its least film from eps 0.3 on) and on uniform meshes (``uniform``:
``grading=0.0``, the search before plain films were graded, the same meshes bit for bit);
the cheapest uniform mesh whose true error is at most the rtol solve's is the baseline. Times: best of ``--repeat`` runs,
one process, CPU time (the machine is shared: wall time measures the other jobs), warm
operator caches for both (meshes built once, as in any loop). "cold":
the mesh search from the start pair (memo cleared); "loop": a design loop's next call,
the memo holding the mesh that sufficed at a state 2 % away in eps.

``--lund-thomsen``: Lund & Thomsen's ten two-groove rows (studies/lund_thomsen.py),
equilibrium at rtol 2e-3 and K, C at rtol 2e-3 with the eps error passed on, one design
loop (the memo carried from row to row, caches cold at the start), beside the same loop on
uniform P2 36 x 8 and 72 x 12 with ``estimate=True`` and beside ROSS 3.1's 40 x 20 film
(.venv-ross31, ``benchmarks/_ross31_env.py``; ``--no-ross``: ours only), against P2 on 288
cells around graded toward the least film (:data:`REFERENCE`): |d eps|, the largest K and
C entry errors relative to each matrix's largest entry (inertial frame), and CPU time.
"""
from __future__ import annotations

import argparse
import cProfile
import itertools
import math
import pstats
import time

import numpy as np

from bearingfem import Bearing, JournalState, solve_reynolds
from bearingfem.accuracy import clear_memo, force_difference
from .common import best_of

N_THETA = (8, 12, 16, 20, 24, 32, 40, 48, 64, 80, 96, 128, 160, 192, 256)
#: n_z against cells as long as wide (n_z = n_theta (L/D) / pi): half, equal, twice
ASPECT = (0.5, 1.0, 2.0)
STATES = [("L/D 1, eps 0.8, Reynolds", 1.0, 0.8, "reynolds"),
          ("L/D 0.2, eps 0.6, Reynolds", 0.2, 0.6, "reynolds"),
          ("L/D 1, eps 0.5, full film", 1.0, 0.5, "none"),
          ("L/D 0.5, eps 0.9, Gumbel", 0.5, 0.9, "gumbel")]
#: The rtol searches compared: as the search grades a plain film, and on uniform meshes
SEARCHES = (("graded", {}), ("uniform", dict(grading=0.0)))


def best(fn, repeat):
    """(best CPU time [s], result) of ``repeat`` calls (the benchmarks' one timer; CPU time:
    on a shared machine wall time measures the other jobs)."""
    t = best_of(fn, repeat)
    return t.cpu, t.out


def uniform_table(b, s, cavitation, ref, repeat):
    """[(seconds, true error, element, n_theta, n_z)] over the grid."""
    rows = []
    for el, nt, a in itertools.product(("P1", "P2"), N_THETA, ASPECT):
        nz = max(2, 2 * round(a * nt * b.length_ratio / math.pi / 2))
        if el == "P1" and nt < 16:
            continue
        solve_reynolds(b, s, nt, nz, el, cavitation)              # build the mesh once
        t, sol = best(lambda: solve_reynolds(b, s, nt, nz, el, cavitation), repeat)
        rows.append((t, force_difference(ref, sol), el, nt, nz))
    return rows


def _ross_rows(cases, repeat):
    """ROSS 3.1's equilibrium + K, C of each case on its 40 x 20 film (.venv-ross31, one
    process; the numba warm-up excluded): rows of benchmarks/_ross31_fluid_film.py."""
    import json
    import os
    import subprocess
    from pathlib import Path

    from . import _ross31_env
    _ross31_env.install()
    spec = dict(cases=[dict(c, design_meshes=[ROSS_MESH]) for c in cases])
    script = Path(__file__).with_name("_ross31_fluid_film.py")
    r = subprocess.run([str(_ross31_env.python()), str(script), json.dumps(spec),
                        "--repeat", str(repeat + 1)], capture_output=True, text=True,
                       env={**os.environ, "MPLBACKEND": "Agg"})
    if r.returncode != 0:
        raise RuntimeError(f"ROSS run failed:\n{r.stderr[-2000:]}")
    return [row for row in json.loads(r.stdout.strip().splitlines()[-1])
            if row["kind"] == "design"]


#: ROSS's film on each pad (elements around x along): its literature test's mesh
ROSS_MESH = (40, 20)
#: The ten rows' reference film: P2 on this many cells around (n_z ~ n_theta L/D / 3) graded
#: toward the least film at this strength; K and C there are within 2e-4 of P2 432 x 72
#: (L/D 0.5, S 0.244 and 0.58) and 5e-5 of 432 x 144 (L/D 1, S 0.108), graded alike
#: (docs/accuracy.md). P2 144 uniform, the study's mesh, is up to 0.2 % off (K of a
#: cavitated film converges slowly and irregularly)
REFERENCE = (288, 0.6)


def _errors(eps, K, C, ref):
    """|d eps|, max|dK| / max|K|, max|dC| / max|C| against ``ref`` (eps, K, C)."""
    e0, K0, C0 = ref
    return (abs(eps - e0), float(np.abs(K - K0).max() / np.abs(K0).max()),
            float(np.abs(C - C0).max() / np.abs(C0).max()))


def _ten_rows():
    """(rows, loop): Lund & Thomsen's ten rows (L/D, S, bearing, load [N]) and
    ``loop(**how)``, the design loop over them (equilibrium, then K and C with the eps
    error passed on) with the mesh options ``how`` ([(eq, kc)] per row)."""
    from bearingfem.design import coefficients, equilibrium
    from bearingfem.design.groups import load_from_sommerfeld
    from studies.lund_thomsen import GROOVES, LOAD_DIRECTION, OMEGA, TABLE, bearing
    film = dict(grooves=GROOVES, cavitation="reynolds")
    rows = [(ld, S, bearing(ld), load_from_sommerfeld(bearing(ld), S, OMEGA))
            for ld, table in TABLE.items() for S, *_ in table]

    def loop(**how):
        out = []
        for ld, S, b, W in rows:
            o = dict(film, **how)
            if "n_z" in o:
                o["n_z"] = max(4, round(o["n_z"] * ld))
            eq = equilibrium(b, W, OMEGA, "fem", direction=LOAD_DIRECTION, **o)
            kc = coefficients(b, eq.state, "fem", eps_error=eq.eps_error, **o)
            out.append((eq, kc))
        return out
    return rows, loop


#: What the profile of the ten rows' loop names: label -> (file, function)
PROFILED = {"equilibria": ("design/equilibrium.py", "equilibrium"),
            "K, C searches (with the eps shift)": ("design/coefficients.py", "_with_error"),
            "grooved tables built": ("fe/grooved_build.py", "build_grooved_tables"),
            "sparse LU factorisations": ("solvers/linsolve.py", "factorise")}


def lund_thomsen_profile(rtol=2e-3):
    """Where one rtol loop over the ten rows (caches and memo cleared) spends its time:
    cProfile on the CPU clock, the shares of :data:`PROFILED` (overlapping: the builds and
    factorisations are inside the equilibria and searches)."""
    from bearingfem.caches import clear_caches
    _, loop = _ten_rows()
    clear_caches()
    clear_memo()
    pr = cProfile.Profile(time.process_time)
    pr.runcall(loop, rtol=rtol)
    stats = pstats.Stats(pr)
    total = stats.total_tt
    print(f"one rtol {rtol:g} loop: {total:.3f} s CPU under the profiler")
    for label, (path, name) in PROFILED.items():
        hits = [v for k, v in stats.stats.items() if k[0].endswith(path) and k[2] == name]
        cum = sum(v[3] for v in hits)
        print(f"  {label:36s} {sum(v[0] for v in hits):5d} calls {cum:7.3f} s "
              f"{100 * cum / total:5.1f} %")


def lund_thomsen(rtol=2e-3, repeat=3, with_ross=True):
    """The ten rows as one design loop (the memo carried from row to row; caches and memo
    cleared before the loop, best of ``repeat`` loops), beside ROSS 3.1's 40 x 20 film on
    each row in the same run; errors against the :data:`REFERENCE` film, K and C in the
    inertial frame (ROSS's). Besides ``rtol``: the same loop on one
    uniform P2 mesh for all rows (36 x 8 and 72 x 12 cells, n_z for L/D 1; half for 0.5),
    with ``estimate=True`` (the error of the mesh given, one half-mesh solve more)."""
    from bearingfem.caches import clear_caches
    from bearingfem.design import coefficients, equilibrium
    from studies.lund_thomsen import LOAD_DIRECTION, OMEGA, mesh
    rows, loop = _ten_rows()
    variants = [(f"rtol {rtol:g}", dict(rtol=rtol)),
                ("P2 36x8 estimate", dict(n_theta=36, n_z=8, element="P2", estimate=True)),
                ("P2 72x12 estimate", dict(n_theta=72, n_z=12, element="P2", estimate=True))]
    timed = [best_of(lambda: loop(**how), repeat, before=lambda: (clear_caches(), clear_memo()))
             for _, how in variants]
    refs, old_refs = [], []
    for ld, S, b, W in rows:
        o = mesh(ld, 144, "P2")
        eq = equilibrium(b, W, OMEGA, "fem", direction=LOAD_DIRECTION, **o)
        kc = coefficients(b, eq.state, "fem", **o)
        old_refs.append((eq.eps, np.asarray(kc.K), np.asarray(kc.C)))
        # the reference: P2 on 288 cells around graded toward the least film (REFERENCE)
        o = dict(mesh(ld, REFERENCE[0], "P2"), grading=(eq.state.gamma, REFERENCE[1]))
        eq = equilibrium(b, W, OMEGA, "fem", direction=LOAD_DIRECTION, start=eq, **o)
        kc = coefficients(b, eq.state, "fem", **o)
        refs.append((eq.eps, np.asarray(kc.K), np.asarray(kc.C)))
    old = np.max([_errors(e, K, C, ref) for (e, K, C), ref in zip(old_refs, refs)], axis=0)
    print(f"reference P2 {REFERENCE[0]} graded ({REFERENCE[1]}); P2 144 uniform (the study's "
          f"mesh) from it: |d eps| {old[0]:.1e}, K {100 * old[1]:.2f} %, C {100 * old[2]:.2f} %")
    ross = []
    if with_ross:
        cases = [dict(name=f"{ld}-{S}", radius=b.radius, length=b.length,
                      clearance=b.clearance, viscosity=b.viscosity, omega=OMEGA,
                      pad_centres=[0.5 * math.pi, 1.5 * math.pi],
                      pad_arcs=[math.radians(160.0)] * 2, load=[0.0, -W], static=[0.5, 0.0])
                 for ld, S, b, W in rows]
        ross = _ross_rows(cases, repeat)
    print(f"{'L/D':>4s} {'S':>6s} {'eps':>8s} {'d eps':>8s} {'eps_err':>8s} {'K err':>8s} "
          f"{'C err':>8s} {'kc.error':>8s} {'eq mesh':>9s} {'kc mesh':>9s} {'solves':>6s} | "
          f"{'ROSS d eps':>10s} {'K err':>8s} {'C err':>8s} {'CPU s':>6s}")
    worst_ross = np.zeros(3)
    for i, ((ld, S, b, W), (eq, kc), ref) in enumerate(zip(rows, timed[0].out, refs)):
        e = _errors(eq.eps, np.asarray(kc.K), np.asarray(kc.C), ref)
        line = (f"{ld:4g} {S:6g} {eq.eps:8.5f} {e[0]:8.1e} {eq.eps_error:8.1e} {e[1]:8.1e} "
                f"{e[2]:8.1e} {kc.error:8.1e} {'{}x{}'.format(*eq.accuracy.mesh):>9s} "
                f"{'{}x{}'.format(*kc.accuracy.mesh):>9s} "
                f"{eq.accuracy.solves + kc.accuracy.solves:6d} |")
        if ross:
            r = ross[i]
            er = _errors(r["eps"], np.array(r["K"]), np.array(r["C"]), ref)
            worst_ross = np.maximum(worst_ross, er)
            line += f" {er[0]:10.1e} {er[1]:8.1e} {er[2]:8.1e} {r['cpu_s']:6.3f}"
        print(line)
    c_ross = sum(r["cpu_s"] for r in ross)
    if ross:
        print(f"ROSS {ROSS_MESH[0]}x{ROSS_MESH[1]}: ten rows {sum(r['time_s'] for r in ross):.3f}"
              f" s wall, {c_ross:.3f} s CPU; largest |d eps| {worst_ross[0]:.1e}, K "
              f"{100 * worst_ross[1]:.2f} %, C {100 * worst_ross[2]:.2f} %")
    for (name, _), t in zip(variants, timed):
        worst, est = np.zeros(3), np.zeros(2)
        for (eq, kc), ref in zip(t.out, refs):
            worst = np.maximum(worst, _errors(eq.eps, np.asarray(kc.K), np.asarray(kc.C), ref))
            est = np.maximum(est, (eq.eps_error, kc.error))
        print(f"ours, {name:18s}: ten rows {t.wall:.3f} s wall, {t.cpu:.3f} s CPU (best of "
              f"{repeat}); largest |d eps| {worst[0]:.1e} (estimated {est[0]:.1e}), K "
              f"{100 * worst[1]:.2f} %, C {100 * worst[2]:.2f} % (estimated {100 * est[1]:.2f} %)"
              + (f"; ROSS / ours {c_ross / t.cpu:.1f}x CPU" if ross else ""))


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true")
    p.add_argument("--repeat", type=int, default=5)
    p.add_argument("--lund-thomsen", action="store_true")
    p.add_argument("--no-ross", action="store_true", help="--lund-thomsen: ours only")
    p.add_argument("--profile", action="store_true",
                   help="--lund-thomsen: where one rtol loop spends its time, instead")
    a = p.parse_args(argv)
    if a.lund_thomsen:
        if a.profile:
            return lund_thomsen_profile()
        return lund_thomsen(repeat=a.repeat, with_ross=not a.no_ross)
    states = STATES[:1] if a.quick else STATES
    tolerances = (1e-2,) if a.quick else (1e-2, 1e-3, 1e-4)
    print(f"{'state':28s} {'rtol':>7s} {'search':>8s} {'estimate':>9s} {'true':>9s} "
          f"{'mesh':>16s} {'solves':>6s} {'cold s':>8s} {'loop s':>8s} "
          f"{'cheapest uniform':>18s} {'its s':>8s} {'cold x':>7s} {'loop x':>7s}")
    worst = {}
    for name, ld, eps, cav in states:
        b = Bearing(radius=0.01, length=0.02 * ld, clearance=20e-6, viscosity=0.0117)
        s = JournalState(eps=eps, omega=250.0)
        near = JournalState(eps=eps * 0.98, omega=250.0)
        ref = solve_reynolds(b, s, 384, 64, "P2", cav, grading=0.6)
        table = uniform_table(b, s, cav, ref, a.repeat)
        for rtol, (search, how) in itertools.product(tolerances, SEARCHES):
            def cold():
                clear_memo()
                return solve_reynolds(b, s, rtol=rtol, cavitation=cav, **how)

            def loop():
                timed = best_of(lambda: solve_reynolds(b, s, rtol=rtol, cavitation=cav,
                                                       **how),
                                before=lambda: (clear_memo(),
                                                solve_reynolds(b, near, rtol=rtol,
                                                               cavitation=cav, **how)))
                return timed.cpu, timed.out
            cold()                                                   # build its meshes
            t_cold, sol = best(cold, a.repeat)
            t_loop = min(loop()[0] for _ in range(a.repeat))
            true = force_difference(ref, sol)
            ok = [r for r in table if r[1] <= true]
            acc = sol.accuracy
            mesh = "{} x {} {}".format(*acc.mesh, acc.element) + (
                "" if acc.grading is None else f" g{acc.grading:g}")
            row = (f"{name:28s} {rtol:7.0e} {search:>8s} {sol.force_error:9.2e} {true:9.2e} "
                   f"{mesh:>16s} {acc.solves:6d} {t_cold:8.4f} {t_loop:8.4f} ")
            if not ok:
                print(row + f"{'none of the grid':>18s}")
                continue
            cheap = min(ok)
            worst[search] = max(worst.get(search, 0.0), t_cold / cheap[0])
            print(row + f"{f'{cheap[3]} x {cheap[4]} {cheap[2]}':>18s} "
                  f"{cheap[0]:8.4f} {t_cold / cheap[0]:7.2f} {t_loop / cheap[0]:7.2f}")
    for search, w in worst.items():
        print(f"largest cold ratio, {search}: {w:.2f}")


if __name__ == "__main__":
    main()
