"""The elastic bush's film-surface compliance: what it costs to build and apply, and what a
reduced (truncated singular) basis loses, for the seed's piston pin.

    python -m benchmarks.bush            # 192 x 8 film nodes, ring and the two solids
    python -m benchmarks.bush --quick    # smoke run (48 x 4)

Bush: R 10 mm, outer 16 mm, length 4 mm, bronze E 110 GPa, nu 0.34, outer surface held,
ends free (solid: per circumferential harmonic; solid-3d: hexahedra). Load: a Hertz-like film pressure 0.8 GPa * sqrt(1 - (s/a)^2) over the
arc |s| < a = 1.5 mm (3 mm), uniform along the length. "error" is max |w_k - w| / max |w|
for that load; "operator" the reduced operator's relative 2-norm error sigma_{k+1} /
sigma_1. Times: one run, best of ``--repeat`` for the applications (the machine is
shared: compare ratios within one run).
"""
from __future__ import annotations

import argparse

import numpy as np

from bearingfem import ElasticBush
from bearingfem.elastic import bush_compliance

from .common import best_of

RADIUS, LENGTH = 0.010, 0.004
BRONZE = dict(outer_radius=0.016, modulus=110e9, poisson=0.34)


def hertz(n_theta, n_z, peak=0.8e9, half_width=1.5e-3):
    theta = 2 * np.pi * np.arange(n_theta) / n_theta
    s = RADIUS * np.where(theta > np.pi, theta - 2 * np.pi, theta)
    return peak * np.sqrt(np.clip(1 - (s / half_width) ** 2, 0, None))[:, None] * np.ones(n_z)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--repeat", type=int, default=20)
    args = parser.parse_args(argv)
    n_theta, n_z = (48, 4) if args.quick else (192, 8)
    p = hertz(n_theta, n_z)
    rows = []
    print(f"film grid {n_theta} x {n_z} nodes; Hertz load 0.8 GPa peak over 3 mm")
    print(f"{'model':6} {'build [s]':>10} {'w max [um]':>11} {'w mid [um]':>11} "
          f"{'w end [um]':>11}")
    built = {}
    for model in ("ring", "solid", "solid-3d"):
        t = best_of(lambda: bush_compliance(ElasticBush(**BRONZE, model=model), RADIUS, LENGTH,
                                            n_theta, n_z))
        c, build = t.out, t.wall
        w = c.deflection(p)
        built[model] = (c, w)
        print(f"{model:6} {build:10.2f} {w.max() * 1e6:11.2f} {w[0, n_z // 2] * 1e6:11.2f} "
              f"{w[0, 0] * 1e6:11.2f}")
        rows.append(dict(model=model, build=build, w_max=float(w.max()),
                         w_mid=float(w[0, n_z // 2]), w_end=float(w[0, 0])))
    c, w = built["solid"]
    n = n_theta * n_z
    dense = c.matrix()
    t_fft = best_of(lambda: c.deflection(p), args.repeat).wall
    t_dense = best_of(lambda: dense @ p.ravel(), args.repeat).wall
    print(f"\nsolid, full operator (N = {n}): FFT apply {t_fft * 1e6:.0f} us, dense "
          f"matvec {t_dense * 1e6:.0f} us (ratio {t_dense / t_fft:.1f})")
    print(f"{'vectors':>8} {'operator':>10} {'error':>10} {'apply/FFT':>10}")
    for k in sorted({8, 16, 32, 64, 128, 256, 512, n // 2, n} & set(range(1, n + 1))):
        reduced = c.reduced(k)
        err = np.abs(reduced.deflection(p) - w).max() / np.abs(w).max()
        t_red = best_of(lambda: reduced.deflection(p), args.repeat).wall
        print(f"{reduced.n_vectors:8d} {reduced.operator_error:10.2e} {err:10.2e} "
              f"{t_red / t_fft:10.2f}")
        rows.append(dict(model="solid-reduced", vectors=reduced.n_vectors,
                         operator=reduced.operator_error, error=float(err)))
    return rows


if __name__ == "__main__":
    main()
