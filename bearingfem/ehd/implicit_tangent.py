"""The implicit-step EHD film with its trial states' force from the last commit's tangent.

:class:`~bearingfem.ehd.implicit.ImplicitStepEHD` solves the whole nonlinear EHD film at
every trial state the integrator asks for (its predictor, its corrector, the differences
of its Jacobian) and again at the commit: about three full solves a step. Here only the
commit solves the film. Between commits the force is the commit's film moved along its
tangent in the journal's state s = (x, y, x', y', omega) (x + i y = eps e^{i gamma}, the
journal centre over the clearance in the bush's frame) and in time:

    F(s, t) = F_n + A (s - s_n) + b (t - t_n)        (inertial frame, [N])

The tangent is the implicit-function theorem's at the committed film (the film of the
next step at dt = 0, which the committed pressure P_n solves, its deflection w_n):
G(P; s, dt) = 0 the film's (semismooth) residual on the rows not held cavitated,
dP/dq = -G_P^-1 G_q for q each of the five coordinates of s and dt, G_P the film's own
Newton matrix at P_n (the bush's part matrix-free; GMRES preconditioned by the film's
sparse LU, as the film's Newton steps), G_q by forward differences of the residual at
P_n held; then A, b = dF/dq = F_q + F_P dP/dq (F_P: the film's force integrals; at
dt = 0 the summits' pressure does not depend on P). Six GMRES solves and six film
evaluations a tangent.

Why a tangent and not a kept-film solve at trial states: a linear solve per trial state
(the cavitated set and the summits held, one GMRES on the film's Newton matrix) costs
about one of the implicit film's 2-3 chord steps, so it cuts the trial solves at most
threefold; the tangent's force is a 2 x 6 product, so a step costs one full solve (the
commit) and the tangent is taken again only where it no longer predicts the film.

The guard: at each commit the full solve's force F is compared with the tangent's at the
committed state and time. Where |F - F_model| <= :data:`GUARD` |F| the tangent is kept,
moved to the new commit (F_n = F, s_n, t_n the commit's), and the trial states take it
(:attr:`TangentStepEHD.trusted`); where it fails, the trial states fall back to the full
solve (:class:`~bearingfem.ehd.implicit.ImplicitStepEHD`'s) and the tangent is taken
again at this commit, to be tried at the next; so the trial states take a tangent only
after it has predicted a commit within the guard. Records: :attr:`~TangentStepEHD.
refreshes` (tangents taken), :attr:`~TangentStepEHD.fallbacks` (guards failed while
trusted), :attr:`~TangentStepEHD.worst` (the largest miss of a trusted tangent). The
trial force jumps at a commit by the tangent's miss there.

Measured (docs/ehd-states.md, "Trial states from the commit's tangent"): the tangent is
second order (tests/test_ehd_implicit_tangent.py), but over a step of the seed pin's run
it misses the full solve by 7e-5 (median) to 2e-2 of the force, far above the
integrator's 1e-6, and the integrator takes 1.5-5x the steps: this film costs more than
the implicit film it was built to speed up; the implicit film stays the "implicit"
coupling and this one is "implicit-tangent".
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg as la

from ..bearing import JournalState
from ..contract import FilmStep
from ..film import local_to_inertial
from ..scales import force_factor
from .coupling import jacobian_tables
from .implicit import ImplicitSnapshot, ImplicitStepEHD
from .newton import _Factor, _merit
from .tangent import state_from_coordinates
from .transient import state_coordinates

__all__ = ["TangentStepEHD", "ForceTangent", "GUARD", "TANGENT_KRYLOV"]

#: The guard: the tangent is kept while the full solve's force at each commit is within
#: this fraction of its size of the tangent's prediction there
GUARD = 1e-3
#: GMRES's relative residual for the tangent's solves (the Newton steps take 1e-3)
TANGENT_KRYLOV = 1e-8
#: Forward-difference steps of the residual in s = (x, y, x', y', omega), as fractions of
#: (1, 1, v, v, v), v = max(|omega|, |x'|, |y'|, 1), and in dt as a fraction of tau
#: (the film converged to 1e-10: truncation and round-off both near 1e-6 relative)
STEP = 1e-6


@dataclass(frozen=True)
class ForceTangent:
    """The film's force [N] (inertial (F_x, F_y)) at the commit (``origin`` s_n, time
    ``t``) and its derivatives: ``slope`` (2, 5) in s [N per unit of s], ``rate`` (2,) in
    t [N/s]."""

    origin: np.ndarray
    t: float
    force: np.ndarray
    slope: np.ndarray
    rate: np.ndarray

    def inertial(self, state: JournalState, t: float) -> np.ndarray:
        """(F_x, F_y) [N] at ``state`` and time ``t`` along the tangent."""
        return (self.force + self.slope @ (state_coordinates(state) - self.origin)
                + self.rate * (float(t) - self.t))

    def local(self, state: JournalState, t: float) -> tuple:
        """(F_r, F_t) [N] in ``state``'s frame."""
        fx, fy = self.inertial(state, t)
        c, s = np.cos(state.gamma), np.sin(state.gamma)
        return float(fx * c + fy * s), float(-fx * s + fy * c)


