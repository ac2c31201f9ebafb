"""Film models by name: the registry of models keeping :mod:`bearingfem.contract`.

Every model maps (bearing, JournalState, **options) to the film force (F_r, F_t) [N] on the
journal, declares its options with their defaults, and gives the partials of that force in
(eps, eps_dot, w): exactly where it can (closed forms by complex step, the FE film by its
discrete sensitivity), by central differences otherwise; a mesh model also gives its whole
film, a model with memory its transient film. The mechanism, the sweeps and the designer
functions (:mod:`bearingfem.design`) all read models from :data:`FILM_MODELS` and ask
them only what the contract names; :func:`register` adds one.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Callable, Mapping

from .bearing import ELASTIC_EPS_CAP, Bearing, JournalState, check_finite, check_inside_clearance
from .closed.long_bearing import (long_bearing_derivatives, long_bearing_exact_force,
                                  long_bearing_force)
from .closed.short_bearing import (short_bearing_derivatives, short_bearing_exact_force,
                                   short_bearing_force)
from .differentiate import central_differences
from .contract import RunFilm, SteadyRun
from .fe.assembly import fe_operator
from .fe.jfo_balance import JFO_AMBIENT
from .fe.grooved import (check_grading, groove_operator_for, grooved_derivatives,
                         grooved_force, grooved_solution)
from .fe.force_table import TABLE_DEFAULTS, force_table, table_force
from .fe.mesh import ELEMENTS
from .fe.reynolds import fe_force, solve_reynolds
from .fe.mixed import check_roughness, contact_partial_eps, film_contact
from .fe.sensitivity import fe_force_derivatives
from .fv.fvm import fvm_force, fvm_reynolds
from .lubricant import Lubricant
from .solution import FilmSolution, ForceDerivatives
from .transient import TransientJFO
from .transient_compressible import OIL_BULK_MODULUS, CompressibleTransientJFO
from .ehd.jfo_run import ehd_model_solution, ehd_run_film
from .elastic import ElasticBush
from .validation import (MIN_N_THETA, MIN_N_Z, REYNOLDS_FAMILY, check_choice, check_grooves,
                         check_int)

__all__ = ["FilmModel", "FILM_MODELS", "NUMERIC_MODELS", "OPTION_RULES", "film_model",
           "register", "solve_film"]

#: How each film option is checked, whichever model takes it: ("int" | "number", (lo, hi))
#: with None for an open end, ("choice", names), ("grooves", None) for Groove tuples, or
#: ("roughness", None) for a :class:`~bearingfem.contact.Roughness` or None.
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
    """A registered film model, keeping :class:`bearingfem.contract.FilmContract` (the
    numbered rules for writing one are in :mod:`bearingfem.contract`).

    Attributes
    ----------
    name : the name scenes, sweeps, the command line and :mod:`bearingfem.design` use
    force : (bearing, state, **options) -> (F_r, F_t) [N] (rule 1)
    defaults : every option the model takes, with its default (rule 2)
    derivatives : (bearing, state, **options) -> :class:`ForceDerivatives`, exact; None
        means central differences of ``force`` (rule 4)
    numeric : solved on a mesh (its force is finite at the wall only with eps capped)
    solution : (bearing, state, **options) -> :class:`FilmSolution`, the whole film; None
        for force-only models (rule 5)
    transient : (bearing, **options) -> a :class:`~bearingfem.contract.RunFilm` with
        memory, one per integration; None for a steady film (rule 9)
    warm : () -> a force function for one integration that keeps what it learnt (rule 7)
    rules : option rules of this model beyond :data:`OPTION_RULES` (rule 3)
    notes : (bearing, **options) -> dict of numbers a run records about the model (rule 8)
    beyond_clearance : the largest eps the film takes (rule 15): an elastic film carries
        the journal beyond the rigid clearance circle up to it; 0 for a rigid film, which
        refuses eps >= 1 by name
    """

    name: str
    force: Callable
    defaults: Mapping = field(default_factory=dict)
    derivatives: Callable | None = None
    numeric: bool = False
    solution: Callable | None = None
    transient: Callable | None = None
    warm: Callable | None = None
    rules: Mapping = field(default_factory=dict)
    notes: Callable | None = None
    beyond_clearance: float = 0.0

    def __post_init__(self):
        unruled = sorted(set(self.defaults) - set(OPTION_RULES) - set(self.rules))
        if unruled:
            raise ValueError(f"film model {self.name!r}: option(s) {', '.join(unruled)} "
                             "have no rule (give them in rules=...)")

    @property
    def memory(self) -> bool:
        """The film has a state of its own (e.g. the JFO film fraction): ``force`` is its
        steady film; a time integration advances it through :meth:`along_run`, and a
        linearisation about a state alone is not defined."""
        return self.transient is not None

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

    def check_state(self, state: JournalState) -> JournalState:
        """``state``, or a ValueError naming eps when it lies beyond the clearance circle
        and the model does not declare ``beyond_clearance`` (rule 15)."""
        if state.eps >= 1.0 and not state.eps < self.beyond_clearance:
            check_inside_clearance(state, f"film model {self.name!r}")
        return state

    def film_force(self, bearing: Bearing, state: JournalState, **options):
        """(F_r, F_t) [N] with the model's defaults for options not given."""
        self.check_state(state)
        return self.force(bearing, state, **self.options(options))

    def film_solution(self, bearing: Bearing, state: JournalState,
                      **options) -> FilmSolution | None:
        """The whole film (pressures, friction, flows), or None for a force-only model."""
        opts = self.options(options)
        self.check_state(state)
        return None if self.solution is None else self.solution(bearing, state, **opts)

    def force_derivatives(self, bearing: Bearing, state: JournalState,
                          **options) -> ForceDerivatives:
        """Force and its partials in (eps, eps_dot, w) (see :class:`ForceDerivatives`)."""
        opts = self.options(options)
        self.check_state(state)
        if self.memory:
            raise ValueError(
                f"film model {self.name!r} has memory (its film fraction is carried by the "
                "flow from earlier states): force derivatives at a state alone are not "
                "defined. Linearise about an orbit with the transient film, or use the "
                "Reynolds-condition model 'fem' (identical where the film does not reform)")
        if self.derivatives is not None:
            return self.derivatives(bearing, state, **opts)
        return central_differences(lambda s: self.force(bearing, s, **opts), state)

    def along_run(self, bearing: Bearing, options: Mapping | None = None) -> RunFilm:
        """A fresh film for one time integration (:class:`~bearingfem.contract.RunFilm`):
        the model's transient film if it has memory, else its (warm) force."""
        opts = self.options(options)
        if self.transient is not None:
            return self.transient(bearing, **opts)
        return SteadyRun(bearing, self.warm() if self.warm is not None else self.force, opts)

    def run_notes(self, bearing: Bearing, options: Mapping | None = None) -> dict:
        """What a run records about the model (rule 8); empty for most models."""
        return {} if self.notes is None else dict(self.notes(bearing, **self.options(options)))


