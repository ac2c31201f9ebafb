"""ROSS's FluidFlow equilibrium + stiffness and damping on Friswell's Example 5.5.1 bearing.

Run by ``python -m benchmarks.design --ross`` with the interpreter of .venv-ross (ROSS is not
a dependency of bearingfem). Prints one JSON line: per mesh, eps, K, C (inertial x, y) and
the wall time of the equilibrium and the coefficients.
"""
import argparse
import json
import time

import numpy as np
from ross.bearings.fluid_flow import FluidFlow
from ross.bearings.fluid_flow_coefficients import calculate_stiffness_and_damping_coefficients

ap = argparse.ArgumentParser()
ap.add_argument("--meshes", default="8x32", help="nz x ntheta, comma-separated")
ap.add_argument("--repeat", type=int, default=1)
args = ap.parse_args()
rows = []
for mesh in args.meshes.split(","):
    nz, ntheta = (int(v) for v in mesh.split("x"))
    best = np.inf
    for _ in range(args.repeat):
        t0 = time.perf_counter()
        # journal radius 0.05 m and clearance 0.1 mm, as in bearingfem's run
        ff = FluidFlow(nz, ntheta, 0.03, 157.1, 0.0, 0.0, 0.05, 0.0501, 0.1, 860.0, load=525.0,
                       immediately_calculate_pressure_matrix_numerically=False)
        K, C = calculate_stiffness_and_damping_coefficients(ff)
        best = min(best, time.perf_counter() - t0)
    rows.append(dict(mesh=f"{ntheta}x{nz} FD", eps=ff.eccentricity / ff.radial_clearance,
                     K=np.reshape(K, (2, 2)).tolist(), C=np.reshape(C, (2, 2)).tolist(),
                     time_s=best))
print(json.dumps(rows))