@dataclass(frozen=True)
class TangentSnapshot:
    """What a :class:`TangentStepEHD` keeps: the implicit film's record and the tangent
    (None: the trial states' full solve)."""

    film: ImplicitSnapshot
    force_tangent: ForceTangent | None
    trusted: bool


def inertial_force(local: tuple, gamma: float) -> np.ndarray:
    return np.array(local_to_inertial(local[0], local[1], gamma), float)


class TangentStepEHD(ImplicitStepEHD):
    """The implicit-step EHD film (:class:`~bearingfem.ehd.implicit.ImplicitStepEHD`, the
    same parameters and commits) whose trial states' force is the last commit's tangent,
    guarded at each commit (module docstring)."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.force_tangent = None
        self.refreshes = 0               # tangents taken (a run's record)
        self.worst = 0.0                 # the largest |F - F_model| / |F| at a commit
        self.trusted = False             # whether trial states take the tangent's force
        self.fallbacks = 0               # commits whose guard failed (a run's record)

    def start(self, state: JournalState, t: float) -> None:
        super().start(state, t)
        self.force_tangent, self.trusted = None, False

    def force(self, state: JournalState, t: float) -> tuple:
        """(F_r, F_t) [N] at a trial ``state`` and time ``t``: the tangent's (the full
        solve before the first commit, or where the tangent could not be taken); keeps
        nothing."""
        if not self.trusted:
            return super().force(state, t)
        if float(t) < self.t:
            raise ValueError(f"t must be >= the last committed step's time {self.t!r} [s] "
                             f"(the implicit-step film steps forward), got {t!r}")
        return self.force_tangent.local(state, t)

    def commit(self, state: JournalState, t: float) -> FilmStep | None:
        """The implicit film's commit (the full solve), its force against the tangent's
        there (the guard), and the tangent kept (moved to this commit) or taken again."""
        kept = self.force_tangent
        step = super().commit(state, t)
        if step is None:
            return None
        force = inertial_force(step.force_local, state.gamma)
        if kept is not None:
            miss = float(np.linalg.norm(force - kept.inertial(state, t))
                         / max(np.linalg.norm(force), 1e-300))
            if self.trusted:
                self.worst = max(self.worst, miss)
            if miss <= GUARD:
                self.force_tangent = replace(kept, origin=state_coordinates(state),
                                             t=float(t), force=force)
                self.trusted = True
                return step
            self.fallbacks += self.trusted
        self.force_tangent = self.take_tangent(state, force)
        self.trusted = False
        return step

    def take_tangent(self, state: JournalState, force: np.ndarray) -> ForceTangent | None:
        """The tangent of the committed film (pressure ``self._P``, deflection w_n, time
        ``self.t``) at ``state``, whose force is ``force`` (inertial [N]); None where the
        film at a moved state or a GMRES solve fails."""
        P, t = self._P, self.t
        film = self.step_film(state, t)
        free = film.op.mesh.free
        phi, _, held, ev = _merit(film, P, 1.0, free, "reynolds")
        if phi is None or state.eps < 1e-6:
            return None
        J, U, V = film.jacobian(P, 1.0, ev)
        try:
            factor = _Factor(J, replace(U, tolerance=TANGENT_KRYLOV), V,
                             jacobian_tables(film.op), free, held)
        except (RuntimeError, la.LinAlgError):
            return None
        base = ev.residual
        s0 = state_coordinates(state)
        steps = np.full(6, STEP)
        steps[2:5] *= max(abs(state.omega), abs(s0[2]), abs(s0[3]), 1.0)
        steps[5] *= self.tau
        slope = np.empty((2, 6))
        for k in range(6):
            if k < 5:
                s1 = s0.copy()
                s1[k] += steps[k]
                moved = state_from_coordinates(s1)
                other = self.step_film(moved, t)
            else:
                moved = state
                other = self.step_film(state, t + steps[5])
            out = other.at(P)
            if out is None:
                return None
            dG = (out.ev.residual - base) / steps[k]
            dF = (inertial_force(self._force(other, P), moved.gamma) - force) / steps[k]
            try:
                dP = factor.lu.solve(-dG[factor.I])
            except la.LinAlgError:
                return None
            full = np.zeros_like(P)
            full[factor.I] = dP
            slope[:, k] = dF + inertial_force(self._force_of(film, full), state.gamma)
        self.refreshes += 1
        return ForceTangent(s0, t, force, slope[:, :5], slope[:, 5])

    def _force_of(self, film, P: np.ndarray) -> tuple:
        """(F_r, F_t) [N] of the film's pressure ``P`` alone (no summits): linear in P."""
        ic, is_ = film.op.force_integrals(P)
        k = force_factor(self.bearing, False)
        return k * float(ic), k * float(is_)

    def snapshot(self) -> TangentSnapshot:
        return TangentSnapshot(super().snapshot(), self.force_tangent, self.trusted)

    def restore(self, snapshot: TangentSnapshot) -> None:
        super().restore(snapshot.film)
        self.force_tangent = snapshot.force_tangent
        self.trusted = snapshot.trusted
