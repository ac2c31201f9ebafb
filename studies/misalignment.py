"""Misaligned journal: the FE film against the tilted short bearing's exact film.

No published finite misaligned-bearing table with numbers (load, attitude, minimum film,
moment at a given tilt) could be reached in a form to transcribe (docs/fields.md,
"Misalignment: published comparison", lists what was checked), so the independent
reference is the short-bearing limit: the axial Reynolds equation of a tilted journal has
an exact solution (:mod:`bearingfem.closed.tilted_short`), and the finite film must tend to
it as L/D -> 0 at the rate of the neglected circumferential flow, (L/D)^2.

The case: eps 0.6, gamma 0.3 rad, omega 250 rad/s, R 10 mm, c 20 um, mu 0.0117 Pa s, the
journal tilted so that its ends sit 0.25 c off the mid-plane centre (direction
(0.6, -0.8) of (tilt_x, tilt_y)), the same film shape at every L/D.

For each L/D and cavitation model ("none" full film, "gumbel" half film) it prints the FE
film (P2) on three meshes with the observed order, the closed form (and its quadrature
error, 2048 against 4096 angles), and the relative difference of the finest FE film from
the closed form in force and moment, divided by (L/D)^2: a constant when the difference
is the short-bearing model's own.

    python -m studies.misalignment [--quick]
"""
from __future__ import annotations

import argparse
import math

import numpy as np

from bearingfem import Bearing, JournalState, solve_reynolds
from bearingfem.closed.tilted_short import tilted_short_bearing

STATE = JournalState(eps=0.6, gamma=0.3, omega=250.0)
RADIUS, CLEARANCE, VISCOSITY = 0.01, 20e-6, 0.0117
END_OFFSET = 0.25            # of c
DIRECTION = (0.6, -0.8)
MESHES = ((120, 8), (240, 16), (480, 32))


def case(length_ratio):
    """The bearing and tilt at ``length_ratio`` L/D."""
    b = Bearing(radius=RADIUS, length=2 * RADIUS * length_ratio, clearance=CLEARANCE,
                viscosity=VISCOSITY)
    t = END_OFFSET * CLEARANCE / (0.5 * b.length)
    return b, (DIRECTION[0] * t, DIRECTION[1] * t)


def _q(film):
    return np.r_[film.force, film.moment]


def _rel(a, b):
    """Relative differences of force and moment vectors (|a - b| / |b| each)."""
    return (np.hypot(*(a[:2] - b[:2])) / np.hypot(*b[:2]),
            np.hypot(*(a[2:] - b[2:])) / np.hypot(*b[2:]))


def run(length_ratios, meshes):
    rows = []
    for cavitation in ("none", "gumbel"):
        for lam in length_ratios:
            b, tilt = case(lam)
            ref = _q(tilted_short_bearing(b, STATE, tilt, cavitation=cavitation,
                                          n_theta=4096))
            coarse = _q(tilted_short_bearing(b, STATE, tilt, cavitation=cavitation,
                                             n_theta=2048))
            fe = [_q(solve_reynolds(b, STATE, nt, nz, "P2", cavitation, tilt=tilt))
                  for nt, nz in meshes]
            mesh_err = [_rel(f, fe[-1]) for f in fe[:-1]]
            order = [math.log2(e1 / e2) if e2 > 0 else float("nan")
                     for e1, e2 in zip(mesh_err[0], mesh_err[1])] if len(fe) == 3 else None
            d = _rel(fe[-1], ref)
            rows.append((cavitation, lam, ref, _rel(coarse, ref), fe, mesh_err, order, d))
    return rows


def table(rows, meshes):
    out = []
    out.append("Tilted journal (ends 0.25 c off centre), eps 0.6: FE P2 film vs the tilted "
               "short bearing")
    out.append(f"{'cav':7s} {'L/D':>7s} {'|F| short':>11s} {'|F| FE':>11s} {'|M| short':>11s} "
               f"{'|M| FE':>11s} {'mesh F':>8s} {'mesh M':>8s} {'order F/M':>10s} "
               f"{'quad':>8s} {'dF':>8s} {'dM':>8s} {'dF/lam2':>8s} {'dM/lam2':>8s}")
    prev = {}
    for cav, lam, ref, quad, fe, mesh_err, order, d in rows:
        f = fe[-1]
        o = "-" if order is None else f"{order[0]:.1f}/{order[1]:.1f}"
        out.append(
            f"{cav:7s} {lam:7.4f} {np.hypot(*ref[:2]):11.5g} {np.hypot(*f[:2]):11.5g} "
            f"{np.hypot(*ref[2:]):11.5g} {np.hypot(*f[2:]):11.5g} {mesh_err[-1][0]:8.1e} "
            f"{mesh_err[-1][1]:8.1e} {o:>10s} {max(quad):8.1e} {d[0]:8.2e} {d[1]:8.2e} "
            f"{d[0] / lam ** 2:8.3f} {d[1] / lam ** 2:8.3f}")
        if cav in prev:
            p = prev[cav]
            out.append(f"{'':15s} difference ratio to the previous L/D: force "
                       f"{p[0] / d[0]:.2f}, moment {p[1] / d[1]:.2f} (4 for (L/D)^2)")
        prev[cav] = d
    out.append(f"mesh F/M: |finest-but-one - finest| / |finest| of the meshes {meshes} "
               f"(P2); quad: closed form 2048 vs 4096 angles; dF, dM: finest FE vs closed "
               f"form")
    return "\n".join(out)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="two L/D and two meshes")
    a = p.parse_args(argv)
    lams = (1 / 8, 1 / 16) if a.quick else (1 / 4, 1 / 8, 1 / 16, 1 / 32)
    meshes = MESHES[:2] if a.quick else MESHES
    print(table(run(lams, meshes), meshes))


if __name__ == "__main__":
    main()
