"""The seed's piston pin with the EHD film, five turns, in the mesh: the convergence table,
where the least film sits, and the bush's deflection at the peak joint load.

    python -m studies.seed_pin [--meshes 48 4 96 8 192 16] [--modes 64] [--crown 2]
        [--turns 5] [--figure results/seed_pin_deflection.png] [--save DIR | --load PATTERN]

Each mesh: the rigid JFO run (``paper-short-jfo``) and the EHD run
(``paper-short-ehd-sharp``, the bush's ``--modes`` integrated with the journal, tau 1e-5 s,
rough surfaces sigma 0.2 um, the isoviscous oil of benchmarks/ehd_states.py, a bush bore
crowned by ``--crown`` um over its whole length, 0 the sharp-edged bore), timed in one
process. Prints per mesh the last turn's least film, peak pressure, the summits' share
of the load (their load's time integral over the film's total force's) and the mean
friction power (film shear and the summits' Coulomb friction), with the change from the
previous mesh, and the cost against the rigid JFO run; then, on each mesh, where the
least film of the last turn sits (crank angle, the bush's angle, z over L/2, the
summits' share then) and its position along the turn every 30 degrees of crank.
Writes the finest mesh's bush deflection and pressure at the peak joint load of the last
turn to ``--figure``. ``--save DIR`` keeps each run (DIR/<n_theta>x<n_z>); ``--load PATTERN``
reads the runs from PATTERN with {mesh} as 48x4 (DIR/{mesh} for runs kept by ``--save``;
no timing then).
"""
from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from bearingfem import ElasticJournalState
from bearingfem.fields import EdgeProfile
from bearingfem.film import inertial_from_theta
from bearingfem.models import film_model
from benchmarks.common import OILS, scene
from benchmarks.ehd_states import (
    ROUGH,
    RUNS,
    last_turn,
    last_turn_work,
    rigid_jfo,
    states_run,
)
from mechanism.result import film_column, load_result

from .ehd_paper import render_deflection

STATE = ("eps", "eps_dot", "gamma", "gamma_dot", "omega")


def run_scene(turns, nt, nz, modes, profile):
    """The scene of the EHD run (:func:`benchmarks.ehd_states.states_run`'s)."""
    _, tau, _, oil = RUNS["base"]
    return scene("paper-short-ehd-sharp", 250.0, turns, n_theta=nt, n_z=nz, modes=modes,
               film_step=0.0, lubricant=OILS[oil], coupling="states", relaxation=tau,
               roughness=ROUGH, profile=profile)


def turn_stats(r, k, radius, friction=ROUGH.friction):
    """(least film [um], peak pressure [MPa], summits' share, friction power [W]) over the
    run's k-th crank turn (from the film record: as benchmarks.ehd_states' last turn)."""
    rec = np.asarray(r.film_record)
    t = film_column(rec, "t")
    crank = np.interp(t, r.t, r.crank_angle)
    on = (crank >= 2 * np.pi * (k - 1)) & (crank < 2 * np.pi * k)
    rec, t = rec[on], t[on]
    a = film_column(rec, "asperity_load")
    f = np.hypot(film_column(rec, "force_x"), film_column(rec, "force_y"))
    om = film_column(rec, "omega")
    power = (film_column(rec, "friction_force") * om + friction * a * np.abs(om)) * radius
    return (1e6 * float(film_column(rec, "film_min").min()),
            float(film_column(rec, "pressure_max").max()) / 1e6,
            float(np.trapezoid(a, t) / np.trapezoid(f, t)),
            float(np.trapezoid(power, t) / (t[-1] - t[0])))


def last_turn_rows(r, turns):
    """Indices of the film record's rows in the run's last whole turn."""
    t0 = r.t[np.argmax(r.crank_angle >= 2 * np.pi * (np.floor(turns) - 1))]
    return np.flatnonzero(film_column(r.film_record, "t") >= t0)


def film_at(sc, r, rows):
    """(state, FilmSolution) of the run's own film at each of the film record's ``rows``
    (solved at the row's journal state and modal coordinates)."""
    rec = r.film_record
    film = film_model(sc.lubrication.model).along_run(sc.bearing, dict(sc.lubrication.options))
    for j in rows:
        state = ElasticJournalState(**{n: float(film_column(rec, n)[j]) for n in STATE})
        yield state, film.solution(state, r.film_z[j])


