"""What a thermal film costs beside the isothermal film of the same mesh.

    python -m benchmarks.thd

The 50 mm bearing of studies/thd_designer.py (ISO VG 32 at 40 C, two 20 deg grooves,
3000 rpm) at eps 0.7: the isothermal grooved film (``solve_reynolds``, its default route)
and the thermal film (``solve_thd``, adiabatic, carry-over 0.8; cold start, and warm from
the film at eps 0.69, as an equilibrium's steps are), one process, best of 3 wall times
(caches built first). Columns: time [ms], fixed-point steps, ratio to the isothermal
solve, and the time split of one thermal step (film / energy equation + mixing).
"""
from __future__ import annotations


from bearingfem import JournalState, solve_reynolds
from bearingfem.routes.thd import solve_thd
from .common import best_of
from bearingfem.thermal import Thermal
from studies.thd_designer import BEARING, GROOVES, OIL, OMEGA, SUPPLY

MESHES = ((48, 8), (96, 16), (192, 32))
THERMAL = Thermal(SUPPLY, carry_over=0.8)


def best(f, repeat=3):
    """(best wall time [s], result) of ``repeat`` calls (the benchmarks' one timer)."""
    t = best_of(f, repeat)
    return t.wall, t.out


def main():
    state = JournalState(eps=0.7, omega=OMEGA, gamma=-1.0)
    near = JournalState(eps=0.69, omega=OMEGA, gamma=-1.0)
    print(f"{'mesh':>7} {'iso ms':>8} {'THD cold ms':>11} {'steps':>5} {'ratio':>6} "
          f"{'THD warm ms':>11} {'steps':>5} {'ratio':>6}")
    for n in MESHES:
        kw = dict(grooves=GROOVES)
        solve_reynolds(BEARING, state, *n, **kw)
        t_iso, _ = best(lambda: solve_reynolds(BEARING, state, *n, **kw))
        thd = dict(lubricant=OIL, thermal=THERMAL, grooves=GROOVES)
        solve_thd(BEARING, state, *n, **thd)
        t_cold, cold = best(lambda: solve_thd(BEARING, state, *n, **thd))
        start = solve_thd(BEARING, near, *n, **thd)
        t_warm, warm = best(lambda: solve_thd(BEARING, state, *n, start=start, **thd))
        print(f"{n[0]:>3}x{n[1]:<3} {1e3 * t_iso:8.1f} {1e3 * t_cold:11.1f} "
              f"{cold.thermal.iterations:5d} {t_cold / t_iso:6.1f} {1e3 * t_warm:11.1f} "
              f"{warm.thermal.iterations:5d} {t_warm / t_iso:6.1f}", flush=True)


if __name__ == "__main__":
    main()