def _contact_force(bearing, state, n_theta, n_z, element, grooves, roughness):
    """(F_r, F_t) [N] of the asperity contact on the "fem" model's mesh ((0, 0) without
    roughness): the film and the summits carry the load together (:mod:`bearingfem.fe.mixed`)."""
    if roughness is None:
        return 0.0, 0.0
    op = fe_operator(bearing, state, n_theta, n_z, element, None, True, grooves)
    return film_contact(bearing, state, op, roughness).force_local


def _graded(bearing, n_theta, n_z, element, grooves, roughness, grading):
    """The bearing-fixed grooved operator of a ``grading`` (None without one); ValueError
    when it is given without grooves or with roughness."""
    if grading is None:
        return None
    if not grooves or roughness is not None:
        raise ValueError("grading is for grooved films on the bearing-fixed mesh: give "
                         "grooves, and no roughness")
    return groove_operator_for(bearing, n_theta, n_z, element, grooves, grading)


def _fem(bearing, state, n_theta, n_z, element, cavitation, grooves, roughness=None,
         grading=None):
    """The "fem" model's force, film plus asperity contact (a cold solve; options always
    come from the registry)."""
    gop = _graded(bearing, n_theta, n_z, element, grooves, roughness, grading)
    if gop is not None:
        return grooved_force(bearing, state, gop, grooves, cavitation)[0]
    film = fe_force(bearing, state, n_theta, n_z, element, cavitation, grooves=grooves)[0]
    contact = _contact_force(bearing, state, n_theta, n_z, element, grooves, roughness)
    return film[0] + contact[0], film[1] + contact[1]


def _fem_solution(bearing, state, n_theta, n_z, element, cavitation, grooves, roughness=None,
                  grading=None):
    gop = _graded(bearing, n_theta, n_z, element, grooves, roughness, grading)
    if gop is not None:
        return grooved_solution(bearing, state, gop, grooves, cavitation, "active-set",
                                1e-10, "full", element)
    return solve_reynolds(bearing, state, n_theta, n_z, element, cavitation, grooves=grooves,
                          roughness=roughness)


