"""The designer's records: an equilibrium and the dynamic coefficients at a state, with
the small functions they are built from (the load vector, the least film, a frame's axes).
Kept apart from the solvers that make them so that every solver of :mod:`bearingfem.design`
(isothermal, thermal, to a tolerance) returns the same records."""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..bearing import Bearing, JournalState, check_finite, check_turn_angle
from ..solution import FilmSolution
from ..validation import check_choice

__all__ = ["EPS_MAX", "Equilibrium", "load_vector", "least_film", "FRAMES", "EPS_FLOOR",
           "DynamicCoefficients", "frame_axes"]

#: Default largest eccentricity ratio searched: past it the film is thinner than 1 % of c,
#: below the roughness of real bearings; a load that needs more is refused.
EPS_MAX = 0.99


@dataclass(frozen=True)
class Equilibrium:
    """A journal at rest under ``load``: where it sits and what the film does there.

    Attributes
    ----------
    eps : eccentricity ratio; attitude : angle from load line to line of centres [rad]
    state : the :class:`JournalState` (eps_dot = gamma_dot = 0)
    load : (W_x, W_y) [N] the external load carried (inertial frame); film_force the film's
    sommerfeld : S = (R/c)^2 mu N / P
    film_min : c (1 - eps) [m]; film_min_angle : its inertial angle [rad]
    friction_force : on the journal, opposing rotation [N] (full Couette shear in cavitated
        zones); friction_coefficient : friction_force / W; power_loss : F_f R |omega| [W]
    pressure_max [Pa], side_leakage [m^3/s] (net, out of both ends), flow_in [m^3/s]:
        the film solution's, for the mesh models; None for the closed forms and the table.
        ``flow_in`` is what grooves or a supply line feed (FilmSolution.flow_in): in a
        mass-conserving film (the full film with grooves, JFO) it equals the side leakage
        at equilibrium (both zero for a JFO film fed at its ends alone); a
        Reynolds-condition film defines none (None), nor does a full film without grooves:
        the former makes up its own oil in the cavity, so the side leakage alone is what a
        supply must replace
    solution : the :class:`FilmSolution` at equilibrium (mesh models) or None
    model, iterations : the film model and the number of film evaluations (a force, or a
        force with its partials: one film solve, grooved FE films too, whose d/dgamma is
        exact on the bearing-fixed mesh of :mod:`bearingfem.fe.grooved`)
    asperity_load_share : with a ``roughness`` option (mixed lubrication), the share of the
        load the asperity contact carries, -(F_a . W)/|W|^2 (the film carries the rest;
        1 at omega = 0, the dry limit); 0 without. ``film_force`` is then the model's force,
        film plus asperities, and the friction adds the summits' Coulomb friction
    eps_error : with ``rtol`` or ``estimate=True``, the estimated absolute discretisation
        error of eps (the h/2h estimate of the journal position's error, |dq| with q = e/c,
        :mod:`bearingfem.accuracy`); None otherwise. An estimate, not a bound
    accuracy : the :class:`~bearingfem.accuracy.AccuracyRecord` of the mesh chosen
    """

    eps: float
    attitude: float
    state: JournalState
    load: tuple
    film_force: tuple
    sommerfeld: float
    film_min: float
    film_min_angle: float
    friction_force: float
    friction_coefficient: float
    power_loss: float
    pressure_max: float | None
    side_leakage: float | None
    flow_in: float | None
    solution: FilmSolution | None
    model: str
    iterations: int
    asperity_load_share: float = 0.0
    eps_error: float | None = None
    accuracy: object = None


def load_vector(load, direction):
    if direction is None:
        try:
            if isinstance(load, (str, bytes)):    # "10" would unpack as (1, 0)
                raise TypeError
            wx, wy = (check_finite("load", v) for v in load)
        except (TypeError, ValueError) as err:
            if isinstance(err, ValueError) and str(err).startswith("load"):
                raise      # a component not a finite number: named already
            # not iterable, or not two components (a 3-vector: "too many values to unpack")
            raise ValueError(f"load must be a vector (W_x, W_y) [N], or a magnitude with "
                             f"direction=angle [rad], got {load!r}") from None
    else:
        W = check_finite("load", load)
        # radians, as every angle of the API (the command line's --direction is degrees)
        a = check_turn_angle("direction", direction)
        wx, wy = W * math.cos(a), W * math.sin(a)
    if wx == 0.0 and wy == 0.0:
        raise ValueError("load must be non-zero: an unloaded journal sits at the centre")
    return wx, wy

