"""Cost of stepping scipy's solvers in the mechanism's own loop (mechanism.stepping)
against solve_ivp, on a paper scene: the same steps (bit-identical results, checked
here), so the ratio is the loop's overhead (accept calls, bookkeeping).

    python -m benchmarks.stepping [--scene paper-short-analytic] [--turns 1] [--repeats 3]

Runs alternate (loop, solve_ivp, loop, ...) so both see the same machine load; the table
gives each one's median wall time and their ratio.
"""
from __future__ import annotations

import argparse
import dataclasses
import importlib
import statistics
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

from mechanism import load_scene, simulate
from mechanism.stepping import Segment

from .common import best_of

#: the module (``mechanism.simulate`` as an attribute is the function)
sim = importlib.import_module("mechanism.simulate")
SCENES = Path(__file__).resolve().parent.parent / "mechanism" / "scenes"


def _solve_ivp_segment(fun, t_span, y0, method="LSODA", events=(), accept=None, **options):
    """solve_ivp in the loop's place (what the mechanism called before): accept unused."""
    r = solve_ivp(fun, t_span, y0, method=method, events=events, dense_output=True,
                  **options)
    return Segment(r.t, r.y, r.sol, r.t_events, r.status, r.message)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default="paper-short-analytic")
    ap.add_argument("--turns", type=float, default=1.0)
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args(argv)
    scene = load_scene(SCENES / f"{args.scene}.toml")
    scene = dataclasses.replace(scene, run=dataclasses.replace(
        scene.run, turns=args.turns, record_from_turn=0))
    own = sim.integrate
    times = {"own loop": [], "solve_ivp": []}
    results = {}
    for _ in range(args.repeats):
        for name, loop in (("own loop", own), ("solve_ivp", _solve_ivp_segment)):
            sim.integrate = loop
            try:
                t = best_of(lambda: simulate(scene, progress=False))
                results[name] = t.out
                times[name].append(t.wall)
            finally:
                sim.integrate = own
    a, b = results["own loop"], results["solve_ivp"]
    same = np.array_equal(a.step_t, b.step_t) and np.array_equal(a.eps, b.eps)
    print(f"{args.scene}, {args.turns} turn(s), {a.stats['steps']} steps, "
          f"results bit-identical: {same}")
    print("| loop | median wall [s] | runs |")
    print("|---|---|---|")
    for name, t in times.items():
        print(f"| {name} | {statistics.median(t):.3f} | {len(t)} |")
    ratio = statistics.median(times["own loop"]) / statistics.median(times["solve_ivp"])
    print(f"own loop / solve_ivp: {ratio:.3f}")
    return ratio, same


if __name__ == "__main__":
    main()
