"""One sweep case: what a worker computes for a film, design or mechanism case.

Parameters and their defaults per kind of sweep (``None``: the film model's own default,
:mod:`bearingfem.models`); :func:`run_case` is what the runner sends to a worker.
"""
from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np

from bearingfem.bearing import (SEED_TABLE1, check_finite, check_squeeze_speed,
                                check_surface_speed)
from mechanism.parameters import check_crank_speed
from mechanism.scene import oil_viscosity, parse_scene, read_toml, scene_path

# parameter -> (default, kind of value); units: m, Pa s, rad/s, 1/s
FILM_PARAMS = {
    "diameter": (SEED_TABLE1["diameter"], float), "length_ratio": (1.0, float),
    "clearance": (SEED_TABLE1["clearance"], float),
    "viscosity": (SEED_TABLE1["viscosity"], float), "omega": (250.0, float), "eps": (0.6, float),
    "eps_dot": (0.0, float), "model": ("fem", str),
    # the command line's --rpm [1/min] and --oil at --oil-temperature [degC], instead of
    # omega and viscosity (the case computes those from them)
    "rpm": (None, float), "oil": (None, str), "oil_temperature": (None, float),
    # None: the film model's own default (bearingfem.models)
    "n_theta": (None, int), "n_z": (None, int), "element": (None, str), "cavitation": (None, str),
}
MECHANISM_PARAMS = {
    "scene": ("scenes/paper-short-fem.toml", str), "turns": (2.0, float),
    "length_ratio": (None, float), "clearance": (None, float), "viscosity": (None, float),
    "crank_speed": (None, float), "model": (None, str), "n_theta": (None, int),
    "n_z": (None, int), "element": (None, str), "cavitation": (None, str),
}
#: "design": the steady film at eps, its Raimondi & Boyd groups and its dimensionless
#: stiffness and damping in the load frame (bearingfem.design) - a design chart's points
DESIGN_PARAMS = {k: v for k, v in FILM_PARAMS.items() if k != "eps_dot"}
KINDS = {"film": FILM_PARAMS, "mechanism": MECHANISM_PARAMS, "design": DESIGN_PARAMS}

#: the unit of every column a case writes (results.csv's companion results_units.csv);
#: "1" dimensionless, "" not a number; the K, C entries of a design case are c/W and
#: c omega/W, dimensionless, in the load frame
UNITS = {"diameter": "m", "length_ratio": "1", "clearance": "m", "viscosity": "Pa s",
         "omega": "rad/s", "rpm": "1/min", "oil": "", "oil_temperature": "degC",
         "eps": "1", "eps_dot": "1/s", "model": "", "n_theta": "1",
         "n_z": "1", "element": "", "cavitation": "", "scene": "", "turns": "1",
         "crank_speed": "rad/s", "pressure_max": "Pa", "friction_force": "N",
         "side_leakage": "m^3/s", "cavitated_fraction": "1", "F_r": "N", "F_t": "N",
         "force": "N", "force_error": "1", "attitude_deg": "deg", "sommerfeld": "1",
         "friction_variable": "1",
         "flow_variable": "1", "coefficient_method": "", "wall_s": "s",
         **{f"{m}{i}{j}{e}": "1" for m in "KC" for i in (1, 2) for j in (1, 2)
            for e in ("", "_error")},
         "crank_speed_max_rad_s": "rad/s", "crank_speed_min_rad_s": "rad/s",
         "max_dspeed_vs_ideal_rad_s": "rad/s", "min_film_um": "um", "peak_eps": "1",
         "peak_slider_acc_m_s2": "m/s^2", "film_solves": "1", "rhs_evals": "1",
         "steps": "1", "status": "", "wall_time_s": "s", "film_rtol": "1",
         "film_force_error": "1"}
#: old column -> its name now (the contract's); results.csv keeps the old columns too,
#: for one version (docs/cli.md), and a case file written under the old names is read
RENAMED = {"force_r": "F_r", "force_t": "F_t", "load": "force"}


def run_case(kind: str, params: dict, scene: dict | None = None) -> dict:
    """Compute one case (runs on a worker); returns its parameters and outputs.

    ``scene``: for mechanism cases, the scene's parsed TOML as the client read it - workers
    of a remote cluster do not have the client's files (without it the worker reads
    ``params["scene"]`` itself)."""
    t0 = time.perf_counter()
    if kind == "mechanism":
        out = _mechanism_case(params, scene)
    else:
        out = {"film": _film_case, "design": _design_case}[kind](params)
        # the speed and viscosity that rpm and oil gave, beside them in the row
        p = _film_params(params)
        out.update({k: p[k] for k, given in (("omega", "rpm"), ("viscosity", "oil"))
                    if given in params})
    return {**params, **out, "wall_s": time.perf_counter() - t0}


