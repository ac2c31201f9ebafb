"""What an EHL line contact costs: time and Newton iterations vs nodes and vs load, the
multilevel Newton-Krylov route against the dense one, and the peak pressure's mesh
convergence at M ~ 7, L ~ 11.

    python -m benchmarks.ehl            # nodes 500 ... 4000 at M ~ 10 and ~ 97; loads 1e5 ... 2e6
    python -m benchmarks.ehl --quick    # a smoke run (CI)

Steel on steel (R = 20 mm, E' = 226 GPa), u_m = 1 m/s, a Barus (alpha = 2e-8 1/Pa) and
Dowson-Higginson oil of 0.0117 Pa s. All times in one run, best of ``--repeat``. The
film columns show the mesh convergence (second order) next to the cost; the last table
times the half-space deflection alone, by FFT against the dense influence matrix.
"""
from __future__ import annotations

import argparse
import contextlib

import numpy as np

from bearingfem import Lubricant, line_contact
from bearingfem.ehl import line
from bearingfem.ehl.halfspace import LineCompliance

from .common import best_of

OIL = Lubricant(viscosity=0.0117, barus=2e-8, density="dowson-higginson")
CONTACT = dict(radius=0.02, reduced_modulus=2.26e11, lubricant=OIL, mean_speed=1.0)


def nodes_rows(loads, grids, repeat):
    rows = []
    for w in loads:
        for n in grids:
            timed = best_of(lambda: line_contact(**CONTACT, load_per_length=w, nodes=n), repeat)
            t, r = timed.wall, timed.out
            rows.append(dict(load=w, nodes=n, M=r.moes_M, L=r.moes_L, time=t,
                             iterations=r.iterations, steps=r.continuation_steps,
                             h_c=r.film_central, h_min=r.film_min,
                             p_max=r.pressure_max / r.hertz_pressure))
    return rows


@contextlib.contextmanager
def dense_route():
    """Every grid by the dense Newton step (the route before the multilevel one)."""
    saved = line.DENSE_NODES
    line.DENSE_NODES = 10**9
    try:
        yield
    finally:
        line.DENSE_NODES = saved


def route_rows(grids, repeat, w=5e5):
    """The same contacts by both routes, back to back in one run."""
    rows = []
    for n in grids:
        new = best_of(lambda: line_contact(**CONTACT, load_per_length=w, nodes=n), repeat)
        with dense_route():
            old = best_of(lambda: line_contact(**CONTACT, load_per_length=w, nodes=n), repeat)
        rows.append(dict(nodes=n, dense=old.cpu, multilevel=new.cpu,
                         iterations=new.out.iterations, M=new.out.moes_M,
                         film=np.abs(new.out.film - old.out.film).max() / old.out.film_central,
                         pressure=np.abs(new.out.pressure - old.out.pressure).max()
                         / old.out.hertz_pressure))
    return rows


def spike_rows(grids, oils):
    """The peak pressure (and films) of the moderate case M ~ 7.4, L ~ 11 vs nodes."""
    rows = []
    for name, oil in oils:
        for n in grids:
            t = best_of(lambda: line_contact(radius=0.02, reduced_modulus=2.26e11,
                                             lubricant=oil, mean_speed=2.0,
                                             load_per_length=2e5, nodes=n))
            r = t.out
            rows.append(dict(oil=name, nodes=n, time=t.wall, M=r.moes_M, L=r.moes_L,
                             h_c=r.film_central, h_min=r.film_min,
                             p_max=r.pressure_max / r.hertz_pressure))
    return rows


