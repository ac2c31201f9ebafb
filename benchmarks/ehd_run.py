"""The EHD-coupled seed pin run against the rigid JFO- and Reynolds-coupled runs: cost,
and the EHD run's film-step, modes and mesh convergence.

    python -m benchmarks.ehd_run [--speed 250] [--turns 0.1] [--mesh 96 8]

The seed's slider-crank with the ``paper-short-ehd-sharp`` film (solid bronze bush, Roelands oil)
at crank speed ``--speed`` [rad/s] (the seed's 250: the pin centre passes the rigid
clearance circle, docs/ehd.md "Beyond the rigid clearance"). Every run covers ``--turns``
from top dead centre, on one machine in one process: "x JFO" is the wall time over the
rigid JFO run's on the same mesh (run once per mesh). The EHD rows vary one of film step,
modes and mesh (n_theta, n_z held) from the base row; "d_orbit" is the largest distance
[um] of the orbit from the base row's finer neighbour (the last row of its group), over
the saved samples; "h_min" the least elastic film over the film steps, "p_max" the peak
pressure.
"""
from __future__ import annotations

import argparse

import numpy as np

from mechanism import simulate
from mechanism.result import film_column

from .common import best_of, scene


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--speed", type=float, default=250.0)
    ap.add_argument("--turns", type=float, default=0.1)
    ap.add_argument("--mesh", type=int, nargs=2, default=(96, 8))
    a = ap.parse_args(argv)
    nt, nz = a.mesh
    base = dict(n_theta=nt, n_z=nz, modes=32, film_step=1e-4)
    sc_jfo = scene("paper-short-jfo", a.speed, a.turns, n_theta=nt, n_z=nz)
    sc_rey = scene("paper-short-fem", a.speed, a.turns, n_theta=nt, n_z=nz,
                   cavitation="reynolds")
    jfo = best_of(lambda: simulate(sc_jfo, progress=False))
    rey = best_of(lambda: simulate(sc_rey, progress=False))
    r_jfo, t_jfo, r_rey, t_rey = jfo.out, jfo.wall, rey.out, rey.wall
    print(f"seed pin at {a.speed:g} rad/s, {a.turns:g} turn(s): rigid JFO {t_jfo:.1f} s "
          f"({r_jfo.stats['steps']} steps), rigid Reynolds {t_rey:.1f} s "
          f"({r_rey.stats['steps']} steps), {nt} x {nz}", flush=True)
    groups = {"film step [s]": ("film_step", (2e-4, 1e-4, 5e-5)),
              "modes": ("modes", (16, 32, 64)),
              "mesh": ("n_theta", (nt, 2 * nt))}
    print(f"{'varied':>14} {'value':>8} {'wall[s]':>8} {'x JFO':>6} {'steps':>6} "
          f"{'EHD solves':>10} {'peak eps':>9} {'p_max[MPa]':>11} {'h_min[um]':>9} "
          f"{'d_orbit[um]':>11}", flush=True)
    rows, cache, jfo_time = [], {}, {(nt, nz): t_jfo}
    for label, (key, values) in groups.items():
        runs = []
        for v in values:
            opts = dict(base, **{key: v})
            k = tuple(sorted(opts.items()))
            if k not in cache:
                sc = scene("paper-short-ehd-sharp", a.speed, a.turns, **opts)
                cache[k] = best_of(lambda: simulate(sc, progress=False))
            runs.append((v, cache[k].out, cache[k].wall))
        ref = runs[-1][1]
        for v, r, t in runs:
            mesh = (v, nz) if key == "n_theta" else (nt, nz)
            if mesh not in jfo_time:
                sc = scene("paper-short-jfo", a.speed, a.turns, n_theta=mesh[0], n_z=mesh[1])
                jfo_time[mesh] = best_of(lambda: simulate(sc, progress=False)).wall
            t_ref = jfo_time[mesh]
            d = (np.max(np.hypot(np.interp(ref.t, r.t, r.e_x) - ref.e_x,
                                 np.interp(ref.t, r.t, r.e_y) - ref.e_y))
                 if not r.partial and not ref.partial else float("nan"))
            rec = r.film_record
            p = float(np.nanmax(film_column(rec, "pressure_max"))) if len(rec) else np.nan
            h = float(np.nanmin(film_column(rec, "film_min"))) if len(rec) else np.nan
            row = dict(varied=label, value=v, wall=t, ratio=t / t_ref,
                       steps=r.stats["steps"], ehd_solves=r.stats["film_steps"],
                       peak_eps=float(r.eps.max()) if len(r.t) else np.nan,
                       pressure_max=p, film_min=h, d_orbit=d, completed=not r.partial)
            rows.append(row)
            print(f"{label:>14} {v:8.3g} {t:8.1f} {t / t_ref:6.1f} {row['steps']:6d} "
                  f"{row['ehd_solves']:10d} {row['peak_eps']:9.4f} {p / 1e6:11.1f} {1e6 * h:9.4f} "
                  f"{1e6 * d:11.4f}" + ("" if not r.partial else f"  ({r.message})"),
                  flush=True)
    return rows


if __name__ == "__main__":
    main()
