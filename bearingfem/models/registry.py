"""The registry of film models and the base class every model keeps
(:mod:`bearingfem.contract` holds the numbered rules).

A model is a :class:`FilmModel`: a subclass that writes the contract's hooks
(``_film_force``, ``_force_derivatives``, ``_film_solution``, ``_along_run``,
``_run_notes``) or, for a quick model, an instance given those functions by keyword.
Callers use the public methods of the same names (``film_force`` ...), which fill in the
defaults, check every option and the state, then call the hook: one vocabulary, in the
manner of scipy's ``OdeSolver.step`` and ``_step_impl``. :func:`register` adds a model to
:data:`FILM_MODELS`; each built-in model's module registers itself.
"""
from __future__ import annotations

from typing import Callable, Mapping

from ..bearing import Bearing, JournalState, check_finite, check_inside_clearance
from ..contract import RunFilm, SteadyRun
from ..differentiate import central_differences
from ..fe.mesh import ELEMENTS, check_grading
from ..fe.mixed import check_roughness
from ..solution import FilmSolution, ForceDerivatives
from ..validation import (MIN_N_THETA, MIN_N_Z, REYNOLDS_FAMILY, check_choice, check_grooves,
                          check_int)

__all__ = ["FilmModel", "FILM_MODELS", "OPTION_RULES", "film_model", "register",
           "solve_film", "numeric_models"]

#: How each film option is checked, whichever model takes it: ("int" | "number", (lo, hi))
#: with None for an open end, ("choice", names), ("grooves", None) for Groove tuples,
#: ("roughness", None) for a :class:`~bearingfem.contact.Roughness` or None, ("grading",
#: None), or ("instance", classes) for an object of those classes or None.
OPTION_RULES = {
    "n_theta": ("int", (MIN_N_THETA, None)), "n_z": ("int", (MIN_N_Z, None)),
    "element": ("choice", tuple(ELEMENTS)), "cavitation": ("choice", REYNOLDS_FAMILY),
    "half_film": ("choice", ("wedge", "fixed")), "switch_speed": ("number", (0.0, None)),
    "n_eps": ("int", (6, 400)), "n_phi": ("int", (16, 1000)),
    "grooves": ("grooves", None), "ambient_pressure": ("number", (0.0, None)),
    "film_step": ("number", (0.0, None)), "roughness": ("roughness", None),
    "grading": ("grading", None),
}


def _check_option(name: str, value, where: str, mass_conserving: bool = False,
                  rules: Mapping = OPTION_RULES):
    kind, allowed = rules[name]
    label = f"{where}.{name}" if where else name
    if kind == "grooves":
        return check_grooves(value, mass_conserving=mass_conserving)
    if kind == "roughness":
        return check_roughness(value)
    if kind == "grading":
        return check_grading(value)
    if kind == "instance":    # an object of one of the allowed classes, or None
        if value is not None and not isinstance(value, allowed):
            raise ValueError(f"{label} must be a {' or '.join(c.__name__ for c in allowed)} "
                             f"or None, got {type(value).__name__}")
        return value
    if kind == "choice" and name == "cavitation" and value == "jfo" and value not in allowed:
        # the mass-conserving film is a model of its own: say which
        raise ValueError(f"{label} must be one of {', '.join(map(repr, allowed))}, got "
                         f"'jfo': the mass-conserving film is the model 'fem-jfo'")
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


