"""The thermal film beside ROSS 3.1's thermal fixed-geometry bearing.

    python -m benchmarks.thd_ross31 [--mesh 96x16 ...] [--ross]

ROSS's numbers are its own solver fixtures ``ross/tests/data/fluid_film/
fixed_isoviscous.json``, ``fixed_adiabatic.json`` and ``fixed_full.json`` at
``_ross31_env.ROSS_COMMIT`` (read from the git mirror of petrobras/ross, as
benchmarks/_ross31_env.py does): two 176 deg pads without preload centred at 90 and 270
deg, D 0.4 m, L 0.263 m, c 194.6 um, 900 rpm, 112.8 kN down, oil at 323 K (exponential
viscosity law through 0.0190 Pa s at 323.0 K and 0.00772 Pa s at 353.0 K, rho 855,
cp 1951.5, k 0.15), hot-oil carry-over 0.8, Reynolds' condition.
With ``--ross`` ROSS's engine (.venv-ross31, built by benchmarks/_ross31_env.py) is also
timed on the three fixtures (``driver.run_case``: equilibrium + K, C; one run each after a
warm-up, single-threaded).

Ours: the same bearing with two 4 deg grooves at 0 and 180 deg at ambient pressure (the
gaps between the pads), model "fem" with cavitation "reynolds" (P1), and

- isothermal: the oil at the supply temperature;
- adiabatic: ``Thermal(323, model="adiabatic", carry_over=0.8)``;
- conducting: ``Thermal(323, model="conducting", carry_over=0.8)`` with the bush
  coefficient of ROSS's pad in series with its back convection,
  1 / (t/k_pad + 1/h_back) = 230 W/(m^2 K) to the ambient, and the journal at
  its zero-net-flux temperature through 2 k_oil / c = 1542 W/(m^2 K) (ROSS: the journal at
  the film's averaged temperature). The ambient is ROSS's: its ``ta_type`` 0 takes the
  supply temperature (323 K) for the pad's back, not the 294.3 K ``environment_temperature``;
- conducting bush: the same with the bush conducting (``Thermal(..., bush=
  BushConduction(ElasticBush(outer_radius=R + t_pad, model="solid"), k_pad, h_back))``,
  the hollow cylinder R -> R + t_pad, its bush mesh n_theta x 8 x 8 unless ``--bush-mesh``
  gives n_radial x n_axial); the film -> bush coefficient 2 k_oil / h.

Columns: eccentricity, attitude [deg], power loss [W], maximum film temperature [K]
(ROSS: the pad surface's, ``tpad_max``), K [N/m] and C [N s/m] (inertial x, y), and
the time of equilibrium + K, C [s] (wall and CPU, one run after a warm-up run, as
ROSS's; ``--repeat N``: the best of N runs, ROSS's and ours). Our K, C are the frozen-viscosity
film's; ROSS perturbs its film with the temperatures of the equilibrium as well.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import time


from dataclasses import replace

from bearingfem import Bearing, Groove, Lubricant, solve_reynolds
from bearingfem.design import coefficients, equilibrium
from bearingfem.elastic import ElasticBush
from bearingfem.thermal import Thermal
from bearingfem.thermal.spec import BushConduction

from . import _ross31_env

CASES = ("fixed_isoviscous", "fixed_adiabatic", "fixed_full")
KEYS = ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy")


def fixture(name: str) -> dict:
    """ROSS's fixture ``name`` at the pinned commit (inputs and outputs)."""
    text = subprocess.run(
        ["git", f"--git-dir={_ross31_env.MIRROR}", "show",
         f"{_ross31_env.ROSS_COMMIT}:ross/tests/data/fluid_film/{name}.json"],
        capture_output=True, text=True, check=True).stdout
    return json.loads(text)


