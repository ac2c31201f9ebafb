"""What one film solve costs: linear vs cavitated (active set, cold / nested / warm) vs PSOR.

    python -m benchmarks.film_solve            # the table, 120x20 and 480x80, eps 0.6 / 0.95
    python -m benchmarks.film_solve --quick    # a smoke run on small meshes (CI)
    python -m benchmarks.film_solve --memory   # peak memory of a ~200k-dof cavitated solve

All times in one run, best of ``--repeat``, warm operator caches (assembly is once per
mesh and excluded); every row is the same P1 film, L/D = 1, omega = 100 rad/s.

* linear: ``fe_pressure(..., "none")``, the full-Sommerfeld solve through the same entry
  point (stiffness values, load, one sparse factorisation and solve);
* cold: the active set from the unconstrained solution, on the fine mesh alone;
* nested: ``fe_pressure(..., "reynolds")``, what a user gets from a cold start;
* warm: started from the solve of a state 0.1 % away in eps, as in time integration;
* PSOR: the multicolour projected SOR to the same tolerance (complementarity residual
  <= 1e-10, as the active set's), at the default omega 1.8 and at the best of a few
  omegas (``psor_best``), the fair baseline on fine meshes.
"""
from __future__ import annotations

import argparse
import subprocess
import sys

import numpy as np

from bearingfem import JournalState
from bearingfem.bearing import seed_bearing
from bearingfem.solvers.cavitation import active_set, graph_colouring, psor as psor_solve
from bearingfem.fe.kernel import fe_operator, fe_pressure

from .common import best_of

BEARING = seed_bearing(1.0)


PSOR_OMEGAS = (1.8, 1.9, 1.95, 1.97)


def measure(n_theta, n_z, eps, repeat=3, psor=True):
    s = JournalState(eps, 0.0, 0.0, 0.0, 100.0)
    near = JournalState(eps * (1.0 + 1e-3), 0.0, 0.0, 0.0, 100.0)   # the next time step
    op = fe_operator(BEARING, s, n_theta, n_z)
    K = op.free_stiffness(eps)
    b = op.load(eps, 0.0, s.wedge_speed)[op.mesh.free]
    t_lin = best_of(lambda: fe_pressure(op, s, "none"), repeat).wall
    timed = best_of(lambda: active_set(K, b), repeat)
    t_cold, cold = timed.wall, timed.out
    timed = best_of(lambda: fe_pressure(op, s, "reynolds"), repeat)
    t_nest, nest = timed.wall, timed.out
    prev = fe_pressure(op, near, "reynolds")
    timed = best_of(lambda: fe_pressure(op, s, "reynolds", active0=prev.active,
                                        factor=prev.factor), repeat)
    t_warm, warm = timed.wall, timed.out
    row = dict(mesh=f"{n_theta}x{n_z}", eps=eps, dofs=len(op.mesh.free), linear_ms=1e3 * t_lin,
               cold_ms=1e3 * t_cold, cold_it=cold.iterations, nested_ms=1e3 * t_nest,
               nested_it=nest.iterations, nested_fact=nest.factorisations,
               warm_ms=1e3 * t_warm, warm_it=warm.iterations, as_res=nest.residual)
    if psor:
        colours = graph_colouring(K)    # once per mesh, like the assembly: not timed
        runs = {}
        for omega in PSOR_OMEGAS if psor == "all" else PSOR_OMEGAS[:1]:
            runs[omega] = best_of(lambda: psor_solve(K, b, omega=omega, colours=colours))
        t_psor, ps = runs[PSOR_OMEGAS[0]].wall, runs[PSOR_OMEGAS[0]].out
        best = min(runs, key=lambda om: runs[om].wall)
        row.update(psor_ms=1e3 * t_psor, psor_it=ps.iterations, psor_res=ps.residual,
                   psor_gap=float(np.max(np.abs(ps.pressure - nest.pressure[op.mesh.free]))
                                  / nest.pressure.max()),
                   psor_best_ms=1e3 * runs[best].wall, psor_best_omega=best)
    for key in ("cold_ms", "nested_ms", "warm_ms"):
        row[key.replace("_ms", "/lin")] = row[key] / row["linear_ms"]
    if psor:
        row["psor/nested"] = row["psor_ms"] / row["nested_ms"]
        row["psor_best/nested"] = row["psor_best_ms"] / row["nested_ms"]
        row["psor/warm"] = row["psor_ms"] / row["warm_ms"]
    return row


def print_table(rows):
    keys = list(rows[0])
    print(" | ".join(keys))
    for r in rows:
        print(" | ".join(f"{r[k]:.3g}" if isinstance(r[k], float) else str(r[k]) for k in keys))


def peak_memory(n_theta, n_z):
    """Peak resident memory [MB] of a fresh process doing one cavitated solve."""
    # the toolkit's solve alone: the benchmarks' shared module (mechanism, design) not loaded
    code = ("import resource; from bearingfem import JournalState; "
            "from bearingfem.bearing import seed_bearing; "
            "from bearingfem.fe.kernel import fe_operator, fe_pressure; "
            f"s = JournalState(0.8, 0.0, 0.0, 0.0, 100.0); "
            f"op = fe_operator(seed_bearing(1.0), s, {n_theta}, {n_z}); "
            "r = fe_pressure(op, s, 'reynolds'); "
            "print(len(op.mesh.free), r.iterations, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    dofs, it, kb = out.stdout.split()
    return int(dofs), int(it), int(kb) / 1024.0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small meshes, one repeat (CI smoke)")
    ap.add_argument("--memory", action="store_true", help="peak memory of a ~200k-dof solve")
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args(argv)
    if a.memory:
        dofs, it, mb = peak_memory(1000, 400)
        print(f"free dofs {dofs}, active-set iterations {it}, peak RSS {mb:.0f} MB")
        return
    meshes = [(48, 8)] if a.quick else [(120, 20), (480, 80)]
    rows = [measure(nt, nz, eps, 1 if a.quick else a.repeat, psor=True if a.quick else "all")
            for nt, nz in meshes for eps in (0.6, 0.95)]
    print_table(rows)
    return rows


if __name__ == "__main__":
    main()
