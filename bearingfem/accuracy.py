"""Answers to a requested accuracy: a mesh chosen to reach a relative tolerance, with the
error estimate that says it did.

The estimate is the h/2h difference of the answer on a pair of meshes, the fine one about
twice the coarse one in both directions, turned into the fine mesh's error by Richardson's
argument: with e(h) ~ C h^p,

    e_fine ~ |q_fine - q_coarse| / (r^p - 1),   r = h_coarse / h_fine ~ 2,

r the smaller of the two directions' ratios (the grid's rounding can make one 1.5), and
p the lower of the element's nominal order (the force of a P1 film converges as h^2;
a P2 film as h^4 without cavitation and as h^2 with it, the free boundary limiting it) and
the order observed on three meshes (never below 1; from one pair alone, at most 2). Taking
the lower order makes the estimate err high before the asymptotic range, where the
observed order is low. Its
effectivity (estimate / true error) is measured in tests/test_accuracy.py and
docs/accuracy.md; ``SAFETY`` is the factor that keeps it above 1 over the measured meshes
and states.

The mesh: the pair is a mesh and its half (about half as many cells each way). When its
estimate is above the tolerance, one more solve, the mesh with n_z halved only, splits the
estimate into its theta and z parts (that solve against the half differs in theta alone,
the mesh against it in z alone), and the next mesh is the least one whose two parts, each
falling as its direction's h^p, reach the tolerance with a 10 % margin (each direction
half of it, the optimum for a sum of two powers; a factor of 1.5 to 4 on the larger part's
direction, neither coarser; a factor near 2 taken as 2, so that this mesh is the next
one's half and a family of three gives an observed order). A short bearing, whose error
lives around the bearing, then gets meshes like 160 x 10 instead of the start's shape.
What sufficed is kept in a small memo under a key the caller gives (the bearing and film
options, not the state) with the estimate and its split, and the next call of a design
loop starts at the mesh the split predicts for its tolerance: the memo's mesh, or coarser
(at most 0.7x each way, with a margin of 2) when the estimate there showed slack.

The grading: a film whose mesh can be graded (:func:`search_grading`) is searched on
meshes graded toward its least film from a moderate eccentricity on, where the pressure
peak is narrow (docs/accuracy.md measures what it saves).

Otherwise this module knows nothing about films: it takes ``evaluate(n_theta, n_z, element)`` and a
``difference(fine, coarse)`` of what is asked for (a film's force, an equilibrium's eps,
a film's K and C).
"""
from __future__ import annotations

import logging
import math
import time
from collections import OrderedDict
from dataclasses import dataclass, field, replace
from typing import Callable, Hashable

import numpy as np

from .bearing import check_finite
from .caches import kept
from .errors import ConvergenceError, LoadCapacityError

__all__ = ["AccuracyRecord", "solve_to_tolerance", "refine_to_tolerance", "check_rtol",
           "refuse_rtol", "refuse_estimate", "check_estimate",
           "check_no_mesh", "nominal_order", "force_difference", "SAFETY", "RTOL_RANGE", "clear_memo",
           "film_to_tolerance", "estimate_error", "estimate_at", "half_mesh",
           "grid_multiple",
           "groove_multiple", "start_mesh", "search_grading", "GRADING_STRENGTH",
           "GRADED_FROM_EPS", "PLAIN_GRADING_STRENGTH", "PLAIN_GRADED_FROM_EPS",
           "richardson_error"]

