"""Which film mesh each bush model needs: the seed pin's heavy state (L/D 0.2, eps 0.995,
250 rad/s, Reynolds' condition; bronze bush E 110 GPa, nu 0.34, outer radius 16 mm) on
meshes refined twice at a time, the load |F|, the peak pressure and the least film, each
against the finest mesh's value and Richardson's extrapolation of the last three, with the
time of each cold solve (compliance build included) and its process's peak memory (each
row a fresh process: ``resource.getrusage``, ~100 MB of it imports) in one run.

    python -m studies.ehd_mesh            # every bush model to 384 x 32
    python -m studies.ehd_mesh --quick    # 48 x 4 .. 96 x 8
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

from bearingfem import ElasticBush, JournalState, solve_reynolds
from bearingfem.bearing import seed_bearing

BRONZE = dict(outer_radius=0.016, modulus=110e9, poisson=0.34)
HEAVY = JournalState(eps=0.995, gamma=0.0, omega=250.0)
MESHES = {"ring": [(48, 4), (96, 8), (192, 16), (384, 32)],
          "liner": [(48, 4), (96, 8), (192, 16), (384, 32)],
          "solid": [(48, 4), (96, 8), (192, 16), (384, 32)]}


def richardson(a, b, c):
    """The limit of a, b, c (meshes refined twice each) and the observed order, or (c,
    nan) where the differences do not shrink monotonically."""
    d1, d2 = b - a, c - b
    if d1 == 0 or d2 / d1 <= 0 or abs(d2) >= abs(d1):
        return c, float("nan")
    order = np.log2(d1 / d2)
    return c + d2 / (2**order - 1), order


def bush_study_args(argv, description: str) -> argparse.Namespace:
    """The options of a study over the bush models: --quick, --models."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--models", default="ring,liner,solid",
                        help="comma list of bush models")
    return parser.parse_args(argv)


def solve(model: str, n_theta: int, n_z: int):
    """One cold solve (compliance build included): load [N], peak pressure [Pa], least
    film [m], time [s], the process's peak memory [MB]."""
    import resource
    t = time.perf_counter()
    sol = solve_reynolds(seed_bearing(0.2), HEAVY, n_theta, n_z,
                         bush=ElasticBush(model=model, **BRONZE))
    return (float(np.hypot(*sol.force_local)), sol.pressure_max, sol.film_min,
            time.perf_counter() - t, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)


def fresh(model: str, n):
    """:func:`solve` in a fresh process (its peak memory that solve's alone)."""
    root = Path(__file__).resolve().parents[1]
    env = dict(os.environ, PYTHONPATH=str(root))
    code = (f"import json; from studies.ehd_mesh import solve; "
            f"print(json.dumps(solve({model!r}, {n[0]}, {n[1]})))")
    proc = subprocess.run([sys.executable, "-c", code], env=env, cwd=root,
                          capture_output=True, text=True, check=True)
    return json.loads(proc.stdout.strip().splitlines()[-1])


def main(argv=None):
    args = bush_study_args(argv, __doc__.splitlines()[0])
    out = {}
    print(f"{'bush':>6} {'mesh':>8} {'|F| [N]':>9} {'p_max[MPa]':>10} {'h_min[um]':>9} "
          f"{'time[s]':>8} {'MB':>6} {'dF/F_fin':>9} {'dp/p_fin':>9}")
    for model in args.models.split(","):
        meshes = MESHES[model]
        meshes = meshes[:2] if args.quick else meshes
        rows = [(n, *fresh(model, n)) for n in meshes]
        F_fin, p_fin = rows[-1][1], rows[-1][2]
        for n, F, p, h, s, mb in rows:
            print(f"{model:>6} {n[0]:>4}x{n[1]:<3} {F:9.2f} {p / 1e6:10.2f} {h * 1e6:9.3f} "
                  f"{s:8.2f} {mb:6.0f} {abs(F / F_fin - 1):9.2e} {abs(p / p_fin - 1):9.2e}",
                  flush=True)
        if len(rows) >= 3:
            for name, k in (("|F|", 1), ("p_max", 2), ("h_min", 3)):
                lim, order = richardson(*(r[k] for r in rows[-3:]))
                errs = ", ".join(f"{abs(r[k] / lim - 1):.1e}" for r in rows)
                print(f"{model:>6} {name:>6}: Richardson limit {lim:.6g} (order {order:.2f}); "
                      f"errors {errs}")
        out[model] = rows
    return out


if __name__ == "__main__":
    main()