def _fem_derivatives(bearing, state, n_theta, n_z, element, cavitation, grooves,
                     roughness=None, grading=None) -> ForceDerivatives:
    """The film's exact partials plus the asperity force and its exact partial in eps (it
    has none in eps_dot or w; its gamma partial with grooves, the mesh moving with them,
    is a quadrature error and is left out)."""
    gop = _graded(bearing, n_theta, n_z, element, grooves, roughness, grading)
    if gop is not None:
        return grooved_derivatives(bearing, state, gop, grooves, cavitation)
    d = fe_force_derivatives(bearing, state, n_theta, n_z, element, cavitation, grooves)
    if roughness is None:
        return d
    op = fe_operator(bearing, state, n_theta, n_z, element, None, True, grooves)
    f = film_contact(bearing, state, op, roughness).force_local
    de = contact_partial_eps(bearing, state, op, roughness)
    return replace(d, force=(d.force[0] + f[0], d.force[1] + f[1]),
                   d_eps=(d.d_eps[0] + de[0], d.d_eps[1] + de[1]))


def _warm_fem():
    """The "fem" force for one integration: each solve starts from the previous one's
    cavitated set and factorisation (consecutive states of an integration are close). The
    answer is the same as a cold solve to the solver tolerance; only the cost changes."""
    last = {}

    def fem(bearing, state, n_theta, n_z, element, cavitation, grooves=(), roughness=None,
            grading=None):
        key = (bearing.length_ratio, n_theta, n_z, element, cavitation, grooves, grading)
        gop = _graded(bearing, n_theta, n_z, element, grooves, roughness, grading)
        if gop is not None:
            force, last[key] = grooved_force(bearing, state, gop, grooves, cavitation,
                                             warm=last.get(key))
            return force
        force, last[key] = fe_force(bearing, state, n_theta, n_z, element, cavitation,
                                    warm=last.get(key), grooves=grooves)
        contact = _contact_force(bearing, state, n_theta, n_z, element, grooves, roughness)
        return force[0] + contact[0], force[1] + contact[1]
    return fem


def _fvm_solution(bearing, state, n_theta, n_z, cavitation):
    return fvm_reynolds(bearing, state, n_theta, n_z, cavitation)


def _table_notes(bearing, **options) -> dict:
    """The table's own measured mesh error (the table the run used: cached)."""
    return {"fem_table_mesh_error": force_table(bearing.length_ratio, **options).mesh_error}


def _jfo_solution(bearing, state, n_theta, n_z, grooves, ambient_pressure, film_step=0.0):
    """The steady JFO film (steady in the frame of the line of centres). ``film_step`` [s]
    is for time integration (:class:`~bearingfem.transient.TransientJFO`); the steady
    film has none."""
    return solve_reynolds(bearing, state, n_theta, n_z, "P1", "jfo", grooves=grooves,
                          ambient_pressure=ambient_pressure)


def _fem_jfo(bearing, state, n_theta, n_z, grooves, ambient_pressure, film_step=0.0):
    """The steady JFO film's force."""
    return _jfo_solution(bearing, state, n_theta, n_z, grooves, ambient_pressure).force_local


def _compressible_jfo_solution(bearing, state, n_theta, n_z, grooves, ambient_pressure,
                               film_step=0.0, bulk_modulus=OIL_BULK_MODULUS):
    """The steady compressible (Elrod) JFO film, oil of bulk modulus ``bulk_modulus`` [Pa]."""
    oil = Lubricant(viscosity=bearing.viscosity, bulk_modulus=bulk_modulus)
    return solve_reynolds(bearing, state, n_theta, n_z, "P1", "jfo", grooves=grooves,
                          ambient_pressure=ambient_pressure, lubricant=oil)


def _fem_jfo_compressible(bearing, state, n_theta, n_z, grooves, ambient_pressure,
                          film_step=0.0, bulk_modulus=OIL_BULK_MODULUS):
    """The steady compressible JFO film's force."""
    return _compressible_jfo_solution(bearing, state, n_theta, n_z, grooves,
                                      ambient_pressure, film_step, bulk_modulus).force_local