#: Tolerances accepted: looser than 10 % is no answer, tighter than 1e-6 is below what a
#: double-precision film on a practical mesh resolves.
RTOL_RANGE = (1e-6, 0.1)
#: Factor on the Richardson estimate: keeps the measured effectivity >= 1 (docs/accuracy.md)
SAFETY = 1.5
#: Largest mesh the search goes to (cells around x along); past it the tolerance is refused
MAX_CELLS = 1536 * 256
#: Each mesh pair's estimate is logged at INFO (a search can take tens of seconds; the
#: command line shows these lines on stderr, the library prints nothing)
LOG = logging.getLogger(__name__)
_MEMO: "OrderedDict[Hashable, tuple]" = kept(OrderedDict())
_MEMO_SIZE = 64
#: A grooved film searched to a tolerance has its theta cells concentrated toward the
#: least film at this strength (the grooved mesh's ``grading``): on Lund & Thomsen's rows
#: it cut the K, C searches' cost 3.4x against uniform meshes, 0.9 1.7x (docs/accuracy.md)
GRADING_STRENGTH = 0.6
#: ... from this eccentricity ratio on: below it the pressure peak is broad and a uniform
#: mesh did as well or better (the light rows)
GRADED_FROM_EPS = 0.3
#: A plain film (meshed in the film frame) searched to a tolerance is graded toward its
#: least film at this strength (docs/accuracy.md)
PLAIN_GRADING_STRENGTH = 0.6
#: ... from this eccentricity ratio on
PLAIN_GRADED_FROM_EPS = 0.3
#: The grid the grooved grading's angle is put on: nearby states (a design loop's, an
#: equilibrium's and its coefficients') share meshes, operators and factors
_ANGLE_STEP = math.pi / 12.0


@dataclass(frozen=True)
class AccuracyRecord:
    """How an answer to a requested accuracy was reached.

    Attributes
    ----------
    rtol : the relative tolerance asked for
    error : the estimated relative error of the answer (<= rtol)
    element : the element used; mesh : (n_theta, n_z) of the answer; partner : the coarse
        mesh of its h/2h pair
    order : the convergence order used in the estimate (nominal, or observed if lower)
    meshes : every (n_theta, n_z) solved, in order, with the estimate found there (None
        for the first)
    solves : number of solves; seconds : their wall time [s]
    memo : whether the search started from the mesh that sufficed at an earlier call
    factor : the estimate per unit h/2h difference, SAFETY / (r^p - 1): an entry's error is
        ``factor`` times its change between the pair
    grading : the grading the search chose (:func:`search_grading`): a grooved mesh's
        (angle [rad], strength), a plain film's strength toward its least film, or None
    """

    rtol: float | None
    error: float
    element: str
    mesh: tuple
    partner: tuple
    order: float
    meshes: tuple = ()
    solves: int = 0
    seconds: float = 0.0
    memo: bool = False
    factor: float = 0.0
    estimates: tuple = field(default=(), repr=False)
    grading: tuple | None = None


def check_rtol(rtol, name: str = "rtol") -> float:
    """``rtol`` as a float in :data:`RTOL_RANGE`, or ValueError naming ``name``."""
    v = check_finite(name, rtol)
    lo, hi = RTOL_RANGE
    if not lo <= v <= hi:
        raise ValueError(f"{name} must lie in [{lo:g}, {hi:g}] (a relative accuracy), "
                         f"got {rtol!r}")
    return v



def refuse_rtol(rtol, tolerance: str) -> None:
    """ValueError where ``rtol`` is given to a function whose own tolerance is another
    (``tolerance``: what it is called there and why rtol cannot be taken): rtol is the
    toolkit's film-accuracy request, never a solver's tolerance."""
    if rtol is not None:
        raise ValueError(f"rtol is a film-accuracy request, got rtol={rtol!r}; {tolerance}")


def refuse_estimate(estimate, reason: str) -> None:
    """ValueError where ``estimate`` is given to a function that carries no error
    estimate (``reason``: why, and where one is made): passed on to each film it would
    double their cost and be dropped unseen."""
    if estimate is not None and estimate is not False:
        raise ValueError(f"estimate={estimate!r} is not taken here: {reason}")


def check_estimate(estimate, rtol=None) -> bool:
    """``estimate`` as a bool (None: False), or ValueError: a tolerance given there by
    mistake (``estimate=1e-3`` for ``rtol=1e-3``) was taken as True and estimated the
    default mesh; and ``estimate=True`` beside an ``rtol`` (not None), which was taken
    silently and dropped (rtol chooses the mesh and reports its own estimate)."""
    if estimate is None:
        return False
    if not isinstance(estimate, (bool, np.bool_)):
        raise ValueError(f"estimate must be True or False, got {estimate!r} (a requested "
                         "accuracy is rtol=)")
    if estimate and rtol is not None:
        raise ValueError("estimate=True is not taken with rtol: rtol chooses the mesh and "
                         "reports its error estimate; estimate=True estimates the error on "
                         "the mesh given (n_theta, n_z)")
    return bool(estimate)