def where(sc, r, rows):
    """(crank [deg], film_min [um], alpha [deg, bush frame], z / (L/2), summits' share)
    of the run's own film at the film record's ``rows``: the node of least gap."""
    rec = r.film_record
    half = 0.5 * sc.bearing.length
    out = []
    for j, (state, sol) in zip(rows, film_at(sc, r, rows)):
        k = int(np.argmin(sol.film_thickness))
        alpha = np.degrees(np.mod(inertial_from_theta(float(np.asarray(sol.theta)[k]),
                                                      state.gamma), 2 * np.pi))
        total = np.hypot(*sol.total_force)
        share = float(np.hypot(*sol.asperity_force) / total) if total else 0.0
        crank = np.degrees(np.interp(film_column(rec, "t")[j], r.t, r.crank_angle)) % 360
        out.append((crank, 1e6 * float(sol.film_thickness[k]), alpha,
                    float(np.asarray(sol.z)[k]) / half, share))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--meshes", type=int, nargs="+", default=[48, 4, 96, 8, 192, 16])
    ap.add_argument("--modes", type=int, default=64)
    ap.add_argument("--crown", type=float, default=2.0, help="crown depth [um] (0: sharp)")
    ap.add_argument("--turns", type=float, default=5.0)
    ap.add_argument("--figure", default="results/seed_pin_deflection.png")
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--save", metavar="DIR", default=None)
    g.add_argument("--load", metavar="PATTERN", default=None,
                   help="read the runs from PATTERN with {mesh} as 48x4 (e.g. DIR/{mesh})")
    a = ap.parse_args(argv)
    if len(a.meshes) % 2:
        raise ValueError("--meshes takes pairs n_theta n_z")
    meshes = list(zip(a.meshes[::2], a.meshes[1::2]))
    profile = EdgeProfile("crown", a.crown * 1e-6) if a.crown > 0 else None
    print(f"seed pin, 250 rad/s, {a.turns:g} turns, {a.modes} modes, bush bore "
          f"{'sharp' if profile is None else f'crowned {a.crown:g} um over its length'}")
    print(f"{'mesh':>9} {'steps':>6} {'CPU[s]':>8} {'JFO[s]':>7} {'x JFO':>6} "
          f"{'h_min[um]':>9} {'d%':>6} {'p_max[MPa]':>10} {'d%':>6} {'share':>7} {'d%':>6} "
          f"{'P_f[W]':>7} {'d%':>6}")
    runs, before = [], None
    for nt, nz in meshes:
        sc = run_scene(a.turns, nt, nz, a.modes, profile)
        if a.load:
            r = load_result(a.load.format(mesh=f"{nt}x{nz}"))
            cpu = jfo = float("nan")
        else:
            rigid_jfo(0.002, nt, nz)            # warm-up: the mesh's operators and tables
            states_run(0.002, nt, nz, *RUNS["base"][:2], a.modes, RUNS["base"][3],
                       profile=profile)
            jfo = rigid_jfo(a.turns, nt, nz)
            rtol, tau, _, oil = RUNS["base"]
            r, cpu = states_run(a.turns, nt, nz, rtol, tau, a.modes, oil, profile=profile)
            if a.save:
                r.save(Path(a.save) / f"{nt}x{nz}")
        h, p = last_turn(r, a.turns)
        share, _, power = last_turn_work(r, a.turns, sc.bearing.radius)
        now = np.array([h, p, share, power])
        d = (np.full(4, np.nan) if before is None else 100 * (now - before) / before)
        before = now
        print(f"{f'{nt} x {nz}':>9} {r.stats['steps']:6d} {cpu:8.1f} {jfo:7.1f} "
              f"{cpu / jfo:6.1f} {h:9.3f} {d[0]:6.1f} {p:10.1f} {d[1]:6.1f} {share:7.4f} "
              f"{d[2]:6.1f} {power:7.3f} {d[3]:6.1f}" + ("" if not r.partial else
                                                         f"  (stopped: {r.message[:60]})"),
              flush=True)
        runs.append((sc, r))
    for (sc, r), (nt, nz) in zip(runs, meshes):
        rows = last_turn_rows(r, a.turns)
        fm = film_column(r.film_record, "film_min")[rows]
        crank = np.degrees(np.interp(film_column(r.film_record, "t")[rows], r.t,
                                     r.crank_angle)) % 360
        pick = [int(rows[np.argmin(fm)])] + [
            int(rows[np.argmin(np.abs((crank - c + 180) % 360 - 180))])
            for c in range(0, 360, 30)]
        print(f"\n{nt} x {nz}: the least film of the last turn (first row), then every 30 "
              "degrees of crank")
        print(f"{'crank[deg]':>10} {'h_min[um]':>9} {'alpha[deg]':>10} {'z/(L/2)':>8} "
              f"{'share':>7}")
        for c, h, al, z, s in where(sc, r, pick):
            print(f"{c:10.1f} {h:9.3f} {al:10.1f} {z:8.3f} {s:7.4f}")
    sc, r = runs[-1]
    rows = last_turn_rows(r, a.turns)
    rec = r.film_record
    force = np.hypot(film_column(rec, "force_x"), film_column(rec, "force_y"))[rows]
    j = int(rows[np.argmax(force)])
    (state, sol), = film_at(sc, r, [j])
    render_deflection(sol, state, Path(a.figure))
    crank = np.degrees(np.interp(film_column(rec, "t")[j], r.t, r.crank_angle)) % 360
    print(f"\nwrote {a.figure}: the peak joint load of the last turn ({force.max():.1f} N at "
          f"crank {crank:.1f} deg), {meshes[-1][0]} x {meshes[-1][1]}: eps {state.eps:.4f}, "
          f"peak pressure {sol.pressure_max / 1e6:.1f} MPa, largest deflection "
          f"{1e6 * np.max(sol.deformation):.2f} um, least film {1e6 * sol.film_min:.3f} um")


if __name__ == "__main__":
    main()
