"""Parameter sweeps on Dask: the product of parameter lists, one atomic file per case.

A sweep file (TOML)::

    name = "capacity"
    kind = "film"                 # "film": one film solve per case; "mechanism": one run
    [base]                        # fixed parameters
    eps = 0.6
    model = "fem"
    [vary]                        # every combination of these lists is a case
    length_ratio = [0.25, 0.5, 1.0]
    eps = [0.3, 0.6, 0.9]

Cases run on a Dask cluster: a local one (``workers`` processes) by default, or an
existing one given its scheduler address. The client writes each finished case at once
to ``DIR/cases/case-<hash>.json`` (atomically: written beside, then renamed), so an
interrupted sweep loses nothing and a rerun skips what is done. ``DIR/results.csv`` and
``DIR/summary.png`` gather every finished case.
"""
from __future__ import annotations

import difflib
import hashlib
import itertools
import json
import math
import os
import time
from dataclasses import dataclass, field
from pathlib import Path

from bearingfem.outputs.tables import write_csv
from bearingfem.models import FILM_MODELS
from mechanism.scene import read_toml, shipped_file

from .cases import KINDS, MECHANISM_PARAMS, RENAMED, UNITS, _precheck, _scene_data, run_case

__all__ = ["Sweep", "load_sweep", "parse_sweep", "sweep_cases", "case_id", "run_case",
           "run_sweep", "gather", "shipped_sweeps", "sweep_path", "CONNECT_TIMEOUT"]

#: The sweeps shipped with the package (``bearingfem sweep capacity`` finds them by name).
SWEEPS = Path(__file__).resolve().parent / "sweeps"
#: Seconds to wait for a Dask scheduler given by address before refusing it.
CONNECT_TIMEOUT = 5.0


@dataclass(frozen=True)
class Sweep:
    name: str
    kind: str
    base: dict = field(default_factory=dict)
    vary: dict = field(default_factory=dict)


def _checked(kind, key, value, where):
    params = KINDS[kind]
    if key in ("rtol", "estimate"):
        raise ValueError(f"{where}.{key} is not a sweep parameter: a sweep's cases are "
                         "solved on the mesh given (n_theta, n_z, element), and each film "
                         "or design case on a mesh reports force_error (a design case also "
                         "K and C's errors), estimated on the half mesh"
                         + ("; a mechanism scene takes rtol in [effects.lubrication]"
                            if kind == "mechanism" else ""))
    if key not in params:
        near = difflib.get_close_matches(key, sorted(params), n=1, cutoff=0.7)
        raise ValueError(f"{where}.{key} is not a {kind} sweep parameter"
                         + (f" (did you mean {near[0]}?)" if near else "")
                         + f" (parameters: {', '.join(sorted(params))})")
    typ = params[key][1]
    if typ is str:
        if not isinstance(value, str):
            raise ValueError(f"{where}.{key} must be a string, got {value!r}")
        if key == "model" and kind != "mechanism" and value not in FILM_MODELS:
            raise ValueError(f"{where}.model must be one of {', '.join(sorted(FILM_MODELS))}, "
                             f"got {value!r}")
        return value
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ValueError(f"{where}.{key} must be a finite number, got {value!r}")
    if typ is int and float(value) != int(value):
        raise ValueError(f"{where}.{key} must be an integer, got {value!r}")
    return typ(value)


def parse_sweep(data: dict, name="sweep") -> Sweep:
    """Validate a sweep given as a dict (the parsed TOML); errors name the key."""
    unknown = set(data) - {"name", "kind", "base", "vary"}
    if unknown:
        raise ValueError(f"sweep: unknown key(s) {', '.join(sorted(unknown))} "
                         "(keys: name, kind, base, vary)")
    kind = data.get("kind", "film")
    if kind not in KINDS:
        raise ValueError(f"sweep.kind must be one of {', '.join(KINDS)}, got {kind!r}")
    base = {k: _checked(kind, k, v, "sweep.base") for k, v in data.get("base", {}).items()}
    vary = {}
    for k, v in data.get("vary", {}).items():
        if not isinstance(v, list) or not v:
            raise ValueError(f"sweep.vary.{k} must be a non-empty list, got {v!r}")
        vary[k] = [_checked(kind, k, x, "sweep.vary") for x in v]
    if not vary:
        raise ValueError("sweep.vary must list at least one parameter")
    return Sweep(str(data.get("name", name)), kind, base, vary)


def shipped_sweeps() -> list[str]:
    """Names of the shipped sweeps."""
    return sorted(p.stem for p in SWEEPS.glob("*.toml"))


