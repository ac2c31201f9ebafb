"""The designer's question with temperature: isothermal against thermal (THD) films.

    python -m studies.thd_designer -o docs/img        # table + two figures, ~1 min

A 50 mm bearing, L/D 0.5, c 50 um, ISO VG 32 (``Lubricant.iso_vg(32)``) supplied at 40 C
through two 20 deg axial grooves at 0 and 180 deg (at ambient pressure), 3000 rpm, 2 kN
down, Reynolds' condition. Rows: the isothermal film at the supply temperature; the
adiabatic thermal film without and with hot-oil carry-over 0.8; the conducting film
(bush and journal coefficients 250 W/(m^2 K), ambient at the supply temperature, journal
at zero net flux). Each on three meshes (the convergence of eps, power loss and maximum
temperature). Time: equilibrium + K, C, wall, one run. Figures: the THD film's temperature
and pressure (adiabatic, carry-over 0.8, the finest mesh), unwrapped.
"""
from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

from bearingfem import Bearing, Groove, Lubricant
from bearingfem.design import coefficients, equilibrium
from bearingfem.outputs.render import render_film
from bearingfem.thermal import Thermal

OIL = Lubricant.iso_vg(32)
SUPPLY = 313.15
BEARING = Bearing(radius=0.025, length=0.025, clearance=50e-6,
                  viscosity=float(OIL.viscosity_at(temperature=SUPPLY)))
GROOVES = (Groove(angle=0.0, width=math.radians(20.0)),
           Groove(angle=math.pi, width=math.radians(20.0)))
OMEGA = 3000.0 * 2.0 * math.pi / 60.0
LOAD = (0.0, -2000.0)
MESHES = ((48, 8), (96, 16), (192, 32))
CASES = {"isothermal 40 C": None,
         "adiabatic": Thermal(SUPPLY),
         "adiabatic, carry-over 0.8": Thermal(SUPPLY, carry_over=0.8),
         "conducting, carry-over 0.8": Thermal(SUPPLY, model="conducting", carry_over=0.8)}


def run(thermal, mesh):
    opts = dict(n_theta=mesh[0], n_z=mesh[1], grooves=GROOVES, cavitation="reynolds")
    extra = {} if thermal is None else dict(lubricant=OIL, thermal=thermal)
    t0 = time.perf_counter()
    eq = equilibrium(BEARING, LOAD, OMEGA, "fem", **opts, **extra)
    kc = coefficients(BEARING, eq.state, "fem", **opts, **extra,
                      **({} if thermal is None else dict(solution=eq.solution)))
    return eq, kc, time.perf_counter() - t0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--out", type=Path, default=Path("."))
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    print(f"{'case':<28} {'mesh':>7} {'eps':>7} {'att deg':>7} {'h_min um':>8} "
          f"{'loss W':>7} {'Tmax C':>7} {'T_in C':>12} {'Kyy N/m':>9} {'Cyy N s/m':>9} "
          f"{'t s':>5}")
    last = None
    for name, thermal in CASES.items():
        for mesh in MESHES:
            eq, kc, wall = run(thermal, mesh)
            sol = eq.solution
            t_max = "-" if sol.temperature_max is None else f"{sol.temperature_max - 273.15:.1f}"
            t_in = "-" if sol.thermal is None else "/".join(
                f"{t - 273.15:.1f}" for t in sol.thermal.inlet_temperatures)
            print(f"{name:<28} {mesh[0]:>3}x{mesh[1]:<3} {eq.eps:7.4f} "
                  f"{math.degrees(eq.attitude):7.2f} {eq.film_min * 1e6:8.2f} "
                  f"{abs(sol.friction_torque * OMEGA):7.1f} {t_max:>7} {t_in:>12} "
                  f"{kc.K[1, 1]:9.3e} {kc.C[1, 1]:9.3e} {wall:5.2f}", flush=True)
            if name == "adiabatic, carry-over 0.8":
                last = sol
    render_film(last, args.out / "thd-temperature.png", field="temperature",
                surface="unwrapped", title="ISO VG 32 at 40 C, 3000 rpm, 2 kN: film temperature")
    render_film(last, args.out / "thd-pressure.png", field="pressure", surface="unwrapped",
                title="ISO VG 32 at 40 C, 3000 rpm, 2 kN: THD film pressure")


if __name__ == "__main__":
    main()
