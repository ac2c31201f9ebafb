"""The film-model contract: what every caller may ask of a film model, written once.

The mechanism (:mod:`mechanism`), the designer functions (:mod:`bearingfem.design`), the
sweeps and the command line reach a film model only through :class:`FilmContract`
(:class:`bearingfem.models.FilmModel` keeps it; the registry is
:data:`bearingfem.models.FILM_MODELS`). Along a time integration they reach it through the
:class:`RunFilm` the model makes for that run. No caller branches on a model's name, and
none probes for an attribute: every member below is typed, with its default.

One vocabulary: a caller calls ``film_force``, ``force_derivatives``, ``film_solution``,
``along_run`` and ``run_notes``; a model writes the hooks of the same names with a
leading underscore (``_film_force`` ...), which the public methods call with the options
filled in and checked (:class:`bearingfem.models.FilmModel`).

Rules for writing a new film model
----------------------------------
A steady film (its force is a function of the journal state alone):

1. ``film_force(bearing, state, **options) -> (F_r, F_t)`` [N]: the film's force on the journal
   in the local frame of :class:`~bearingfem.JournalState` (r̂ along the eccentricity,
   t̂ turned +90°). Plain floats, finite for 0 <= eps < 1; bad input raises ValueError
   naming the parameter before any work; a solve that does not converge raises (it never
   returns an unconverged force).
2. ``defaults``: every option the model takes, with its default. Nothing else reaches
   ``film_force``: the registry fills the defaults in and rejects unknown names.
3. Each option is checked by a rule, ``("int" | "number", (lo, hi))``, ``("choice",
   names)`` or ``("grooves", None)``: the shared ones are
   :data:`bearingfem.models.OPTION_RULES`; a model adds its own in ``rules``. An option
   without a rule is refused when the model is made.
4. ``force_derivatives(bearing, state, **options) -> ForceDerivatives``: the partials in
   (eps, eps_dot, w) where the model has them exactly (``exact_derivatives`` is then
   True); a model without them gets central differences of its force (:func:`bearingfem.differentiate.central_differences`).
5. ``film_solution(bearing, state, **options) -> FilmSolution``: the whole film (pressures,
   friction, flows) where the model has one; None for force-only models (closed forms,
   tables). :func:`bearingfem.models.solve_film` calls it, whatever the model's name.
6. ``numeric``: True when the force is solved on a mesh (finite at the wall only with eps
   capped: scenes then default to eps_max = 0.999).
7. ``along_run(bearing, options) -> RunFilm``: a steady model's run film forwards its
   force (:class:`SteadyRun`); it may keep what it learnt between calls (a
   factorisation, a cavitated set), its answers equal to ``film_force``'s to the solver
   tolerance: only the cost may change.
8. ``run_notes(bearing, options) -> dict`` (optional): numbers a run should record about the
   model (e.g. a table's measured mesh error); they go into the run's statistics.

A film with memory (its state carries the past, e.g. the JFO film fraction) adds:

9. ``along_run(bearing, options) -> RunFilm``: a fresh film for one integration, keeping
   :class:`RunFilm`. The model's ``memory`` is then True, its ``film_force`` is the steady film
   (what a design calculation or a start uses), and force derivatives at a state alone are
   refused (a linearisation needs an orbit).
10. ``RunFilm.start(state, t)`` begins the film at the first state; ``force(state, t)``
    is the film the integrator sees at a trial state: a function of (state, t) with no
    jumps, that changes nothing kept (integrators evaluate trial states they reject).
11. ``commit(state, t) -> FilmStep | None`` advances what is kept to an *accepted* state;
    it is called once per accepted integrator step, in time order, and by nothing else
    (never from an event function, never on a rejected step). It returns what the film
    step gave, or None when the film chose not to step (e.g. within its own film step).
    A commit that raises (:class:`ConvergenceError`) leaves the kept film unchanged, so
    the integrator can cut its step and try again.
12. ``snapshot()`` / ``restore(snapshot)``: the kept film as one immutable record and back.
13. ``replay(start, steps)``: the committed steps taken again from the recorded
    (t, state) of the start and of each step; yields (t, FilmSolution) per step (None for
    a model without a whole film), the same solves on the same data as the run.
    ``replay_tolerance``: the largest departure of a replayed step's force from the
    run's, relative to the run's largest force, that the film's own solves allow
    (:data:`REPLAY_TOLERANCE`, round-off, unless its solves stop short of it); a caller
    refuses a replay that departs further (its scene is not the run's).
14. ``steps``: the number of film steps taken.

A film that carries the journal beyond the rigid clearance circle:

15. An elastic film (its gap opened by a bush's deflection, h = c (1 + eps cos theta) + w)
    declares ``beyond_clearance``: the largest eps it takes
    (:data:`~bearingfem.bearing.ELASTIC_EPS_CAP`); a rigid film leaves it 0. Such a film
    takes an :class:`~bearingfem.bearing.ElasticJournalState` with 1 <= eps < that cap
    and gives a finite force there; every film given eps >= 1 without a bush raises a
    ValueError naming eps (the public :class:`~bearingfem.JournalState` itself keeps
    eps in [0, 1)). A caller that integrates a journal (:mod:`mechanism`) then moves the
    wall from eps = 1 to the declared cap.

A film whose memory is integrated with the journal:

16. Every run film declares ``state_size`` (0 for most). A run film may keep n > 0
    states of its own that the caller integrates with the journal (e.g. a bush's modal
    deflection, :class:`~bearingfem.ehd.states.ModalStateEHD`): it gives
    ``rates(state, z, t) -> ((F_r, F_t), dz/dt)`` at a trial (state, z, t), changing
    nothing kept (rule 10); z starts at zero with the run, and ``commit(state, t, z)``
    replaces rule 11's commit. Its ``force`` is refused. With ``state_size`` 0 every
    caller integrates it as before.
17. Every run film declares ``has_tangent`` (False for most). With True, ``tangent()``
    gives its force and dz/dt of the last ``rates`` call differentiated in z with the
    journal's state held (:class:`StateTangent`). A caller with an implicit integrator
    then builds its Jacobian from it instead of n film solves by differences
    (:class:`mechanism.simulate.JointEquations`); without it, the integrator's own
    differences.

A steady model's :class:`RunFilm` (made by the registry) forwards ``force`` and commits
nothing, so a caller treats every model the same way.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Iterator, Mapping, Protocol, runtime_checkable

import numpy as np

from .bearing import Bearing, JournalState
from .solution import FilmSolution, ForceDerivatives

from .errors import ConvergenceError   # a solve that did not converge

__all__ = ["FilmContract", "RunFilm", "FilmStep", "SteadyRun", "StatelessRun", "StateTangent",
           "ConvergenceError", "REPLAY_TOLERANCE"]

#: Largest departure of a replayed film step's force from the run's record, relative to
#: the record's largest force, for a film whose replay takes the same solves on the same
#: data (round-off only; a film solved again from its kept states starts elsewhere than
#: the run's warm solve did, so the two agree to the Newton tolerance, 1e-10 of the
#: residual's terms: 1e-11 measured) (rule 13)
REPLAY_TOLERANCE = 1e-9


@dataclass(frozen=True)
class FilmStep:
    """What one committed film step gave: its time [s], the journal state it was taken at,
    the film's force on the journal (F_r, F_t) [N], local frame, and the whole film when
    the model solves one (None otherwise)."""

    t: float
    state: JournalState
    force_local: tuple
    solution: FilmSolution | None = None


@dataclass(frozen=True, eq=False)
class StateTangent:
    """A film's force and state rates differentiated in its own states z (n of them), the
    journal's state held (rule 17): force_local (2, n) [N/m], d(F_r, F_t)/dz; rates
    (n, n) [1/s], d(dz/dt)/dz."""

    force_local: np.ndarray
    rates: np.ndarray


@runtime_checkable
class RunFilm(Protocol):
    """A film along one time integration (rules 10-17 of the module)."""

    memory: bool
    steps: int
    state_size: int
    has_tangent: bool
    replay_tolerance: float

    def start(self, state: JournalState, t: float) -> None: ...

    def force(self, state: JournalState, t: float) -> tuple: ...

    def commit(self, state: JournalState, t: float) -> FilmStep | None: ...

    def snapshot(self) -> object: ...

    def restore(self, snapshot) -> None: ...

    def replay(self, start: tuple, steps) -> Iterator[tuple]: ...

    def rates(self, state: JournalState, z: np.ndarray, t: float) -> tuple: ...

    def tangent(self) -> StateTangent: ...


@runtime_checkable
class FilmContract(Protocol):
    """A film model as its callers see it (rules 1-9 of the module)."""

    name: str
    defaults: Mapping
    numeric: bool
    memory: bool
    beyond_clearance: float
    exact_derivatives: bool

    def options(self, options: Mapping | None = None, where: str = "") -> dict: ...

    def film_force(self, bearing: Bearing, state: JournalState, **options) -> tuple: ...

    def force_derivatives(self, bearing: Bearing, state: JournalState,
                          **options) -> ForceDerivatives: ...

    def film_solution(self, bearing: Bearing, state: JournalState,
                      **options) -> FilmSolution | None: ...

    def along_run(self, bearing: Bearing, options: Mapping | None = None) -> RunFilm: ...

    def run_notes(self, bearing: Bearing, options: Mapping | None = None) -> dict: ...


class StatelessRun:
    """What a run film without states of its own declares (rules 13, 16-17): a base for
    the run films; ``rates`` and ``tangent`` are refused; a replay to round-off."""

    state_size = 0
    has_tangent = False
    replay_tolerance = REPLAY_TOLERANCE

    def rates(self, state: JournalState, z, t: float):
        raise ValueError(f"{type(self).__name__} has no states of its own (state_size 0): "
                         "ask its force")

    def tangent(self) -> StateTangent:
        raise ValueError(f"{type(self).__name__} has no tangent (has_tangent False)")


class SteadyRun(StatelessRun):
    """A steady film along a run: the force of the state alone; nothing to keep."""

    memory = False
    steps = 0

    def __init__(self, bearing: Bearing, force: Callable, options: Mapping):
        self.bearing, self._force, self._options = bearing, force, dict(options)

    def start(self, state: JournalState, t: float) -> None:
        return None

    def force(self, state: JournalState, t: float) -> tuple:
        return self._force(self.bearing, state, **self._options)

    def commit(self, state: JournalState, t: float) -> None:
        return None

    def snapshot(self) -> None:
        return None

    def restore(self, snapshot) -> None:
        return None

    def replay(self, start, steps):
        raise ValueError("a steady film has no film steps to replay: solve it at the "
                         "recorded states instead")
