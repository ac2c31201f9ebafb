"""A design chart: eps, attitude, friction and the dynamic coefficients against the
Sommerfeld number (Raimondi & Boyd 1958 for the static columns; Lund & Thomsen 1978 and
Someya 1989 for the coefficients), from any film model with exact partials.

For a rigid, isoviscous bearing every dimensionless output depends on S = (R/c)^2 mu N / P
alone, so one bearing at one speed walks the whole chart by its load. Each point is the
Newton equilibrium of :mod:`bearingfem.design.newton` started from the previous point (the
first from the closed form), then K and C at that state: with the FE film's grooved
operator (:mod:`bearingfem.fe.grooved`) every evaluation reuses the mesh, the operator
and the previous cavitated set, and the coefficients reuse the last solve's film.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..accuracy import (check_estimate, estimate_at, estimate_error, nominal_order,
                        refuse_rtol)
from ..bearing import Bearing, JournalState, check_finite, check_turn_angle
from ..errors import ConvergenceError
from ..fe.mesh import GRADING_MAX
from ..models import film_model
from .coefficients import coefficients
from .equilibrium import EPS_MAX
from .groups import load_from_sommerfeld, petroff_friction
from .newton import closed_form_start, film_mesh, newton_position, polar_linearisation

__all__ = ["ChartPoint", "DesignChart", "design_chart", "CHART_SOMMERFELD", "chart_grading"]

#: The chart's default abscissa: 20 Sommerfeld numbers from 10 (light load) to 0.01.
CHART_SOMMERFELD = tuple(float(s) for s in np.geomspace(10.0, 0.01, 20))


@dataclass(frozen=True)
class ChartPoint:
    """One Sommerfeld number of the chart.

    Attributes
    ----------
    sommerfeld : S; eps : eccentricity ratio; attitude : angle from the load line to the
        line of centres, in the sense of rotation [rad]
    friction_variable : (R/c) f, f the friction coefficient (full Couette shear in the
        cavity, :func:`~bearingfem.design.groups.petroff_friction`)
    K, B : 2x2 K c / W and C c omega / W in the load frame (axis 1 along the load)
    state : the journal's :class:`JournalState` there
    eps_error, K_error, B_error : with ``estimate=True``, the estimated absolute errors of
        the journal position |q| = eps and of K and B's entries (same units); else None
    """

    sommerfeld: float
    eps: float
    attitude: float
    friction_variable: float
    K: np.ndarray
    B: np.ndarray
    state: JournalState
    eps_error: float | None = None
    K_error: np.ndarray | None = None
    B_error: np.ndarray | None = None


@dataclass(frozen=True)
class DesignChart:
    """The chart's points in the order asked, the model, and the film evaluations (each a
    force with its partials) the walk took; ``accuracy``: with ``estimate=True`` the
    :class:`~bearingfem.accuracy.AccuracyRecord` of the chart's h/2h pair (its ``error``
    the largest point's relative position error), else None."""

    points: tuple
    model: str
    evaluations: int
    accuracy: object = None

    def column(self, name: str) -> np.ndarray:
        """One output over the chart: an array of the points' ``name`` (e.g. "eps", "K")."""
        return np.array([getattr(p, name) for p in self.points])


def _sommerfeld_numbers(sommerfeld) -> np.ndarray:
    S = np.atleast_1d(np.asarray(sommerfeld, dtype=float))
    if S.ndim != 1 or S.size == 0 or not np.all(np.isfinite(S)) or not np.all(S > 0.0):
        raise ValueError(f"sommerfeld must be one or more finite numbers > 0, got "
                         f"{sommerfeld!r}")
    return S


