"""Reproduce the seed's Section 3 (Figs. 2-7): the six paper scenes, their figures and a
summary table.

    python -m studies.paper -o results/paper            # all six scenes
    python -m studies.paper -o out --turns 1 --scenes paper-long-analytic paper-long-fem
"""
from __future__ import annotations

import argparse
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

from bearingfem.outputs.tables import write_csv
from mechanism import load_scene, simulate
from mechanism.figures import plot_comparison
from mechanism.parameters import GRAVITY
from mechanism.rigid import simulate_rigid
from mechanism.scene import SCENES

PAPER = [f"paper-{b}-{m}" for b in ("short", "long") for m in ("analytic", "fem", "fvm")]
COLUMNS = ("scene", "status", "wall_time_s", "steps", "rhs_evals", "film_solves", "peak_eps",
           "min_film_um", "crank_speed_min_rad_s", "crank_speed_max_rad_s",
           "max_dspeed_vs_ideal_rad_s", "peak_slider_acc_m_s2")


def ideal_crank_speed(scene, crank_angle):
    """The ideal (rigid-joint) mechanism's crank speed at the given crank angles."""
    g = GRAVITY if scene.gravity else 0.0
    _, q, qd = simulate_rigid(scene.mechanism, scene.crank_speed, scene.run.turns + 0.1, g,
                              samples_per_turn=4000)
    return np.interp(crank_angle, q, qd)


def summarise(name, r, scene=None):
    """The run's summary row, with its departure from the ideal mechanism when the scene
    is given."""
    ideal = None if scene is None or len(r.t) == 0 else ideal_crank_speed(scene, r.crank_angle)
    return {**r.summary_row(ideal), "scene": name}


def run(out: Path, names=PAPER, turns=None, progress=None):
    out.mkdir(parents=True, exist_ok=True)
    results, rows = {}, []
    for name in names:
        scene = load_scene(SCENES / f"{name}.toml")
        if turns is not None:
            scene = replace(scene, run=replace(scene.run, turns=turns,
                                               record_from_turn=max(0.0, turns - 1.0)))
        r = simulate(scene, progress=progress)
        r.save(out / name)
        results[name] = (scene, r)
        rows.append(summarise(name, r, scene))
        print(r.summary(), flush=True)
    for bearing, figs in (("short", "Figs. 2-4"), ("long", "Figs. 5-7")):
        chosen = [n for n in names if n.startswith(f"paper-{bearing}-")]
        if not chosen:
            continue
        c = results[chosen[0]][0].bearing.clearance
        plot_comparison([results[n][1] for n in chosen], [n.split("-")[-1] for n in chosen], c,
                        title=f"{bearing} bearing (L/D = {results[chosen[0]][0].bearing.length_ratio:g})"
                              f" - seed {figs}", path=out / f"paper-{bearing}.png")
    write_csv(rows, out / "summary.csv", COLUMNS)
    print("\n" + markdown_table(rows))
    return results, rows


def markdown_table(rows):
    head = "| " + " | ".join(COLUMNS) + " |\n|" + "---|" * len(COLUMNS) + "\n"
    return head + "".join("| " + " | ".join(str(r.get(k, "")) for k in COLUMNS) + " |\n"
                          for r in rows)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("-o", "--output", default="results/paper")
    p.add_argument("--scenes", nargs="+", default=PAPER, choices=PAPER)
    p.add_argument("--turns", type=float, default=None,
                   help="override the scenes' number of crank turns (quick looks)")
    a = p.parse_args(argv)
    _, rows = run(Path(a.output), a.scenes, a.turns)
    return 1 if any(r["status"] != "completed" for r in rows) else 0


if __name__ == "__main__":
    sys.exit(main())