def deflection_rows(sizes, repeat):
    rows = []
    for n in sizes:
        c = LineCompliance(n, 6.0 / n)
        P = np.random.default_rng(0).random(n)
        K = c.matrix()
        t_fft = best_of(lambda: c.deflection(P), repeat * 5).wall
        t_dense = best_of(lambda: K @ P, repeat * 5).wall
        rows.append(dict(nodes=n, fft=t_fft, dense=t_dense))
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--repeat", type=int, default=1)
    args = ap.parse_args(argv)
    if args.quick:
        grids, loads, load_sweep, sizes = (250, 500), (1e5,), (), (1000,)
        route_grids, spike_grids = (800,), (800,)
    else:
        grids, loads = (500, 1000, 2000, 4000), (1e5, 1e6)
        load_sweep, sizes = (1e5, 3e5, 1e6, 2e6), (1000, 4000, 16000)
        route_grids, spike_grids = (1000, 2000, 4000), (1500, 3000, 6000, 8000, 12000, 24000)

    routes = route_rows(route_grids, args.repeat)
    print("Newton step: dense LU (before) vs multilevel Newton-Krylov, w = 5e5 N/m, "
          "one run, CPU time")
    print(f"{'nodes':>6} {'M':>5} {'dense [s]':>9} {'multilevel [s]':>14} {'Newton':>6} "
          f"{'film diff':>9} {'p diff':>8}")
    for r in routes:
        print(f"{r['nodes']:6d} {r['M']:5.1f} {r['dense']:9.3f} {r['multilevel']:14.3f} "
              f"{r['iterations']:6d} {r['film']:9.1e} {r['pressure']:8.1e}")
    if len(routes) > 1:
        a, b = routes[0], routes[-1]
        print(f"  {b['nodes']}/{a['nodes']} nodes: dense x{b['dense'] / a['dense']:.1f}, "
              f"multilevel x{b['multilevel'] / a['multilevel']:.1f}\n")

    oils = [("Barus", Lubricant(viscosity=0.04, barus=2e-8, density="dowson-higginson")),
            ("Roelands", Lubricant(viscosity=0.04, roelands=0.6, density="dowson-higginson"))]
    spikes = spike_rows(spike_grids, oils)
    print("Moderate case (R 20 mm, E' 226 GPa, mu0 0.04 Pa s, u_m 2 m/s, w 2e5 N/m): "
          "peak pressure vs nodes")
    print(f"{'oil':>8} {'nodes':>6} {'M':>5} {'L':>5} {'time [s]':>8} {'h_c [nm]':>9} "
          f"{'h_min [nm]':>10} {'p_max/p_h':>9}")
    for r in spikes:
        print(f"{r['oil']:>8} {r['nodes']:6d} {r['M']:5.2f} {r['L']:5.2f} {r['time']:8.2f} "
              f"{r['h_c'] * 1e9:9.3f} {r['h_min'] * 1e9:10.3f} {r['p_max']:9.4f}")
    print()

    rows = nodes_rows(loads, grids, args.repeat)
    print("EHL line contact vs nodes (cold start + mesh sequencing from 200 nodes)")
    print(f"{'w [N/m]':>9} {'M':>6} {'L':>5} {'nodes':>6} {'time [s]':>9} {'Newton':>7} "
          f"{'h_c [nm]':>9} {'h_min [nm]':>10} {'p_max/p_h':>9}")
    for r in rows:
        print(f"{r['load']:9.3g} {r['M']:6.1f} {r['L']:5.2f} {r['nodes']:6d} {r['time']:9.3f} "
              f"{r['iterations']:7d} {r['h_c'] * 1e9:9.2f} {r['h_min'] * 1e9:10.2f} {r['p_max']:9.3f}")
    for w in loads:
        sub = [r for r in rows if r["load"] == w]
        for a, b in zip(sub[:-1], sub[1:]):
            print(f"  w = {w:.3g}: time ratio {b['nodes']}/{a['nodes']} nodes = "
                  f"{b['time'] / a['time']:.1f}")

    sweep = nodes_rows(load_sweep, (1000,), args.repeat)
    if sweep:
        print("\nvs load at 1000 nodes")
        print(f"{'w [N/m]':>9} {'M':>6} {'time [s]':>9} {'Newton':>7} {'h_c [nm]':>9} {'p_h [GPa]':>9}")
        for r in sweep:
            ph = 1e-9 * r["load"] * 2 / np.pi / np.sqrt(8 * r["load"] * 0.02 / (np.pi * 2.26e11))
            print(f"{r['load']:9.3g} {r['M']:6.1f} {r['time']:9.3f} {r['iterations']:7d} "
                  f"{r['h_c'] * 1e9:9.2f} {ph:9.3f}")

    defl = deflection_rows(sizes, args.repeat)
    print("\nhalf-space deflection alone: FFT vs dense matrix-vector product")
    print(f"{'nodes':>6} {'FFT [ms]':>9} {'dense [ms]':>10} {'dense/FFT':>9}")
    for r in defl:
        print(f"{r['nodes']:6d} {r['fft'] * 1e3:9.3f} {r['dense'] * 1e3:10.3f} "
              f"{r['dense'] / r['fft']:9.1f}")
    return rows + sweep + routes + spikes


if __name__ == "__main__":
    main()
