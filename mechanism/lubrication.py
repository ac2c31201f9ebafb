"""The one place the mechanism meets bearingfem: film models by name -> (F_r, F_t) [N].

Every model is a function (bearing, JournalState, **options) -> (F_r, F_t) on the journal.
"""
from __future__ import annotations

from bearingfem import (long_bearing_exact_force, long_bearing_force, short_bearing_exact_force,
                        short_bearing_force)
from bearingfem.force_table import table_force
from bearingfem.fvm import fvm_force
from bearingfem.reynolds import fe_force

__all__ = ["FILM_MODELS", "NUMERIC_MODELS", "film_force_function"]


def _fem(bearing, state, n_theta=48, n_z=8, element="P1", cavitation="gumbel"):
    return fe_force(bearing, state, n_theta, n_z, element, cavitation)[0]


def _warm_fem():
    """The "fem" model with memory: each solve starts from the previous one's cavitated set
    and factorisation (consecutive states of an integration are close). The answer is the
    same as a cold solve to the solver tolerance; only the cost changes."""
    last = {}

    def fem(bearing, state, n_theta=48, n_z=8, element="P1", cavitation="gumbel"):
        key = (bearing.slenderness, n_theta, n_z, element, cavitation)
        force, last[key] = fe_force(bearing, state, n_theta, n_z, element, cavitation,
                                    warm=last.get(key))
        return force
    return fem


def _fvm(bearing, state, n_theta=48, n_z=8, cavitation="gumbel"):
    return fvm_force(bearing, state, n_theta, n_z, cavitation)


FILM_MODELS = {
    "short": short_bearing_force,
    "long": long_bearing_force,
    "short-exact": short_bearing_exact_force,
    "long-exact": long_bearing_exact_force,
    "fem": _fem,
    "fvm": _fvm,
    "fem-table": table_force,
}
#: Options each model accepts in a scene's lubrication table (besides "model", "eps_max").
MODEL_OPTIONS = {
    "short": {"half_film", "switch_speed"}, "long": set(), "short-exact": set(), "long-exact": set(),
    "fem": {"n_theta", "n_z", "element", "cavitation"},
    "fvm": {"n_theta", "n_z", "cavitation"},
    "fem-table": {"n_theta", "n_z", "element", "cavitation", "n_eps", "n_phi"},
}
#: Film models solved numerically: their force stays finite up to the wall only when eps is
#: capped (scene default eps_max 0.999); the closed forms are evaluated to 1 - 1e-6.
NUMERIC_MODELS = {"fem", "fvm", "fem-table"}


def film_force_function(model: str):
    if model not in FILM_MODELS:
        raise ValueError(f"lubrication.model must be one of {', '.join(sorted(FILM_MODELS))}, "
                         f"got {model!r}")
    # A fresh warm-started solver per caller: its memory belongs to one integration.
    return _warm_fem() if model == "fem" else FILM_MODELS[model]