def least_film(bearing: Bearing, state: JournalState, tilt=(0.0, 0.0)):
    """(h_min [m], its inertial angle [rad]) of the journal at ``state`` tilted by ``tilt``.

    The centre at axial position z sits at e(z) = e + z (tilt_y, -tilt_x), its least gap
    c - |e(z)| in the direction of e(z); |e(z)| is convex in z, so the least film is at
    an end, z = +-L/2 (c (1 - eps) at gamma for an aligned journal).
    """
    c = bearing.clearance
    e = c * state.eps * np.array([math.cos(state.gamma), math.sin(state.gamma)])
    d = 0.5 * bearing.length * np.array([tilt[1], -tilt[0]])
    end = max((e + d, e - d), key=lambda v: math.hypot(*v))
    angle = math.atan2(end[1], end[0]) if any(tilt) else state.gamma
    return c - math.hypot(*end), float(np.mod(angle, 2.0 * math.pi))

FRAMES = ("inertial", "local", "load")
#: Smallest eccentricity ratio linearised as such (the polar frame is singular at 0).
EPS_FLOOR = 1e-6


@dataclass(frozen=True)
class DynamicCoefficients:
    """Stiffness and damping of the film at ``state``.

    Attributes
    ----------
    K : 2x2 [N/m], K_ij = -dF_i/dx_j;  C : 2x2 [N s/m], C_ij = -dF_i/dv_j
    frame : "inertial" (x, y), "local" (r along the eccentricity, t), or "load" (axis 1
        along the load the film carries, i.e. opposite the film force; axis 2 turned +90 deg)
    axes : the two axes of ``frame`` as unit vectors in the inertial frame (rows)
    state : the journal state; force : film force (F_x, F_y) there [N], inertial
    model, method : the film model and how its partials were found
    clearance : radial clearance c [m] of the bearing
    K_groove_shift : 2x2 [N/m], the part of K from grooves fixed in the bearing that the
        film moves against as the journal turns (zero without grooves).
        ``K - K_groove_shift`` is the stiffness of grooves turning with the line of centres.
        Published tables differ in which form they give: Someya's Journal-Bearing Databook
        (1989) matches the turning form (within 3 % of the largest entry; ``K`` misses by
        10-40 %, tests/test_someya.py), Lund & Thomsen (1978) match ``K``, the grooves fixed
        in the bearing (within 1 %; the turning form misses by 23-53 % of the largest entry,
        Kyx by up to 179 %, tests/test_lund_thomsen.py). Check a table's form before
        comparing.
    error : with ``rtol`` or ``estimate=True``, the estimated discretisation error of K and
        of C, each relative to its largest entry, the larger of the two (h/2h estimate,
        :mod:`bearingfem.accuracy`); None otherwise. An estimate, not a bound
    K_error, C_error : the estimated error of each entry [N/m], [N s/m] (magnitudes; with
        ``eps_error`` given, the effect of the state's eps error is added)
    accuracy : the :class:`~bearingfem.accuracy.AccuracyRecord` of the mesh chosen
    """

    K: np.ndarray
    C: np.ndarray
    frame: str
    axes: np.ndarray
    state: JournalState
    force: tuple
    model: str
    method: str
    clearance: float
    K_groove_shift: np.ndarray
    error: float | None = None
    K_error: np.ndarray | None = None
    C_error: np.ndarray | None = None
    accuracy: object = None

    @property
    def load(self) -> float:
        """|F| [N]: the load the film carries at this state."""
        return float(math.hypot(*self.force))

    def dimensionless(self):
        """(K c / W, C c omega / W) with W = |F|, the usual non-dimensional coefficients."""
        c = self.clearance
        W = self.load
        if W == 0.0:
            raise ValueError("the film carries no load at this state: no dimensionless "
                             "coefficients")
        return self.K * c / W, self.C * c * abs(self.state.omega) / W

    def in_frame(self, frame: str) -> "DynamicCoefficients":
        """The same coefficients in another frame."""
        check_choice("frame", frame, FRAMES)
        Q = frame_axes(frame, self.state.gamma, self.force)
        T = Q @ self.axes.T          # new components from old ones
        A = np.abs(T)                # entry errors turn as magnitudes: a bound, |T| E |T|^T
        return replace(self, K=T @ self.K @ T.T, C=T @ self.C @ T.T, frame=frame, axes=Q,
                       K_groove_shift=T @ self.K_groove_shift @ T.T,
                       K_error=None if self.K_error is None else A @ self.K_error @ A.T,
                       C_error=None if self.C_error is None else A @ self.C_error @ A.T)


def frame_axes(frame: str, gamma: float, force) -> np.ndarray:
    if frame == "inertial":
        return np.eye(2)
    if frame == "local":
        angle = gamma
    else:
        if force[0] == 0.0 and force[1] == 0.0:
            raise ValueError("frame='load' needs a film that carries a load (|F| > 0)")
        angle = math.atan2(-force[1], -force[0])
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, s], [-s, c]])