def check_no_mesh(n_theta=None, n_z=None, hint: str = "") -> None:
    """ValueError naming n_theta and/or n_z when given (not None) beside ``rtol``: the
    search's mesh would replace them unseen. ``hint`` ends the message."""
    given = [k for k, v in (("n_theta", n_theta), ("n_z", n_z)) if v is not None]
    if given:
        raise ValueError(f"{' and '.join(given)} {'is' if len(given) == 1 else 'are'} not "
                         f"taken with rtol (the mesh is chosen to reach rtol): give rtol or "
                         f"the mesh, not both{hint}")


def nominal_order(element: str, smooth: bool) -> float:
    """The asymptotic order of a film's force in the mesh size h: 2 for P1; for P2, 4 on a
    smooth film (the force is a linear functional: twice the element's order) and 2 with a
    cavitation front (the pressure's second derivative jumps there)."""
    return 4.0 if element == "P2" and smooth else 2.0


def clear_memo():
    """Forget the meshes that sufficed at earlier calls (each call is then a cold search)."""
    _MEMO.clear()


def force_difference(fine, coarse) -> float:
    """|F_fine - F_coarse| / |F_fine| of two :class:`~bearingfem.solution.FilmSolution`
    (film plus asperity force; the vector, so the attitude's error counts too)."""
    f = np.add(fine.force_local, fine.asperity_force_local)
    g = np.add(coarse.force_local, coarse.asperity_force_local)
    n = float(np.linalg.norm(f))
    return float(np.linalg.norm(f - g)) / n if n > 0.0 else 0.0


def richardson_error(difference: float, ratio: float, order: float) -> float:
    """The fine mesh's error from the h/2h ``difference`` of a pair ``ratio`` apart (h_coarse
    / h_fine) at convergence ``order``, times :data:`SAFETY`."""
    return SAFETY * difference / (ratio ** order - 1.0)


def _observed_order(d1: float, d2: float, r1: float, r2: float) -> float | None:
    """The order p of e = C h^p through three meshes h0 > h1 > h2 (r1 = h0/h1, r2 = h1/h2)
    from d1 = |q1 - q0| and d2 = |q2 - q1|: d1 / d2 = ((r1 r2)^p - r2^p) / (r2^p - 1).
    0 when the differences do not shrink, None when one is zero."""
    if not (d1 > 0.0 and d2 > 0.0) or d1 <= d2:
        return None if not (d1 > 0.0 and d2 > 0.0) else 0.0

    def g(p):   # d1/d2 for e = C h^p: (h0^p - h1^p) / (h1^p - h2^p), h2 = 1
        return (((r1 * r2) ** p - r2 ** p) / (r2 ** p - 1.0)) - d1 / d2
    lo, hi = 0.05, 12.0
    if g(lo) > 0.0 or g(hi) < 0.0:
        return None if g(hi) < 0.0 else lo
    for _ in range(80):      # bisection: g is increasing in p
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if g(mid) < 0.0 else (lo, mid)
    return 0.5 * (lo + hi)


def estimate_error(scales, differences, order: float):
    """(estimated relative error of the finest answer, order used) from the last two or
    three mesh ``scales`` (1/h, increasing) and the ``differences`` between consecutive
    answers (the last the finest pair's; the one before it None when unknown): Richardson's
    estimate at the nominal ``order``, or at the observed order when that is lower (>= 1);
    from one pair alone (no observed order) at most order 2, since a first pair is often
    short of the asymptotic range (P2, L/D 1, eps 0.9, full film: 12 x 2 / 24 x 4 at order
    4 gives effectivity 0.68)."""
    d = differences[-1]
    p = min(order, 2.0)     # an order above 2 (the smooth P2 film's 4) only when observed
    if len(scales) == 3 and differences[0] is not None:
        p_obs = _observed_order(differences[0], d, scales[1] / scales[0],
                                scales[2] / scales[1])
        if p_obs is not None:
            p = min(order, max(1.0, p_obs))
    return richardson_error(d, scales[-1] / scales[-2], p), p


