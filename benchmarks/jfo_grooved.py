"""What a new journal angle costs the grooved JFO film: the grooves' moving mesh (a mesh and
operator built for every angle) against the bearing-fixed mesh (:mod:`bearingfem.fe.jfo_grooved`:
the angle shifts the gap's integrals, the tables are built once).

    python -m benchmarks.jfo_grooved [--quick] [--angles N]

Lund & Thomsen's two-axial-groove bearing geometry (20 deg grooves at 0 and 180 deg, L/D 1,
D 0.1 m, c 100 um, 0.02 Pa s, 3000 rpm), one groove starved (fraction 0.5), the other
flooded at 0.1 MPa; eps 0.6. Steady JFO film, P1, cold (no cavitated set from an earlier
solve). "build" is the first solve on the bearing-fixed mesh (mesh, operator, harmonic
tables); "new angle" the mean over ``angles`` journal angles not seen before, each route
in the same run. Both routes give the same force (to round-off, printed). "transient":
20 backward-Euler steps of 0.2 ms of a whirling, squeezing journal (JFOFilm on the moving
mesh against GroovedJFOFilm), mean per step, each film built before the clock starts.
"""
from __future__ import annotations

import argparse
import math

import numpy as np

from bearingfem import Bearing, Groove, JournalState
from bearingfem.fe.assembly import fe_operator
from bearingfem.fe.jfo_steady import jfo_force
from bearingfem.fe.jfo import JFOFilm
from bearingfem.fe.jfo_grooved import grooved_jfo_force
from bearingfem.fe.jfo_grooved_transient import GroovedJFOFilm

from .common import best_of

BEARING = Bearing(radius=0.05, length=0.1, clearance=100e-6, viscosity=0.02)
OMEGA = 3000.0 * math.pi / 30.0
GROOVES = (Groove(angle=0.0, width=math.radians(20.0), fraction=0.5),
           Groove(angle=math.pi, width=math.radians(20.0), pressure=1e5))
MESHES = ((48, 8), (96, 16), (192, 32))


def moving(state, nt, nz):
    return jfo_force(BEARING, state, lambda a, b: fe_operator(BEARING, state, a, b, "P1",
                                                              None, True, GROOVES),
                     nt, nz, GROOVES)[0]


def fixed(state, nt, nz):
    return grooved_jfo_force(BEARING, state, nt, nz, GROOVES)[0]


def per_state(route, states, nt, nz):
    """(mean wall time [s] of a new angle, the forces)."""
    t = best_of(lambda: np.array([route(s, nt, nz) for s in states]))
    return t.wall / len(states), t.out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="the 48x8 mesh, 3 angles")
    ap.add_argument("--angles", type=int, default=8)
    a = ap.parse_args(argv)
    n_angles = 3 if a.quick else a.angles
    rows = []
    print("| mesh | fixed: build [ms] | fixed: new angle [ms] | moving mesh: new angle [ms] "
          "| moving / fixed | max |dF| / |F| |")
    print("|---|---|---|---|---|---|")
    for nt, nz in MESHES[:1] if a.quick else MESHES:
        build = best_of(lambda: fixed(JournalState(eps=0.6, gamma=-0.5, omega=OMEGA), nt, nz),
                        cold=True).wall
        # angles not seen before by either route (the moving mesh's cache keys on them)
        gammas = -0.4 + 0.37 * np.arange(n_angles) + 1e-3 * nt
        states = [JournalState(eps=0.6, gamma=float(g), omega=OMEGA) for g in gammas]
        t_fix, f_fix = per_state(fixed, states, nt, nz)
        t_mov, f_mov = per_state(moving, states, nt, nz)
        dev = float(np.max(np.abs(f_fix - f_mov)) / np.abs(f_mov).max())
        rows.append(dict(mesh=f"{nt}x{nz}", build_ms=1e3 * build, fixed_ms=1e3 * t_fix,
                         moving_ms=1e3 * t_mov, ratio=t_mov / t_fix, deviation=dev))
        w = rows[-1]
        print(f"| {w['mesh']} | {w['build_ms']:.1f} | {w['fixed_ms']:.1f} | "
              f"{w['moving_ms']:.1f} | {w['ratio']:.1f} | {dev:.1e} |", flush=True)
    print("\n| mesh | transient step, fixed [ms] | moving mesh [ms] | moving / fixed | "
          "max |dF| / |F| |")
    print("|---|---|---|---|---|")
    for nt, nz in MESHES[:1] if a.quick else MESHES[:2]:
        t_fix, f_fix = stepped(GroovedJFOFilm, nt, nz, 4 if a.quick else 20)
        t_mov, f_mov = stepped(JFOFilm, nt, nz, 4 if a.quick else 20)
        dev = float(np.max(np.abs(f_fix - f_mov)) / np.abs(f_mov).max())
        rows.append(dict(mesh=f"{nt}x{nz} transient", fixed_ms=1e3 * t_fix,
                         moving_ms=1e3 * t_mov, ratio=t_mov / t_fix, deviation=dev))
        print(f"| {nt}x{nz} | {1e3 * t_fix:.1f} | {1e3 * t_mov:.1f} | {t_mov / t_fix:.1f} | "
              f"{dev:.1e} |", flush=True)
    return rows


def stepped(film_class, nt, nz, steps, dt=2e-4):
    """Mean wall time of a step and the steps' forces."""
    film = film_class(BEARING, JournalState(0.5, 0.0, 1.0, 0.0, OMEGA), nt, nz,
                      grooves=GROOVES)
    states = [JournalState(0.5 + 0.2 * math.sin(60 * k * dt), 12 * math.cos(60 * k * dt),
                           1.0 + 40 * k * dt, 40.0, OMEGA) for k in range(1, steps + 1)]
    t = best_of(lambda: np.array([film.step(s, dt).force_local for s in states]))
    return t.wall / steps, t.out


if __name__ == "__main__":
    main()
