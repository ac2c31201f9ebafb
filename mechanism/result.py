"""Simulation results: arrays over the saved time points, run statistics, saving."""
from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from bearingfem import ElasticJournalState, JournalState
from bearingfem.contract import FilmStep
from bearingfem.film import local_to_inertial
from bearingfem.outputs.tables import write_csv

__all__ = ["SimulationResult", "load_result", "provenance", "FIELDS", "FILM_COLUMNS",
           "film_row", "film_column", "film_states"]

FIELDS = ("t", "crank_angle", "crank_speed", "rod_angle", "slider_position",
          "slider_acceleration", "eps", "e_x", "e_y", "film_min", "force_x", "force_y")
DENSE = ("dense_t", "dense_e_x", "dense_e_y", "film_record", "film_z", "step_t")
#: Columns of ``film_record`` (a film with memory: one row per committed film step), by
#: name with their units: what the step gave, then the journal state it was taken at
#: (the fields of :class:`bearingfem.JournalState`: enough to replay the film). A model
#: that solves no whole film leaves the solution's columns NaN.
FILM_COLUMNS = {"t": "s", "force_x": "N", "force_y": "N", "pressure_max": "Pa",
                "cavitated_fraction": "1", "friction_force": "N", "mass_balance": "m^3/s",
                "eps": "1", "eps_dot": "1/s", "gamma": "rad", "gamma_dot": "rad/s",
                "omega": "rad/s", "film_min": "m", "asperity_load": "N"}
_COLUMN = {name: i for i, name in enumerate(FILM_COLUMNS)}
_STATE_FIELDS = tuple(f.name for f in dataclasses.fields(JournalState))
#: film_min: the whole film's own minimum (an EHD film's includes the bush's deflection,
#: unlike the run's rigid c (1 - eps), which is 0 beyond the clearance circle)
#: asperity_load: |the summits' force| (mixed lubrication; 0 without roughness)
_SOLUTION_FIELDS = ("pressure_max", "cavitated_fraction", "friction_force", "mass_balance",
                    "film_min", "asperity_load")


def film_row(step: FilmStep) -> tuple:
    """One ``film_record`` row of a committed film step, filled by column name."""
    row = dict(zip(_STATE_FIELDS, dataclasses.astuple(step.state)), t=step.t)
    row["force_x"], row["force_y"] = local_to_inertial(*step.force_local, step.state.gamma)
    for name in _SOLUTION_FIELDS:
        # NaN where the film does not define it (no whole film; a Reynolds-condition
        # film's mass balance)
        value = None if step.solution is None else getattr(step.solution, name)
        row[name] = math.nan if value is None else value
    return tuple(float(row[name]) for name in FILM_COLUMNS)


def film_column(record: np.ndarray, name: str) -> np.ndarray:
    """The column ``name`` (a key of :data:`FILM_COLUMNS`) of a film record."""
    return np.asarray(record)[:, _COLUMN[name]]


def film_states(record: np.ndarray) -> list:
    """(t, JournalState) of each row of a film record: what a replay takes (an
    ElasticJournalState beyond the clearance circle, where an elastic film went)."""
    cols = np.column_stack([film_column(record, k) for k in ("t",) + _STATE_FIELDS])
    return [(float(r[0]), (JournalState if r[1] < 1.0 else ElasticJournalState)(
        *(float(v) for v in r[1:]))) for r in cols]


UNITS = {"t": "s", "crank_angle": "rad", "crank_speed": "rad/s", "rod_angle": "rad",
         "slider_position": "m", "slider_acceleration": "m/s^2", "eps": "1", "e_x": "m",
         "e_y": "m", "film_min": "m", "force_x": "N", "force_y": "N"}