def _read_scene(params: dict):
    """(TOML data, parsed scene) of a mechanism case, read and validated on the client
    (before any work)."""
    path = scene_path(params.get("scene", MECHANISM_PARAMS["scene"][0]))
    data = read_toml(path, "scene")
    data.setdefault("name", path.stem)
    try:
        return data, parse_scene(data, path.stem)
    except ValueError as err:
        raise ValueError(f"sweep case {params}: {err}") from None


def _scene_data(params: dict) -> dict:
    """The scene of a mechanism case as TOML data, validated on the client."""
    return _read_scene(params)[0]


MESH_KEYS = ("n_theta", "n_z", "element", "cavitation")


def _film_options(p: dict) -> dict:
    """The film model's options: the case's mesh settings where it gives them, the model's
    own defaults elsewhere (one home for them: bearingfem.models)."""
    from bearingfem.models import film_model
    m = film_model(p["model"])
    return m.options({k: p[k] for k in MESH_KEYS if p.get(k) is not None and k in m.defaults})


def _film_params(params: dict) -> dict:
    """A film or design case's parameters with their defaults; ``rpm`` gives omega and
    ``oil`` at ``oil_temperature`` (default 40 degC) the viscosity, as on the command line
    (a sweep refused them: 'sweep.base.rpm is not a design sweep parameter')."""
    p = {k: params.get(k, d) for k, (d, _) in FILM_PARAMS.items()}
    if p["rpm"] is not None:
        if "omega" in params:
            raise ValueError("rpm and omega are one speed: give one of them")
        # named as given: a NaN rpm was refused as 'omega must be finite'
        p["omega"] = check_finite("rpm", p["rpm"]) * math.pi / 30.0
    if p["oil"] is not None:
        if "viscosity" in params:
            raise ValueError("oil and viscosity are one viscosity: give one of them")
        p["viscosity"] = oil_viscosity(p["oil"], 40.0 if p["oil_temperature"] is None
                                       else p["oil_temperature"])
    elif p["oil_temperature"] is not None:
        raise ValueError("oil_temperature is the oil's temperature: give oil (e.g. "
                         "'ISO VG 32'), or the viscosity at that temperature")
    return p


def _film_inputs(p: dict):
    """The case's bearing and steady-or-squeezing journal state."""
    from bearingfem import Bearing, JournalState
    D = p["diameter"]
    b = Bearing(radius=D / 2, length=p["length_ratio"] * D, clearance=p["clearance"],
                viscosity=p["viscosity"])
    return b, JournalState(p["eps"], p.get("eps_dot", 0.0), 0.0, 0.0, p["omega"])


def _force_error(b, model, options: dict, state) -> dict:
    """``force_error``: the estimated relative error of the case's film force (h/2h with
    the half mesh, one film more at a quarter of the cost) for a model on a mesh; nothing
    for a closed form. The Sommerfeld number, W's inverse, has the same relative error."""
    from bearingfem.design.tolerance import run_force_error
    if not {"n_theta", "n_z"} <= set(model.defaults):
        return {}
    return {"force_error": run_force_error(b, model.name, options, [state])}


def _film_case(params: dict) -> dict:
    from bearingfem.design import sommerfeld_number
    from bearingfem.models import film_model
    p = _film_params(params)
    o = _film_options(p)
    b, s = _film_inputs(p)
    out = {}
    model = film_model(p["model"])
    out.update(_force_error(b, model, o, s))
    sol = model.film_solution(b, s, **o)
    if sol is not None:
        f_r, f_t = sol.force_local
        out.update(pressure_max=sol.pressure_max, friction_force=sol.friction_force,
                   side_leakage=sol.side_leakage, cavitated_fraction=sol.cavitated_fraction)
    else:
        f_r, f_t = model.film_force(b, s, **o)
    load = math.hypot(f_r, f_t)
    # the contract's names (F_r, F_t as sol.force_local; force = |F|, the convergence CSV's)
    out.update(F_r=f_r, F_t=f_t, force=load,
               attitude_deg=math.degrees(math.atan2(f_t, -f_r)) if load else 0.0,
               sommerfeld=(sommerfeld_number(b, load, p["omega"]) if load and p["omega"]
                           else math.inf))
    return out