def grid_multiple(edges, largest: int = 360) -> int:
    """The least n (even, <= ``largest``) whose grid of 2 pi / n cells around puts a node
    on every angle of ``edges`` [rad] (relative to the first), e.g. a groove's edges; 2
    when none does."""
    edges = np.asarray(edges, float)
    if edges.size < 2:
        return 2
    rel = np.mod(edges - edges[0], 2.0 * math.pi) / (2.0 * math.pi)
    for n in range(2, largest + 1, 2):
        if np.all(np.abs(rel * n - np.round(rel * n)) < 1e-6):
            return n
    return 2


def _grid(n_theta: float, n_z: float, multiple: int, least: tuple = (8, 2)) -> tuple:
    """(n_theta, n_z) at least ``least`` and rounded up onto the grid: n_theta a multiple
    of ``multiple`` (nodes on the grooves' edges, :func:`grid_multiple`), n_z even."""
    m = max(2, int(multiple))
    return (m * max(math.ceil(least[0] / m), math.ceil(n_theta / m - 1e-9)),
            2 * max(math.ceil(least[1] / 2), math.ceil(n_z / 2 - 1e-9)))


def _fine(n_theta: float, n_z: float, multiple: int) -> tuple:
    """A mesh the search answers on: on the grid, large enough for a half partner."""
    return _grid(n_theta, n_z, multiple, least=(16, 4))


def _half(mesh: tuple, multiple: int) -> tuple:
    """The h/2h partner of ``mesh``: about half as many cells each way, on the grid."""
    return _grid(mesh[0] / 2.0, mesh[1] / 2.0, multiple)


def _refinement(error: float, share: float, up: float, down: float) -> float:
    """The factor on a direction's cell count that brings its ``error`` to ``share``: at
    the order ``up`` when refining, the order ``down`` when coarsening (the higher order:
    a coarsening predicted at too low an order would be too bold), within [0.5, 4]."""
    if error <= 0.0:
        return 0.5
    ratio = error / share
    return min(4.0, max(0.5, ratio ** (1.0 / (up if ratio > 1.0 else down))))


def _predict(mesh: tuple, split: tuple, target: float, up: float, down: float,
             multiple: int, grow: bool, least: float = 1.0) -> tuple:
    """The least mesh whose error, ``split`` = (theta part, z part) of ``mesh``'s
    estimate each falling as its direction's h^order, is ``target``: each direction gets
    half the target (the least cells n_theta n_z for a sum of two powers), what one
    direction cannot use (its factor at the bound ``least``) goes to the other. ``grow``:
    the larger part's direction at least 1.5x finer (the search must advance)."""
    e_t, e_z = split
    r_t = max(least, _refinement(e_t, 0.5 * target, up, down))
    r_z = max(least, _refinement(e_z, 0.5 * target, up, down))
    rest = lambda e, r: target - e / r ** (up if r > 1.0 else down)    # noqa: E731
    if r_z == least and rest(e_z, r_z) > 0.5 * target:
        r_t = max(least, _refinement(e_t, rest(e_z, r_z), up, down))
    elif r_t == least and rest(e_t, r_t) > 0.5 * target:
        r_z = max(least, _refinement(e_z, rest(e_t, r_t), up, down))
    if grow:
        if e_t >= e_z:
            r_t = max(r_t, 1.5)
        else:
            r_z = max(r_z, 1.5)
    # a doubling (or keeping) reuses solves: this mesh, or the split's (n_theta, n_z / 2),
    # becomes the next one's partner, for the cost of a 1.5x step
    snap = lambda r: 2.0 if 1.5 <= r <= 2.3 else 1.0 if 0.85 <= r <= 1.2 else r  # noqa: E731
    return _fine(mesh[0] * snap(r_t), mesh[1] * snap(r_z), multiple)


