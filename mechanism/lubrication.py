"""Where the mechanism takes its film forces: bearingfem's registry, plus memory for "fem".

Every model is a function (bearing, JournalState, **options) -> (F_r, F_t) on the journal
(:data:`bearingfem.models.FILM_MODELS`); the integration gets its force functions here.
The rest of the mechanism meets bearingfem only through its inputs and outputs: the input
types and checks (``parameters``, ``effects``, ``scene``, which also reads each model's
options from the registry), the film solve and its pictures along a saved run
(``film_history``), and the CSV writer (``result``).
"""
from __future__ import annotations

from bearingfem import JournalState
from bearingfem.models import FILM_MODELS, NUMERIC_MODELS, film_model
from bearingfem.fe.jfo import JFOFilm
from bearingfem.fe.reynolds import fe_force

__all__ = ["FILM_MODELS", "NUMERIC_MODELS", "film_force_function", "TransientJFO"]

#: Shortest time between film steps taken early (a refill, a turn), in film steps.
EARLY = 1e-3


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


class TransientJFO:
    """The "fem-jfo" model along one integration: a :class:`~bearingfem.fe.jfo.JFOFilm`
    whose content advances only at the integrator's accepted steps.

    ``commit(bearing, state, t, **options)`` advances the content to ``t`` by one
    backward-Euler step of the mass-conserving film, once the option ``film_step`` [s] has
    passed since the last one, or sooner when the kept film no longer fits the journal: a
    kept cavity refilled (:meth:`JFOFilm.refilled`) or the line of centres turned by half
    a cell (:meth:`JFOFilm.turned`). ``force(bearing, state, t, **options)`` is the film at
    ``state`` with the kept cavities (:meth:`JFOFilm.instant`, continuous in the state)
    plus what is left of the last film step's change of force: a routine film step moves
    the cavities at once, and the force it changes is faded in over the next film step
    (smoothstep: continuous, with continuous slope, in time) instead of jumping under the
    integrator's error control. A refill acts at once: the support it gives a closing gap
    is not delayed (fading it in lets a fast pin sink: on a coarse film, 30 % off the
    minimum film). A commit earlier than the last one (the integrator went back to an
    event inside its step) first restores what it kept.
    """

    def __init__(self):
        self.film: JFOFilm | None = None
        self.t = 0.0
        self._before = None             # (t, film snapshot, jump, fade) before the last commit
        self._warm = None
        self.steps = 0
        self._jump = (0.0, 0.0)         # force before the last film step minus after [N]
        self._fade = 1.0                # [s] over which that jump fades

    def _start(self, bearing, state, t, n_theta, n_z, grooves, ambient_pressure,
               film_step=0.0):
        self.film = JFOFilm(bearing, state, n_theta, n_z, grooves=grooves,
                            ambient_pressure=ambient_pressure)
        self.t = float(t)
        self.film_step = float(film_step)

    def force(self, bearing, state, t, **options):
        if self.film is None:
            self._start(bearing, state, t, **options)
        f, self._warm = self.film.instant(state, self._warm)
        x = min(max((float(t) - self.t) / self._fade, 0.0), 1.0)
        left = 1.0 - x * x * (3.0 - 2.0 * x)
        return (f[0] + left * self._jump[0], f[1] + left * self._jump[1])

    def commit(self, bearing, state, t, **options):
        """Advance the content to ``t``; returns the step's :class:`FilmSolution` (None
        when there was nothing to advance)."""
        if self.film is None:
            self._start(bearing, state, t, **options)
        t = float(t)
        if t < self.t and self._before is not None:
            self.t, snap, self._jump, self._fade = self._before
            self.film.restore(snap)
            self._before = None
        dt = t - self.t
        # film_step: accepted steps closer than this to the last film step leave the
        # content as it is (the next film step spans them: backward Euler is exact in mass
        # whatever its step), unless the kept film no longer fits the journal; not within
        # film_step / 1000 either: an integrator crawling through an event would otherwise
        # take a film step at each of its tiny steps
        refill = self.film.refilled(state)
        early = dt > EARLY * self.film_step and (refill or self.film.turned(state))
        if dt <= 1e-12 * max(abs(self.t), 1e-3) or not (dt > self.film_step or early):
            return None
        self._before = (self.t, self.film.snapshot(), self._jump, self._fade)
        before = self.force(bearing, state, t)
        sol = self.film.step(state, dt)
        after, _ = self.film.instant(state, None)
        self._jump = (0.0, 0.0) if refill else (before[0] - after[0], before[1] - after[1])
        self._fade = max(self.film_step, dt)
        self.t = t
        self.steps += 1
        return sol

    def replay(self, bearing, start, steps, **options):
        """The film steps of a run taken again: ``start`` = (t, eps, eps_dot, gamma,
        gamma_dot, omega) where the film began, ``steps`` rows (t, eps, eps_dot, gamma,
        gamma_dot, omega) of its committed steps in order. Yields (t, FilmSolution) per
        step: the same solves on the same data as the run, so the same films."""
        state = lambda row: JournalState(*(float(v) for v in row[1:6]))   # noqa: E731
        self._start(bearing, state(start), start[0], **options)
        for row in steps:
            sol = self.film.step(state(row), float(row[0]) - self.t)
            self.t = float(row[0])
            self.steps += 1
            yield self.t, sol


def film_force_function(model: str):
    """The force function of ``model``; "fem" gets a fresh warm-started solver per caller,
    since its memory belongs to one integration, and a model with memory ("fem-jfo") its
    own :class:`TransientJFO`."""
    m = film_model(model, "lubrication.model")
    if m.memory:
        return TransientJFO()
    return _warm_fem() if model == "fem" else m.force