def chart_grading(bearing: Bearing, omega: float, sommerfeld=CHART_SOMMERFELD,
                  direction: float = -0.5 * math.pi, strength: float = 0.9) -> tuple:
    """The "fem" model's ``grading`` (angle [rad], strength) for a grooved chart: the
    cells concentrated where the closed form (:func:`~bearingfem.design.newton.closed_form_start`)
    puts the minimum film at the geometric mean of the chart's heavy loads (S < 0.1, whose
    narrow pressure peaks set the mesh's error; the smallest S if none). One mesh serves
    the whole chart: grading per point would rebuild it per point. ``strength`` 0.9 is
    what benchmarks/chart_accuracy.py measured best (cells ~19x finer there than opposite).
    """
    S = _sommerfeld_numbers(sommerfeld)
    direction = check_turn_angle("direction", direction)
    strength = check_finite("strength", strength)
    if not 0.0 <= strength <= GRADING_MAX:      # the grading's own range (check_grading)
        raise ValueError(f"strength must lie in [0, {GRADING_MAX:g}], got {strength!r}")
    heavy = S[S < 0.1]
    s = float(np.exp(np.mean(np.log(heavy)))) if heavy.size else float(S.min())
    W = load_from_sommerfeld(bearing, s, check_finite("omega", omega))
    u = np.array([math.cos(direction), math.sin(direction)])
    q = closed_form_start(bearing, omega, W * u)
    return math.atan2(q[1], q[0]), float(strength)


def design_chart(bearing: Bearing, omega: float, sommerfeld=CHART_SOMMERFELD,
                 model: str = "fem", *, direction: float = -0.5 * math.pi,
                 eps_max: float = EPS_MAX, xtol: float = 1e-10, rtol=None,
                 estimate: bool = False, **options) -> DesignChart:
    """Walk the Sommerfeld numbers ``sommerfeld`` of ``bearing`` turning at ``omega``
    [rad/s] under a load along ``direction`` [rad] (inertial; default downward, the
    grooves of :class:`~bearingfem.bearing.Groove` stay where they are given).

    ``model`` must have exact partials (Newton's method; e.g. "fem", "short", "long") and
    ``options`` are its options. ``xtol`` (formerly ``rtol``): Newton stops once a step is
    below sqrt(xtol) |q|; the film force then balances the load to about xtol (checked: a
    point off by more than max(1e-8, 10 xtol) raises :class:`ConvergenceError`). A load
    beyond what the film carries before eps_max raises ValueError.
    ``rtol`` (a film accuracy elsewhere) is refused: the chart is solved on the mesh given,
    a mesh per point would break the warm-started walk and multiply its cost.
    ``estimate=True`` (models on a mesh): the chart is walked again on the half mesh (a
    quarter of the cost) and each point's ``eps_error``, ``K_error``, ``B_error`` are the
    h/2h estimates (:func:`~bearingfem.accuracy.estimate_at`; the position at the film
    force's order, K and B at order 1 for a cavitated film, as
    :func:`~bearingfem.design.coefficients.coefficients` estimates them).
    """
    refuse_rtol(rtol, "Newton's tolerance is xtol (the chart is solved on the mesh given)")
    m = film_model(model)
    opts = m.options(options)
    if not m.exact_derivatives or m.memory:
        raise ValueError(f"design_chart needs a model with exact partials (Newton's method), "
                         f"got model={model!r}")
    omega = check_finite("omega", omega)
    if omega == 0.0:
        raise ValueError("omega must be non-zero [rad/s]: without rotation a film carries "
                         "no steady load")
    direction = check_turn_angle("direction", direction)
    eps_max = check_finite("eps_max", eps_max)
    if not 0.0 < eps_max < 1.0:
        raise ValueError(f"eps_max must lie in (0, 1), got {eps_max!r}")
    xtol = check_finite("xtol", xtol)
    if not 0.0 < xtol < 1e-3:
        raise ValueError(f"xtol must lie in (0, 1e-3), got {xtol!r}: Newton's tolerance on "
                         "each point's equilibrium")
    S = _sommerfeld_numbers(sommerfeld)
    if not check_estimate(estimate):
        return _walk(bearing, omega, S, m, opts, direction, eps_max, xtol, model)
    if not {"n_theta", "n_z"} <= set(m.defaults):
        raise ValueError(f"estimate=True is for film models on a mesh (options n_theta, "
                         f"n_z); model {model!r} has none")
    has_element = "element" in m.defaults
    element = opts["element"] if has_element else "P1"
    smooth = opts.get("cavitation") == "none" and not opts.get("grooves")

    def walk(n_theta, n_z, el):
        o = {**opts, "n_theta": n_theta, "n_z": n_z, **({"element": el} if has_element else {})}
        return _walk(bearing, omega, S, m, o, direction, eps_max, xtol, model)

    def difference(fine, coarse):      # the largest point's relative position change
        return max(float(np.linalg.norm(_position(f) - _position(c)) / f.eps)
                   for f, c in zip(fine.points, coarse.points))

    fine, coarse, record = estimate_at(walk, difference, (opts["n_theta"], opts["n_z"]),
                                       element=element, order=nominal_order(element, smooth))
    ratio = math.sqrt(record.mesh[0] * record.mesh[1] / (record.partner[0] * record.partner[1]))
    # K and B of a cavitated film at order 1 (design.coefficients._order: the held set's
    # error behaves like noise in where the nodes fall), else the force's
    kc_order = 1.0 if opts.get("cavitation", "reynolds") != "none" else record.order
    points = []
    for f, c in zip(fine.points, coarse.points):
        eps_error = estimate_error([1.0, ratio], [float(np.linalg.norm(_position(f)
                                                                       - _position(c)))],
                                   record.order)[0]
        K_error = estimate_error([1.0, ratio], [np.abs(f.K - c.K)], kc_order)[0]
        B_error = estimate_error([1.0, ratio], [np.abs(f.B - c.B)], kc_order)[0]
        points.append(replace(f, eps_error=float(eps_error), K_error=K_error,
                              B_error=B_error))
    return DesignChart(tuple(points), model, fine.evaluations + coarse.evaluations, record)


