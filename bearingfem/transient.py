"""The mass-conserving (JFO) film along a time integration: when the film steps, and what
force the integrator sees between its steps.

:class:`TransientJFO` is the "fem-jfo" model's :class:`~bearingfem.contract.RunFilm`: a
:class:`~bearingfem.fe.jfo.JFOFilm` (the physics) driven by a stepping policy (this
module): film steps at accepted integrator steps only, spaced by ``film_step``, taken early
when the kept film no longer fits the journal, and their change of force faded in.
"""
from __future__ import annotations

from dataclasses import dataclass

from .bearing import Bearing, JournalState
from .contract import FilmStep, StatelessRun
from .errors import ConvergenceError
from .fe.jfo import JFOFilm, JFOSnapshot
from .fe.jfo_fields import FilmSpec
from .fe.jfo_grooved_transient import GroovedJFOFilm

__all__ = ["TransientJFO", "TransientSnapshot", "EARLY"]

#: Shortest time between film steps taken early (a refill, a turn), in film steps.
EARLY = 1e-3


def faded_force(force: tuple, jump: tuple, elapsed: float, fade: float) -> tuple:
    """(F_r, F_t) [N]: ``force`` plus what is left of the ``jump`` [N] a film step made,
    ``elapsed`` [s] after it; the jump fades out smoothly (C1, smoothstep) over ``fade``
    [s] so the integrator sees no discontinuity in the force."""
    x = min(max(elapsed / fade, 0.0), 1.0)
    left = 1.0 - x * x * (3.0 - 2.0 * x)
    return (force[0] + left * jump[0], force[1] + left * jump[1])


def since_film_step(t: float, last: float) -> float:
    """Time [s] from the last film step at ``last`` to an accepted step at ``t``; a step
    back in time raises (a film with memory goes back only by restoring a snapshot)."""
    if t < last:
        raise ValueError(f"t = {t!r} s is before the last film step ({last!r} s): "
                         "restore a snapshot to go back")
    return t - last


@dataclass(frozen=True)
class TransientSnapshot:
    """What a :class:`TransientJFO` keeps: the time of its last film step [s], the film,
    the change of force that step made (before minus after, (F_r, F_t) [N]) and the time
    [s] over which it fades, and the number of film steps."""

    t: float
    film: JFOSnapshot
    jump: tuple
    fade: float
    steps: int


