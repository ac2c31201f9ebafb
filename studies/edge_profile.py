"""Does the least film of the seed pin's heavy EHD state converge in the mesh with a bush
edge profile? The state of ``studies/ehd_mesh.py`` (L/D 0.2, eps 0.995, 250 rad/s,
Reynolds' condition; bronze bush E 110 GPa, nu 0.34, outer radius 16 mm) with a sharp
edge, a crown over the whole length, a crown over the last mm at each end and a chamfer,
on meshes refined twice at a time: the load |F|, the peak pressure, the least film and
where it sits (|z|/L, theta from the maximum film), one run. Then beyond the clearance
circle (eps 1.02), where the ring bush is refused with a sharp edge (its end slices cannot
deflect) but not with a crown (the crown opens its ends): the ring crowned, the solid
sharp and crowned.

    python -m studies.edge_profile            # ring, liner to 384 x 32, solid to 192 x 16
    python -m studies.edge_profile --quick    # ring, 96 x 8 and 192 x 16
"""
from __future__ import annotations

import time

import numpy as np

from bearingfem import ElasticBush, ElasticJournalState, JournalState, solve_reynolds
from bearingfem.bearing import seed_bearing
from bearingfem.fields import EdgeProfile

from .ehd_mesh import bush_study_args

BRONZE = dict(outer_radius=0.016, modulus=110e9, poisson=0.34)
HEAVY = JournalState(eps=0.995, gamma=0.0, omega=250.0)
BEYOND = ElasticJournalState(eps=1.02, gamma=0.0, omega=250.0)
MESHES = {"ring": [(96, 8), (192, 16), (384, 32)],
          "liner": [(96, 8), (192, 16), (384, 32)],
          "solid": [(96, 8), (192, 16)]}
PROFILES = {"sharp": None,
            "crown 2um": EdgeProfile("crown", 2e-6),
            "crown 2um/1mm": EdgeProfile("crown", 2e-6, 1e-3),
            "chamfer 2um/0.5mm": EdgeProfile("chamfer", 2e-6, 0.5e-3)}


def least_film(sol, length):
    """(h_min [m], |z|/L, theta [deg]) of the least nodal film."""
    i = int(np.argmin(sol.film_thickness))
    return (float(sol.film_thickness[i]), abs(float(sol.z[i])) / length,
            float(np.degrees(sol.theta[i])))


def main(argv=None):
    args = bush_study_args(argv, __doc__.splitlines()[0])
    b = seed_bearing(0.2)
    models = ["ring"] if args.quick else args.models.split(",")
    print(f"{'bush':>6} {'profile':>18} {'mesh':>8} {'|F| [N]':>8} {'p_max[MPa]':>10} "
          f"{'h_min[um]':>9} {'|z|/L':>6} {'theta[deg]':>10} {'time[s]':>7}")
    out = {}
    cases = [(HEAVY, model, name) for model in models for name in PROFILES]
    if not args.quick:
        cases += [(BEYOND, "ring", "crown 2um"), (BEYOND, "solid", "sharp"),
                  (BEYOND, "solid", "crown 2um")]
    for state, model, name in cases:
        bush = ElasticBush(model=model, **BRONZE)
        meshes = MESHES[model][:2] if args.quick else MESHES[model]
        if state is BEYOND and model == "ring":
            print(f"eps {BEYOND.eps} (beyond the clearance circle)")
        for n in meshes:
            t = time.perf_counter()
            sol = solve_reynolds(b, state, *n, bush=bush, profile=PROFILES[name])
            s = time.perf_counter() - t
            h, z, th = least_film(sol, b.length)
            out[state.eps, model, name, n] = (float(np.hypot(*sol.force_local)),
                                              sol.pressure_max, h, z, th)
            print(f"{model:>6} {name:>18} {n[0]:>4}x{n[1]:<3} "
                  f"{out[state.eps, model, name, n][0]:8.1f} {sol.pressure_max / 1e6:10.2f} "
                  f"{h * 1e6:9.3f} {z:6.3f} {th:10.1f} {s:7.2f}", flush=True)
    return out


if __name__ == "__main__":
    main()
