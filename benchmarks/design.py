"""What the designer's numbers cost: equilibrium + 8 coefficients, accuracy against time.

    python -m benchmarks.design            # our table (FE P1 / P2 ladders, short bearing)
    python -m benchmarks.design --quick    # smoke run (CI)
    python -m benchmarks.design --ross     # also ROSS's FluidFlow on the same bearing, side by
                                           # side (installs ross-rotordynamics into .venv-ross
                                           # on first use; it is not a dependency)
    python -m benchmarks.design --grooved  # Newton's equilibrium against the root search it
                                           # replaced, grooved and periodic (see grooved.py)

Bearing: Friswell et al. (2010) Example 5.5.1 (D 0.1 m, L 0.03 m, c 0.1 mm, mu 0.1 Pa s,
157.1 rad/s, 525 N downward), with Gumbel's condition (ROSS's FluidFlow clips negative
pressure the same way). Reference: FE P2 on 384x48. Error = the largest of |d eps| / eps,
max|dK| / max|K| and max|dC| / max|C| (entries pass through zero, so entry-wise relative
errors would be meaningless). Times: one run, best of ``--repeat``; "cold" includes
building the mesh and assembling its matrices (once per mesh in a session), "warm" reuses
them, as every later call on that mesh does.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from bearingfem import Bearing
from bearingfem.fe.assembly import film_operator
from bearingfem.design import coefficients, equilibrium
from bearingfem.fe.mesh import film_mesh

BEARING = Bearing(radius=0.05, length=0.03, clearance=0.1e-3, viscosity=0.1)
LOAD, OMEGA = (0.0, -525.0), 157.1
CAVITATION = "gumbel"
REFERENCE = dict(n_theta=384, n_z=48, element="P2")
LADDER = [("fem", dict(n_theta=n, n_z=z, element=el))
          for el, meshes in (("P1", ((48, 8), (96, 12), (192, 24))),
                             ("P2", ((24, 4), (36, 6), (48, 8), (72, 12))))
          for n, z in meshes] + [("short", {})]
ROOT = Path(__file__).resolve().parent.parent


def design_numbers(model, opts):
    """eps and the inertial K, C at equilibrium."""
    if model == "fem":
        opts = dict(opts, cavitation=CAVITATION)
    eq = equilibrium(BEARING, LOAD, OMEGA, model, **opts)
    kc = coefficients(BEARING, eq.state, model, **opts)
    return eq.eps, kc.K, kc.C


def error(numbers, ref):
    eps, K, C = numbers
    e0, K0, C0 = ref
    return max(abs(eps - e0) / e0, np.abs(K - K0).max() / np.abs(K0).max(),
               np.abs(C - C0).max() / np.abs(C0).max())


def timed(f, repeat, cold=None):
    best = np.inf
    for _ in range(repeat):
        if cold:
            cold()
        t0 = time.perf_counter()
        out = f()
        best = min(best, time.perf_counter() - t0)
    return best, out


def clear_caches():
    film_operator.cache_clear()
    film_mesh.cache_clear()


def ross_numbers(repeat, quick):
    """Run ROSS's FluidFlow equilibrium + coefficients in its own venv; rows as dicts."""
    venv = ROOT / ".venv-ross"
    py = venv / "bin" / "python"
    if not py.exists():
        print("installing ross-rotordynamics into .venv-ross (once) ...", flush=True)
        subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
        # ROSS 2.3 themes plotly with "scattermapbox", which plotly 6 removed
        subprocess.run([str(py), "-m", "pip", "install", "--quiet", "ross-rotordynamics",
                        "plotly<6"],
                       check=True)
    script = Path(__file__).with_name("_ross_fluidflow.py")
    meshes = "8x32" if quick else "8x32,16x64,32x128"
    r = subprocess.run([str(py), str(script), "--meshes", meshes, "--repeat", str(repeat)],
                       capture_output=True, text=True, env={**os.environ, "MPLBACKEND": "Agg"})
    if r.returncode != 0:
        raise RuntimeError(f"ROSS run failed:\n{r.stderr[-2000:]}")
    return json.loads(r.stdout.strip().splitlines()[-1])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--quick", action="store_true", help="two meshes, coarse reference")
    ap.add_argument("--ross", action="store_true", help="measure ROSS side by side")
    ap.add_argument("--grooved", action="store_true",
                    help="Newton vs root search on Lund & Thomsen's two-groove bearing")
    args = ap.parse_args(argv)
    if args.grooved:
        from .grooved import grooved_table
        return grooved_table(max(1, args.repeat // 2), args.quick)
    ref_opts = dict(n_theta=96, n_z=12, element="P2") if args.quick else REFERENCE
    ref = design_numbers("fem", ref_opts)
    ladder = LADDER[:1] + LADDER[3:4] if args.quick else LADDER
    rows = []
    print(f"reference: FE P2 {ref_opts['n_theta']}x{ref_opts['n_z']}, {CAVITATION}: "
          f"eps = {ref[0]:.6f}")
    print(f"{'model':6s} {'mesh':12s} {'error':>9s} {'cold [ms]':>10s} {'warm [ms]':>10s}")
    for model, opts in ladder:
        t_cold, _ = timed(lambda: design_numbers(model, opts), 1 if args.quick else 3,
                          cold=clear_caches)
        t_warm, out = timed(lambda: design_numbers(model, opts), args.repeat)
        mesh = f"{opts['element']} {opts['n_theta']}x{opts['n_z']}" if opts else "-"
        row = dict(model=model, mesh=mesh, error=error(out, ref), cold_s=t_cold, warm_s=t_warm)
        rows.append(row)
        print(f"{model:6s} {mesh:12s} {row['error']:9.2e} {1e3 * t_cold:10.2f} "
              f"{1e3 * t_warm:10.2f}")
    if args.ross:
        for r in ross_numbers(max(1, args.repeat // 2), args.quick):
            row = dict(model="ROSS", mesh=r["mesh"],
                       error=error((r["eps"], np.array(r["K"]), np.array(r["C"])), ref),
                       cold_s=r["time_s"], warm_s=r["time_s"])
            rows.append(row)
            print(f"{'ROSS':6s} {row['mesh']:12s} {row['error']:9.2e} "
                  f"{1e3 * r['time_s']:10.1f} {'':>10s}")
        ok = [r for r in rows if r["model"] == "fem" and r["error"] <= 0.005]
        ross = [r for r in rows if r["model"] == "ROSS"]
        if ok and ross:
            ours = min(ok, key=lambda r: r["cold_s"])
            best_ross = min(ross, key=lambda r: r["error"])
            print(f"ours at <= 0.5 % ({ours['mesh']}, cold): {1e3 * ours['cold_s']:.1f} ms; "
                  f"ROSS's most accurate ({best_ross['mesh']}, error "
                  f"{100 * best_ross['error']:.2g} %): {best_ross['cold_s']:.2f} s = "
                  f"{best_ross['cold_s'] / ours['cold_s']:.0f}x")
    return rows


if __name__ == "__main__":
    main()
