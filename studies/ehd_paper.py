"""Rigid Reynolds, rigid JFO and EHD films side by side for the seed's piston pin.

    python -m studies.ehd_paper -o results/ehd_paper [--turns 5] [--mesh 192 8] [--speed 250]
        [--coupling kept|states] [--modes 64]

Runs ``paper-short-fem`` under Reynolds' condition (rigid Reynolds), ``paper-short-jfo``
(rigid, mass-conserving) and ``paper-short-ehd-sharp`` (elastic bronze bush, piezoviscous oil,
Reynolds' condition; ``--coupling states`` integrates the bush's modes with the journal,
on rough surfaces, the coupling that converges at 250 rad/s: docs/ehd-states.md),
each over ``--turns`` (the last one recorded; shorter than the scenes' five when the machine
allows less) on the same mesh, at crank speed ``--speed`` [rad/s] (the seed's 250: the EHD
film carries the pin centre past the rigid clearance circle, docs/ehd.md). Prints one line
per film: peak eccentricity, minimum film (of the film steps for a film with memory: the
EHD film's includes the bush's deflection),
peak film pressure (at the recorded film steps of a film with memory, at 72 instants
otherwise),
asperity load share (the summits' largest share of the force over the recorded film steps;
zero on smooth surfaces: the rigid films and the "kept" coupling here), friction power
(the film's Newtonian shear at 72 instants, or over every recorded film step for a film
whose states the run integrates: no limiting shear stress bounds it under a piezoviscous
oil), crank speed range, peak slider acceleration, wall time and cost per turn; a run
that stopped says where and why. Writes ``ehd_paper.csv`` and renders the bush's
deflection and the film pressure at the EHD run's peak film force in the recorded turn
(its film step there, up to where it stopped) to
``docs/img/ehd_deflection.png`` (``--figure`` elsewhere).
"""
from __future__ import annotations

import argparse
import dataclasses
from pathlib import Path

import numpy as np

from bearingfem import ElasticJournalState, JournalState
from bearingfem.contact import Roughness
from bearingfem.ehd.transient import ehd_solution
from bearingfem.outputs.tables import write_csv
from mechanism import load_scene, simulate
from mechanism.figures import render_deflection
from mechanism.film_history import film_history
from mechanism.result import film_column

from .jfo_paper import friction_power


#: Rough surfaces for the "states" coupling (assumed: the seed gives none): a ground pin and
#: a honed bronze bush, combined sigma 0.2 um; E* of steel (210 GPa, 0.3) on bronze (110
#: GPa, 0.34), 80.8 GPa; Greenwood-Tripp factor K 1e-3; boundary friction 0.1.
ROUGH = Roughness(sigma=0.2e-6, contact_modulus=80.8e9, elastic_factor=1e-3, friction=0.1)


def scenes(turns: float, n_theta: int, n_z: int, speed: float = 250.0,
           coupling: str = "kept", modes: int | None = None):
    """The three scenes on one mesh, ``turns`` long, the last turn recorded, at crank
    speed ``speed`` [rad/s]. ``coupling`` "states" integrates the bush's ``modes`` with
    the journal (Kelvin-Voigt tau 1e-5 s, rough surfaces :data:`ROUGH`,
    docs/ehd-states.md); "kept" is the scene's (deflection held between film steps)."""
    ehd = {} if modes is None else dict(modes=modes)
    if coupling == "states":
        ehd.update(coupling="states", relaxation=1e-5, film_step=0.0, roughness=ROUGH)
    elif coupling != "kept":
        raise ValueError(f"coupling must be 'kept' or 'states', got {coupling!r}")
    out = []
    for name, extra in (("paper-short-fem", dict(cavitation="reynolds")),
                        ("paper-short-jfo", {}), ("paper-short-ehd-sharp", ehd)):
        sc = load_scene(name)
        lub = dataclasses.replace(sc.lubrication, options=dict(
            sc.lubrication.options, n_theta=n_theta, n_z=n_z, **extra))
        out.append(dataclasses.replace(sc, lubrication=lub, crank_speed=speed,
                                       run=dataclasses.replace(
            sc.run, turns=turns, record_from_turn=max(0.0, turns - 1.0))))
    return out


def row(label, sc, r, turns):
    """The film's line: orbit and film numbers over the recorded samples."""
    out = dict(film=label, completed=not r.partial, message="" if not r.partial else r.message,
               wall_time_s=r.stats["wall_time"], cost_per_turn_s=r.stats["wall_time"] / turns)
    if len(r.t) < 3:
        return out
    rec = r.film_record
    # a film whose states the run integrated has its every step in the record (its
    # friction from there); the others' films at 72 crank angles (replayed with memory)
    frames = film_history(r, sc, n_frames=72) if not (r.partial or r.film_z.shape[1]) else []
    recorded = film_column(rec, "t") >= r.t[0] if len(rec) else []
    p_max = (np.nanmax(film_column(rec, "pressure_max")[recorded]) if np.any(recorded)
             else max((f.solution.pressure_max for f in frames), default=float("nan")))
    h_min = (np.nanmin(film_column(rec, "film_min")[recorded]) if np.any(recorded)
             else float(r.film_min.min()))
    # the summits' largest share of the film + summits force over the recorded steps (0
    # without roughness; films without a record: no summits in these scenes)
    share = 0.0
    if np.any(recorded):
        load = np.hypot(film_column(rec, "force_x"), film_column(rec, "force_y"))[recorded]
        summits = np.nan_to_num(film_column(rec, "asperity_load")[recorded])
        share = float(np.max(np.divide(summits, load, out=np.zeros_like(load),
                                       where=load > 0)))
    out.update(peak_eps=float(r.eps.max()), film_min_um=1e6 * float(h_min),
               peak_pressure_MPa=float(p_max) / 1e6, asperity_share=share,
               friction_power_W=(friction_power(r, frames, sc.bearing.radius) if frames
                                 else record_friction_power(r, rec[recorded],
                                                            sc.bearing.radius)),
               crank_speed_min=float(r.crank_speed.min()),
               crank_speed_max=float(r.crank_speed.max()),
               peak_slider_acc=float(np.max(np.abs(r.slider_acceleration))))
    return out


