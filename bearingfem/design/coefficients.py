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

from dataclasses import replace

import numpy as np

from ..accuracy import check_estimate
from ..bearing import Bearing, JournalState, check_finite
from ..fe.sensitivity import fe_tilt_coefficients
from ..fields import check_tilt
from ..film import local_to_inertial
from ..models import film_model
from ..validation import check_choice, check_inputs
from .records import EPS_FLOOR, FRAMES, DynamicCoefficients, frame_axes
from .thermal import thd_coefficients
from .tolerance import answer_to_tolerance

__all__ = ["DynamicCoefficients", "coefficients", "FRAMES", "EPS_FLOOR"]


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

    ``thermal`` and ``lubricant`` (model "fem"): the thermal film's K and C with its
    viscosity field frozen (:func:`bearingfem.design.thermal.thd_coefficients`; give
    ``solution=eq.solution`` to reuse the equilibrium's thermal film); with ``rtol`` or
    ``estimate`` the thermal film is solved on each mesh of the search (P1 unless an
    ``element`` is given; ``solution`` is then refused).

    ``rtol`` (mesh models): a requested accuracy of K and C, each relative to its largest
    entry, in [1e-6, 0.1]; the mesh (and element, P2 unless given) is chosen to reach it and
    ``error``, ``K_error``, ``C_error`` report the estimate (:mod:`bearingfem.accuracy`; a
    cavitated film on a graded mesh is also compared with its half mesh shifted); n_theta
    and n_z are then refused. ``estimate=True``: the same estimate for the mesh given (one more linearisation on the
    half mesh). ``eps_error``: the estimated error of the state's eps (an equilibrium's
    ``eps_error``); its effect on K and C (one more linearisation at eps + eps_error) is
    added to the entries' errors and to ``error``.
    """
    check_inputs(bearing, state)
    check_choice("frame", frame, FRAMES)
    estimate = check_estimate(estimate, rtol)
    if options.get("thermal") is not None:     # the thermal film (bearingfem.design.thermal)
        if model != "fem":
            raise ValueError(f"a thermal film needs model 'fem', got {model!r}")
        if rtol is None and not estimate and eps_error is None:
            return thd_coefficients(bearing, state, frame, **options)
        if (rtol is not None or estimate) and options.get("solution") is not None:
            raise ValueError("solution: not taken with rtol or estimate (the thermal film "
                             "is solved on each mesh of the pair)")
        # on to the same search as the isothermal film's (P1 unless given: tolerance.py)
    if eps_error is not None:
        # no upper bound: a coarse mesh's equilibrium estimates 1 or more (the shifted
        # state below stops halfway to the wall)
        eps_error = check_finite("eps_error", eps_error)
        if eps_error < 0.0:
            raise ValueError(f"eps_error (the absolute error of eps, an equilibrium's "
                             f"eps_error) must be >= 0, got {eps_error!r}")
        if rtol is None and not estimate:
            # it is added to an estimate: without one it was dropped unseen
            raise ValueError("eps_error is added to K and C's estimated error: give rtol= "
                             "or estimate=True with it")
    if rtol is not None or estimate:
        if options.get("tilt") is not None:
            raise ValueError(f"tilt: not taken with {'rtol' if rtol is not None else 'estimate'}"
                             " (the tilted film's K and C are found on the mesh given: "
                             "n_theta, n_z)")
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
    local = DynamicCoefficients(K, C, "local", frame_axes("local", g, force), state, force, model,
                                d.method, c, K_shift)
    out = local if frame == "local" else local.in_frame(frame)
    return replace(out, K=K) if limit else out    # K turns into itself, without rounding


def _relative(kc: DynamicCoefficients, dK, dC) -> float:
    """The larger of |dK| / max|K| and |dC| / max|C| (entry-wise). A matrix zero on both
    meshes adds nothing: K of a film without rotation (a squeeze film only damps) is
    exactly zero, and its 0 / 0 made the estimate NaN (``estimate=True``) or never met
    (``rtol``: the search ran to its largest mesh)."""
    terms = [np.inf if not np.any(M) else np.max(np.abs(d)) / np.max(np.abs(M))
             for M, d in ((kc.K, dK), (kc.C, dC)) if np.any(M) or np.any(d)]
    return float(max(terms, default=0.0))


def _order(m, options) -> float | None:
    """K and C's nominal convergence order: 1 for a cavitated film (the partials hold the
    discrete cavitated set, whose edge moves by whole cells: C of L/D 0.2, eps 0.6, P2 at
    48 / 96 / 192 x 6 is 2.0e-2, 6e-5, 1.4e-3 from the converged; a pair at order 2 erred
    low 5x; at L/D 1, eps 0.8, P2 24 x 8 / 48 x 16 / 96 x 32, K is 3.3e-3, 5.0e-3, 3.3e-3
    and C 3.3e-2, 2.2e-2, 1.3e-2 from P2 256 x 64: K too is not safe at order 2), else the
    film force's (None). Even at order 1 a pair can err low: the held set's error behaves
    like noise in where the nodes fall relative to the boundary, so two meshes can agree
    by luck (Lund & Thomsen's rows: ``python -m studies.effectivity --coefficients``,
    docs/accuracy.md)."""
    cavitation = options.get("cavitation", m.defaults.get("cavitation", "reynolds"))
    return None if cavitation == "none" else 1.0


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
                                             bearing.length_ratio,
                                             toward=(state.gamma, state.eps),
                                             order=_order(m, options),
                                             shifted=_order(m, options) is not None)
    K_err = record.factor * np.abs(kc.K - coarse.K)
    C_err = record.factor * np.abs(kc.C - coarse.C)
    if eps_error:
        mesh = {**options, "n_theta": record.mesh[0], "n_z": record.mesh[1]}
        if record.grading is not None:
            mesh["grading"] = record.grading
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
    m = film_model(model)
    if not m.tilts:
        raise ValueError(f"tilt needs a model that solves a tilted journal (model 'fem'), "
                         f"got model={model!r}")
    o = m.options(options)
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