class TransientJFO(StatelessRun):
    """The "fem-jfo" model along one integration: a :class:`~bearingfem.fe.jfo.JFOFilm`
    whose content advances only at the integrator's accepted steps.

    Parameters
    ----------
    bearing : the bearing
    n_theta, n_z, grooves, ambient_pressure : the film (:class:`JFOFilm`)
    film_step : [s] time between film steps (0: a film step at every accepted step)
    fields, tilt, tilt_rate : the film on fields and a tilted journal (:class:`JFOFilm`;
        functions of time are called with the integrator's time t [s])

    :meth:`commit` advances the content to ``t`` by one backward-Euler step of the
    mass-conserving film, once ``film_step`` has passed since the last one, or sooner when
    the kept film no longer fits the journal: a kept cavity refilled
    (:meth:`JFOFilm.refilled`) or the line of centres turned by half a cell
    (:meth:`JFOFilm.turned`). :meth:`force` is the film at ``state`` with the kept cavities
    (:meth:`JFOFilm.instant`, continuous in the state) plus what is left of the last film
    step's change of force: a routine film step moves the cavities at once, and the force
    it changes is faded in over the next film step (smoothstep: continuous, with continuous
    slope, in time) instead of jumping under the integrator's error control. A refill acts
    at once: the support it gives a closing gap is not delayed (fading it in lets a fast
    pin sink: on a coarse film, 30 % off the minimum film).
    """

    memory = True
    #: shortest time between film steps taken early, in film steps (:data:`EARLY`)
    early_fraction = EARLY

    def __init__(self, bearing: Bearing, n_theta: int, n_z: int, grooves=(),
                 ambient_pressure: float = 0.0, film_step: float = 0.0, *, fields=None,
                 tilt=(0.0, 0.0), tilt_rate=(0.0, 0.0)):
        self.bearing = bearing
        self._film_options = dict(n_theta=n_theta, n_z=n_z, grooves=grooves,
                                  ambient_pressure=ambient_pressure, fields=fields,
                                  tilt=tilt, tilt_rate=tilt_rate)
        self.film_step = float(film_step)
        self.film: JFOFilm | None = None
        self.t = 0.0
        self._warm = None
        self.steps = 0
        self._jump = (0.0, 0.0)         # force before the last film step minus after [N]
        self._fade = 1.0                # [s] over which that jump fades

    def start(self, state: JournalState, t: float) -> None:
        """Begin a full film at ``state``, time ``t`` [s]."""
        o = self._film_options
        if o["grooves"] and FilmSpec.checked(o["fields"], o["tilt"], o["tilt_rate"]) is None:
            # rigid grooved film: the bearing-fixed mesh (no operator per journal angle)
            self.film = GroovedJFOFilm(self.bearing, state, o["n_theta"], o["n_z"],
                                       grooves=o["grooves"], time=float(t),
                                       ambient_pressure=o["ambient_pressure"])
        else:
            self.film = JFOFilm(self.bearing, state, time=float(t), **o)
        self.t = float(t)
        self._warm, self._jump, self._fade, self.steps = None, (0.0, 0.0), 1.0, 0

    def force(self, state: JournalState, t: float) -> tuple:
        """(F_r, F_t) [N] at a trial ``state`` and time ``t``; keeps nothing but the warm
        start of the next solve (a film not started yet starts here)."""
        if self.film is None:
            self.start(state, t)
        f, self._warm = self.film.instant(state, self._warm, float(t))
        return faded_force(f, self._jump, float(t) - self.t, self._fade)

    def commit(self, state: JournalState, t: float) -> FilmStep | None:
        """Advance the content to the accepted ``state`` at ``t``; returns the film step
        (None when there was nothing to advance). A failed film step raises and keeps the
        film as it was."""
        if self.film is None:
            self.start(state, t)
        t = float(t)
        dt = since_film_step(t, self.t)
        # film_step: accepted steps closer than this to the last film step leave the
        # content as it is (the next film step spans them: backward Euler is exact in mass
        # whatever its step), unless the kept film no longer fits the journal; not within
        # film_step / 1000 either: an integrator crawling through an event would otherwise
        # take a film step at each of its tiny steps
        refill = self.film.refilled(state, t)
        early = dt > self.early_fraction * self.film_step and (refill or self.film.turned(state))
        if dt <= 1e-12 * max(abs(self.t), 1e-3) or not (dt > self.film_step or early):
            return None
        before = self.force(state, t)
        kept = self.film.snapshot()
        try:
            sol = self.film.step(state, dt)      # raises before changing the film
            after, _ = self.film.instant(state, None, t)
        except ConvergenceError:
            self.film.restore(kept)              # the instant failed after the step: undo it
            raise
        self._jump = (0.0, 0.0) if refill else (before[0] - after[0], before[1] - after[1])
        self._fade = max(self.film_step, dt)
        self.t = t
        self.steps += 1
        return FilmStep(t, state, sol.force_local, sol)

    def snapshot(self) -> TransientSnapshot:
        return TransientSnapshot(self.t, self.film.snapshot(), self._jump, self._fade,
                                 self.steps)

    def restore(self, snapshot: TransientSnapshot) -> None:
        self.t, self._jump, self._fade = snapshot.t, snapshot.jump, snapshot.fade
        self.film.restore(snapshot.film)
        self.steps = snapshot.steps

    def replay(self, start: tuple, steps):
        """The film steps of a run taken again: ``start`` = (t, JournalState) where the
        film began, ``steps`` (t, JournalState) of its committed steps in order. Yields
        (t, FilmSolution) per step: the same solves on the same data as the run, so the
        same films."""
        t0, s0 = start
        self.start(s0, t0)
        for t, state in steps:
            sol = self.film.step(state, float(t) - self.t)
            self.t = float(t)
            self.steps += 1
            yield self.t, sol