def sweep_path(path) -> Path:
    """The sweep file ``path`` if it exists; else the shipped sweep of that name, given as
    ``capacity``, ``capacity.toml`` or ``sweeps/capacity.toml`` (the checkout's path)."""
    return shipped_file(path, SWEEPS)


def load_sweep(path) -> Sweep:
    """Read and validate a sweep TOML file, or a shipped sweep by name."""
    p = sweep_path(path)
    if not p.is_file():
        raise ValueError(f"sweep file not found: {path} (shipped sweeps: "
                         f"{', '.join(shipped_sweeps())})")
    return parse_sweep(read_toml(p, "sweep"), p.stem)


def sweep_cases(sweep: Sweep) -> list[dict]:
    """Every case: the base parameters updated by one combination of the varied lists."""
    keys = list(sweep.vary)
    return [{**sweep.base, **dict(zip(keys, combo))}
            for combo in itertools.product(*(sweep.vary[k] for k in keys))]


def case_id(kind: str, params: dict) -> str:
    """Stable name of a case: the same parameters give the same file on every rerun."""
    text = json.dumps({"kind": kind, **params}, sort_keys=True)
    return "case-" + hashlib.sha1(text.encode()).hexdigest()[:12]


@dataclass(frozen=True)
class SweepResult:
    """What a call of :func:`run_sweep` did; ``rows`` are all finished cases on disk."""

    rows: list
    computed: int
    skipped: int
    failed: dict              # case id -> error message
    interrupted: bool
    wall_time: float


def _write_atomic(path: Path, data: dict) -> None:
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_text(json.dumps(data, indent=1, default=float))
    os.replace(tmp, path)     # atomic: a reader sees the old file or the whole new one


def run_sweep(sweep: Sweep, out, scheduler: str | None = None, workers: int = 2,
              progress: bool | None = None) -> SweepResult:
    """Run the cases not yet on disk on Dask; write each as it finishes; gather.

    ``scheduler``: address of a running Dask scheduler (``tcp://host:8786``); without it a
    local cluster of ``workers`` single-threaded processes is started and closed.
    """
    from dask.distributed import Client, LocalCluster, as_completed
    from mechanism.progress import Progress

    if scheduler is None and (isinstance(workers, bool) or not isinstance(workers, int)
                              or workers < 1):
        raise ValueError(f"workers must be an integer >= 1, got {workers!r}")
    if scheduler is not None:
        from .checks import check_scheduler_address
        check_scheduler_address(scheduler)
    cases = sweep_cases(sweep)
    for params in cases:                  # physical ranges, before any work starts
        _precheck(sweep.kind, params)
    # mechanism cases travel with their scene: remote workers do not have our files
    scenes = {}
    if sweep.kind == "mechanism":
        for params in cases:
            key = params.get("scene", MECHANISM_PARAMS["scene"][0])
            if key not in scenes:
                scenes[key] = _scene_data(params)
    out = Path(out)
    cases_dir = out / "cases"
    todo = {}
    for params in cases:
        cid = case_id(sweep.kind, params)
        if not (cases_dir / f"{cid}.json").exists():
            todo[cid] = params
    skipped = len(cases) - len(todo)
    failed, computed, interrupted = {}, 0, False
    t0 = time.perf_counter()
    bar = Progress(max(len(todo), 1), f"{sweep.name}: {len(todo)} cases", progress)
    if todo:
        cluster = None
        if scheduler is None:
            cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                   dashboard_address=None)
            client = Client(cluster)
        else:
            client = _connect(scheduler)
        cases_dir.mkdir(parents=True, exist_ok=True)   # nothing is left behind until here
        try:
            futures = {client.submit(run_case, sweep.kind, params,
                                     scenes.get(params.get("scene", MECHANISM_PARAMS["scene"][0])),
                                     key=cid, pure=False): cid
                       for cid, params in todo.items()}
            for fut in as_completed(futures):
                cid = futures[fut]
                try:
                    _write_atomic(cases_dir / f"{cid}.json", fut.result())
                    computed += 1
                except Exception as err:          # one bad case must not lose the others
                    failed[cid] = f"{type(err).__name__}: {err}"
                    _write_atomic(cases_dir / f"{cid}.error.json",
                                  {**todo[cid], "error": failed[cid]})
                bar.update(computed + len(failed))
        except KeyboardInterrupt:
            interrupted = True
        finally:
            client.close()
            if cluster is not None:
                cluster.close()
    bar.close(f"{computed} computed, {skipped} already done, {len(failed)} failed"
              + (", interrupted" if interrupted else ""))
    rows = gather(out, sweep)
    return SweepResult(rows, computed, skipped, failed, interrupted, time.perf_counter() - t0)


