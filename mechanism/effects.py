"""Joint effects: each turns the joint's kinematic state into a force on the pin.

One interface, ``effect.force(k) -> (F_x, F_y)`` [N] in the inertial frame, for a
:class:`JointKinematics` ``k``. The simulator sums the effects a scene lists and nothing
else, so an effect the scene does not call for costs nothing.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from bearingfem import Bearing, ElasticJournalState, JournalState
from bearingfem.contract import FilmStep
from bearingfem.film import local_to_inertial

from bearingfem.models import film_model

from .result import FILM_COLUMNS, film_column, film_row

__all__ = ["JointKinematics", "Effect", "FilmEffect", "HertzContact", "CoulombFriction", "LinearSpring",
           "hertz_stiffness"]


@dataclass(frozen=True)
class JointKinematics:
    """Pin relative to the bearing (slider): eccentricity vector, its rate, the
    journal's angular speed relative to the bearing (the rod's, counter-clockwise) and the
    time [s] (which a film with memory needs)."""

    e_x: float
    e_y: float
    de_x: float
    de_y: float
    omega: float
    t: float = 0.0

    @property
    def e(self) -> float:
        return math.hypot(self.e_x, self.e_y)


class Effect:
    """What every joint effect declares, with its default: ``force(k)`` (F_x, F_y) [N];
    ``memory`` (a film with a state of its own, recorded at its committed steps),
    ``solves`` (film solves so far), ``state_size`` (states integrated with the joint)
    and ``wall`` (the eps where the journal meets the bush)."""

    memory = False
    solves = 0
    state_size = 0
    wall = 1.0


@dataclass
class FilmEffect(Effect):
    """Hydrodynamic film force from a bearingfem model, through the film-model contract
    (:mod:`bearingfem.contract`): the model makes the film for this run
    (:meth:`~bearingfem.models.FilmModel.along_run`), which gives the force at each trial
    state and advances what it keeps at :meth:`commit` (each accepted step).

    Beyond ``eps_max`` the film is evaluated at eps_max along the same direction: the force
    stays finite and continuous when an integrator's trial step crosses eps = 1 (the
    contact effect, or the simulator's stop at eps = 1, takes over there). A model that
    carries the journal beyond the clearance circle (its ``beyond_clearance``, contract
    rule 15: an elastic bush) has its ``wall`` there instead: its states are
    :class:`~bearingfem.bearing.ElasticJournalState` capped at ``eps_max`` times that wall.

    A model with memory keeps what it committed in ``history``: one row per film step,
    columns :data:`mechanism.result.FILM_COLUMNS` (what the step gave, then the journal
    state it was taken at), and the film's first state in ``start`` (t and the state's
    fields): what the model's ``replay`` needs to take the same film steps again. Of the
    steps that hand their whole film it keeps one in ``peak``: the step with the largest
    force (film and summits) among those committed while the run records, or, until the
    run records, among all (what a run stopped before its recorded turns keeps): the film
    at the peak load with no replay, one solution held, not one per step.
    """

    bearing: Bearing
    model: str
    options: dict = field(default_factory=dict)
    eps_max: float = 0.999
    solves: int = 0
    #: keep every n-th state the film is asked at (0: none), and the one nearest the wall:
    #: a run with an accuracy asked estimates its film error there afterwards
    sample_every: int = 0

    def __post_init__(self):
        self.film_model = film_model(self.model, "lubrication.model")
        self.run = self.film_model.along_run(self.bearing, self.options)
        self.memory = self.film_model.memory
        self.history: list = []
        self.z_history: list = []       # the film's own states z at each history row
        self.start: tuple | None = None
        # a film whose memory is integrated with the joint (contract rule 16): its states
        # z are set by the integrator before each force, their rates read after it
        self.state_size = int(self.run.state_size)
        self.z = np.zeros(self.state_size)
        self.z_rate = np.zeros(self.state_size)
        self.samples: list = []
        self.deepest: JournalState | None = None
        self.peak: FilmStep | None = None
        self._peak_recorded = False      # whether ``peak`` is of the recorded steps

    @property
    def wall(self) -> float:
        """The eps where the film's journal meets the bush: 1, or the model's
        ``beyond_clearance`` (an elastic film)."""
        return max(1.0, self.film_model.beyond_clearance)

    def _state(self, k: JointKinematics) -> JournalState:
        wall = self.wall
        cls = JournalState if wall == 1.0 else ElasticJournalState
        return cls.from_eccentricity(k.e_x, k.e_y, k.de_x, k.de_y, self.bearing.clearance,
                                     k.omega, self.eps_max * wall)

    def force(self, k: JointKinematics):
        s = self._state(k)
        self.solves += 1
        if self.sample_every:
            if self.solves % self.sample_every == 0:
                self.samples.append(s)
            if self.deepest is None or s.eps > self.deepest.eps:
                self.deepest = s
        if self.start is None:              # the film begins at its first state
            self.start = (k.t,) + dataclasses.astuple(s)
            self.run.start(s, k.t)
        if self.state_size:
            (f_r, f_t), self.z_rate = self.run.rates(s, self.z, k.t)
            self._gamma = s.gamma
        else:
            f_r, f_t = self.run.force(s, k.t)
        return local_to_inertial(f_r, f_t, s.gamma)

    @property
    def has_tangent(self) -> bool:
        """The film's own states come with their derivatives (contract rule 17)."""
        return bool(self.state_size) and self.run.has_tangent

    def tangent(self):
        """(d(F_x, F_y)/dz (2, n) [N/m], d(dz/dt)/dz (n, n) [1/s]) at the last force's
        kinematics and z, the journal's state held (contract rule 17)."""
        t = self.run.tangent()
        fx, fy = local_to_inertial(t.force_local[0], t.force_local[1], self._gamma)
        return np.vstack([fx, fy]), t.rates

    def commit(self, k: JointKinematics, recording: bool = True) -> bool:
        """Advance the film to the accepted state ``k`` (at time k.t); a film step that
        fails raises and leaves the film and its history as they were. ``recording``:
        whether the run records at ``k`` (its peak film is then kept from the recorded
        steps alone). Returns whether a film step was taken (the force at ``k`` may then
        have changed)."""
        step = (self.run.commit(self._state(k), k.t, self.z) if self.state_size
                else self.run.commit(self._state(k), k.t))
        if step is not None:
            self.history.append(film_row(step))
            if self.state_size:
                self.z_history.append(np.array(self.z, float))
        if recording and not self._peak_recorded:
            # the run-up's forgotten at the first recorded commit, a film step or not: a
            # run stopped before its first recorded film step keeps none, not a film from
            # before its saved samples
            self.peak, self._peak_recorded = None, True
        if step is not None:
            self._keep_peak(step)
        return step is not None

    def _keep_peak(self, step: FilmStep) -> None:
        """``step`` as ``peak`` where it carries more than the one kept."""
        if step.solution is None:
            return
        if self.peak is None or (math.hypot(*step.force_local)
                                 > math.hypot(*self.peak.force_local)):
            self.peak = step

    @property
    def steps(self) -> int:
        """Film steps committed (a film with memory; 0 otherwise)."""
        return self.run.steps

    def recorded_force(self, t):
        """(F_x, F_y) [N] at times ``t`` from the committed steps (linear in between)."""
        h = np.array(self.history) if self.history else np.zeros((1, len(FILM_COLUMNS)))
        return (np.interp(t, film_column(h, "t"), film_column(h, "force_x")),
                np.interp(t, film_column(h, "t"), film_column(h, "force_y")))