def setup(inputs: dict, bush_mesh=(8, 8)):
    """(bearing, load, omega, grooves, oil, thermals) of ROSS's fixture inputs; the
    conducting bush on ``bush_mesh`` (n_radial, n_axial) cells."""
    i = inputs
    R = 0.5 * i["journal_diameter"]
    oil = Lubricant.two_point((i["temp1"], i["viscosity1"]), (i["temp2"], i["viscosity2"]),
                              density=i["lube_density"], specific_heat=i["lube_cp"],
                              conductivity=i["lube_conduct"], law="exponential")
    ts = i["oil_supply_temperature"]
    mu_supply = float(oil.viscosity_at(temperature=ts))
    bearing = Bearing(radius=R, length=i["pad_axial_length"][0],
                      clearance=i["radial_clearance"], viscosity=mu_supply)
    gap = 2.0 * math.pi - sum(i["pad_arc"])              # both gaps between the pads
    centres = [p + 0.5 * math.pi for p in i["pivot_angle"]]     # 0 and 180 deg
    grooves = [Groove(angle=a, width=0.5 * gap) for a in centres]
    h_bush = 1.0 / (i["pad_thickness"] / i["pad_conductivity"] + 1.0 / i["pad_convection"][0])
    h_journal = 2.0 * i["lube_conduct"] / i["radial_clearance"]
    lam = i["hot_oil_lambda"]
    if i["ta_type"] != 0:
        raise ValueError("only ROSS's ta_type 0 (the pad's back to the supply "
                         "temperature) is read here")
    conducting = Thermal(ts, model="conducting", carry_over=lam, bush_coefficient=h_bush,
                         ambient_temperature=ts, journal_coefficient=h_journal)
    bush = BushConduction(ElasticBush(outer_radius=R + i["pad_thickness"], model="solid"),
                          conductivity=i["pad_conductivity"],
                          outer_coefficient=i["pad_convection"][0],
                          n_radial=bush_mesh[0], n_axial=bush_mesh[1])
    thermals = {
        "isothermal": None,
        "adiabatic": Thermal(ts, carry_over=lam),
        "conducting": conducting,
        "conducting bush": replace(conducting, bush_coefficient=None, bush=bush),
    }
    return bearing, (0.0, -i["weight"]), i["frequency"][0], grooves, oil, thermals


def ours(bearing, load, omega, grooves, oil, thermal, mesh, repeat: int = 1):
    """(row dict, equilibrium) of our film: equilibrium + K, C, timed (wall and CPU, the
    best of ``repeat`` runs; the caller runs it once before, as ROSS is run once before
    its timed runs)."""
    if repeat > 1:
        rows = [ours(bearing, load, omega, grooves, oil, thermal, mesh) for _ in range(repeat)]
        row, eq = rows[-1]
        return dict(row, time=min(r["time"] for r, _ in rows),
                    cpu=min(r["cpu"] for r, _ in rows)), eq
    opts = dict(n_theta=mesh[0], n_z=mesh[1], grooves=grooves, cavitation="reynolds")
    t0, c0 = time.perf_counter(), time.process_time()
    if thermal is None:
        eq = equilibrium(bearing, load, omega, "fem", **opts)
        kc = coefficients(bearing, eq.state, "fem", **opts)
        t_max = float("nan")
    else:
        eq = equilibrium(bearing, load, omega, "fem", lubricant=oil, thermal=thermal, **opts)
        kc = coefficients(bearing, eq.state, "fem", lubricant=oil, thermal=thermal,
                          solution=eq.solution, **opts)
        t_max = eq.solution.temperature_max
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    sol = eq.solution
    power = abs(sol.friction_torque * omega)
    row = dict(eps=eq.eps, attitude=math.degrees(eq.attitude), power=power, t_max=t_max,
               time=wall, cpu=cpu, **{k: v for k, v in zip(KEYS, [*kc.K.ravel(), *kc.C.ravel()])})
    return row, eq


def ross_row(outputs: dict) -> dict:
    o = outputs
    t_max = o["tpad_max"][0] if o.get("max_pad_temperature", [0.0])[0] else float("nan")
    return dict(eps=o["eccentricity"][0], attitude=math.degrees(o["attitude"][0]),
                power=o["power_loss"][0], t_max=t_max, time=float("nan"), cpu=float("nan"),
                **{k: o[k][0] for k in KEYS})


def ross_times(data: dict, names, repeat: int = 1) -> dict:
    """(wall, CPU) time [s] of ROSS's ``driver.run_case`` on each fixture's inputs
    (equilibrium + K, C, as ROSS's bearing classes call it), after one warm-up run (numba
    compiled); the best of ``repeat`` runs."""
    code = r"""
import json, sys, time
from ross.bearings.fluid_film.driver import run_case
cases, repeat = json.loads(sys.stdin.read())
out = {}
for name, inputs in cases.items():
    run_case(**inputs)
    best = (float("inf"), float("inf"))
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        run_case(**inputs)
        t = (time.perf_counter() - t0, time.process_time() - c0)
        best = (min(best[0], t[0]), min(best[1], t[1]))
    out[name] = best
print(json.dumps(out))
"""
    cases = json.dumps([{n: data[n]["inputs"] for n in names}, repeat])
    try:
        res = subprocess.run([str(_ross31_env.python()), "-c", code], input=cases,
                             capture_output=True, text=True, timeout=1800,
                             env={**os.environ, "OMP_NUM_THREADS": "1",
                                  "NUMBA_NUM_THREADS": "1"})
        if res.returncode:
            print("ROSS failed:", res.stderr.strip().splitlines()[-1:])
            return {}
        return json.loads(res.stdout.strip().splitlines()[-1])
    except (OSError, subprocess.SubprocessError, ValueError, IndexError) as err:
        print("ROSS failed:", err)
        return {}


