"""Linearised film: stiffness K and damping C at a journal state, from the force partials.

The film force depends on the journal's position x and velocity v through eps = |x|/c,
gamma, eps_dot = (x.v)/(c|x|) and w = omega - 2 gamma_dot, gamma_dot = (x cross v)/|x|^2,
and turns with gamma. Differentiating F = R(gamma) F_loc(eps, eps_dot, w) in the local
frame (r = along the eccentricity, t = r turned +90 deg), with A, B, W the partials of
F_loc in eps, eps_dot and w:

    -c K[:, r] = A + 2 gamma_dot W / eps
    -c K[:, t] = (J F + G) / eps + gamma_dot B + 2 eps_dot W / eps^2,   J F = (-F_t, F_r)

with G = dF_loc/dgamma, zero unless grooves stay fixed while the film turns.
    -c C[:, r] = B
    -c C[:, t] = -2 W / eps

K_ij = -dF_i/dx_j, C_ij = -dF_i/dv_j. Every term stays finite as eps -> 0 (F, W ~ eps);
eps below ``EPS_FLOOR`` takes the limit eps -> 0: K, C are found at EPS_FLOOR along the same
gamma and the terms that vanish with eps are dropped. The centred journal is attitude-free:
F_r = O(eps^2) (full film: F_r = 0; Gumbel and Reynolds' condition: the leading-order film
and its cavity are symmetric about theta = pi/2), so K_rr, K_tt, C_rt, C_tr = O(eps) are 0
there and K = [[0, k], [-k, 0]], the same in every frame; F is scaled to eps (0 at eps = 0).
Grooves fixed in the bearing, or a moving journal, break the symmetry: then the film is
linearised at EPS_FLOOR as it is.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..bearing import Bearing, JournalState
from ..fe.sensitivity import fe_tilt_coefficients
from ..fields import check_tilt
from ..film import local_to_inertial
from ..models import film_model
from ..validation import check_choice, check_inputs
from .tolerance import answer_to_tolerance

__all__ = ["DynamicCoefficients", "coefficients", "FRAMES", "EPS_FLOOR"]

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
        Q = _axes(frame, self.state.gamma, self.force)
        T = Q @ self.axes.T          # new components from old ones
        A = np.abs(T)                # entry errors turn as magnitudes: a bound, |T| E |T|^T
        return replace(self, K=T @ self.K @ T.T, C=T @ self.C @ T.T, frame=frame, axes=Q,
                       K_groove_shift=T @ self.K_groove_shift @ T.T,
                       K_error=None if self.K_error is None else A @ self.K_error @ A.T,
                       C_error=None if self.C_error is None else A @ self.C_error @ A.T)


def _axes(frame: str, gamma: float, force) -> np.ndarray:
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


def coefficients(bearing: Bearing, state: JournalState, model: str = "fem",
                 frame: str = "inertial", *, rtol: float | None = None,
                 estimate: bool = False, eps_error: float | None = None,
                 **options) -> DynamicCoefficients:
    """Stiffness K [N/m] and damping C [N s/m] of the film at ``state``.

    ``model`` is a name of :data:`bearingfem.models.FILM_MODELS` and ``options`` its
    options (mesh, element, cavitation...). The partials are exact for the closed forms
    ("short", "long": complex step) and the FE film ("fem": discrete sensitivity with the
    cavitated set fixed, on the solve's own factors); other models use central
    differences.

    ``tilt=(tilt_x, tilt_y)`` [rad] (model "fem", steady state): the translational 2x2
    block of the misaligned film's 4x4 coefficients
    (:func:`bearingfem.fe.sensitivity.fe_tilt_coefficients`, which also gives the moment
    rows and tilt columns).

    ``rtol`` (mesh models): a requested accuracy of K and C, each relative to its largest
    entry, in [1e-6, 0.1]; the mesh (and element, P2 unless given) is chosen to reach it and
    ``error``, ``K_error``, ``C_error`` report the estimate (:mod:`bearingfem.accuracy`).
    ``estimate=True``: the same estimate for the mesh given (one more linearisation on the
    half mesh). ``eps_error``: the estimated error of the state's eps (an equilibrium's
    ``eps_error``); its effect on K and C (one more linearisation at eps + eps_error) is
    added to the entries' errors and to ``error``.
    """
    check_inputs(bearing, state)
    check_choice("frame", frame, FRAMES)
    if rtol is not None or estimate:
        return _with_error(bearing, state, model, frame, rtol, eps_error, options)
    tilt = check_tilt("tilt", options.pop("tilt", (0.0, 0.0)))
    if any(tilt):
        return _tilted(bearing, state, model, frame, tilt, options)
    m = film_model(model)
    centred = state.eps < EPS_FLOOR
    at = replace(state, eps=EPS_FLOOR) if centred else state
    d = m.force_derivatives(bearing, at, **options)
    e, ed, gd = at.eps, at.eps_dot, at.gamma_dot
    A, B, W, F, G = (np.asarray(v, float) for v in (d.d_eps, d.d_eps_dot, d.d_wedge, d.force,
                                                     d.d_gamma))
    # turning the eccentricity turns the film (J F) and, with grooves fixed in space,
    # moves them against it (G = dF_loc/dgamma)
    JF = np.array([-F[1], F[0]]) + G
    c = bearing.clearance
    K = -np.column_stack([A + 2.0 * gd * W / e, JF / e + gd * B + 2.0 * ed * W / e ** 2]) / c
    C = -np.column_stack([B, -2.0 * W / e]) / c
    K_shift = np.zeros((2, 2))
    K_shift[:, 1] = -G / (e * c)
    limit = centred and not np.any(G) and ed == 0.0 and gd == 0.0
    if limit:   # the steady eps -> 0 limit (module docstring)
        k = 0.5 * (K[0, 1] - K[1, 0])
        K, C = np.array([[0.0, k], [-k, 0.0]]), np.diag(np.diag(C))
        F = F * (state.eps / EPS_FLOOR)
    g = state.gamma
    force = tuple(float(f) for f in local_to_inertial(F[0], F[1], g))
    local = DynamicCoefficients(K, C, "local", _axes("local", g, force), state, force, model,
                                d.method, c, K_shift)
    out = local if frame == "local" else local.in_frame(frame)
    return replace(out, K=K) if limit else out    # K turns into itself, without rounding


def _relative(kc: DynamicCoefficients, dK, dC) -> float:
    """The larger of |dK| / max|K| and |dC| / max|C| (entry-wise)."""
    return float(max(np.max(np.abs(dK)) / np.max(np.abs(kc.K)),
                     np.max(np.abs(dC)) / np.max(np.abs(kc.C))))


def _with_error(bearing, state, model, frame, rtol, eps_error, options):
    """The coefficients on the mesh that reaches ``rtol`` (or on the mesh given) with the
    estimated error of each entry; the state's ``eps_error`` added as K, C's change over
    it (one more linearisation on the chosen mesh)."""
    m = film_model(model)

    def evaluate(opts):
        return coefficients(bearing, state, model, frame, **opts)

    def difference(fine, coarse):
        return _relative(fine, fine.K - coarse.K, fine.C - coarse.C)

    kc, coarse, record = answer_to_tolerance(m, "coefficients",
                                             round(bearing.length_ratio, 12), options,
                                             evaluate, difference, rtol,
                                             bearing.length_ratio)
    K_err = record.factor * np.abs(kc.K - coarse.K)
    C_err = record.factor * np.abs(kc.C - coarse.C)
    if eps_error:
        mesh = {**options, "n_theta": record.mesh[0], "n_z": record.mesh[1]}
        if "element" in m.defaults:
            mesh["element"] = record.element
        shifted = coefficients(bearing, replace(state, eps=min(state.eps + eps_error,
                                                              0.5 * (1.0 + state.eps))),
                               model, frame, **mesh)
        K_err = K_err + np.abs(shifted.K - kc.K)
        C_err = C_err + np.abs(shifted.C - kc.C)
    return replace(kc, error=max(record.error, _relative(kc, K_err, C_err)), K_error=K_err,
                   C_error=C_err, accuracy=record)


def _tilted(bearing, state, model, frame, tilt, options) -> DynamicCoefficients:
    """The (x, y) block of the misaligned FE film's exact 4x4 coefficients."""
    if model != "fem":
        raise ValueError(f"tilt needs model 'fem' (a misaligned film), got model={model!r}")
    o = film_model(model).options(options)
    if o.get("grooves"):
        raise ValueError("coefficients with tilt: grooves are not supported")
    if o.get("roughness") is not None:
        raise ValueError("coefficients with tilt: roughness is not supported")
    kc = fe_tilt_coefficients(bearing, state, tilt, o["n_theta"], o["n_z"], o["element"],
                              o["cavitation"])
    force = tuple(float(f) for f in kc.force[:2])
    inertial = DynamicCoefficients(kc.K[:2, :2], kc.C[:2, :2], "inertial", np.eye(2), state,
                                   force, model, kc.method, bearing.clearance,
                                   np.zeros((2, 2)))
    return inertial if frame == "inertial" else inertial.in_frame(frame)
