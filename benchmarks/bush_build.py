"""The solid bush's compliance build: the 3-D solid (``model="solid-3d"``, one sparse LU
of the hexahedral body) against the solid per circumferential harmonic (``model="solid"``,
one banded Cholesky of the (r, z) section per harmonic), time and peak memory per film
grid, and the steady EHD film on the latter.

    python -m benchmarks.bush_build                 # 48 x 8 .. 480 x 80, 3-D up to 120
    python -m benchmarks.bush_build --old-max 96 --quick
    python -m benchmarks.bush_build --old-max 0 --q1-max 0 --finest --before DIR
                          # to 960 x 160, the harmonic solid also from the checkout DIR
    python -m benchmarks.bush_build --old-max 0 --q1-max 0 --finest --from-theta 240 \
        --model ring --before DIR        # the same with the ring bush (or liner)

Each cell is one fresh Python process (its peak RSS, ``resource.getrusage``, over ~100 MB
of imports): ``bush_compliance(bush, R, L, n_theta, n_z + 1)`` (the film grid of
``solve_reynolds(..., n_theta, n_z)``), timed, then for the harmonic solid the seed pin's
heavy state solved on it (``solve_reynolds(..., bush=compliance)``: the film operator and
the Newton solve, the compliance given; from 240 x 40 up its Newton starts from the film
of the mesh half as fine, whose solve and compliance build are in "solve", and "iters" are
the Newton steps on the film's own mesh; ``--model ring`` or ``liner``: that bush instead
of the harmonic solid in the new and before columns). "q1" is the harmonic solid
with the alias sum to |q| <= 1 (three times the harmonics). Case: R 10 mm, L 4 mm, c 20
um, 250 rad/s, eps 0.995, gamma 0.2, bronze bush (E 110 GPa, nu 0.34, outer radius 16 mm,
free ends), Reynolds' condition. Times are one run on a shared machine: compare the
ratios within one run ("cpu": the process's CPU time, less moved by the other jobs on a
shared machine than the wall time). ``--before DIR``: the same bush (``--model``) from another checkout (its
build, solve and memory; "same": its load over this tree's, minus one) in the same run.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
MESHES = [(48, 8), (96, 16), (120, 20), (240, 40), (480, 80)]
FINEST = (960, 160)
#: Bush models whose compliance is also solved on (``--model``).
SOLVED = ("solid", "ring", "liner")


def child(model: str, n_theta: int, n_z: int):
    """Build (and for "solid", solve on) the compliance; print one JSON line."""
    import resource
    import time

    import numpy as np

    import bearingfem.elastic.compliance as compliance
    from bearingfem import ElasticBush, JournalState, solve_reynolds
    from bearingfem.bearing import seed_bearing
    seed = seed_bearing(0.2)
    base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    if model == "q1":
        compliance.ALIASES = 1
    bush = ElasticBush(outer_radius=0.016, modulus=110e9, poisson=0.34,
                       model=model if model in ("solid-3d", "ring", "liner") else "solid")
    t, cpu = time.perf_counter(), time.process_time()
    c = compliance.bush_compliance(bush, seed.radius, seed.length, n_theta, n_z + 1)
    out = dict(build=time.perf_counter() - t, build_cpu=time.process_time() - cpu, base=base,
               build_rss=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)
    if model in SOLVED:
        t, cpu = time.perf_counter(), time.process_time()
        sol = solve_reynolds(seed, JournalState(eps=0.995, gamma=0.2, omega=250.0),
                             n_theta, n_z, bush=c)
        out.update(solve=time.perf_counter() - t, solve_cpu=time.process_time() - cpu,
                   iterations=sol.iterations,
                   force=float(np.linalg.norm(sol.force)), p_max=sol.pressure_max,
                   h_min=float(np.min(sol.film_thickness)),
                   rss=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)
    print(json.dumps(out))


def run(model: str, mesh, tree: Path = ROOT):
    env = dict(os.environ, PYTHONPATH=str(tree), OMP_NUM_THREADS="1",
               OPENBLAS_NUM_THREADS="1", MPLBACKEND="Agg")
    cmd = [sys.executable, str(Path(__file__).resolve()), "--child", model, *map(str, mesh)]
    proc = subprocess.run(cmd, env=env, cwd="/tmp", capture_output=True, text=True)
    if proc.returncode:
        lines = proc.stderr.strip().splitlines()
        return dict(error=lines[-1][:60] if lines else f"exit {proc.returncode}")
    return json.loads(proc.stdout.strip().splitlines()[-1])


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--old-max", type=int, default=120,
                        help="largest n_theta the 3-D solid is built at")
    parser.add_argument("--q1-max", type=int, default=240,
                        help="largest n_theta the alias sum |q| <= 1 is built at")
    parser.add_argument("--quick", action="store_true", help="48 x 8 and 96 x 16 only")
    parser.add_argument("--finest", action="store_true", help="also 960 x 160")
    parser.add_argument("--before", type=Path, default=None,
                        help="a checkout whose bush (--model) runs beside this one's")
    parser.add_argument("--model", choices=SOLVED, default="solid",
                        help="the bush built and solved on in the new and before columns")
    parser.add_argument("--from-theta", type=int, default=0,
                        help="skip the meshes of fewer n_theta")
    parser.add_argument("--child", nargs=3, default=None)
    args = parser.parse_args(argv)
    if args.child:
        model, n_theta, n_z = args.child
        return child(model, int(n_theta), int(n_z))
    meshes = MESHES[:2] if args.quick else MESHES + [FINEST] * args.finest
    meshes = [m for m in meshes if m[0] >= args.from_theta]
    print(f"{'mesh':>7} {'3d[s]':>7} {'3d[MB]':>7} {'new[s]':>7} {'new[MB]':>7} "
          f"{'q1[s]':>7} {'solve[s]':>8} {'MB':>6} {'iters':>5} {'|F|[N]':>8} "
          f"{'p_max[MPa]':>10} {'h_min[um]':>9}"
          + f" {'cpu':>6} {'cpu':>7}"
          + (f" {'bef[s]':>7} {'cpu':>6} {'solve[s]':>8} {'cpu':>7} {'MB':>6} {'same':>8}"
             if args.before else ""))
    rows = []
    for mesh in meshes:
        old = run("solid-3d", mesh) if mesh[0] <= args.old_max else None
        q1 = run("q1", mesh) if mesh[0] <= args.q1_max else None
        new = run(args.model, mesh)
        before = run(args.model, mesh, args.before) if args.before else None
        rows.append(dict(mesh=mesh, old=old, new=new, q1=q1, before=before))

        def cell(r, key, fmt):
            width = fmt.split(".")[0]
            return (format("-", ">" + width) if r is None or key not in r and
                    "error" not in r else
                    format(r["error"][:int(width)], ">" + width) if "error" in r else
                    format(r[key], fmt))
        print(f"{mesh[0]:>3}x{mesh[1]:<3} {cell(old, 'build', '7.2f')} "
              f"{cell(old, 'build_rss', '7.0f')} {cell(new, 'build', '7.2f')} "
              f"{cell(new, 'build_rss', '7.0f')} {cell(q1, 'build', '7.2f')} "
              f"{cell(new, 'solve', '8.2f')} {cell(new, 'rss', '6.0f')} "
              f"{cell(new, 'iterations', '5d')} {cell(new, 'force', '8.2f')} "
              f"{new.get('p_max', float('nan')) / 1e6:10.2f} "
              f"{new.get('h_min', float('nan')) * 1e6:9.3f} "
              f"{cell(new, 'build_cpu', '6.2f')} {cell(new, 'solve_cpu', '7.2f')}"
              + ("" if before is None else
                 f" {cell(before, 'build', '7.2f')} {cell(before, 'build_cpu', '6.2f')} "
                 f"{cell(before, 'solve', '8.2f')} {cell(before, 'solve_cpu', '7.2f')} "
                 f"{cell(before, 'rss', '6.0f')} " + (format(before['force'] / new['force']
                                                             - 1.0, '8.1e')
                                                      if 'force' in before and 'force'
                                                      in new else format('-', '>8'))),
              flush=True)
    return rows


if __name__ == "__main__":
    main()
