"""Steady EHD film, full compliance: the dense route (compliance matrix, dense LU Newton
steps) against the FFT-GMRES route (compliance per theta harmonic, GMRES steps
preconditioned by the film's sparse LU), time and peak memory per mesh.

    python -m benchmarks.ehd_fast --old-tree DIR     # DIR: a checkout of the dense route
    python -m benchmarks.ehd_fast --quick            # smoke run (new route, 60 x 10)
    python -m benchmarks.ehd_fast --jfo --old-max 120    # the EHD-JFO film
    python -m benchmarks.ehd_fast --solid            # also the 3-D solid bush (new route,
                                                     # heavy state, two coarser meshes)

Each cell is one fresh Python process (so its peak RSS, ``resource.getrusage``, is the
solve's own, over ~100 MB of imports) that calls ``solve_reynolds(..., bush=)`` once,
cold: the film operator, the bush's compliance and the Newton solve from the rigid film,
all timed. Cases: R 10 mm, c 20 um, mu 0.0117 Pa s, 250 rad/s, bronze bush (E 110 GPa,
nu 0.34, outer radius 16 mm), Reynolds' condition: L/D 0.5 and 1 at eps 0.8 and 0.9, and
the seed pin's heavy state (L/D 0.2, eps 0.995: the bush carries the film, p_max falls
tenfold). The dense route is run where its matrix fits (``--old-max`` cells around);
"same" is max |p_new - p_old| / p_max. Times are one run on a shared machine: compare the
ratios within one run.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CASES = [(0.5, 0.8), (0.5, 0.9), (1.0, 0.8), (1.0, 0.9), (0.2, 0.995)]
MESHES = [(120, 20), (240, 40), (480, 80)]


def child(ld: float, eps: float, n_theta: int, n_z: int, model: str, out: str):
    """Solve once and print time [s], peak RSS [MB], Newton iterations, the pressure
    (``model`` "ring-jfo" etc.: the EHD-JFO film, ambient 1e5 Pa)."""
    model, _, jfo = model.partition("-")
    import resource
    import time

    import numpy as np

    from bearingfem import ElasticBush, JournalState, solve_reynolds
    from bearingfem.bearing import seed_bearing
    base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    bush = ElasticBush(outer_radius=0.016, modulus=110e9, poisson=0.34, model=model)
    t = time.perf_counter()
    kw = dict(cavitation="jfo", ambient_pressure=1e5) if jfo else {}
    sol = solve_reynolds(seed_bearing(ld), JournalState(eps=eps, omega=250.0), n_theta,
                         n_z, bush=bush, **kw)
    seconds = time.perf_counter() - t
    np.save(out, sol.pressure)
    print(json.dumps(dict(where=str(Path(sys.modules["bearingfem"].__file__).parent),
                          seconds=seconds, rss=resource.getrusage(
        resource.RUSAGE_SELF).ru_maxrss / 1024, base=base, iterations=sol.iterations,
        p_max=sol.pressure_max, w_max=float(np.max(sol.deformation)))))


def run(tree: Path, case, mesh, model: str, out: str):
    env = dict(os.environ, PYTHONPATH=str(tree), OMP_NUM_THREADS="1",
               OPENBLAS_NUM_THREADS="1", MPLBACKEND="Agg")
    # this file run as a script (not -m: the working directory stays off sys.path), its
    # bearingfem the one of ``tree``
    cmd = [sys.executable, str(Path(__file__).resolve()), "--child",
           *map(str, (*case, *mesh)), model, out]
    proc = subprocess.run(cmd, env=env, cwd="/tmp", capture_output=True, text=True)
    if proc.returncode:
        lines = proc.stderr.strip().splitlines()
        return dict(error=lines[-1][:60] if lines else f"exit {proc.returncode}")
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    if Path(out["where"]) != tree.resolve() / "bearingfem":
        raise RuntimeError(f"the child imported {out['where']}, not {tree}")
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--old-tree", type=Path, default=None)
    parser.add_argument("--old-max", type=int, default=240)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--solid", action="store_true")
    parser.add_argument("--jfo", action="store_true",
                        help="the EHD-JFO film instead (ring, L/D 1, eps 0.8)")
    parser.add_argument("--child", nargs=6, default=None)
    args = parser.parse_args(argv)
    if args.child:
        ld, eps, n_theta, n_z, model, out = args.child
        return child(float(ld), float(eps), int(n_theta), int(n_z), model, out)
    import numpy as np
    meshes = [(60, 10)] if args.quick else MESHES
    cases = CASES[-1:] if args.quick else CASES
    if args.jfo:
        cases = [(1.0, 0.8)]
    runs = [("ring-jfo" if args.jfo else "ring", c, meshes) for c in cases] + (
        [("solid", c, meshes[:2]) for c in cases[-1:]] if args.solid else [])
    print(f"{'bush':>5} {'L/D':>4} {'eps':>6} {'mesh':>7} {'old[s]':>8} {'old[MB]':>8} "
          f"{'new[s]':>7} {'new[MB]':>8} {'iters':>5} {'p_max[MPa]':>10} {'same':>8}")
    rows = []
    tmp = Path("/tmp") / f"ehd_fast_{os.getpid()}"
    for model, case, on in runs:
        for mesh in on:
            new = run(ROOT, case, mesh, model, f"{tmp}_new.npy")
            old = (run(args.old_tree, case, mesh, model, f"{tmp}_old.npy")
                   if args.old_tree and mesh[0] <= args.old_max
                   and not model.startswith("solid")
                   else None)
            same = (float(np.max(np.abs(np.load(f"{tmp}_new.npy") - np.load(
                f"{tmp}_old.npy"))) / new["p_max"])
                    if old and "error" not in old and "error" not in new else None)
            rows.append(dict(model=model, case=case, mesh=mesh, old=old, new=new, same=same))

            def cell(r, key, fmt):
                return (format("-", ">" + fmt.split(".")[0]) if r is None else
                        format(r["error"][:8], ">8") if "error" in r else
                        format(r[key], fmt))
            print(f"{model:>5} {case[0]:4.1f} {case[1]:6.3f} {mesh[0]:>3}x{mesh[1]:<3} "
                  f"{cell(old, 'seconds', '8.2f')} {cell(old, 'rss', '8.0f')} "
                  f"{cell(new, 'seconds', '7.2f')} {cell(new, 'rss', '8.0f')} "
                  f"{cell(new, 'iterations', '5d')} "
                  f"{(new.get('p_max', float('nan'))) / 1e6:10.2f} "
                  f"{'-' if same is None else format(same, '8.1e')}", flush=True)
    for ext in ("new", "old"):
        Path(f"{tmp}_{ext}.npy").unlink(missing_ok=True)
    return rows


if __name__ == "__main__":
    main()
