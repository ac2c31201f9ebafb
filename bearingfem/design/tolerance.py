"""The designer functions to a requested accuracy: a film model's mesh options chosen by
:mod:`bearingfem.accuracy` for an equilibrium or a linearisation, or the error of a mesh
given (its h/2h pair with the half mesh)."""
from __future__ import annotations

import math
from dataclasses import replace
from typing import Callable

import numpy as np

from ..accuracy import (GRADED_FROM_EPS, GRADING_STRENGTH, check_no_mesh, check_rtol,
                        estimate_at, groove_multiple, nominal_order, refine_to_tolerance,
                        search_grading, start_mesh)
from ..bearing import JournalState
from ..models import FilmModel, film_model
from ..routes import FilmProblem
from .thermal import thermal_mesh

__all__ = ["answer_to_tolerance", "mesh_for_run", "run_force_error", "RUN_PROBES",
           "GRADING_STRENGTH", "GRADED_FROM_EPS"]

#: The second partner of a graded search asked for it (``shifted``): the half mesh with its
#: grading focus moved by half the 15 deg grid, its nodes shifted against the cavitation
#: boundary; on Lund & Thomsen's rows it turned 5 of 6 low K, C estimates of the graded
#: pairs high, the estimate 1.08x the single pair's (median; docs/accuracy.md)
PARTNER_SHIFT = math.pi / 24.0


def answer_to_tolerance(m: FilmModel, what: str, key, options: dict, evaluate: Callable,
                        difference: Callable, rtol: float | None,
                        length_ratio: float = 0.5, toward: tuple | None = None,
                        order: float | None = None, shifted: bool = False):
    """(answer, coarse answer, record): ``evaluate(options)`` with the model's mesh options
    (n_theta, n_z and, if the model has it, element) chosen to reach ``rtol`` (relative,
    ``difference(fine, coarse)``; n_theta or n_z in ``options`` is then refused, an element
    kept), or, with ``rtol`` None, on the mesh of ``options`` with
    its error estimated. ``what`` names the quantity in messages; ``key`` (hashable or
    None) the memo entry, to which the model and its other options are added;
    ``length_ratio`` L/D shapes the start mesh (:func:`~bearingfem.accuracy.start_mesh`).
    ``toward`` = (journal angle gamma [rad], eps), known or estimated: a film searched to
    ``rtol`` without a grading of its own is graded toward the least film there
    (:func:`~bearingfem.accuracy.search_grading`: grooved films from
    :data:`GRADED_FROM_EPS`, plain films from
    :data:`~bearingfem.accuracy.PLAIN_GRADED_FROM_EPS` on); the memo keeps that it was
    graded, not the angle (a design loop's next state has its own).
    ``order``: the quantity's nominal convergence order where it is not the film force's
    (:func:`~bearingfem.accuracy.nominal_order`). ``shifted``: a graded search also
    compares each answer with its half mesh graded :data:`PARTNER_SHIFT` further (the
    ``shifted`` partner of :func:`~bearingfem.accuracy.refine_to_tolerance`; a plain
    film's focus moved off its least film at ``toward``'s angle, the state's own)."""
    if not {"n_theta", "n_z"} <= set(m.defaults):
        raise ValueError(f"rtol and error estimates are for film models on a mesh (options "
                         f"n_theta, n_z); model {m.name!r} has none")
    if rtol is not None:
        rtol = check_rtol(rtol)
        check_no_mesh(options.get("n_theta"), options.get("n_z"),
                      " (estimate=True estimates the error of a mesh given)")
    has_element = "element" in m.defaults
    element = options.get("element") if has_element else None
    given = element is not None
    # a thermal film is searched on P1 unless given, as solve_reynolds' search takes it
    thermal = options.get("thermal") is not None
    element = element or ("P2" if has_element and rtol is not None and not thermal else
                          m.defaults.get("element", "P1"))
    cavitation = options.get("cavitation", m.defaults.get("cavitation", "reynolds"))
    smooth = cavitation == "none" and not options.get("grooves")
    order = nominal_order(element, smooth) if order is None else order
    graded = None
    if rtol is not None and toward is not None and "grading" in m.defaults and not thermal:
        graded = search_grading(_problem(m, options), toward)

    def run(n_theta, n_z, el, grading=graded):
        o = {**options, "n_theta": n_theta, "n_z": n_z}
        if grading is not None:
            o["grading"] = grading
        if has_element:
            o["element"] = el
        return evaluate(o)

    def run_shifted(n_theta, n_z, el):
        # a grooved grading's angle moved; a plain film's focus moved off its least film
        # (the pair form: toward the inertial angle, the state's gamma its least film)
        if isinstance(graded, tuple):
            return run(n_theta, n_z, el, (graded[0] + PARTNER_SHIFT, graded[1]))
        return run(n_theta, n_z, el, (float(toward[0]) + PARTNER_SHIFT, graded))

    if rtol is None:
        # the mesh given, or the film's default (a thermal film's its own, 48 x 8)
        o = thermal_mesh(options) if thermal else m.options(options)
        return estimate_at(run, difference, (o["n_theta"], o["n_z"]), element=element,
                           order=order)
    rest = {k: v for k, v in options.items() if k not in ("n_theta", "n_z", "element")}
    try:
        memo = (what, m.name, key, given, graded is not None,
                tuple(sorted((k, repr(v)) for k, v in rest.items())))
        hash(memo)
    except TypeError:
        memo = None
    start = start_mesh(element, length_ratio)
    fine, coarse, record = refine_to_tolerance(
        run, difference, rtol, element=element, start_mesh=start, order=order, key=memo,
        n_theta_multiple=groove_multiple(options.get("grooves")),
        shifted=run_shifted if shifted and graded is not None else None)
    return fine, coarse, replace(record, grading=graded)