class FilmModel:
    """A film model keeping :class:`bearingfem.contract.FilmContract` (rules in
    :mod:`bearingfem.contract`).

    A subclass sets the class attributes and writes the hooks; an instance may instead be
    given them by keyword (``FilmModel("toy", film_force=f, defaults={...})``).

    Attributes
    ----------
    name : the name scenes, sweeps, the command line and :mod:`bearingfem.design` use
    defaults : every option the model takes, with its default (rule 2)
    rules : option rules of this model beyond :data:`OPTION_RULES` (rule 3)
    numeric : solved on a mesh (its force is finite at the wall only with eps capped)
    memory : the film has a state of its own (rule 9): ``_along_run`` gives its film
    beyond_clearance : the largest eps the film takes (rule 15); 0 for a rigid film
    tilts : the model's film takes a tilted journal (``equilibrium(..., tilt=)``)
    disk_cache : the model keeps what it builds in files (a caller checks the folder first)

    Hooks (each takes the model's checked options as keywords)
    -----
    _film_force(bearing, state, **options) -> (F_r, F_t) [N] (rule 1)
    _force_derivatives(bearing, state, **options) -> :class:`ForceDerivatives`, exact
        (rule 4); None (the default) means central differences of ``_film_force``
    _film_solution(bearing, state, **options) -> :class:`FilmSolution` (rule 5); None
        for force-only models
    _along_run(bearing, **options) -> :class:`~bearingfem.contract.RunFilm` (rules 7, 9):
        by default the steady force, warm where ``_warm`` gives a warm force factory
    _run_notes(bearing, **options) -> dict (rule 8)
    """

    name: str = ""
    defaults: Mapping = {}
    rules: Mapping = {}
    numeric: bool = False
    memory: bool = False
    beyond_clearance: float = 0.0
    tilts: bool = False
    disk_cache: bool = False
    _force_derivatives: Callable | None = None
    _film_solution: Callable | None = None
    _warm: Callable | None = None

    def __init__(self, name: str | None = None, film_force: Callable | None = None,
                 defaults: Mapping | None = None, *, force_derivatives=None,
                 film_solution=None, along_run=None, run_notes=None, warm=None,
                 rules: Mapping | None = None, numeric: bool | None = None,
                 beyond_clearance: float | None = None):
        given = dict(name=name, defaults=defaults, rules=rules, numeric=numeric,
                     beyond_clearance=beyond_clearance, _film_force=film_force,
                     _force_derivatives=force_derivatives, _film_solution=film_solution,
                     _along_run=along_run, _run_notes=run_notes, _warm=warm)
        for k, v in given.items():
            if v is not None:
                setattr(self, k, v)
        if along_run is not None:
            self.memory = True
        self.defaults, self.rules = dict(self.defaults), dict(self.rules)
        if not self.name:
            raise ValueError("a film model needs a name")
        unruled = sorted(set(self.defaults) - set(OPTION_RULES) - set(self.rules))
        if unruled:
            raise ValueError(f"film model {self.name!r}: option(s) {', '.join(unruled)} "
                             "have no rule (give them in rules=...)")

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.name!r})"

    # -- hooks: what a model writes ----------------------------------------------------
    def _film_force(self, bearing: Bearing, state: JournalState, **options) -> tuple:
        raise NotImplementedError(f"film model {self.name!r} has no force")

    def _along_run(self, bearing: Bearing, **options) -> RunFilm:
        force = self._warm() if self._warm is not None else self._film_force
        return SteadyRun(bearing, force, options)

    def _run_notes(self, bearing: Bearing, **options) -> dict:
        return {}

    # -- the contract: what callers use ------------------------------------------------
    @property
    def exact_derivatives(self) -> bool:
        """The model gives its force's partials exactly (Newton's method may use them)."""
        return self._force_derivatives is not None

    def options(self, options: Mapping | None = None, where: str = "") -> dict:
        """The model's defaults updated by ``options``, each checked (OPTION_RULES and the
        model's ``rules``); an unknown or out-of-range option raises ValueError naming it
        (after ``where``)."""
        options = dict(options or {})
        unknown = sorted(set(options) - set(self.defaults))
        if unknown:
            names = ", ".join(f"{where}.{k}" if where else k for k in unknown)
            raise ValueError(f"{names} {'is not an option' if len(unknown) == 1 else 'are not options'} "
                             f"of film model {self.name!r} (options: "
                             f"{', '.join(sorted(self.defaults)) or 'none'})")
        rules = {**OPTION_RULES, **self.rules}
        return {k: _check_option(k, options.get(k, d), where, self.memory, rules)
                for k, d in self.defaults.items()}

    def film_fields(self, options: Mapping | None = None) -> tuple:
        """The nodal fields its whole films carry with ``options``: the film pressure and
        thickness of a mesh model, the film fraction too for a mass-conserving one;
        none for a force-only model."""
        if self._film_solution is None:
            return ()
        return ("pressure", "film_thickness") + (
            ("fraction",) if self._mass_conserving(self.options(options)) else ())

    def _mass_conserving(self, options: Mapping) -> bool:
        return False

    def check_state(self, state: JournalState) -> JournalState:
        """``state``, or a ValueError naming eps when it lies beyond the clearance circle
        and the model does not declare ``beyond_clearance`` (rule 15)."""
        if state.eps >= 1.0 and not state.eps < self.beyond_clearance:
            check_inside_clearance(state, f"film model {self.name!r}")
        return state

    def film_force(self, bearing: Bearing, state: JournalState, **options) -> tuple:
        """(F_r, F_t) [N] with the model's defaults for options not given."""
        opts = self.options(options)
        self.check_state(state)
        return self._film_force(bearing, state, **opts)

    def film_solution(self, bearing: Bearing, state: JournalState,
                      **options) -> FilmSolution | None:
        """The whole film (pressures, friction, flows), or None for a force-only model."""
        opts = self.options(options)
        self.check_state(state)
        return None if self._film_solution is None else self._film_solution(bearing, state,
                                                                            **opts)

    def force_derivatives(self, bearing: Bearing, state: JournalState,
                          **options) -> ForceDerivatives:
        """Force and its partials in (eps, eps_dot, w) (see :class:`ForceDerivatives`)."""
        opts = self.options(options)
        self.check_state(state)
        if self.memory:
            raise ValueError(
                f"film model {self.name!r} has memory (its film at a state depends on the "
                "states before it: a film fraction carried by the flow, a bush's deflection "
                "or a film temperature): force derivatives at a state alone are not "
                "defined. Linearise about an orbit with the transient film, or use the "
                "steady model 'fem' (its bush=, lubricant= and thermal= films are steady; "
                "Reynolds' condition is identical to the JFO film where it does not reform)")
        if self._force_derivatives is not None:
            return self._force_derivatives(bearing, state, **opts)
        return central_differences(lambda s: self._film_force(bearing, s, **opts), state)

    def along_run(self, bearing: Bearing, options: Mapping | None = None) -> RunFilm:
        """A fresh film for one time integration (:class:`~bearingfem.contract.RunFilm`):
        the model's transient film if it has memory, else its (warm) force."""
        run = self._along_run(bearing, **self.options(options))
        if not isinstance(run, RunFilm):
            raise TypeError(f"film model {self.name!r}: its run film {type(run).__name__} "
                            "does not keep bearingfem.contract.RunFilm")
        return run

    def run_notes(self, bearing: Bearing, options: Mapping | None = None) -> dict:
        """What a run records about the model (rule 8); empty for most models."""
        return dict(self._run_notes(bearing, **self.options(options)))