def refine_to_tolerance(evaluate: Callable, difference: Callable, rtol: float, *,
                        element: str, start_mesh: tuple, order: float,
                        key: Hashable | None = None, error_of=None,
                        n_theta_multiple: int = 2, shifted: Callable | None = None):
    """(answer, coarse answer, :class:`AccuracyRecord`): ``evaluate(n_theta, n_z,
    element)`` on a mesh whose estimated error is within ``rtol``, refined around and
    along as the estimate's split says.

    ``difference(fine, coarse)`` is the relative difference of two answers (what the
    tolerance is on); ``order`` the nominal convergence order of that quantity; ``key``
    names the memo entry (None: no memo); ``error_of(answer)`` a floor of the answer's
    error besides the mesh's (None: 0); ``n_theta_multiple``: n_theta is kept a multiple
    of it (:func:`grid_multiple`: nodes on the grooves' edges). ``shifted(n_theta, n_z,
    element)``: the answer on a mesh of that size with its nodes shifted (None: no such
    mesh); each pair's difference is then the larger of the fine answer's against the
    coarse one and against the coarse mesh shifted, and the coarse answer returned is the
    farther one: an answer whose error behaves like noise in where the nodes fall (K and
    C of a cavitated film: docs/accuracy.md) can agree with one partner by luck. Raises
    :class:`ConvergenceError` when the mesh would pass :data:`MAX_CELLS`.
    """
    rtol = check_rtol(rtol)
    t0 = time.perf_counter()
    multiple = max(2, int(n_theta_multiple))
    by_mesh: dict = {}
    solved: list = []
    shifted_solves = [0]

    def at(mesh):
        if mesh[0] * mesh[1] > MAX_CELLS:
            raise ConvergenceError(
                f"the mesh search for rtol = {rtol:g} ({element})", len(solved), None,
                f"{mesh[0]} x {mesh[1]} cells, past the largest mesh ({MAX_CELLS} cells); "
                f"ask for a looser rtol" + ("" if element == "P2" else " or element P2"))
        if mesh not in by_mesh:
            by_mesh[mesh] = evaluate(mesh[0], mesh[1], element)
            solved.append(mesh)
        return by_mesh[mesh]

    target = rtol / 1.1            # a 10 % margin on the predicted meshes
    memo_key = None if key is None else (key, element, multiple)
    remembered = memo_key is not None and memo_key in _MEMO
    share = None                   # the theta part's share of the error, once split
    if remembered:
        mesh, error, share, p = _MEMO[memo_key]
        _MEMO.move_to_end(memo_key)
        # the memo's mesh, or coarser when its estimate showed slack: a margin of 2 for
        # the state's change since, and at most 0.7x each way (a cavitated film's error is
        # not monotone in the mesh: a bolder step is often undone at the cost of a search)
        fine = _predict(mesh, (error * share, error * (1.0 - share)), rtol / 2.0, p, order,
                        multiple, grow=False, least=0.7)
    else:
        fine = _fine(*start_mesh, multiple)
    last = None                    # (fine, coarse, difference) of the last pair
    estimates: list = []
    while True:
        coarse = _half(fine, multiple)
        # the coarse one first: an evaluation warm-started from the last (an equilibrium's
        # Newton) then starts the fine one near its answer
        q_coarse = at(coarse)
        q_fine = at(fine)
        d = difference(q_fine, q_coarse)
        partner = q_coarse
        if shifted is not None:
            q_shifted = shifted(coarse[0], coarse[1], element)
            shifted_solves[0] += 1
            d_shifted = difference(q_fine, q_shifted)
            if d_shifted > d:
                d, partner = d_shifted, q_shifted
        r = min(fine[0] / coarse[0], fine[1] / coarse[1])
        if last is not None and last[0] == coarse and _half(coarse, multiple) == last[1]:
            r0 = min(coarse[0] / last[1][0], coarse[1] / last[1][1])   # one family of three
            err, p = estimate_error([1.0, r0, r0 * r], [last[2], d], order)
        else:
            err, p = estimate_error([1.0, r], [d], order)
        if error_of is not None:
            err = max(err, error_of(q_fine))
        estimates.append((fine, err))
        LOG.info("rtol %g: %d x %d %s, estimated error %.2g%s (%d solves, %.1f s)", rtol,
                 fine[0], fine[1], element, err, "" if err <= rtol else ", refining",
                 len(solved) + shifted_solves[0], time.perf_counter() - t0)
        if err <= rtol:
            break
        # the split: the partner refined around only (n_theta's, n_z halved) separates
        # the theta part (it against the partner) from the z part (the fine one against it)
        if coarse[1] < fine[1]:
            q_mid = at((fine[0], coarse[1]))
            e_t = difference(q_mid, q_coarse) / ((fine[0] / coarse[0]) ** p - 1.0)
            e_z = difference(q_fine, q_mid) / ((fine[1] / coarse[1]) ** p - 1.0)
            share = e_t / (e_t + e_z) if e_t + e_z > 0.0 else 0.5
        elif share is None:
            share = 0.5
        last = (fine, coarse, d)
        # neither direction coarser: a split from one coarse pair is too rough for it
        fine = _predict(fine, (err * share, err * (1.0 - share)), target, p, order,
                        multiple, grow=True, least=1.0)
    if memo_key is not None:
        _MEMO[memo_key] = (fine, float(err), 0.5 if share is None else share, p)
        while len(_MEMO) > _MEMO_SIZE:
            _MEMO.popitem(last=False)
    record = AccuracyRecord(
        rtol=rtol, error=float(err), element=element, mesh=fine, partner=coarse,
        order=float(p), meshes=tuple(solved), solves=len(solved) + shifted_solves[0],
        seconds=time.perf_counter() - t0, memo=remembered,
        factor=SAFETY / (r ** p - 1.0), estimates=tuple(estimates))
    return q_fine, partner, record


