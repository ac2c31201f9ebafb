"""Film models by name: one contract for the closed forms, the FE and FV films and the table.

Every model maps (bearing, JournalState, **options) to the film force (F_r, F_t) [N] on the
journal, declares its options with their defaults, and gives the partials of that force in
(eps, eps_dot, w): exactly where it can (closed forms by complex step, the FE film by its
discrete sensitivity), by central differences otherwise. The mechanism, the sweeps and the
designer functions (:mod:`bearingfem.design`) all read models from :data:`FILM_MODELS`.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Mapping

from .bearing import Bearing, JournalState, check_finite
from .closed.long_bearing import (long_bearing_derivatives, long_bearing_exact_force,
                                  long_bearing_force)
from .closed.short_bearing import (short_bearing_derivatives, short_bearing_exact_force,
                                   short_bearing_force)
from .differentiate import central_differences
from .fe.force_table import TABLE_DEFAULTS, table_force
from .fe.mesh import ELEMENTS
from .fe.reynolds import fe_force, solve_reynolds
from .fe.sensitivity import fe_force_derivatives
from .fv.fvm import fvm_force, fvm_reynolds
from .solution import FilmSolution, ForceDerivatives
from .validation import (MIN_N_THETA, MIN_N_Z, REYNOLDS_FAMILY, check_choice, check_grooves,
                         check_int)

__all__ = ["FilmModel", "FILM_MODELS", "NUMERIC_MODELS", "OPTION_RULES", "film_model",
           "solve_film"]

#: How each film option is checked, whichever model takes it: ("int" | "number", (lo, hi))
#: with None for an open end, ("choice", names), or ("grooves", None) for Groove tuples.
OPTION_RULES = {
    "n_theta": ("int", (MIN_N_THETA, None)), "n_z": ("int", (MIN_N_Z, None)),
    "element": ("choice", tuple(ELEMENTS)), "cavitation": ("choice", REYNOLDS_FAMILY),
    "half_film": ("choice", ("wedge", "fixed")), "switch_speed": ("number", (0.0, None)),
    "n_eps": ("int", (6, 400)), "n_phi": ("int", (16, 1000)),
    "grooves": ("grooves", None), "ambient_pressure": ("number", (0.0, None)),
    "film_step": ("number", (0.0, None)),
}


def _check_option(name: str, value, where: str, mass_conserving: bool = False):
    kind, allowed = OPTION_RULES[name]
    label = f"{where}.{name}" if where else name
    if kind == "grooves":
        return check_grooves(value, mass_conserving=mass_conserving)
    if kind == "choice":
        return check_choice(label, value, allowed)
    lo, hi = allowed
    if kind == "int":    # the solvers' own wording: one message for one check
        value = check_int(label, value, lo)
        if hi is not None and value > hi:
            raise ValueError(f"{label} must be an integer in [{lo}, {hi}], got {value!r}")
        return value
    value = check_finite(label, value)
    if value < lo or (hi is not None and value > hi):
        raise ValueError(f"{label} must lie in [{lo}, {'inf)' if hi is None else f'{hi}]'}, "
                         f"got {value!r}")
    return value


@dataclass(frozen=True)
class FilmModel:
    """A film model: its force, its options with their defaults, its derivatives.

    Attributes
    ----------
    name : the name scenes, sweeps, the command line and :mod:`bearingfem.design` use
    force : (bearing, state, **options) -> (F_r, F_t) [N]
    defaults : every option the model takes, with its default
    derivatives : (bearing, state, **options) -> :class:`ForceDerivatives`, exact; None
        means central differences of ``force``
    numeric : solved on a mesh (its force is finite at the wall only with eps capped)
    memory : the film has a state of its own (the JFO film fraction): ``force`` is its
        steady film; a time integration advances it instead (:mod:`mechanism`), and a
        linearisation about a state alone is not defined
    """

    name: str
    force: Callable
    defaults: Mapping = field(default_factory=dict)
    derivatives: Callable | None = None
    numeric: bool = False
    memory: bool = False

    def options(self, options: Mapping | None = None, where: str = "") -> dict:
        """The model's defaults updated by ``options``, each checked (OPTION_RULES);
        an unknown or out-of-range option raises ValueError naming it (after ``where``)."""
        options = dict(options or {})
        unknown = sorted(set(options) - set(self.defaults))
        if unknown:
            names = ", ".join(f"{where}.{k}" if where else k for k in unknown)
            raise ValueError(f"{names} {'is not an option' if len(unknown) == 1 else 'are not options'} "
                             f"of film model {self.name!r} (options: "
                             f"{', '.join(sorted(self.defaults)) or 'none'})")
        return {k: _check_option(k, options.get(k, d), where, self.memory)
                for k, d in self.defaults.items()}

    def film_force(self, bearing: Bearing, state: JournalState, **options):
        """(F_r, F_t) [N] with the model's defaults for options not given."""
        return self.force(bearing, state, **self.options(options))

    def force_derivatives(self, bearing: Bearing, state: JournalState,
                          **options) -> ForceDerivatives:
        """Force and its partials in (eps, eps_dot, w) (see :class:`ForceDerivatives`)."""
        opts = self.options(options)
        if self.memory:
            raise ValueError(
                f"film model {self.name!r} has memory (its film fraction is carried by the "
                "flow from earlier states): force derivatives at a state alone are not "
                "defined. Linearise about an orbit with the transient film, or use the "
                "Reynolds-condition model 'fem' (identical where the film does not reform)")
        if self.derivatives is not None:
            return self.derivatives(bearing, state, **opts)
        return central_differences(lambda s: self.force(bearing, s, **opts), state)