def _design_case(params: dict) -> dict:
    from bearingfem.design import (coefficients, flow_variable, friction_variable,
                                   petroff_friction, sommerfeld_number)
    from bearingfem.models import film_model
    p = _film_params(params)
    b, s = _film_inputs(p)
    model = film_model(p["model"])
    opts = _film_options(p)
    # a model on a mesh gives K and C's estimated errors too (one half-mesh linearisation
    # more): the chart's error bars
    on_mesh = {"n_theta", "n_z"} <= set(model.defaults)
    kc = coefficients(b, s, p["model"], frame="load", estimate=on_mesh, **opts)
    k, c = kc.dimensionless()
    f_r, f_t = model.film_force(b, s, **opts)
    load = math.hypot(f_r, f_t)
    out = dict(force=load, sommerfeld=sommerfeld_number(b, load, p["omega"]),
               attitude_deg=math.degrees(math.atan2(f_t, -f_r)),
               friction_variable=friction_variable(
                   b, petroff_friction(b, p["eps"], p["omega"], f_t), load),
               coefficient_method=kc.method)
    out.update(_force_error(b, model, opts, s))
    sol = model.film_solution(b, s, **opts)
    if sol is not None:
        out["flow_variable"] = flow_variable(b, sol.side_leakage, p["omega"])
    for name, m in (("K", k), ("C", c)):
        for (i, j), v in np.ndenumerate(m):
            out[f"{name}{i + 1}{j + 1}"] = float(v)
    if kc.K_error is not None:      # the entries' errors in the same units
        k_err, c_err = replace(kc, K=kc.K_error, C=kc.C_error).dimensionless()
        for name, m in (("K", k_err), ("C", c_err)):
            for (i, j), v in np.ndenumerate(m):
                out[f"{name}{i + 1}{j + 1}_error"] = float(v)
    return out


def _precheck(kind: str, params: dict) -> None:
    if kind == "mechanism":
        if "crank_speed" in params:     # against the scene's crank (rpm typed as rad/s?)
            mech = _read_scene(params)[1].mechanism
            try:
                check_crank_speed(mech, params["crank_speed"], "crank_speed")
            except ValueError as err:
                raise ValueError(f"sweep case {params}: {err}") from None
        return
    try:
        p = _film_params(params)
        b, state = _film_inputs(p)
        _film_options(p)
        # as the command line's: rpm typed as omega, or an eps_dot with a wrong exponent,
        # ran (a film at 1000 m/s) where solve_reynolds and the CLI refuse them
        check_surface_speed(b.radius, state.omega, "rpm" if "rpm" in params else "omega",
                            rpm="rpm" in params)
        check_squeeze_speed(b.clearance, state.eps_dot)
    except ValueError as err:
        raise ValueError(f"sweep case {params}: {err}") from None


def _mechanism_case(params: dict, scene: dict | None = None) -> dict:
    from dataclasses import replace
    from mechanism import load_scene, simulate
    from mechanism.scene import Lubrication, parse_scene
    sc = (parse_scene(scene, scene.get("name", "scene")) if scene is not None else
          load_scene(params.get("scene", MECHANISM_PARAMS["scene"][0])))
    turns = params.get("turns", MECHANISM_PARAMS["turns"][0])
    sc = replace(sc, run=replace(sc.run, turns=turns, record_from_turn=max(0.0, turns - 1)))
    b = sc.bearing
    if "length_ratio" in params:
        b = replace(b, length=params["length_ratio"] * 2 * b.radius)
    b = replace(b, **{k: params[k] for k in ("clearance", "viscosity") if k in params})
    sc = replace(sc, bearing=b, crank_speed=params.get("crank_speed", sc.crank_speed))
    opts = {k: params[k] for k in ("n_theta", "n_z", "element", "cavitation") if k in params}
    if sc.lubrication is not None and ("model" in params or opts):
        from bearingfem.models import film_model
        lub = sc.lubrication
        model = params.get("model", lub.model)
        keep = {} if model != lub.model else lub.options
        # the scene's rtol (a mesh chosen at the start) holds unless the case gives a mesh
        # or a model without one: dropped, the case ran on the model's default mesh unseen
        on_mesh = {"n_theta", "n_z"} <= set(film_model(model).defaults)
        rtol = lub.rtol if on_mesh and not {"n_theta", "n_z"} & set(opts) else None
        sc = replace(sc, lubrication=Lubrication(model, {**keep, **opts}, lub.eps_max,
                                                 rtol))
    r = simulate(sc, progress=False)
    row = r.summary_row()
    # a run whose mesh was chosen to an rtol says what it asked and what it estimates
    row.update({k: r.stats[k] for k in ("film_rtol", "film_force_error") if k in r.stats})
    return {k: v for k, v in row.items() if k != "scene"}