def fmt(row: dict) -> str:
    t = "    -  " if math.isnan(row["t_max"]) else f"{row['t_max']:6.1f} "
    tm = " ".join("     -" if math.isnan(row[k]) else f"{row[k]:6.3f}" for k in ("time", "cpu"))
    return (f"{row['eps']:7.4f} {row['attitude']:7.2f} {row['power']:8.0f} {t}"
            + " ".join(f"{row[k]:10.3e}" for k in KEYS) + f" {tm}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesh", action="append", default=None,
                    help="n_thetaxn_z of our film (repeatable; default 96x16 and 192x32)")
    ap.add_argument("--ross", action="store_true", help="also time ROSS's engine")
    ap.add_argument("--case", action="append", default=None,
                    choices=("isothermal", "adiabatic", "conducting", "conducting bush"),
                    help="our cases to run (repeatable; default all)")
    ap.add_argument("--repeat", type=int, default=1,
                    help="time the best of this many runs, ROSS's and ours (default 1)")
    ap.add_argument("--bush-mesh", default="8x8",
                    help="n_radialxn_axial of the conducting bush (default 8x8)")
    args = ap.parse_args(argv)
    if args.repeat < 1:
        ap.error(f"--repeat must be at least 1, got {args.repeat}")
    meshes = [tuple(int(v) for v in m.split("x")) for m in (args.mesh or ["96x16", "192x32"])]
    data = {name: fixture(name) for name in CASES}
    bearing, load, omega, grooves, oil, thermals = setup(
        data["fixed_adiabatic"]["inputs"], tuple(int(v) for v in args.bush_mesh.split("x")))
    times = ross_times(data, CASES, args.repeat) if args.ross else {}
    head = (f"{'case':<30} {'eps':>7} {'att deg':>7} {'loss W':>8} {'Tmax K':>6} "
            + " ".join(f"{k:>10}" for k in KEYS) + f" {'t s':>6} {'cpu s':>6}")
    print(head)
    print("-" * len(head))
    pairs = (("isothermal", "fixed_isoviscous"), ("adiabatic", "fixed_adiabatic"),
             ("conducting", "fixed_full"), ("conducting bush", "fixed_full"))
    for ours_name, ross_name in pairs:
        if args.case and ours_name not in args.case:
            continue
        row = ross_row(data[ross_name]["outputs"])
        row["time"], row["cpu"] = times.get(ross_name, (float("nan"), float("nan")))
        print(f"{'ROSS ' + ross_name:<30} " + fmt(row))
        for mesh in meshes:
            ours(bearing, load, omega, grooves, oil, thermals[ours_name], mesh)   # warm
            r, eq = ours(bearing, load, omega, grooves, oil, thermals[ours_name], mesh,
                         args.repeat)
            label = f"ours {ours_name} {mesh[0]}x{mesh[1]}"
            print(f"{label:<30} " + fmt(r), flush=True)
            if eq.solution.thermal is None:      # ROSS scales the cavity's shear
                dry = solve_reynolds(bearing, eq.state, mesh[0], mesh[1], grooves=grooves,
                                     cavitated_shear="none")
                print(f"{'':<30}   power loss without shear in the cavity "
                      f"{abs(dry.friction_torque * omega):.0f} W", flush=True)
            else:
                rec = eq.solution.thermal
                print(f"{'':<30}   inlets {', '.join(f'{t:.1f}' for t in rec.inlet_temperatures)}"
                      f" K; journal {rec.journal_temperature:.1f} K; balance residual "
                      f"{rec.balance.residual:.1e} W of {rec.balance.dissipation:.0f} W; "
                      f"film solves {rec.iterations}", flush=True)
                if rec.bush is not None:
                    print(f"{'':<30}   bush: {rec.balance.bush:.0f} W through it, max "
                          f"{rec.bush.temperature.max():.1f} K, inner mean "
                          f"{rec.bush.inner_mean:.1f} K", flush=True)


if __name__ == "__main__":
    main()