def _fem(bearing, state, n_theta, n_z, element, cavitation, grooves):
    """The "fem" model's force (a cold solve; options always come from the registry)."""
    return fe_force(bearing, state, n_theta, n_z, element, cavitation, grooves=grooves)[0]


def _fem_jfo(bearing, state, n_theta, n_z, grooves, ambient_pressure, film_step=0.0):
    """The steady JFO film's force (steady in the frame of the line of centres).
    ``film_step`` [s] is for time integration (time between film steps, sooner on a
    refill: 0, every accepted step); the steady film has none."""
    return solve_reynolds(bearing, state, n_theta, n_z, "P1", "jfo", grooves=grooves,
                          ambient_pressure=ambient_pressure).force_local


_MESH = dict(n_theta=48, n_z=8)
#: Oil around the film at atmospheric pressure, the cavity near zero absolute: the default
#: supply of the JFO model (it needs one; grooves add to it).
JFO_AMBIENT = 1e5
FILM_MODELS = {m.name: m for m in (
    # switch 1 rad/s: the literal sharp switch of Eq. 9's half film makes integrators chatter
    # (a steady film, w >> 1 rad/s, is the same to round-off)
    FilmModel("short", short_bearing_force, dict(half_film="wedge", switch_speed=1.0),
              short_bearing_derivatives),
    FilmModel("long", long_bearing_force, {}, long_bearing_derivatives),
    FilmModel("short-exact", short_bearing_exact_force),
    FilmModel("long-exact", long_bearing_exact_force),
    FilmModel("fem", _fem, dict(_MESH, element="P1", cavitation="gumbel", grooves=()),
              fe_force_derivatives, numeric=True),
    FilmModel("fvm", fvm_force, dict(_MESH, cavitation="gumbel"), numeric=True),
    FilmModel("fem-table", table_force, dict(TABLE_DEFAULTS),
              numeric=True),
    FilmModel("fem-jfo", _fem_jfo, dict(_MESH, grooves=(), ambient_pressure=JFO_AMBIENT,
                                        film_step=0.0),
              numeric=True, memory=True),
)}
#: Film models solved numerically: their force stays finite up to the wall only when eps is
#: capped (scene default eps_max 0.999); the closed forms are evaluated to 1 - 1e-6.
NUMERIC_MODELS = frozenset(name for name, m in FILM_MODELS.items() if m.numeric)


def film_model(name: str, what: str = "model") -> FilmModel:
    """The registered model ``name``; an unknown name raises ValueError naming ``what``."""
    if name not in FILM_MODELS:
        raise ValueError(f"{what} must be one of {', '.join(sorted(FILM_MODELS))}, "
                         f"got {name!r}")
    return FILM_MODELS[name]


def solve_film(model: str, bearing: Bearing, state: JournalState,
               options: Mapping | None = None) -> FilmSolution | None:
    """The whole film (pressures, friction, flows) of a mesh model with its options
    (defaults filled in), or None for the models without one (closed forms, the table)."""
    o = film_model(model).options(options)
    if model == "fem":
        return solve_reynolds(bearing, state, o["n_theta"], o["n_z"], o["element"],
                              o["cavitation"], grooves=o["grooves"])
    if model == "fvm":
        return fvm_reynolds(bearing, state, o["n_theta"], o["n_z"], o["cavitation"])
    if model == "fem-jfo":
        return solve_reynolds(bearing, state, o["n_theta"], o["n_z"], "P1", "jfo",
                              grooves=o["grooves"], ambient_pressure=o["ambient_pressure"])
    return None
