"""Where the mechanism takes its film forces: bearingfem's registry, plus memory for "fem".

Every model is a function (bearing, JournalState, **options) -> (F_r, F_t) on the journal
(:data:`bearingfem.models.FILM_MODELS`); the integration gets its force functions here.
The rest of the mechanism meets bearingfem only through its inputs and outputs: the input
types and checks (``parameters``, ``effects``, ``scene``, which also reads each model's
options from the registry), the film solve and its pictures along a saved run
(``film_history``), and the CSV writer (``result``).
"""
from __future__ import annotations

from bearingfem.models import FILM_MODELS, NUMERIC_MODELS, film_model
from bearingfem.fe.reynolds import fe_force

__all__ = ["FILM_MODELS", "NUMERIC_MODELS", "film_force_function"]


def _warm_fem():
    """The "fem" model with memory: each solve starts from the previous one's cavitated set
    and factorisation (consecutive states of an integration are close). The answer is the
    same as a cold solve to the solver tolerance; only the cost changes."""
    last = {}

    def fem(bearing, state, n_theta, n_z, element, cavitation, grooves=()):  # scene options
        key = (bearing.length_ratio, n_theta, n_z, element, cavitation, grooves)
        force, last[key] = fe_force(bearing, state, n_theta, n_z, element, cavitation,
                                    warm=last.get(key), grooves=grooves)
        return force
    return fem


def film_force_function(model: str):
    """The force function of ``model``; "fem" gets a fresh warm-started solver per caller,
    since its memory belongs to one integration."""
    m = film_model(model, "lubrication.model")
    return _warm_fem() if model == "fem" else m.force