@dataclass(frozen=True, eq=False)
class SimulationResult:
    """One run. Arrays (SI, rad) over the saved time points; ``force_x``/``force_y`` are the
    joint's total force on the pin (inertial frame); ``film_min`` = c (1 - eps), clipped at 0
    in contact (where eps > 1 measures the penetration); an elastic film's (a model with
    ``beyond_clearance``) is its own minimum gap, bush deflection included, from its film
    steps (``film_record``), linear between them. ``partial`` is True when the run
    stopped early; ``message`` says why and when."""

    t: np.ndarray
    crank_angle: np.ndarray
    crank_speed: np.ndarray
    rod_angle: np.ndarray
    slider_position: np.ndarray
    slider_acceleration: np.ndarray
    eps: np.ndarray
    e_x: np.ndarray
    e_y: np.ndarray
    film_min: np.ndarray
    force_x: np.ndarray
    force_y: np.ndarray
    scene: str = ""
    partial: bool = False
    message: str = "completed"
    stats: dict = field(default_factory=dict)
    provenance: dict = field(default_factory=dict)   # resolved scene, versions, date
    #: the orbit from the integrator's dense output, 10x finer than the saved points
    #: (no film solves are needed for it): time [s], e_x, e_y [m]
    dense_t: np.ndarray = field(default_factory=lambda: np.empty(0))
    dense_e_x: np.ndarray = field(default_factory=lambda: np.empty(0))
    dense_e_y: np.ndarray = field(default_factory=lambda: np.empty(0))
    #: a film with memory: one row per committed step, columns FILM_COLUMNS
    film_record: np.ndarray = field(default_factory=lambda: np.empty((0, len(FILM_COLUMNS))))
    #: a film whose states are integrated with the joint (contract rule 16, e.g. the bush's
    #: modal coordinates [m] of the "states" coupling): its states z at each film_record
    #: row, (rows, state_size); (0, 0) for every other film. With the row's state they
    #: give the film that step took (the run film's ``solution(state, z)``)
    film_z: np.ndarray = field(default_factory=lambda: np.empty((0, 0)))
    #: where the integrator's accepted steps end [s] (the whole run, not only the
    #: recorded turns): where a run spends its steps, e.g. per crank angle
    step_t: np.ndarray = field(default_factory=lambda: np.empty(0))
    #: a film with memory that hands its whole film at each step: the committed film step
    #: (t, journal state, force, ``.solution`` the FilmSolution) with the largest force,
    #: film and summits, in the recorded turns (over the whole run for one stopped before
    #: them); None for a run without such steps (or stopped in its recorded turns before
    #: their first film step). Not re-read by :func:`load_result`:
    #: :meth:`save` writes its film beside the arrays (``peak_film.vtu``)
    peak_film: FilmStep | None = None

    def __repr__(self) -> str:
        # the arrays hold thousands of points: name the run, not every value
        span = (f"{len(self.t)} points, t {self.t[0]:.6g}-{self.t[-1]:.6g} s"
                if len(self.t) else "no points")
        return (f"SimulationResult(scene={self.scene!r}, {span}, message={self.message!r}"
                + (", partial" if self.partial else "") + ")")

    def crank_angle_at(self, t: float) -> float:
        """The crank angle [rad] at time ``t`` [s]: linear between the saved samples, and
        beyond them from the nearest one at its crank speed (the run's last steps and a
        kept film step may lie after its last sample, up to a sample's interval)."""
        if not len(self.t):
            raise ValueError("crank_angle_at needs a result with saved samples, got none")
        i = 0 if t < self.t[0] else -1 if t > self.t[-1] else None
        if i is None:
            return float(np.interp(t, self.t, self.crank_angle))
        return float(self.crank_angle[i] + self.crank_speed[i] * (t - self.t[i]))

    def summary(self) -> str:
        s = self.stats
        lines = [f"scene {self.scene}: {self.message}" + (" (PARTIAL)" if self.partial else "")]
        if len(self.t):
            lines.append(
                f"  wall {s.get('wall_time', 0):.2f} s, steps {s.get('steps', 0)}, rhs "
                f"{s.get('rhs_evals', 0)}, film solves {s.get('film_solves', 0)}, "
                f"contact evals {s.get('contact_evals', 0)}")
            lines.append(
                f"  peak eps {np.max(self.eps):.4f}, min film {np.min(self.film_min) * 1e6:.3f} um, "
                f"crank speed {np.min(self.crank_speed):.2f}-{np.max(self.crank_speed):.2f} rad/s, "
                f"peak |slider acc| {np.max(np.abs(self.slider_acceleration)):.1f} m/s^2")
        if s.get("step_cuts"):
            lines.append(f"  {len(s['step_cuts'])} step(s) cut where a film solve did not "
                         "converge (stats['step_cuts'])")
        if s.get("film_rtol") is not None and "film_force_error" in s:
            # the mesh a scene's rtol chose and the run's own estimate (docs/accuracy.md):
            # a run that went deeper than the start's probes says so here, not only in
            # result.json
            n_theta, n_z, element = s["film_mesh"]
            err, rtol = s["film_force_error"], s["film_rtol"]
            lines.append(f"  film mesh {n_theta} x {n_z} {element} chosen for rtol {rtol:g}; "
                         f"estimated force error over the run {err:.2g}"
                         + (" (above the request: the run met states beyond the probes)"
                            if err > rtol else ""))
        if "fem_table_mesh_error" in s:
            lines.append(f"  fem-table: its mesh's forces are within "
                         f"{100 * s['fem_table_mesh_error']:.2g} % of a mesh twice as fine "
                         "(measured when the table was built)")
        return "\n".join(lines)

    def summary_row(self, ideal_speed=None) -> dict:
        """The run in one table row (units in the names: _s, _um, _rad_s, _m_s2; peak_eps
        and the counts are pure numbers); ``ideal_speed`` (the ideal
        mechanism's crank speed at ``crank_angle``, rad/s) adds the largest departure."""
        if len(self.t) == 0:
            return {"scene": self.scene, "status": self.message}
        s = self.stats
        return {"scene": self.scene,
                "status": "partial: " + self.message if self.partial else "completed",
                "wall_time_s": round(s["wall_time"], 2), "steps": s["steps"],
                "rhs_evals": s["rhs_evals"], "film_solves": s["film_solves"],
                "peak_eps": round(float(np.max(self.eps)), 5),
                "min_film_um": round(float(np.min(self.film_min)) * 1e6, 4),
                "crank_speed_min_rad_s": round(float(np.min(self.crank_speed)), 2),
                "crank_speed_max_rad_s": round(float(np.max(self.crank_speed)), 2),
                "max_dspeed_vs_ideal_rad_s": "" if ideal_speed is None else round(float(
                    np.max(np.abs(self.crank_speed - ideal_speed))), 3),
                "peak_slider_acc_m_s2": round(float(np.max(np.abs(self.slider_acceleration))),
                                              1)}

    def save(self, directory) -> Path:
        """Write ``result.npz`` (arrays), ``result.csv`` (the same histories, units in the
        header) and ``result.json`` (units, statistics, message, and the provenance: the
        resolved scene, the toolkit and library versions, the date - enough to re-run it);
        with a ``peak_film``, its film to ``peak_film.vtu`` (its time, crank angle and eps
        as uniform fields)."""
        d = Path(directory)
        d.mkdir(parents=True, exist_ok=True)
        if self.peak_film is not None and self.peak_film.solution is not None:
            from bearingfem.outputs.export import write_solution   # meshio: on demand
            step = self.peak_film
            write_solution(step.solution, d / "peak_film.vtu", constants={
                "time [s]": step.t, "crank_angle [rad]": self.crank_angle_at(step.t),
                "eps [1]": step.state.eps})
        np.savez_compressed(d / "result.npz", **{k: getattr(self, k) for k in FIELDS + DENSE})
        columns = [f"{k} [{UNITS[k]}]" for k in FIELDS]
        write_csv([dict(zip(columns, row)) for row in
                   np.column_stack([getattr(self, k) for k in FIELDS]).tolist()],
                  d / "result.csv", columns)
        meta = {"scene": self.scene, "partial": self.partial, "message": self.message,
                "units": UNITS, "stats": self.stats, "provenance": self.provenance}
        (d / "result.json").write_text(json.dumps(meta, indent=2, default=float))
        return d