def hertz_stiffness(radius, clearance, young_modulus, poisson):
    """Generalised stiffness [N/m^1.5] of a journal (R) in a bush (R + c), both steel-like:
    K = 4 / (3 (s_i + s_j)) sqrt(R_i R_j / (R_i - R_j)), s = (1 - nu^2) / E."""
    s = (1.0 - poisson ** 2) / young_modulus
    Ri, Rj = radius + clearance, radius
    return 4.0 / (3.0 * 2.0 * s) * math.sqrt(Ri * Rj / (Ri - Rj))


@dataclass
class HertzContact(Effect):
    """Hertz contact with Lankarani-Nikravesh hysteresis damping when e > c.

    F_n = K d^n (1 + 3 (1 - c_e^2) / 4 * d_dot / v_impact), d = e - c, acting along -r_hat
    on the pin. ``v_impact`` is the approach speed at contact onset, set by the simulator's
    contact event; ``min_impact_speed`` guards a start in contact.
    """

    clearance: float
    stiffness: float
    restitution: float = 0.9
    exponent: float = 1.5
    min_impact_speed: float = 1e-4
    v_impact: float = 1e-4
    evaluations: int = 0

    def normal_force(self, k: JointKinematics) -> float:
        e = k.e
        d = e - self.clearance
        if d <= 0.0:
            return 0.0
        self.evaluations += 1
        d_dot = (k.e_x * k.de_x + k.e_y * k.de_y) / e
        v0 = max(self.v_impact, self.min_impact_speed)
        damp = 1.0 + 0.75 * (1.0 - self.restitution ** 2) * d_dot / v0
        return max(self.stiffness * d ** self.exponent * damp, 0.0)

    def force(self, k: JointKinematics):
        fn = self.normal_force(k)
        if fn == 0.0:
            return 0.0, 0.0
        e = k.e
        return -fn * k.e_x / e, -fn * k.e_y / e


@dataclass
class CoulombFriction(Effect):
    """Coulomb friction at the contact, regularised: F_t = -mu_f F_n tanh(v_t / v_reg).

    v_t = e gamma_dot + omega R is the sliding speed of the pin surface over the bush at the
    contact point, along t_hat.
    """

    contact: HertzContact
    coefficient: float
    radius: float
    v_reg: float = 1e-4

    def force(self, k: JointKinematics):
        fn = self.contact.normal_force(k)
        if fn == 0.0:
            return 0.0, 0.0
        e = k.e
        tx, ty = -k.e_y / e, k.e_x / e
        v_t = k.de_x * tx + k.de_y * ty + k.omega * self.radius
        ft = -self.coefficient * fn * math.tanh(v_t / self.v_reg)
        return ft * tx, ft * ty


@dataclass
class LinearSpring(Effect):
    """A linear spring-damper joint, F = -k e - d e_dot: as k grows the clearance joint
    tends to the ideal joint (a verification device, not a bearing model)."""

    stiffness: float
    damping: float = 0.0

    def force(self, k: JointKinematics):
        return (-self.stiffness * k.e_x - self.damping * k.de_x,
                -self.stiffness * k.e_y - self.damping * k.de_y)
