"""Where the long bearing's JFO-coupled run spends its time, against the Reynolds one.

    python -m benchmarks.jfo_coupled [--turns N] [--integrators lsoda bdf radau]
                                     [--reference-rtol R] [-o results/benchmarks]

Scene paper-long-jfo (L/D 2, 48x16, film step 1e-4 s, rtol 1e-6) run with Reynolds'
condition ("fem", cavitation reynolds, the same mesh) and with the JFO film ("fem-jfo"),
each with every integrator named, all in one process, once each. Per run: accepted steps,
right-hand-side evaluations (each one film solve at a trial state), film steps (of them
early: the kept film no longer fitted the journal; refills: early steps whose force acts at
once), the share of LSODA's steps taken with its stiff method (BDF, else Adams), the
process's CPU time [s], the part of it in the commits (film steps and their
checks) and the mean cost of one trial-state evaluation [ms]; the ratios to the Reynolds
run with the same integrator and to the Reynolds run with LSODA (the scenes'
integrator); the minimum film of the last turn and, with ``--reference-rtol``, the orbit's
largest distance over the last turn from a JFO run at that tolerance with Radau [um]
(the film's accuracy the cheaper runs are held to). CPU time, not wall time: the machine is
shared. Writes jfo_coupled.csv.

The timing of force and commit wraps the mechanism's film effect for the run's duration
(one process_time call around each; measurement only, the film is not changed).
"""
from __future__ import annotations

import argparse
import contextlib
import dataclasses
import time
from pathlib import Path

import numpy as np

from scipy.integrate._ivp.lsoda import LSODA

from bearingfem import transient
from bearingfem.outputs.tables import write_csv
from mechanism import effects, load_scene, simulate

from .common import best_of


@contextlib.contextmanager
def _timed_film(counts: dict):
    """Time FilmEffect.commit (CPU), count early and refill film steps and LSODA's steps
    taken with its stiff method (BDF; its other is Adams) while inside."""
    commit, jfo_commit = effects.FilmEffect.commit, transient.TransientJFO.commit
    lsoda_step = LSODA._step_impl

    def counted(self):
        out = lsoda_step(self)
        counts["stiff"] += int(self._lsoda_solver._integrator.iwork[18] == 2)  # MUSED
        return out

    def timed(self, k, recording=True):
        c0 = time.process_time()
        try:
            return commit(self, k, recording)
        finally:
            counts["commit_cpu"] += time.process_time() - c0

    def classified(self, state, t):
        last = self.t
        step = jfo_commit(self, state, t)
        if step is not None and t - last <= self.film_step:
            counts["early"] += 1
            counts["refills"] += self._jump == (0.0, 0.0)
        return step
    effects.FilmEffect.commit, transient.TransientJFO.commit = timed, classified
    LSODA._step_impl = counted
    try:
        yield counts
    finally:
        effects.FilmEffect.commit, transient.TransientJFO.commit = commit, jfo_commit
        LSODA._step_impl = lsoda_step


def _scene(turns: float, model: str, integrator: str, rtol: float | None = None):
    sc = load_scene("paper-long-jfo")
    run = dataclasses.replace(sc.run, turns=turns, record_from_turn=max(0.0, turns - 1.0),
                              integrator=integrator, rtol=rtol or sc.run.rtol)
    lub = sc.lubrication
    if model == "fem":
        lub = dataclasses.replace(lub, model="fem", options=dict(
            n_theta=lub.options["n_theta"], n_z=lub.options["n_z"], cavitation="reynolds"))
    return dataclasses.replace(sc, run=run, lubrication=lub)


def _run(scene) -> dict:
    counts = dict(commit_cpu=0.0, early=0, refills=0, stiff=0)
    with _timed_film(counts):
        t = best_of(lambda: simulate(scene, progress=False))
        r, cpu = t.out, t.cpu
    s = r.stats
    return dict(film=scene.lubrication.model, integrator=scene.run.integrator,
                steps=int(s["steps"]), rhs_evals=int(s["rhs_evals"]),
                film_steps=int(s["film_steps"]), early=counts["early"],
                refills=counts["refills"], stiff_fraction=counts["stiff"] / s["steps"],
                cpu_s=cpu, commit_cpu_s=counts["commit_cpu"],
                ms_per_eval=1e3 * (cpu - counts["commit_cpu"]) / s["rhs_evals"],
                partial=bool(r.partial), film_min_um=1e6 * float(r.film_min.min()),
                peak_eps=float(r.eps.max()), orbit=(r.t, r.e_x, r.e_y))


def _distance_um(orbit, ref) -> float:
    """Largest distance [um] of an orbit from the reference's over the reference's times."""
    t, ex, ey = orbit
    tr, rx, ry = ref
    return 1e6 * float(np.max(np.hypot(np.interp(tr, t, ex) - rx, np.interp(tr, t, ey) - ry)))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--output", default="results/benchmarks")
    ap.add_argument("--turns", type=float, default=4.0)
    ap.add_argument("--integrators", nargs="*", default=["lsoda", "bdf", "radau"])
    ap.add_argument("--reference-rtol", type=float, default=None,
                    help="also run the JFO film with Radau at this rtol (e.g. 1e-8)")
    a = ap.parse_args(argv)
    rows = [_run(_scene(a.turns, m, i)) for m in ("fem", "fem-jfo") for i in a.integrators]
    ref = None
    if a.reference_rtol is not None:
        ref = _run(_scene(a.turns, "fem-jfo", "radau", a.reference_rtol))
    rey = {r["integrator"]: r["cpu_s"] for r in rows if r["film"] == "fem"}
    print(f"paper-long-jfo, {a.turns:g} turns, rtol 1e-6, CPU time of one process")
    print("| film | integrator | steps | rhs evals | evals/step | film steps (early, refills) "
          "| LSODA stiff steps | CPU [s] | in commits [s] | ms / eval | / Reynolds, same "
          "integrator | / Reynolds LSODA | min film [um] | orbit vs reference [um] |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows + ([ref] if ref else []):
        r["over_reynolds"] = r["cpu_s"] / rey.get(r["integrator"], np.nan)
        r["over_reynolds_lsoda"] = r["cpu_s"] / rey.get("lsoda", np.nan)
        r["orbit_vs_reference_um"] = (_distance_um(r["orbit"], ref["orbit"])
                                      if ref and r["film"] == "fem-jfo" else np.nan)
        name = "reference" if r is ref else r["film"]
        print(f"| {name}{' (partial)' if r['partial'] else ''} | {r['integrator']} | "
              f"{r['steps']} | {r['rhs_evals']} | {r['rhs_evals'] / r['steps']:.2f} | "
              f"{r['film_steps']} ({r['early']}, {r['refills']}) | "
              f"{r['stiff_fraction']:.0%} | {r['cpu_s']:.1f} | "
              f"{r['commit_cpu_s']:.1f} | {r['ms_per_eval']:.2f} | "
              f"{r['over_reynolds']:.2f} | {r['over_reynolds_lsoda']:.2f} | "
              f"{r['film_min_um']:.3f} | {r['orbit_vs_reference_um']:.3f} |", flush=True)
    out = Path(a.output)
    out.mkdir(parents=True, exist_ok=True)
    write_csv([{k: v for k, v in r.items() if k != "orbit"} for r in rows + ([ref] if ref else [])],
              out / "jfo_coupled.csv")
    return rows


if __name__ == "__main__":
    main()
