"""Film models by name: the registry (:mod:`bearingfem.models.registry`) and the built-in
models, each in its own module that registers itself.

Every model maps (bearing, JournalState, **options) to the film force (F_r, F_t) [N] on the
journal, declares its options with their defaults, and gives the partials of that force in
(eps, eps_dot, w): exactly where it can (closed forms by complex step, the FE film by its
discrete sensitivity), by central differences otherwise; a mesh model also gives its whole
film, a model with memory its transient film. The mechanism, the sweeps and the designer
functions (:mod:`bearingfem.design`) all read models from :data:`FILM_MODELS` and ask
them only what the contract (:mod:`bearingfem.contract`) names; :func:`register` adds one.

================  =================================================  ==================
model             film                                               module
================  =================================================  ==================
short, long       closed forms (seed Eq. 9, 10-13 corrected)          ``closed``
short-exact, ...  exact quadratures of those pressures                ``closed``
fem               FE film, Reynolds family, grooves, roughness        ``fem``
fvm               finite-volume film                                  ``fvm``
fem-table         FE forces tabulated and interpolated                ``table``
fem-jfo           mass-conserving film, transient along a run         ``jfo``
fem-jfo-compr.    compressible mass-conserving film                   ``jfo``
fem-ehd           elastic bush, pressure-dependent oil, summits       ``ehd``
fem-thd           thermal film, temperatures advancing along a run    ``thd``
================  =================================================  ==================
"""
from __future__ import annotations

from . import closed, ehd, fem, fvm, jfo, table, thd  # noqa: F401  (each registers its models)
from .registry import (FILM_MODELS, OPTION_RULES, FilmModel, film_model, numeric_models,
                       register, solve_film)

__all__ = ["FilmModel", "FILM_MODELS", "NUMERIC_MODELS", "OPTION_RULES", "film_model",
           "register", "solve_film", "numeric_models"]

#: Film models solved numerically, as registered at import (a model's own ``numeric`` is
#: the contract): their force stays finite up to the wall only when eps is capped (scene
#: default eps_max 0.999); the closed forms are evaluated to 1 - 1e-6.
NUMERIC_MODELS = numeric_models()
