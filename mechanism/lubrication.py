"""Where the mechanism takes its film models: bearingfem's registry, read through the
film-model contract (:mod:`bearingfem.contract`).

Every model is a :class:`bearingfem.models.FilmModel`; the integration asks it for a film
along the run (:meth:`~bearingfem.models.FilmModel.along_run`) and nothing else
(:class:`mechanism.effects.FilmEffect`). The rest of the mechanism meets bearingfem only
through its inputs and outputs: the input types and checks (``parameters``, ``effects``,
``scene``, which also reads each model's options from the registry), the film solve and
its pictures along a saved run (``film_history``), and the CSV writer (``result``).
"""
from __future__ import annotations

from bearingfem.models import FILM_MODELS, NUMERIC_MODELS, film_model
from bearingfem.transient import TransientJFO

__all__ = ["FILM_MODELS", "NUMERIC_MODELS", "film_model", "TransientJFO"]
