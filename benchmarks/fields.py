"""What a film on general fields costs against the rigid cylinder's fast path.

    python -m benchmarks.fields            # 120x20 and 480x80, P1 and P2, eps 0.6
    python -m benchmarks.fields --quick    # a smoke run on small meshes (CI)

Both paths solve the same film, H = 1 + eps cos(theta), over the whole length, L/D = 1,
omega = 100 rad/s, Swift-Stieber cavitation (active set, nested first set), warm operator
caches (mesh, pattern and the general path's element tables are built once per mesh and
excluded). Times are the best of ``--repeat`` in one run:

* fast: ``fe_pressure(op, state)``, stiffness combined from the four cos^k terms;
* general: the fields evaluated at the quadrature points (``FilmFields.on``), the general
  assembly (``film_system``) and the same solve;
* assembly: the general path's fields and assembly alone.

JFO rows (P1, ambient 2e4 Pa at the ends): the steady mass-conserving film, fast path
(``solve_reynolds(..., cavitation="jfo", half=False)``) against the same film given as
fields through the general balance (:func:`bearingfem.fe.jfo_fields.balance_films`: the
control volumes' Gauss quadrature of the fields on every level of the nested solve,
rebuilt per solve, as a state's fields change); "assembly" is that balance data alone.
"""
from __future__ import annotations

import argparse

import numpy as np

from bearingfem import JournalState
from bearingfem.bearing import seed_bearing
from bearingfem import solve_reynolds
from bearingfem.fe.general import film_system, general_assembly
from bearingfem.fe.jfo import solve_jfo
from bearingfem.fe.jfo_fields import balance_films
from bearingfem.fe.kernel import fe_operator, fe_pressure
from bearingfem.fields import FilmFields

from .common import best_of

BEARING = seed_bearing(1.0)
STATE = JournalState(eps=0.6, omega=100.0)


def row(n_theta, n_z, element, repeat):
    op = fe_operator(BEARING, STATE, n_theta, n_z, element, None, False)
    general_assembly(op)                  # tables once per mesh, as the operator
    spec = FilmFields(gap=lambda t, z: 1.0 + STATE.eps * np.cos(t))

    def general():
        system = film_system(op, spec.on(op, STATE), STATE.wedge_speed, STATE.eps)
        return fe_pressure(op, STATE, "reynolds", system=system)

    timed = best_of(lambda: fe_pressure(op, STATE, "reynolds"), repeat)
    t_fast, fast = timed.wall, timed.out
    timed = best_of(general, repeat)
    t_gen, gen = timed.wall, timed.out
    t_asm = best_of(lambda: film_system(op, spec.on(op, STATE), STATE.wedge_speed,
                                          STATE.eps),
                    repeat).wall
    gap = float(np.max(np.abs(gen.pressure - fast.pressure)) / np.max(fast.pressure))
    return dict(mesh=f"{n_theta}x{n_z}", element=element, dofs=op.mesh.ndofs,
                fast=t_fast, general=t_gen, assembly=t_asm, ratio=t_gen / t_fast, gap=gap)


AMBIENT = 2e4


def jfo_row(n_theta, n_z, repeat):
    def operator(nt, nz):
        return fe_operator(BEARING, STATE, nt, nz, "P1", None, False)
    spec = FilmFields(gap=lambda t, z: 1.0 + STATE.eps * np.cos(t))
    fine = operator(n_theta, n_z)
    general_assembly(fine)

    def general():
        film = balance_films(BEARING, STATE, fine, spec)
        return solve_jfo(BEARING, STATE, operator, n_theta, n_z, (), AMBIENT, film)

    timed = best_of(lambda: solve_reynolds(
        BEARING, STATE, n_theta, n_z, cavitation="jfo", ambient_pressure=AMBIENT,
        half=False), repeat)
    t_fast, fast = timed.wall, timed.out
    timed = best_of(general, repeat)
    t_gen, gen = timed.wall, timed.out
    t_asm = best_of(lambda: balance_films(BEARING, STATE, fine, spec), repeat).wall
    gap = float(np.max(np.abs(gen.pressure - fast.pressure)) / fast.pressure_max)
    return dict(mesh=f"{n_theta}x{n_z}", element="JFO", dofs=fine.mesh.ndofs, fast=t_fast,
                general=t_gen, assembly=t_asm, ratio=t_gen / t_fast, gap=gap)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small meshes (smoke run)")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    meshes = [(24, 4), (48, 8)] if args.quick else [(120, 20), (480, 80)]
    rows = [row(nt, nz, el, args.repeat) for nt, nz in meshes for el in ("P1", "P2")]
    rows += [jfo_row(nt, nz, args.repeat) for nt, nz in meshes]
    print(f"{'mesh':>8} {'elem':>4} {'dofs':>7} {'fast [s]':>9} {'general [s]':>11} "
          f"{'assembly [s]':>12} {'general/fast':>12} {'max |dP|/P':>10}")
    for r in rows:
        print(f"{r['mesh']:>8} {r['element']:>4} {r['dofs']:>7} {r['fast']:>9.4f} "
              f"{r['general']:>11.4f} {r['assembly']:>12.4f} {r['ratio']:>12.2f} "
              f"{r['gap']:>10.1e}")
    return rows


if __name__ == "__main__":
    main()