def _fem_ehd(bearing, state, lubricant, bush, roughness, n_theta, n_z, modes, film_step=0.0,
             cavitation="reynolds", coupling="kept", relaxation=1e-5):
    """The steady EHD film's force, film plus asperity contact (``coupling`` and
    ``relaxation`` are for time integration only)."""
    sol = ehd_model_solution(bearing, state, lubricant, bush, roughness, n_theta, n_z, modes,
                             cavitation=cavitation)
    f, c = sol.force_local, sol.asperity_force_local
    return float(f[0] + c[0]), float(f[1] + c[1])


#: The "fem-ehd" model's own options: lubricant and bush objects (or None), modes the
#: number of compliance vectors (0: the full compliance).
EHD_RULES = {"lubricant": ("instance", (Lubricant,)), "bush": ("instance", (ElasticBush,)),
             "modes": ("int", (0, None)), "cavitation": ("choice", ("reynolds", "jfo")),
             "coupling": ("choice", ("kept", "states")), "relaxation": ("number", (1e-12, 1.0))}
_MESH = dict(n_theta=48, n_z=8)
FILM_MODELS: dict = {}


def register(model: FilmModel) -> FilmModel:
    """Add ``model`` to :data:`FILM_MODELS` under its name (replacing one of that name):
    scenes, sweeps, :func:`solve_film` and :mod:`bearingfem.design` then take it."""
    if not isinstance(model, FilmModel):
        raise ValueError(f"model must be a FilmModel, got {type(model).__name__}")
    FILM_MODELS[model.name] = model
    return model


for _m in (
    # switch 1 rad/s: the literal sharp switch of Eq. 9's half film makes integrators chatter
    # (a steady film, w >> 1 rad/s, is the same to round-off)
    FilmModel("short", short_bearing_force, dict(half_film="wedge", switch_speed=1.0),
              short_bearing_derivatives),
    FilmModel("long", long_bearing_force, {}, long_bearing_derivatives),
    FilmModel("short-exact", short_bearing_exact_force),
    FilmModel("long-exact", long_bearing_exact_force),
    FilmModel("fem", _fem, dict(_MESH, element="P1", cavitation="gumbel", grooves=(),
                                roughness=None, grading=None),
              _fem_derivatives, numeric=True, solution=_fem_solution, warm=_warm_fem),
    FilmModel("fvm", fvm_force, dict(_MESH, cavitation="gumbel"), numeric=True,
              solution=_fvm_solution),
    FilmModel("fem-table", table_force, dict(TABLE_DEFAULTS), numeric=True,
              notes=_table_notes),
    FilmModel("fem-jfo", _fem_jfo, dict(_MESH, grooves=(), ambient_pressure=JFO_AMBIENT,
                                        film_step=0.0),
              numeric=True, solution=_jfo_solution, transient=TransientJFO),
    FilmModel("fem-jfo-compressible", _fem_jfo_compressible,
              dict(_MESH, grooves=(), ambient_pressure=JFO_AMBIENT, film_step=0.0,
                   bulk_modulus=OIL_BULK_MODULUS),
              numeric=True, solution=_compressible_jfo_solution,
              transient=CompressibleTransientJFO,
              # below 1e5 Pa (a gas's) nothing is an oil
              rules={"bulk_modulus": ("number", (1e5, None))}),
    FilmModel("fem-ehd", _fem_ehd, dict(_MESH, lubricant=None, bush=None, roughness=None,
                                        modes=64, film_step=0.0, cavitation="reynolds",
                                        coupling="kept", relaxation=1e-5),
              numeric=True, solution=ehd_model_solution, transient=ehd_run_film, rules=EHD_RULES,
              beyond_clearance=ELASTIC_EPS_CAP),
):
    register(_m)
#: Film models solved numerically, as registered at import (a model's own ``numeric`` is
#: the contract): their force stays finite up to the wall only when eps is capped (scene
#: default eps_max 0.999); the closed forms are evaluated to 1 - 1e-6.
NUMERIC_MODELS = frozenset(name for name, m in FILM_MODELS.items() if m.numeric)


def film_model(name: str, what: str = "model") -> FilmModel:
    """The registered model ``name``; an unknown name raises ValueError naming ``what``."""
    if name not in FILM_MODELS:
        raise ValueError(f"{what} must be one of {', '.join(sorted(FILM_MODELS))}, "
                         f"got {name!r}")
    return FILM_MODELS[name]


def solve_film(model: str, bearing: Bearing, state: JournalState,
               options: Mapping | None = None) -> FilmSolution | None:
    """The whole film (pressures, friction, flows) of ``model`` with its options (defaults
    filled in), or None for the models without one (closed forms, the table)."""
    return film_model(model).film_solution(bearing, state, **dict(options or {}))