def half_mesh(mesh: tuple) -> tuple:
    """The partner (n_theta, n_z) of :func:`estimate_at`'s h/2h pair: half of ``mesh``
    (even counts), at least the coarsest mesh 8 x 2, which is its own half."""
    return (max(8, 2 * math.ceil(mesh[0] / 4.0)), max(2, 2 * math.ceil(mesh[1] / 4.0)))


def estimate_at(evaluate: Callable, difference: Callable, mesh: tuple, *, element: str,
                order: float):
    """(answer, coarse answer, :class:`AccuracyRecord`) on the ``mesh`` given, its error
    estimated from the h/2h pair with the half mesh (one more solve, a quarter's cost) at
    the nominal ``order``; ``record.rtol`` is None."""
    t0 = time.perf_counter()
    mesh = tuple(int(v) for v in mesh)
    half = half_mesh(mesh)
    if half == mesh:       # the coarsest mesh is its own half: no pair to estimate from
        raise ValueError(f"an error estimate needs a mesh finer than {half[0]} x {half[1]} "
                         f"(n_theta > {half[0]} or n_z > {half[1]}), got {mesh[0]} x {mesh[1]}")
    fine = evaluate(*mesh, element)
    try:
        coarse = evaluate(*half, element)
    except (ConvergenceError, LoadCapacityError) as err:
        # the half mesh is the estimate's, not the caller's: a failure there named no mesh
        # (and a thermal film's "start it nearer" cannot be followed), so it is named
        raise _on_half_mesh(err, mesh, half) from err
    ratio = math.sqrt(mesh[0] * mesh[1] / (half[0] * half[1]))
    err, order = estimate_error([1.0, ratio], [difference(fine, coarse)], order)
    record = AccuracyRecord(rtol=None, error=float(err), element=element, mesh=mesh,
                            partner=half, order=float(order), meshes=(mesh, half), solves=2,
                            seconds=time.perf_counter() - t0,
                            factor=SAFETY / (ratio ** order - 1.0))
    return fine, coarse, record


def _on_half_mesh(err, mesh: tuple, half: tuple):
    """``err`` (a film's ConvergenceError or LoadCapacityError on the half mesh ``half`` of
    an estimate at ``mesh``) with that said, and what helps: a finer mesh (rtol= where the
    function takes it)."""
    words = (f"on the error estimate's half mesh {half[0]} x {half[1]} (the mesh given, "
             f"{mesh[0]} x {mesh[1]}, solved): give a finer mesh")
    if isinstance(err, ConvergenceError):
        return err.at(words)
    return LoadCapacityError(err.load, err.capacity, err.eps_max, err.model, err.mesh,
                             f"{err.note}, {words}" if err.note else words)


def solve_to_tolerance(solve: Callable, rtol: float, *, start_mesh: tuple, element: str,
                       smooth: bool = False, key: Hashable | None = None,
                       n_theta_multiple: int = 2):
    """(FilmSolution, AccuracyRecord): ``solve(n_theta, n_z, element)`` -> FilmSolution on
    the least mesh whose estimated relative error of the film force is within ``rtol``;
    the solution carries ``force_error`` (the estimate) and ``accuracy`` (the record).
    ``smooth``: the film has no cavitation front (the P2 force then converges as h^4)."""
    sol, _, record = refine_to_tolerance(solve, force_difference, rtol, element=element,
                                      start_mesh=start_mesh,
                                      order=nominal_order(element, smooth), key=key,
                                      n_theta_multiple=n_theta_multiple)
    return replace(sol, force_error=record.error, accuracy=record), record