def _connect(scheduler: str):
    """A client of the scheduler at ``scheduler``, or one line saying it does not answer."""
    import logging

    from dask.distributed import Client
    quiet = logging.getLogger("distributed")
    level = quiet.level
    quiet.setLevel(logging.CRITICAL)      # its own retry warnings would say it many times
    try:
        return Client(scheduler, timeout=CONNECT_TIMEOUT)
    except (OSError, TimeoutError) as err:
        raise ValueError(f"--scheduler: no Dask scheduler answers at {scheduler} within "
                         f"{CONNECT_TIMEOUT:g} s ({type(err).__name__})") from None
    finally:
        quiet.setLevel(level)


def _sort_key(value):
    """Numbers in numeric order, then names in alphabetical order."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return (0, float(value), "")
    return (1, 0.0, str(value))


def gather(out, sweep: Sweep | None = None) -> list[dict]:
    """Collect every finished case of ``out`` into ``results.csv`` (+ ``summary.png``)."""
    out = Path(out)
    rows = [_renamed(json.loads(p.read_text()))
            for p in sorted((out / "cases").glob("case-*.json"))
            if not p.name.endswith(".error.json")]
    if rows:
        # sorted by the varied parameters; columns no case filled left out
        order = list(sweep.vary) if sweep is not None else []
        rows = sorted(rows, key=lambda r: tuple(_sort_key(r.get(k)) for k in order))
        keys = [k for k in dict.fromkeys(k for r in rows for k in r)
                if any(r.get(k, "") != "" for r in rows)]
        # the old names of renamed columns, kept beside the new for one version
        old = [o for o, new in RENAMED.items() if new in keys]
        write_csv([{**{k: r.get(k, "") for k in keys},
                    **{o: r.get(RENAMED[o], "") for o in old}} for r in rows],
                  out / "results.csv", keys + old)
        write_csv([{"column": k, "unit": UNITS.get(RENAMED.get(k, k), "")}
                   for k in keys + old], out / "results_units.csv", ["column", "unit"])
        if sweep is not None:
            plot_summary(rows, sweep, out / "summary.png")
    return rows


def _renamed(row: dict) -> dict:
    """A case's outputs under today's column names (a case file written before a rename,
    resumed, keeps its numbers)."""
    return {RENAMED.get(k, k): v for k, v in row.items()}


#: How each sweep parameter is shown: (display scale, label with units).
DISPLAY = {"diameter": (1e3, "diameter [mm]"), "length_ratio": (1.0, "L/D [-]"),
           "clearance": (1e6, "clearance [\u00b5m]"), "viscosity": (1.0, "viscosity [Pa s]"),
           "omega": (1.0, "omega [rad/s]"), "eps": (1.0, "eccentricity ratio [-]"),
           "eps_dot": (1.0, "eps_dot [1/s]"), "crank_speed": (1.0, "crank speed [rad/s]"),
           "turns": (1.0, "turns [-]"), "n_theta": (1.0, "n_theta [-]"), "n_z": (1.0, "n_z [-]")}
#: What each kind of sweep plots: (result column, label with units, log scale).
OUTPUTS = {"film": [("force", "load capacity |F| [N]", True)],
           "design": [("sommerfeld", "Sommerfeld number S [-]", True),
                      ("attitude_deg", "attitude angle [deg]", False),
                      ("friction_variable", "friction variable (R/c) f [-]", True),
                      ("flow_variable", "flow variable Q / (R c N L) [-]", False)]
           + [(f"{m}{i}{j}", f"{m}_{i}{j} {'c / W' if m == 'K' else 'c omega / W'} [-] "
               "(load frame)", False) for m in "KC" for i in (1, 2) for j in (1, 2)],
           "mechanism": [("min_film_um", "minimum film [\u00b5m]", True),
                         ("peak_eps", "peak eccentricity ratio [-]", False)]}


def _shown(key, value):
    scale, label = DISPLAY.get(key, (1.0, key))
    if isinstance(value, (int, float)):
        return f"{label.split(' [')[0]} {value * scale:g}" + (
            f" {label.split('[')[1][:-1]}" if "[" in label and label.split("[")[1][:-1] != "-"
            else "")
    return f"{key} {value}"


def _film_named(sweep: Sweep) -> str:
    """The film model(s) and cavitation the cases used, in words."""
    def said(key, default):
        if key in sweep.vary:
            return ", ".join(map(str, sweep.vary[key])) + " (varied)"
        return str(sweep.base.get(key, default))
    if sweep.kind == "mechanism":
        from mechanism import load_scene
        scene = load_scene(sweep.base.get("scene", MECHANISM_PARAMS["scene"][0]))
        lub = scene.lubrication
        model = lub.model if lub is not None else "none"
        cav = lub.options.get("cavitation", "the model's") if lub is not None else "-"
        return (f"film model {said('model', model)}; cavitation {said('cavitation', cav)} "
                f"(scene {scene.name})")
    models = sweep.vary.get("model", [sweep.base.get("model", "fem")])
    closed = any(not FILM_MODELS[m].numeric for m in models if m in FILM_MODELS)
    return (f"film model {said('model', 'fem')}; cavitation "
            f"{said('cavitation', 'each model default')}"
            + (" (closed forms: half film)" if closed else ""))


def plot_summary(rows, sweep: Sweep, path) -> None:
    """First varied parameter on x (with units); each output the kind promises on its own
    panel; one line per combination of the other varied parameters."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from mechanism.figures import label_log_axis
    x_key = next(iter(sweep.vary))
    others = [k for k in sweep.vary if k != x_key]
    outputs = OUTPUTS[sweep.kind]
    xscale, xlabel = DISPLAY.get(x_key, (1.0, x_key))
    cols = min(len(outputs), 4)
    rows_n = -(-len(outputs) // cols)
    size = (7, 4.5) if cols < 3 else (4.6, 3.4)
    fig, axes = plt.subplots(rows_n, cols, figsize=(size[0] * cols, size[1] * rows_n + 0.6),
                             constrained_layout=True, squeeze=False)
    # one sequential colormap over the first numeric parameter of the lines (its order
    # reads from the colour), the others by marker and line style
    numeric = [k for k in others if all(isinstance(v, (int, float)) for v in sweep.vary[k])]
    shade_key = numeric[0] if numeric else None
    shades = sorted(set(sweep.vary[shade_key])) if shade_key else []
    styled = [k for k in others if k != shade_key]
    styles = sorted({tuple(r.get(k) for k in styled) for r in rows}, key=str)
    cmap = plt.get_cmap("viridis")
    markers, lines = "os^Dv<>p", ["-", "--", ":", "-."]
    for ax, (y_key, ylabel, log) in zip(axes.ravel(), outputs):
        groups = {}
        for r in rows:
            if r.get(y_key, "") != "":
                groups.setdefault(tuple(r.get(k) for k in others), []).append(r)
        for k, (g, rs) in enumerate(sorted(groups.items(), key=lambda kv: str(kv[0]))):
            rs = sorted(rs, key=lambda r: r[x_key])
            label = ", ".join(_shown(k, v) for k, v in zip(others, g)) or None
            xs = [r[x_key] * xscale if isinstance(r[x_key], (int, float)) else r[x_key]
                  for r in rs]
            named = dict(zip(others, g))
            i = shades.index(named[shade_key]) if shade_key else k
            n = len(shades) if shade_key else len(groups)
            j = styles.index(tuple(named.get(s) for s in styled))
            ax.plot(xs, [r[y_key] for r in rs], color=cmap(0.85 * i / max(n - 1, 1)),
                    marker=markers[j % len(markers)], ls=lines[j % len(lines)], label=label)
        # a log axis needs a positive value (a still journal's load is 0): else linear
        log = log and any(r[y_key] > 0 for rs in groups.values() for r in rs)
        ax.set(xlabel=xlabel, ylabel=ylabel, yscale="log" if log else "linear")
        ax.grid(True, alpha=0.3)
        if log and groups:      # one way of writing every tick (not 6x10^0 beside 10^1)
            label_log_axis(ax.yaxis)
        if len(groups) > 1 and ax is axes.ravel()[0]:    # one legend: the lines are shared
            ax.legend(fontsize=7)
    for ax in axes.ravel()[len(outputs):]:
        ax.set_visible(False)
    fixed = ", ".join(_shown(k, v) for k, v in sorted(sweep.base.items())
                      if k not in ("scene", "model", "element", "cavitation"))
    fig.suptitle(f"sweep {sweep.name} ({sweep.kind}): {len(rows)} cases"
                 + (f"; {fixed}" if fixed else "") + f"\n{_film_named(sweep)}", fontsize=9)
    if path is None:
        return fig
    fig.savefig(path, dpi=110)
    plt.close(fig)
