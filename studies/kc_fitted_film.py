"""The film on the mesh fitted to its cavitation boundary (studies/kc_fitted.py, steps 4-5):
the linear film with the held set at zero, its force, K and C (:func:`held_film`), and the
fit iterated from the LCP's film (:func:`films`).
"""
from __future__ import annotations

import time

import numpy as np
from scipy.sparse.linalg import splu

from bearingfem.design.records import DynamicCoefficients, frame_axes
from bearingfem.fe.grooved import (_held, _system, groove_operator_for, grooved_pressure,
                                   partials_load, rotated)
from bearingfem.film import local_to_inertial
from bearingfem.scales import force_factor

from .kc_fitted_band import BandFit
from .kc_fitted_mesh import Fit, _filled
from .lund_thomsen import GROOVES

#: fit (relocate the boundary, rebuild, resolve) this many times after the first solve
FIT_ITERATIONS = 4


def held_film(gop, bearing, state, active):
    """(force (F_r, F_t) [N], K, C inertial, pressure) of the linear film with ``active``
    held at zero and the grooves at their pressure: the held set's tangent."""
    op = gop.op
    m = op.mesh
    G = _held(bearing, gop, GROOVES)
    values, load = _system(gop, state)
    A = op.matrix(values).tocsr()
    inner = m.free[~active[m.free]]
    lu = splu(A[inner][:, inner].tocsc())
    P = G.copy()
    P[inner] = lu.solve((load - A @ G)[inner])
    g = state.gamma
    rhs = partials_load(gop, state, P)
    dP = np.zeros((m.ndofs, 4))
    dP[inner] = lu.solve(rhs[inner])
    k = force_factor(bearing, True)
    I = op.force_integrals(np.concatenate([P[None], dP.T]))
    F = k * rotated(I, g)
    d_gamma = F[:, 4] + np.array([F[1, 0], -F[0, 0]])
    return _coefficients(bearing, state, F[:, 0], F[:, 1], F[:, 2], F[:, 3], d_gamma), P


def _coefficients(bearing, state, F, A, B, W, G):
    """(force inertial, K, C inertial) from the local partials (steady state, as
    :func:`bearingfem.design.coefficients`)."""
    e, c = state.eps, bearing.clearance
    JF = np.array([-F[1], F[0]]) + G
    K = -np.column_stack([A, JF / e]) / c
    C = -np.column_stack([B, -2.0 * W / e]) / c
    force = tuple(float(f) for f in local_to_inertial(F[0], F[1], state.gamma))
    kc = DynamicCoefficients(K, C, "local", frame_axes("local", state.gamma, force), state,
                             force, "fem", "held", c, np.zeros((2, 2))).in_frame("inertial")
    return np.array(force), np.asarray(kc.K), np.asarray(kc.C)


def films(bearing, state, n_theta, n_z, element, grading=None, iterations=FIT_ITERATIONS,
          band=False):
    """({"plain": (F, K, C), "fitted": (F, K, C)}, the fit's last step [rad], the number of
    fitted boundaries, (CPU of the LCP and the plain tangent, of all) [s]): the film on the
    mesh (the LCP's held set) and on the mesh fitted to its boundary (``iterations``
    operators; with none, or no boundary found, the plain film)."""
    gop = groove_operator_for(bearing, n_theta, n_z, element, GROOVES, grading)
    gop.last.clear()
    t0 = time.process_time()
    res = grooved_pressure(gop, bearing, state, GROOVES, "reynolds")
    plain, _ = held_film(gop, bearing, state, res.active)
    t1 = time.process_time()
    fit = (BandFit if band else Fit)(gop, element)
    m = gop.op.mesh
    located = fit.locate(res.pressure, m.theta, ~res.active & (res.pressure > 0.0))
    cols = fit.choose(located)
    active = fit.held(cols, res.active)
    x = {key: _filled(located[key]) for key in cols}
    last = {}
    move = 0.0
    out = plain
    h = np.min(np.diff(fit.columns))
    for _ in range(iterations if cols else 0):
        fop = fit.operator(cols, {**located, **x})
        out, P = held_film(fop, bearing, state, active)
        vertex = fit.relocate(P, fop.op.mesh.theta, cols, x)
        step = {}
        for key in cols:
            r = vertex[key] - x[key]
            dx = r
            if key in last:     # a secant step per row where the last step gives a slope
                x0, r0 = last[key]
                run = x[key] - x0
                slope = np.divide(r - r0, run, out=np.zeros_like(r), where=np.abs(run) > 1e-12)
                use = slope < -0.05
                dx = np.where(use, -r / np.where(use, slope, 1.0), r)
            last[key] = (x[key], r)
            step[key] = np.clip(dx, -h, h)
        move = max(float(np.max(np.abs(r))) for r in step.values())
        x = {key: x[key] + step[key] for key in cols}
    seconds = (t1 - t0, time.process_time() - t0)
    return {"plain": plain, "fitted": out}, move, len(cols), seconds