def record_friction_power(r, rec, radius: float) -> float:
    """Mean friction power [W] of the film's shear over the film record's rows ``rec``
    (a film without a replay, whose steps are the integrator's: time-weighted by the
    trapezoid rule), as :func:`~studies.jfo_paper.friction_power` takes it: friction
    force times R omega, omega the journal's speed relative to the rod."""
    if len(rec) < 2:
        return float("nan")
    t = film_column(rec, "t")
    omega = np.interp(t, r.t, -np.gradient(r.rod_angle, r.t))
    power = film_column(rec, "friction_force") * radius * omega
    return float(np.trapezoid(power, t) / (t[-1] - t[0]))


def peak_film(sc, r, rigid, speed: float):
    """The EHD run's film at its peak film force over the recorded turn (its film step
    there, up to where it stopped): the state and the :class:`FilmSolution` of that step.
    The "states" coupling's is the run film's own at the step's state and modal
    coordinates (``r.film_z``); the "kept" coupling's the steady EHD film at the step's
    state (what its film step solves). A "kept" run without a recorded film step: the
    steady film at the peak eccentricity of the ``rigid`` Reynolds run (a "states" run
    without one raises: no steady film is its film)."""
    from bearingfem.models import film_model
    o = sc.lubrication.options
    rec = r.film_record
    recorded = np.flatnonzero(film_column(rec, "t") >= r.t[0]) if len(r.t) else []
    if len(recorded):
        force = np.hypot(film_column(rec, "force_x"), film_column(rec, "force_y"))
        j = int(recorded[np.argmax(force[recorded])])
        state = ElasticJournalState(**{n: float(film_column(rec, n)[j])
                                       for n in ("eps", "eps_dot", "gamma", "gamma_dot",
                                                 "omega")})
        if o.get("coupling") == "states":
            film = film_model(sc.lubrication.model).along_run(sc.bearing, dict(o))
            return state, film.solution(state, r.film_z[j])
    elif o.get("coupling") == "states":
        raise ValueError("the EHD run has no film step in its recorded turn: no film of "
                         "its own to render")
    else:
        i = int(np.argmax(np.hypot(rigid.force_x, rigid.force_y)))
        state = JournalState(eps=min(float(rigid.eps[i]), 0.995), gamma=0.0, omega=speed)
    return state, ehd_solution(sc.bearing, state, o["lubricant"], o["bush"], None,
                               o["n_theta"], o["n_z"], o["modes"])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--output", default="results/ehd_paper")
    ap.add_argument("--turns", type=float, default=5.0)
    ap.add_argument("--mesh", type=int, nargs=2, default=(192, 8))
    ap.add_argument("--speed", type=float, default=250.0)
    ap.add_argument("--figure", default="docs/img/ehd_deflection.png")
    ap.add_argument("--coupling", choices=("kept", "states"), default="kept")
    ap.add_argument("--modes", type=int, default=None, help="the bush's modes (scene's: 64)")
    a = ap.parse_args(argv)
    out = Path(a.output)
    out.mkdir(parents=True, exist_ok=True)
    labels = ("rigid, Reynolds' condition", "rigid, JFO",
              "EHD (bronze bush, Roelands oil" + (", modes integrated, rough)"
                                                  if a.coupling == "states" else ")"))
    runs = [(lab, sc, simulate(sc, progress=False))
            for lab, sc in zip(labels, scenes(a.turns, *a.mesh, a.speed, a.coupling, a.modes))]
    rows = [row(lab, sc, r, a.turns) for lab, sc, r in runs]
    keys = ("peak_eps", "film_min_um", "peak_pressure_MPa", "asperity_share",
            "friction_power_W", "crank_speed_min", "crank_speed_max", "peak_slider_acc",
            "wall_time_s", "cost_per_turn_s")
    print("| film | " + " | ".join(keys) + " |")
    print("|---" * (len(keys) + 1) + "|")
    for w in rows:
        print(f"| {w['film']} | " + " | ".join(
            f"{w[k]:.4g}" if k in w else "-" for k in keys) + " |")
        if w["message"]:
            print(f"  ({w['film']} stopped: {w['message']})")
    write_csv(rows, out / "ehd_paper.csv")
    _, sc_ehd, r_ehd = runs[2]
    state, sol = peak_film(sc_ehd, r_ehd, runs[0][2], a.speed)
    render_deflection(sol, state, Path(a.figure),
                      f"seed pin, EHD film at the peak joint load (eps {state.eps:.4f})")
    print(f"deflection at the peak load (eps {state.eps:.4f}): max "
          f"{1e6 * np.max(sol.deformation):.3f} um, peak pressure "
          f"{sol.pressure_max / 1e6:.1f} MPa -> {a.figure}")
    return rows


if __name__ == "__main__":
    main()