def _problem(m: FilmModel, options: dict) -> FilmProblem:
    """The film problem of a model whose options are a film solve's (the finite-element
    model), without bearing and state: what its route's kind needs."""
    o = m.options({k: v for k, v in options.items()
                   if k not in ("n_theta", "n_z", "element")})   # the search's, not the kind's
    return FilmProblem(None, None, **{k: v for k, v in o.items()
                                      if k in FilmProblem.__dataclass_fields__})


#: Steady states at which a run's mesh is chosen (eps, below the scene's eps_max): a
#: journal's film is hardest to resolve near the wall, so the set reaches close to it.
RUN_PROBES = (0.3, 0.6, 0.9, 0.97)


def mesh_for_run(bearing, model: str, options: dict, rtol: float, omega: float,
                 eps_max: float = 0.999) -> tuple:
    """(options with the mesh chosen, record): the mesh on which the model's force is
    within ``rtol`` (estimated) at every steady state of :data:`RUN_PROBES` (eps capped at
    ``eps_max``) at journal speed ``omega`` [rad/s]; for a time integration, where the
    state is not known beforehand. The run's own states are checked after it
    (:func:`run_force_error`)."""
    m = film_model(model)
    states = [JournalState(min(e, eps_max), omega=omega) for e in RUN_PROBES]

    def evaluate(opts):
        return [m.film_force(bearing, s, **opts) for s in states]

    def difference(fine, coarse):
        return max(float(np.hypot(*np.subtract(f, c)) / np.hypot(*f))
                   for f, c in zip(fine, coarse))

    _, _, record = answer_to_tolerance(m, "run", round(bearing.length_ratio, 12), options,
                                       evaluate, difference, rtol,
                                       bearing.length_ratio)
    chosen = {**options, "n_theta": record.mesh[0], "n_z": record.mesh[1]}
    if "element" in m.defaults:
        chosen["element"] = record.element
    return chosen, record


def run_force_error(bearing, model: str, options: dict, states) -> float:
    """The largest estimated relative force error (h/2h with the half mesh) of the model
    on its mesh over ``states`` (JournalStates met in a run)."""
    m = film_model(model)
    worst = 0.0
    for s in states:
        def evaluate(opts, s=s):
            return m.film_force(bearing, s, **opts)

        def difference(fine, coarse):
            n = float(np.hypot(*fine))
            return float(np.hypot(*np.subtract(fine, coarse))) / n if n else 0.0

        worst = max(worst, answer_to_tolerance(m, "run", None, options, evaluate,
                                               difference, None)[2].error)
    return worst