def _position(point: ChartPoint) -> np.ndarray:
    """The journal position q = e/c of a chart point."""
    return point.eps * np.array([math.cos(point.state.gamma), math.sin(point.state.gamma)])


def _walk(bearing, omega, S, m, opts, direction, eps_max, xtol, model) -> DesignChart:
    """The chart's points on the mesh of ``opts`` (the module docstring's walk)."""
    count = [0]

    def partials(eps, gamma):
        count[0] += 1
        return m.force_derivatives(bearing, JournalState(eps, omega=omega, gamma=gamma),
                                   **opts)

    def capacity():     # asked only when a load looks too heavy: the periodic film's
        o = {**opts, "grooves": ()} if opts.get("grooves") else dict(opts)
        if o.get("grading") is not None:      # a grading is for the grooved mesh
            o["grading"] = None
        return math.hypot(*m.film_force(bearing, JournalState(eps_max, omega=omega), **o))

    film = polar_linearisation(partials)
    u = np.array([math.cos(direction), math.sin(direction)])
    points, q = [], None
    for s in S:
        W = load_from_sommerfeld(bearing, s, omega)
        load = W * u
        q0 = closed_form_start(bearing, omega, load) if q is None else q
        eps, gamma = newton_position(film, load, q0, eps_max, xtol, capacity, model,
                                     mesh=film_mesh(opts))
        q = eps * np.array([math.cos(gamma), math.sin(gamma)])
        state = JournalState(eps, omega=omega, gamma=gamma)
        kc = coefficients(bearing, state, model, frame="load", **opts)
        count[0] += 1
        residual = math.hypot(*(np.add(kc.force, load))) / W
        if not residual <= max(1e-8, 10.0 * xtol):
            raise ConvergenceError(f"design chart's equilibrium ({model} model)", count[0],
                                   residual, f"S = {s:g}, eps = {eps:.6g}")
        c, sn = math.cos(gamma), math.sin(gamma)
        f_r = kc.force[0] * c + kc.force[1] * sn
        f_t = kc.force[1] * c - kc.force[0] * sn
        K, B = kc.dimensionless()
        friction = petroff_friction(bearing, eps, omega, f_t)
        points.append(ChartPoint(
            sommerfeld=float(s), eps=eps, attitude=math.atan2(f_t, -f_r),
            friction_variable=bearing.radius / bearing.clearance * friction / W,
            K=K, B=B, state=state))
    return DesignChart(tuple(points), model, count[0])
