"""Mixed EHD (asperity contact with the elastic bush): solve time against the EHD film
without roughness, and the seed pin's asperity load share, on the seed's heavy state.

    python -m benchmarks.ehd_mixed            # 192 x 8 cells, ring bush (~1 min)
    python -m benchmarks.ehd_mixed --quick    # smoke run (48 x 4, modes 32 only)

Seed pin: R 10 mm, L/D 0.2, c 20 um, mu 0.0117 Pa s, 250 rad/s, eps 0.995 (rigid minimum
film 0.1 um), Reynolds cavitation; bronze ring bush E 110 GPa, nu 0.34, outer radius
16 mm; full compliance and its best 64 vectors ("modes 64"), built once and passed in.

Surfaces: ground steel pin on a bored bronze bush, combined roughness sigma = 0.1, 0.2,
0.4 um; contact modulus E* = 80.8 GPa (steel 210 GPa, nu 0.3; bronze 110 GPa, nu 0.34).
Summits: sigma eta beta = 0.04 and sigma / beta = 1e-3, the middle of the ranges Greenwood
& Williamson measured on ground and bead-blasted metal surfaces (Proc. R. Soc. A 295
(1966) 300: sigma eta beta 0.03-0.05, sigma / beta 1e-4 - 1e-2), so beta = 1000 sigma
(0.1-0.4 mm) and eta = 0.04 / (1000 sigma^2) (0.25e9-4e9 1/m^2); then K = 2.4e-4 for every
sigma. "share": the asperities' part of the total force at this state, F_a . F / |F|^2
(the load share the journal would report in equilibrium under that force); "rigid": the
rigid bush's mixed film (bearingfem.fe.mixed) at the same state. Times are the best of 2
cold solves; "x EHD" divides by the EHD solve without roughness of the same compliance in
the same run. "iters": Newton iterations.
"""
from __future__ import annotations

import argparse

import numpy as np

from bearingfem import ElasticBush, Roughness, solve_reynolds
from bearingfem.bearing import seed_bearing
from bearingfem.elastic import bush_compliance

from .common import BRONZE, HEAVY, best_of

CONTACT_MODULUS = 80.8e9
SUMMIT_PRODUCT, SUMMIT_RATIO = 0.04, 1e-3      # sigma eta beta, sigma / beta


def roughness(sigma: float) -> Roughness:
    """Ground steel on bored bronze with the module docstring's summit statistics."""
    beta = sigma / SUMMIT_RATIO
    return Roughness(sigma=sigma, contact_modulus=CONTACT_MODULUS,
                     asperity_density=SUMMIT_PRODUCT / (sigma * beta), asperity_radius=beta,
                     friction=0.1)


def share(sol) -> float:
    """F_a . F / |F|^2: the asperities' part of the total force."""
    fa, ft = np.array(sol.asperity_force), np.array(sol.total_force)
    return float(fa @ ft / (ft @ ft))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args(argv)
    n_theta, n_z = (48, 4) if args.quick else (192, 8)
    sigmas = (0.1e-6, 0.2e-6, 0.4e-6)
    b = seed_bearing(0.2)
    full = bush_compliance(ElasticBush(model="ring", **BRONZE), b.radius, b.length, n_theta,
                           n_z + 1)
    print(f"seed pin, {n_theta} x {n_z} cells, eps {HEAVY.eps}, ring bush; K = "
          f"{roughness(0.4e-6).factor:.3g}")
    print(f"{'compliance':>11} {'sigma[um]':>9} {'ehd[s]':>7} {'iters':>5} {'mixed[s]':>8} "
          f"{'iters':>5} {'x EHD':>6} {'share':>8} {'rigid':>8} {'F[N]':>7} "
          f"{'h_min/sig':>9} {'w_max[um]':>9}")
    rows = []
    kinds = ((("modes 32", full.reduced(32)),) if args.quick else
             (("modes 64", full.reduced(64)), ("full", full)))
    for kind, comp in kinds:
        timed = best_of(lambda: solve_reynolds(b, HEAVY, n_theta, n_z, bush=comp), 2)
        ehd, t_ehd = timed.out, timed.wall
        for sigma in sigmas:
            rough = roughness(sigma)
            timed = best_of(lambda: solve_reynolds(b, HEAVY, n_theta, n_z, bush=comp,
                                                   roughness=rough), 2)
            mixed, t_mixed = timed.out, timed.wall
            rigid = solve_reynolds(b, HEAVY, n_theta, n_z, roughness=rough)
            row = dict(compliance=kind, sigma=sigma, ehd=t_ehd, mixed=t_mixed,
                       ratio=t_mixed / t_ehd, share=share(mixed), rigid_share=share(rigid),
                       force=float(np.hypot(*mixed.total_force)),
                       gap_ratio=float(np.min(mixed.film_thickness)) / sigma,
                       deflection=float(np.max(mixed.deformation)),
                       residual=mixed.residual, ehd_iterations=ehd.iterations,
                       iterations=mixed.iterations)
            rows.append(row)
            print(f"{kind:>11} {sigma * 1e6:9.1f} {t_ehd:7.3f} {ehd.iterations:5d} "
                  f"{t_mixed:8.3f} {mixed.iterations:5d} {row['ratio']:6.2f} "
                  f"{row['share']:8.2e} {row['rigid_share']:8.2e} {row['force']:7.1f} "
                  f"{row['gap_ratio']:9.2f} {row['deflection'] * 1e6:9.3f}")
    return rows


if __name__ == "__main__":
    main()