def load_result(directory) -> SimulationResult:
    d = Path(directory)
    arr = np.load(d / "result.npz")
    meta = json.loads((d / "result.json").read_text())
    return SimulationResult(**{k: arr[k] for k in FIELDS},
                            **{k: arr[k] for k in DENSE if k in arr}, scene=meta["scene"],
                            partial=meta["partial"], message=meta["message"],
                            stats=meta["stats"], provenance=meta.get("provenance", {}))


def _git_commit(where: Path):
    """The commit of the checkout ``where`` lies in (+ "-dirty" with local changes), or None
    for an installed package (then the version says what ran)."""
    import functools
    import subprocess
    try:
        run = functools.partial(subprocess.run, cwd=where, capture_output=True, text=True,
                                timeout=5)
        head = run(["git", "rev-parse", "HEAD"])
        if head.returncode != 0:
            return None
        dirty = run(["git", "status", "--porcelain", "--untracked-files=no"]).stdout.strip()
        return head.stdout.strip() + ("-dirty" if dirty else "")
    except (OSError, subprocess.SubprocessError):
        return None


def provenance(scene) -> dict:
    """What a run was made from: the resolved scene (every default filled in), the toolkit
    and library versions, the git commit of a checkout (None if installed) and the date
    (UTC)."""
    import dataclasses
    import datetime
    import platform

    import scipy
    import skfem

    import bearingfem
    return {"scene": dataclasses.asdict(scene), "bearingfem": bearingfem.__version__,
            "git_commit": _git_commit(Path(bearingfem.__file__).parent),
            "numpy": np.__version__, "scipy": scipy.__version__,
            "scikit-fem": getattr(skfem, "__version__", "?"),
            "python": platform.python_version(),
            "created": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")}