#: The registered film models by name.
FILM_MODELS: dict = {}


def register(model: FilmModel) -> FilmModel:
    """Add ``model`` to :data:`FILM_MODELS` under its name (replacing one of that name):
    scenes, sweeps, :func:`solve_film` and :mod:`bearingfem.design` then take it."""
    if not isinstance(model, FilmModel):
        raise ValueError(f"model must be a FilmModel, got {type(model).__name__}")
    FILM_MODELS[model.name] = model
    return model


def film_model(name: str, what: str = "model") -> FilmModel:
    """The registered model ``name``; an unknown name raises ValueError naming ``what``."""
    if name not in FILM_MODELS:
        raise ValueError(f"{what} must be one of {', '.join(sorted(FILM_MODELS))}, "
                         f"got {name!r}")
    return FILM_MODELS[name]


def numeric_models() -> frozenset:
    """The names of the registered models solved on a mesh (``numeric``)."""
    return frozenset(name for name, m in FILM_MODELS.items() if m.numeric)


def solve_film(model: str, bearing: Bearing, state: JournalState,
               options: Mapping | None = None) -> FilmSolution | None:
    """The whole film (pressures, friction, flows) of ``model`` with its options (defaults
    filled in), or None for the models without one (closed forms, the table)."""
    return film_model(model).film_solution(bearing, state, **dict(options or {}))