def start_mesh(element: str, length_ratio: float) -> tuple:
    """The search's start (n_theta, n_z): 24 cells around for P2, 48 for P1, and along the
    length cells about as long as wide (n_z ~ n_theta (L/D) / pi), at least 4: the error
    of a film with much longer cells along z than around is the z-direction's, which a
    uniform refinement never fixes (Lund & Thomsen's L/D 1 rows: K's estimate stalls at
    2e-3 from 144 x 16 to 288 x 32)."""
    n = 24 if element == "P2" else 48
    return n, max(4, 2 * round(n * length_ratio / math.pi / 2.0))


def film_to_tolerance(solve: Callable, bearing, rtol: float, element: str | None,
                      options: dict):
    """A film solve to a requested accuracy: ``solve(n_theta, n_z, element)`` with the
    element given, else P2 where the film takes it (P1 for JFO and EHD films, whose solvers
    are P1); the start mesh :func:`start_mesh`, n_theta on the grooves' edges, the memo keyed on the
    bearing's L/D and the film options that change the mesh needed. Returns the
    FilmSolution with ``force_error`` and ``accuracy`` set."""
    cavitation = options.get("cavitation", "reynolds")
    p1_only = cavitation == "jfo" or options.get("lubricant") is not None \
        or options.get("bush") is not None
    if element is None:
        element = "P1" if p1_only else "P2"
    start = start_mesh(element, bearing.length_ratio)
    smooth = cavitation == "none" and not options.get("grooves")
    try:
        key = ("film", options.get("discretisation", "fe"), round(bearing.length_ratio, 12),
               cavitation, element, tuple(options.get("grooves") or ()),
               options.get("supply_angle"), tuple(options.get("tilt", (0.0, 0.0))),
               tuple(options.get("tilt_rate", (0.0, 0.0))), options.get("half", True),
               options.get("ambient_pressure", 0.0), options.get("grading"),
               options.get("lubricant") is None, options.get("bush") is None,
               options.get("fields") is None, options.get("profile"),
               options.get("roughness") is None,
               options.get("thermal") is None)
        hash(key)
    except TypeError:
        key = None
    return solve_to_tolerance(solve, rtol, start_mesh=start, element=element,
                              smooth=smooth, key=key,
                              n_theta_multiple=groove_multiple(options.get("grooves")))[0]


def search_grading(problem, toward: tuple):
    """The grading a mesh search gives a film that has none of its own: ``problem`` a
    :class:`~bearingfem.routes.FilmProblem` (its route's kind and roughness are read),
    ``toward`` = (journal angle gamma [rad], eps), known or estimated. A plain film on the
    film-frame mesh ("rigid"): :data:`PLAIN_GRADING_STRENGTH` toward its least film from
    :data:`PLAIN_GRADED_FROM_EPS` on (one mesh for every state); a grooved film on the
    bearing-fixed mesh without roughness: (gamma on a 15 deg grid,
    :data:`GRADING_STRENGTH`) from :data:`GRADED_FROM_EPS` on; None otherwise."""
    if problem.grading is not None:
        return None
    gamma, eps = (float(v) for v in toward)
    if problem.kind == "rigid" and eps >= PLAIN_GRADED_FROM_EPS:
        return PLAIN_GRADING_STRENGTH
    if problem.kind == "grooved" and problem.roughness is None and eps >= GRADED_FROM_EPS:
        return (_ANGLE_STEP * round(gamma / _ANGLE_STEP), GRADING_STRENGTH)
    return None


def groove_multiple(grooves) -> int:
    """:func:`grid_multiple` of the grooves' edges (objects with ``angle`` and ``width``
    [rad]); 2 without grooves or when no grid of <= 360 cells holds them all."""
    edges = [g.angle + s * 0.5 * g.width for g in (grooves or ()) for s in (-1.0, 1.0)]
    return grid_multiple(edges)
